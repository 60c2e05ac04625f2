"""What a robust design is made of: the derived formulations (each constraint at a corner of its own, or backed off
by the standard deviation it propagates) and, at a design, the corners, Monte Carlo samples and margin
sensitivities in float64, vectorised (``clutchopt.optimise.robust`` designs with them; docs/robust.md)."""

from __future__ import annotations

import itertools
import math
from dataclasses import replace
from types import SimpleNamespace

import casadi as ca
import numpy as np

from clutchopt.backend import is_symbolic
from clutchopt.model import Constraint, Formulation, Quantity, followed, namespace
from clutchopt.optimise.verify import FEASIBILITY_TOL, ConstraintCheck, check_constraints, constraint_table

SAMPLES = 10_000
CONFIDENCE = 0.95  # of the failure probabilities' intervals
SEED = 20261123


# --- The derived formulations ----------------------------------------------------------------------------------------
def corner_name(quantity: str, constraint: str) -> str:
    return f"{quantity}@{constraint}"


START_UP = "start_up"  # the corner a [start_up] is designed at: where it binds (chance: of the quantiles)


def start_up_view(declared: dict, scattered: tuple[str, ...], follows: tuple = ()):
    """(quantities ``q@start_up``, the view that puts a [start_up] at them, the followers it moves): a start-up is
    designed at one corner of the scattered quantities, the defaults that follow one of them (``Case.follows``
    items) following it there."""
    moved = {name: rule for name, rule in follows if rule[0] in scattered}
    corner = tuple(replace(declared[q], name=corner_name(q, START_UP), section="scatter", default=None,
                           description=f"{q} where the start-up is designed") for q in scattered)

    def at_start_up(values: dict) -> dict:
        return followed({**values, **{q: values.get(corner_name(q, START_UP), values.get(q)) for q in scattered}},
                        moved)

    return corner, at_start_up, moved


def worst_case_formulation(base: Formulation, scattered: tuple[str, ...], names: tuple[str, ...],
                           declared: dict, follows: tuple = ()) -> Formulation:
    """``base`` with constraint ``names[i]`` evaluated where each scattered quantity q takes the value of the case
    quantity ``q@names[i]`` (its corner), a start-up at ``q@start_up``; objective and outputs at the nominal values.
    ``declared``: the case's quantities by name (a start-up's may scatter too); ``follows``: the case's defaults that
    follow another quantity (``Case.follows`` items), which follow a scattered one to its start-up corner."""
    start_up, at_start_up, moved = start_up_view(declared, scattered, follows)
    corners = tuple(replace(declared[q], name=corner_name(q, c), section="scatter", default=None,
                            description=f"{q} at the worst corner of {c}") for c in names for q in scattered)

    def constraints(x, p):
        out = []
        for i, name in enumerate(names):
            at_corner = SimpleNamespace(**{**vars(p), **{q: getattr(p, corner_name(q, name)) for q in scattered}})
            out.append(base.constraints(x, at_corner)[i])
        return out

    return replace(base, quantities=base.quantities + corners + start_up, constraints=constraints,
                   variant=f"{base.variant} worst case over {', '.join(scattered)}".strip()
                   + (f" ({', '.join(moved)} following)" if moved else ""), start_up_view=at_start_up)


def mean_name(quantity: str) -> str:
    return f"{quantity}~mean"


def sd_name(quantity: str) -> str:
    return f"{quantity}~sd"


CHANCE_Z = "chance_z"


def chance_formulation(base: Formulation, scattered: tuple[str, ...], declared: dict,
                       follows: tuple = ()) -> Formulation:
    """``base`` at the scattered quantities' means, each constraint backed off by z sigma_h (to first order); a
    start-up at ``q@start_up`` (its quantile corner, :func:`start_up_corner`).
    ``declared``: the case's quantities by name (a start-up's scatter only where the formulation uses them)."""
    start_up, at_start_up, _ = start_up_view(declared, scattered, follows)
    own = [q.name for q in base.quantities]
    extra = tuple(replace(declared[q], name=mean_name(q), section="scatter", default=None, description=f"mean of {q}")
                  for q in scattered)
    extra += tuple(replace(declared[q], name=sd_name(q), section="scatter", default=None, above=None, at_least=0,
                           below=None, at_most=None, description=f"standard deviation of {q}") for q in scattered)
    extra += (Quantity(CHANCE_Z, "", "normal quantile of the target probability", "z", "scatter", None),)
    gradient = _violation_gradient(base)

    def constraints(x, p):
        mean = SimpleNamespace(**{**vars(p), **{q: getattr(p, mean_name(q)) for q in scattered}})
        nominal = base.constraints(x, mean)
        symbolic = is_symbolic(*vars(p).values())
        if not symbolic:  # float64 check: CasADi's derivatives evaluated at this point
            matrix = gradient(x, mean)
        out = []
        for row, c in enumerate(nominal):
            violation = c.normalised()
            terms = []
            for q in scattered:
                sd = getattr(p, sd_name(q))
                if q not in own:  # a start-up's quantity: the formulation's constraints do not depend on it
                    continue
                if symbolic:
                    slope = ca.jacobian(ca.SX(violation), getattr(mean, q))
                else:
                    slope = matrix[row, own.index(q)]
                terms.append((slope * sd) ** 2)
            sigma = (sum(terms) + 1e-24) ** 0.5
            shift = p.chance_z * sigma * (c.limit if c.scale is None else c.scale)
            value = c.value + shift if c.sense == "<=" else c.value - shift
            out.append(Constraint(c.name, c.equation, value, c.limit, c.sense, c.unit, c.scale,
                                  f"{c.description}, backed off by z sigma", c.constant_acceleration))
        return out

    return replace(base, quantities=base.quantities + extra + start_up, constraints=constraints,
                   variant=f"{base.variant} chance over {', '.join(scattered)}".strip(), start_up_view=at_start_up)


def _violation_gradient(base: Formulation):
    """(x, p) -> d(normalised violation of each constraint) / d(case quantity), by CasADi, evaluated in float64."""
    x_sym = ca.SX.sym("x", len(base.variables))
    p_sym = ca.SX.sym("p", len(base.quantities))
    x = namespace({v.name: x_sym[i] for i, v in enumerate(base.variables)})
    p = namespace({q.name: p_sym[j] for j, q in enumerate(base.quantities)})
    h = ca.vertcat(*[ca.SX(c.normalised()) for c in base.constraints(x, p)])
    function = ca.Function("dh_dp", [x_sym, p_sym], [ca.jacobian(h, p_sym)])

    def evaluate(x_values, p_values) -> np.ndarray:
        xs = [float(getattr(x_values, v.name)) for v in base.variables]
        ps = [float(getattr(p_values, q.name, math.nan)) for q in base.quantities]
        return np.array(function(xs, ps))

    return evaluate


# --- Corners, samples, sensitivities at a design (float64, vectorised) ------------------------------------------
def at_values(params: SimpleNamespace, values: dict) -> SimpleNamespace:
    return SimpleNamespace(**{**vars(params), **values})


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
    constraints = formulation.constraints(namespace(design), at_values(params, table))
    margins = _margins(constraints, 2 ** len(scatter))
    worst = np.nanargmin(np.where(np.isnan(margins), -np.inf, margins), axis=1)
    return ({c.name: {q: float(values[i]) for q, values in table.items()} for c, i in zip(constraints, worst)},
            constraints)


def failure_probabilities(formulation: Formulation, design: dict, params: SimpleNamespace, scatter,
                          samples: int = SAMPLES, seed: int = SEED) -> dict[str, list[float]]:
    """Monte Carlo: each constraint's failure probability (relative margin below -FEASIBILITY_TOL) with its
    Clopper-Pearson interval."""
    rng = np.random.default_rng(seed)
    drawn = {s.name: s.sample(rng, samples) for s in scatter}
    constraints = formulation.constraints(namespace(design), at_values(params, drawn))
    margins = _margins(constraints, samples)
    # active constraints sit at 0 +- round-off
    return {c.name: clopper_pearson(int(np.count_nonzero(~(row >= -FEASIBILITY_TOL))), samples)
            for c, row in zip(constraints, margins)}


def clopper_pearson(failed: int, count: int) -> list[float]:
    """[failed / count, low, high]: a failure frequency and its CONFIDENCE Clopper-Pearson interval."""
    from scipy.stats import beta

    alpha = 1.0 - CONFIDENCE
    low = float(beta.ppf(alpha / 2, failed, count - failed + 1)) if failed else 0.0
    high = float(beta.ppf(1 - alpha / 2, failed + 1, count - failed)) if failed < count else 1.0
    return [failed / count, low, high]


def tornado(formulation: Formulation, design: dict, params: SimpleNamespace, scatter) -> dict[str, dict[str, float]]:
    """How much each scattered quantity moves each constraint's relative margin over its range (high - low),
    the others at their nominal values: the bars of a tornado chart."""
    bars: dict[str, dict[str, float]] = {}
    for s in scatter:
        ends = formulation.constraints(namespace(design), at_values(params, {s.name: np.array([s.low, s.high])}))
        for c, (low, high) in zip(ends, _margins(ends, 2)):
            bars.setdefault(c.name, {})[s.name] = float(high - low)
    return bars


def corner_checks(formulation: Formulation, design: dict, params: SimpleNamespace, scatter) -> list[ConstraintCheck]:
    """Every constraint at every corner, each reported at its worst."""
    return check_constraints(formulation.constraints(namespace(design), at_values(params, corner_table(scatter))))
