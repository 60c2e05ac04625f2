"""What a robust design is made of: the derived formulation (each constraint at a corner of its own: of the ranges,
or its performance point) and, at a design, the corners, Monte Carlo samples and margin
sensitivities in float64, vectorised (``clutchopt.optimise.robust`` designs with them; docs/robust.md)."""

from __future__ import annotations

import itertools
from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from clutchopt.model import Constraint, Formulation, followed, namespace
from clutchopt.optimise.verify import FEASIBILITY_TOL, ConstraintCheck, check_constraints, constraint_table
from clutchopt.scatter import draw

SAMPLES = 10_000
CONFIDENCE = 0.95  # of the failure probabilities' intervals
SEED = 20261123


# --- The derived formulations ----------------------------------------------------------------------------------------
def corner_name(quantity: str, constraint: str) -> str:
    return f"{quantity}@{constraint}"


START_UP = "start_up"  # the corner a [start_up]'s start is designed at: where it binds (chance: of the quantiles)


def design_at(design: dict, values: dict) -> dict:
    """The design with each of its variables that scatters at its value in ``values``: a scattered design variable
    is one the case fixes (a free one enters as no case value: refused), so it scatters as the case's value does."""
    return {**design, **{q: v for q, v in values.items() if q in design}}


def at_point(x: dict, p: dict, values: dict) -> tuple[SimpleNamespace, SimpleNamespace]:
    """The design and the case values (dicts) where each scattered quantity takes its value in ``values``, as a case
    quantity and as the design variable the case fixes at it (:func:`design_at`)."""
    return namespace(design_at(x, values)), namespace({**p, **values})


def start_up_view(declared: dict, scattered: tuple[str, ...], follows: tuple = (), names: tuple[str, ...] = ()):
    """(quantities ``q@start_up`` and ``q@name`` of each start-up constraint, the view ``(x, p, name) -> (x, p)``
    that puts a [start_up]'s start (name None) and each of its constraints at its corner, the followers it moves): a
    start is simulated at one corner, where its figures bind, and each constraint evaluated with them at its own (a
    limit at its strict end, an engagement window at the preload that narrows it); the defaults that follow a
    scattered quantity follow it there (``Case.follows`` items)."""
    moved = {name: rule for name, rule in follows if rule[0] in scattered}
    corner = tuple(replace(declared[q], name=corner_name(q, c), section="scatter", default=None,
                           description=f"{q} where the start-up {'is designed' if c == START_UP else c + ' binds'}")
                   for c in (START_UP, *names) for q in scattered)

    def view(x: dict, p: dict, name: str | None) -> tuple[dict, dict]:
        at = START_UP if name is None else name
        x, p = at_point(x, p, {q: p.get(corner_name(q, at), p.get(q)) for q in scattered})
        return vars(x), followed(vars(p), moved)

    return corner, view, moved


def worst_case_formulation(base: Formulation, scattered: tuple[str, ...], names: tuple[str, ...],
                           declared: dict, follows: tuple = (), start_up_names: tuple[str, ...] = ()) -> Formulation:
    """``base`` with constraint ``names[i]`` evaluated where each scattered quantity q takes the value of the case
    quantity ``q@names[i]`` (its corner), a start-up's at ``q@start_up`` and ``q@name`` (:func:`start_up_view`,
    ``start_up_names`` its constraints); objective and outputs at the nominal values. ``declared``: the case's
    quantities by name (a start-up's may scatter too); ``follows``: the case's defaults that follow another quantity
    (``Case.follows`` items), which follow a scattered one to its start-up corner."""
    start_up, view, moved = start_up_view(declared, scattered, follows, start_up_names)
    corners = tuple(replace(declared[q], name=corner_name(q, c), section="scatter", default=None,
                            description=f"{q} at the worst corner of {c}") for c in names for q in scattered)

    def constraints(x, p):
        return [base.constraints(*at_point(vars(x), vars(p), {q: getattr(p, corner_name(q, name))
                                                               for q in scattered}))[i]
                for i, name in enumerate(names)]

    return replace(base, quantities=base.quantities + corners + start_up, constraints=constraints,
                   variant=f"{base.variant} worst case over {', '.join(scattered)}".strip()
                   + (f" ({', '.join(moved)} following)" if moved else ""), start_up_view=view)


# --- Corners, samples, sensitivities at a design (float64, vectorised) ------------------------------------------
def at_values(params: SimpleNamespace, values: dict) -> SimpleNamespace:
    return SimpleNamespace(**{**vars(params), **values})


def constraints_at(formulation: Formulation, design: dict, params: SimpleNamespace, values: dict) -> list[Constraint]:
    """The formulation's constraints at ``design`` with each scattered quantity at ``values`` (floats or arrays: one
    point per element; :func:`at_point`)."""
    return formulation.constraints(*at_point(design, vars(params), values))


def _margins(constraints: list[Constraint], count: int) -> np.ndarray:
    """Relative margins, one row per constraint, one column per point (broadcast)."""
    return constraint_table(constraints, count)[3]


def corner_table(scatter, ends: dict[str, tuple[float, float]] | None = None) -> dict[str, np.ndarray]:
    """Every corner of the ranges (or of other ``ends``, quantity -> (one, other)): quantity -> its value at each
    of the 2^n corners."""
    pairs = [ends[s.name] if ends else (s.low, s.high) for s in scatter]
    columns = np.array(list(itertools.product(*pairs))).T
    return {s.name: columns[i] for i, s in enumerate(scatter)}


def worst_corners(formulation: Formulation, design: dict, params: SimpleNamespace, scatter):
    """Each constraint's worst corner (quantity -> value) at ``design``, and the constraints at every corner."""
    table = corner_table(scatter)
    constraints = constraints_at(formulation, design, params, table)
    margins = _margins(constraints, 2 ** len(scatter))
    worst = np.nanargmin(np.where(np.isnan(margins), -np.inf, margins), axis=1)
    return ({c.name: {q: float(values[i]) for q, values in table.items()} for c, i in zip(constraints, worst)},
            constraints)


def failure_probabilities(formulation: Formulation, design: dict, params: SimpleNamespace, scatter,
                          samples: int = SAMPLES, seed: int = SEED, correlation=None) -> dict[str, list[float]]:
    """Monte Carlo: each constraint's failure probability (relative margin below -FEASIBILITY_TOL) with its
    Clopper-Pearson interval; ``correlation``: of the scattered quantities' normal scores (``Case.correlation``,
    :func:`clutchopt.scatter.draw`)."""
    drawn = draw(scatter, np.random.default_rng(seed), samples, correlation)
    constraints = constraints_at(formulation, design, params, drawn)
    margins = _margins(constraints, samples)
    # active constraints sit at 0 +- round-off
    return {c.name: clopper_pearson(int(np.count_nonzero(~(row >= -FEASIBILITY_TOL))), samples)
            for c, row in zip(constraints, margins)}


def largest_failure(failure: dict[str, list[float]]) -> tuple[str, float, float, float]:
    """The constraint likeliest to fail by :func:`failure_probabilities`: its name, P(fail) and 95 % interval (low,
    high); ("", 0, 0, 0) with no constraint."""
    if not failure:
        return "", 0.0, 0.0, 0.0
    name, (p, low, high) = max(failure.items(), key=lambda item: item[1][0])
    return name, p, low, high


def clopper_pearson(failed: int, count: int, confidence: float = CONFIDENCE) -> list[float]:
    """[failed / count, low, high]: a failure frequency and its Clopper-Pearson interval (``confidence``, two-sided)."""
    from scipy.stats import beta

    alpha = 1.0 - confidence
    low = float(beta.ppf(alpha / 2, failed, count - failed + 1)) if failed else 0.0
    high = float(beta.ppf(1 - alpha / 2, failed + 1, count - failed)) if failed < count else 1.0
    return [failed / count, low, high]


def tornado(formulation: Formulation, design: dict, params: SimpleNamespace, scatter) -> dict[str, dict[str, float]]:
    """How much each scattered quantity moves each constraint's relative margin over its range (high - low),
    the others at their nominal values: the bars of a tornado chart."""
    bars: dict[str, dict[str, float]] = {}
    for s in scatter:
        ends = constraints_at(formulation, design, params, {s.name: np.array([s.low, s.high])})
        for c, (low, high) in zip(ends, _margins(ends, 2)):
            bars.setdefault(c.name, {})[s.name] = float(high - low)
    return bars


def corner_checks(formulation: Formulation, design: dict, params: SimpleNamespace, scatter) -> list[ConstraintCheck]:
    """Every constraint at every corner, each reported at its worst."""
    return check_constraints(constraints_at(formulation, design, params, corner_table(scatter)))
