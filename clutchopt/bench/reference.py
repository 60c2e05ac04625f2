"""What every benchmark and torture case is measured against: the coupling's cases and the closed form.

Convention (generic over the registry): a coupling's comparison may have a reference column named
``closed_form``: the closed-form optimum of the mode of its first NLP column (``Comparison.solves[0]``), its rows
naming that mode's design variables. Benchmarks and torture cases use that mode; a coupling without the column
(the ball clutch: the paper gives a procedure, not an optimum) is measured without a closed form, and one
without a comparison in its default mode.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from clutchopt.cases import Case, load_case, read_toml
from clutchopt.formulations import MODULES, get_coupling
from clutchopt.model import Formulation
from clutchopt.optimise.verify import ConstraintCheck, check_design, evaluate_objective

CASES = Path(__file__).resolve().parents[2] / "cases"
CLOSED_FORM_COLUMN = "closed_form"


@dataclass
class ClosedForm:
    design: dict[str, float]
    objective: float
    constraints: list[ConstraintCheck]
    in_bounds: bool  # every variable within its search box

    @property
    def feasible(self) -> bool:
        return self.in_bounds and all(c.feasible for c in self.constraints)

    @property
    def worst_violation(self) -> float:
        return max([0.0] + [-c.margin for c in self.constraints])


def coupling_cases(coupling: str) -> list[Path]:
    """The case files of a coupling in ``cases/``, sorted by name (a neutral case, ``coupling = "any"``, is
    choose-coupling's, no coupling's)."""
    return [path for path in sorted(CASES.glob("*.toml")) if read_toml(path).get("coupling") == coupling]


def bench_cases() -> list[Case]:
    """One case per registered coupling that has a case file (the first by name)."""
    return [load_case(paths[0]) for name in MODULES if (paths := coupling_cases(name))]


def reference_mode(coupling: str) -> str:
    """The mode the closed form belongs to: the first NLP column of the comparison, else the default mode."""
    c = get_coupling(coupling)
    return c.comparison.solves[0][1] if c.comparison else c.default_mode


def search_box(formulation: Formulation, case: Case) -> dict[str, tuple[float, float]]:
    """Each variable's bounds for this case; variables fixed unless freed sit at the case value."""
    box = {}
    for v in formulation.variables:
        if v.fixed_unless_freed and v.name not in case.free:
            box[v.name] = (case.values[v.name], case.values[v.name])
        else:
            box[v.name] = case.bounds.get(v.name, (v.lower, v.upper))
    return box


def closed_form(case: Case, objective: str = "mass") -> ClosedForm | None:
    """The ``closed_form`` column's design evaluated in float64 with the reference mode's own equations; None if
    the coupling has none or it is undefined (NaN) at this case."""
    coupling = get_coupling(case.coupling)
    if coupling.comparison is None:
        return None
    formulation = coupling.formulation(reference_mode(case.coupling))
    params = case.params()
    with np.errstate(invalid="ignore", divide="ignore"):
        column = coupling.comparison.references(params).get(CLOSED_FORM_COLUMN, {})
    design = {v.name: column.get(v.name, case.values.get(v.name, math.nan)) for v in formulation.variables}
    if not all(isinstance(value, (int, float)) and math.isfinite(value) for value in design.values()):
        return None
    design = {name: float(value) for name, value in design.items()}
    box = search_box(formulation, case)
    in_bounds = all(lo * (1 - 1e-12) <= design[name] <= hi * (1 + 1e-12) for name, (lo, hi) in box.items())
    with np.errstate(invalid="ignore", divide="ignore"):
        return ClosedForm(design, evaluate_objective(formulation, objective, design, params),
                          check_design(formulation, design, params), in_bounds)
