"""Pareto front of mass against cost by the epsilon-constraint method over the NLP, for any coupling.

The two ends are the mass optimum and the cost optimum. Between them, mass is minimised subject to
``cost <= epsilon`` for evenly spaced epsilon from the cost of the mass optimum down to the cost optimum: the
formulation gains one named constraint (``cost_cap``) and one quantity (the cap), so the same solver layer,
float64 check and warm starts apply. Each point is warm-started from the one before.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from clutchopt.cases import Case
from clutchopt.formulations import get_coupling
from clutchopt.model import Formulation, Quantity, at_most
from clutchopt.optimise.design import Robustness, check_robustness, choices
from clutchopt.optimise.problem import case_formulation, case_problem, problem_for
from clutchopt.optimise.robust import RobustResult
from clutchopt.optimise.robust_models import largest_failure
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.optimise.sweep_grid import column_name
from clutchopt.records import DESIGN_STATUSES
from clutchopt.optimise.verify import evaluate_objective
from clutchopt.start_up.drive import Structure
from clutchopt.units import from_si

CAP = "cost_cap"


def capped(formulation: Formulation, bounded: str = "cost") -> Formulation:
    """The formulation with ``<bounded> <= cost_cap`` added (the cap a case quantity), in the same mode: a variant."""
    objective = formulation.objective(bounded)
    cap = Quantity(CAP, objective.unit, f"upper limit on {bounded} (epsilon-constraint)", "epsilon", "pareto")
    return replace(
        formulation,
        variant=f"{formulation.variant} {bounded} capped".strip(),
        quantities=formulation.quantities + (cap,),
        constraints=lambda x, p: formulation.constraints(x, p) + [
            at_most(CAP, objective.function(x, p), getattr(p, CAP), equation="epsilon", unit=objective.unit,
                    description=f"{bounded} within the cap")],
    )


@dataclass
class ParetoFront:
    case: Case
    mode: str
    frame: pd.DataFrame  # one row per point: cost cap, status, mass, cost, design
    solutions: list[Solution]
    caps: list[float]  # the cost cap of each solution (NaN at the two ends)
    note: str = ""  # why there is no front (one end not optimal, or both ends the same design)
    choice: dict[str, str] = field(default_factory=dict)  # the choice of options.choose this front is made of
    robust: list[RobustResult] = field(default_factory=list)  # with --robust: each point's robust result
    caveat: str = ""  # what a robust front's cost column is not (review 30: the cap held at a corner, unsaid)


_CAPPED: dict[tuple[str, str], Formulation] = {}  # one capped formulation per mode: one problem in problem_for


def pareto_fronts(case: Case, mode: str | None = None, points: int = 9, options: SolverOptions = SolverOptions(),
                  robust: Robustness | None = None, progress: bool = False) -> list[ParetoFront]:
    """One front per choice of ``options.choose`` (the case's own without it), each of designs for the scatter
    with ``robust`` (``progress``: see :func:`~clutchopt.optimise.design.choices`)."""
    check_robustness(case, robust, case_problem(case, mode, "mass", options) if robust is not None else None)
    return [replace(pareto_front(variant, mode, points, options, robust), choice=choice)
            for choice, variant in choices(case, progress)]


def pareto_front(case: Case, mode: str | None = None, points: int = 9, options: SolverOptions = SolverOptions(),
                 robust: Robustness | None = None) -> ParetoFront:
    """Mass optimum, cost optimum, and ``points - 2`` epsilon-constrained mass optima between them; with
    ``robust``, each designed for the case's scatter (the cap bounds the robust design's cost)."""
    formulation = case_formulation(case, mode)
    structure = Structure.of(case) if case.start_up is not None else None
    base = get_coupling(case.coupling).formulation(case.mode_of(mode))
    capped_base = _CAPPED.setdefault((base.coupling, base.mode), capped(base))
    results: list[RobustResult] = []

    def design(point: Case, objective: str, posed: Formulation, warm: Solution | None = None) -> Solution:
        if robust is None:
            return problem_for(posed, objective, options, structure).solve(point, warm=warm)
        results.append(robust.solve(point, base.mode, objective, options, base=posed))
        return results[-1].solution

    mass_end, cost_end = design(case, "mass", base), design(case, "cost", base)
    solutions, caps = [mass_end], [np.nan]
    note = ""
    if mass_end.status != "optimal" or cost_end.status != "optimal":
        note = "no front: " + "; ".join(f"{s.objective_name} optimum {s.status}" for s in (mass_end, cost_end))
    else:
        high = evaluate_objective(formulation, "cost", mass_end.design, case.params())
        low = cost_end.objective
        if high - low <= 1e-7 * abs(high):
            note = "no trade-off: the mass optimum is also the cost optimum"
        else:
            previous = mass_end
            for cap in np.linspace(high, low, points)[1:-1]:
                capped_case = replace(case, values={**case.values, CAP: float(cap)})
                solution = design(capped_case, "mass", capped_base, previous if previous.status == "optimal" else None)
                solutions.append(solution)
                caps.append(float(cap))
                previous = solution
            solutions.append(cost_end)
            caps.append(np.nan)
    if robust is not None:  # in the order of the points: the mass end, the capped ones, the cost end
        results = [results[0], *results[2:], results[1]][: len(solutions)]
    moved = sorted({q for result in results for q, effect in result.bars.get(CAP, {}).items() if abs(effect) > 1e-12})
    caveat = (f"the cost cap holds where the scatter ({', '.join(moved)}) makes the cost highest, its corner or "
              "performance point; the cost column is the nominal cost, at most the cap") if moved else ""
    return ParetoFront(case, formulation.mode, _frame(formulation, case, caps, solutions, results), solutions, caps,
                       note, robust=results, caveat=caveat)


def _frame(formulation: Formulation, case: Case, caps: list[float], solutions: list[Solution],
           robust: list[RobustResult]) -> pd.DataFrame:
    params = case.params()
    mass, cost = formulation.objective("mass"), formulation.objective("cost")
    rows = []
    for k, (cap, solution) in enumerate(zip(caps, solutions)):
        row = {column_name(CAP, cost.unit): cap, "status": solution.status}
        if robust:  # Monte Carlo: the estimate, and its 95 % upper bound beside it
            _, row["largest P(fail)"], _, row["largest P(fail) 95% high"] = largest_failure(robust[k].failure)
        designed = solution.status in DESIGN_STATUSES  # no design values for a point that has none
        for objective in (mass, cost):
            row[column_name(objective.name, objective.unit)] = evaluate_objective(
                formulation, objective.name, solution.design, params) if designed else np.nan
        row.update({column_name(v.name, v.unit): from_si(solution.design[v.name], v.unit) if designed else np.nan
                    for v in formulation.variables})
        row["active"] = " ".join(c.name for c in solution.constraints if c.active and c.name != CAP) if designed else ""
        rows.append(row)
    return pd.DataFrame(rows)
