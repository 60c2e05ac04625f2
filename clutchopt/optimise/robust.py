"""Designs that hold under scatter (a case's ``[scatter]`` section; docs/robust.md).

- ``worst-case``: every constraint holds at its own worst corner of the scattered quantities' ranges. The NLP is the
  mode's formulation with each constraint evaluated at a corner of its own (the corner values are NLP parameters,
  so a new assignment re-solves the built problem); the worst corner of each constraint is found by evaluating all
  2^n corners in float64 at the design (vectorised), the problem re-solved until the assignment settles, and the
  optimum checked at every corner.
- ``chance=P``: each constraint holds with probability P to first order: h(x, mu) + z_P sigma_h(x) <= 0, h the
  constraint's normalised violation, sigma_h^2 = sum_j (dh/dp_j sigma_j)^2 through CasADi's derivatives with
  respect to the case quantities (the back-off of the limit by the propagated standard deviation).
- Both are then checked by Monte Carlo: ``samples`` draws of the distributions (a range: uniform over it),
  evaluated vectorised in float64 by the formulation's own equations; each constraint's failure probability with
  its Clopper-Pearson interval, for the robust and for the nominal design.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass, field, replace
from types import SimpleNamespace

import casadi as ca
import numpy as np

from clutchopt.backend import is_symbolic
from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.formulations import get_coupling
from clutchopt.model import Constraint, Formulation, Quantity, namespace
from clutchopt.optimise.problem import problem_for, solve_case
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.optimise.start_up import Structure
from clutchopt.optimise.verify import FEASIBILITY_TOL, ConstraintCheck, check_constraints, constraint_table

WORST_CASE = "worst-case"
CHANCE = "chance"
SAMPLES = 10_000
MAX_SAMPLES = 1_000_000  # vectorised in float64: about 100 MB for the widest formulation
CONFIDENCE = 0.95  # of the failure probabilities' intervals
CORNER_STEPS = 8  # re-solves while the worst corners move
SEED = 20261123


def parse_method(text: str) -> tuple[str, float | None]:
    """``worst-case`` or ``chance=P`` (0.5 < P < 1) from the command line."""
    if text == WORST_CASE:
        return WORST_CASE, None
    name, sep, value = text.partition("=")
    if name == CHANCE and sep:
        try:
            probability = float(value)
        except ValueError:
            probability = math.nan
        if 0.5 < probability < 1.0 and probability <= 1.0 - 1e-9:
            return CHANCE, probability
        raise InputError("--robust", f"chance=P needs 0.5 < P <= 1 - 1e-9 (e.g. chance=0.999), got {value!r}")
    raise InputError("--robust", f"expected worst-case or chance=P (e.g. chance=0.999), got {text!r}")


# --- The derived formulations ----------------------------------------------------------------------------------------
def corner_name(quantity: str, constraint: str) -> str:
    return f"{quantity}@{constraint}"


START_UP = "start_up"  # the corner a [start_up] is designed at: where the start takes longest


def worst_case_formulation(base: Formulation, scattered: tuple[str, ...], names: tuple[str, ...],
                           declared: dict) -> Formulation:
    """``base`` with constraint ``names[i]`` evaluated where each scattered quantity q takes the value of the case
    quantity ``q@names[i]`` (its corner), a start-up at ``q@start_up``; objective and outputs at the nominal values.
    ``declared``: the case's quantities by name (a start-up's may scatter too)."""
    corners = tuple(replace(declared[q], name=corner_name(q, c), section="scatter", default=None,
                            description=f"{q} at the worst corner of {c}") for c in names + (START_UP,)
                    for q in scattered)

    def at_start_up(values: dict) -> dict:
        return {**values, **{q: values.get(corner_name(q, START_UP), values.get(q)) for q in scattered}}

    def constraints(x, p):
        out = []
        for i, name in enumerate(names):
            at_corner = SimpleNamespace(**{**vars(p), **{q: getattr(p, corner_name(q, name)) for q in scattered}})
            out.append(base.constraints(x, at_corner)[i])
        return out

    return replace(base, quantities=base.quantities + corners, constraints=constraints,
                   variant=f"worst case over {', '.join(scattered)}", start_up_view=at_start_up)


def mean_name(quantity: str) -> str:
    return f"{quantity}~mean"


def sd_name(quantity: str) -> str:
    return f"{quantity}~sd"


CHANCE_Z = "chance_z"


def chance_formulation(base: Formulation, scattered: tuple[str, ...], declared: dict) -> Formulation:
    """``base`` at the scattered quantities' means, each constraint backed off by z sigma_h (to first order).
    ``declared``: the case's quantities by name (a start-up's scatter only where the formulation uses them)."""
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

    return replace(base, quantities=base.quantities + extra, constraints=constraints,
                   variant=f"chance over {', '.join(scattered)}")


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
def _at(params: SimpleNamespace, values: dict) -> SimpleNamespace:
    return SimpleNamespace(**{**vars(params), **values})


def _margins(constraints: list[Constraint], count: int) -> np.ndarray:
    """Relative margins, one row per constraint, one column per point (broadcast)."""
    return constraint_table(constraints, count)[3]


def corner_table(scatter) -> dict[str, np.ndarray]:
    """Every corner of the ranges: quantity -> its value at each of the 2^n corners."""
    columns = np.array(list(itertools.product(*[(s.low, s.high) for s in scatter]))).T
    return {s.name: columns[i] for i, s in enumerate(scatter)}


def worst_corners(formulation: Formulation, design: dict, params: SimpleNamespace, scatter):
    """Each constraint's worst corner (quantity -> value) at ``design``, and the constraints at every corner."""
    table = corner_table(scatter)
    constraints = formulation.constraints(namespace(design), _at(params, table))
    margins = _margins(constraints, 2 ** len(scatter))
    worst = np.nanargmin(np.where(np.isnan(margins), -np.inf, margins), axis=1)
    return ({c.name: {q: float(values[i]) for q, values in table.items()} for c, i in zip(constraints, worst)},
            constraints)


def failure_probabilities(formulation: Formulation, design: dict, params: SimpleNamespace, scatter,
                          samples: int = SAMPLES, seed: int = SEED) -> dict[str, list[float]]:
    """Monte Carlo: each constraint's failure probability (relative margin below -FEASIBILITY_TOL) with its
    Clopper-Pearson interval."""
    from scipy.stats import beta

    rng = np.random.default_rng(seed)
    drawn = {s.name: s.sample(rng, samples) for s in scatter}
    constraints = formulation.constraints(namespace(design), _at(params, drawn))
    margins = _margins(constraints, samples)
    alpha = 1.0 - CONFIDENCE
    result = {}
    for c, row in zip(constraints, margins):
        failed = int(np.count_nonzero(~(row >= -FEASIBILITY_TOL)))  # active constraints sit at 0 +- round-off
        low = float(beta.ppf(alpha / 2, failed, samples - failed + 1)) if failed else 0.0
        high = float(beta.ppf(1 - alpha / 2, failed + 1, samples - failed)) if failed < samples else 1.0
        result[c.name] = [failed / samples, low, high]
    return result


def tornado(formulation: Formulation, design: dict, params: SimpleNamespace, scatter) -> dict[str, dict[str, float]]:
    """How much each scattered quantity moves each constraint's relative margin over its range (high - low),
    the others at their nominal values: the bars of a tornado chart."""
    bars: dict[str, dict[str, float]] = {}
    for s in scatter:
        ends = formulation.constraints(namespace(design), _at(params, {s.name: np.array([s.low, s.high])}))
        for c, (low, high) in zip(ends, _margins(ends, 2)):
            bars.setdefault(c.name, {})[s.name] = float(high - low)
    return bars


# --- Solving ------------------------------------------------------------------------------------------------------
@dataclass
class RobustResult:
    method: str  # worst-case | chance
    target: float | None  # chance: the probability each constraint holds with
    solution: Solution  # the robust design
    nominal: Solution  # the same mode and objective without scatter
    checks: list[ConstraintCheck]  # the robust design's constraints: each at its worst corner, or backed off
    nominal_checks: list[ConstraintCheck]  # the nominal design's, likewise
    samples: int
    failure: dict[str, list[float]]  # constraint -> [p, low, high], robust design
    nominal_failure: dict[str, list[float]]
    bars: dict[str, dict[str, float]]  # tornado: constraint -> quantity -> change of relative margin over its range
    corners: dict[str, dict[str, float]] = field(default_factory=dict)  # worst-case: constraint -> its corner
    formulation: Formulation | None = None  # the mode's, as solved nominally: what corners and samples evaluate
    status: str = "optimal"
    diagnosis: str | None = None

    def as_dict(self) -> dict:
        return {
            "method": self.method, "target": self.target, "status": self.status, "diagnosis": self.diagnosis,
            "samples": self.samples, "confidence": CONFIDENCE,
            "failure_probability": self.failure, "nominal_failure_probability": self.nominal_failure,
            "corners": self.corners,
            "checks": [c.as_dict() for c in self.checks],
            "nominal_checks": [c.as_dict() for c in self.nominal_checks],
            "nominal_objective": {"name": self.nominal.objective_name, "value": self.nominal.objective,
                                  "unit": self.nominal.objective_unit},
            "nominal_design": self.nominal.design,
            "margin_sensitivity": self.bars,
        }


_DERIVED: dict[tuple, Formulation] = {}


def _derived(kind: str, base: Formulation, case: Case, names: tuple[str, ...]) -> Formulation:
    scattered = tuple(s.name for s in case.scatter)
    key = (kind, base.coupling, base.mode, scattered, names, case.start_up is not None)
    if key not in _DERIVED:
        _DERIVED[key] = (worst_case_formulation(base, scattered, names, {q.name: q for q in case.quantities})
                         if kind == WORST_CASE else chance_formulation(base, scattered,
                                                                       {q.name: q for q in case.quantities}))
    return _DERIVED[key]


def start_up_corner(case: Case, mode: str, design: dict, scatter) -> dict[str, float]:
    """The corner a start-up is designed at: each scattered quantity at the end of its range where the simulated
    start, the others nominal, takes longer (no lock-up counts as longest)."""
    from clutchopt.simulate.design import run_start_up, start_up_model

    corner = {}
    for s in scatter:
        times = [run_start_up(start_up_model(replace(case, values={**case.values, s.name: end}), mode, design,
                                         rtol=1e-9)).headline["start_time"] for end in (s.low, s.high)]
        corner[s.name] = s.low if times[0] > times[1] else s.high
    return corner


def start_up_checks(case: Case, mode: str, design: dict, scatter, corner: dict) -> list[ConstraintCheck]:
    """The start-up's limits checked by simulation at every corner of the ranges (up to 16 corners; with more, at
    the start-up's corner), each at its worst."""
    from clutchopt.simulate.design import run_start_up, start_up_model

    table = corner_table(scatter) if len(scatter) <= 4 else {q: np.array([v]) for q, v in corner.items()}
    heads = [run_start_up(start_up_model(replace(case, values={**case.values, **{q: float(v[i]) for q, v in table.items()}}),
                                     mode, design)).headline for i in range(len(next(iter(table.values()))))]
    v, limits = case.values, case.start_up.limits
    figures = [("start_time", "max_start_time", "s"), ("friction_work", "max_friction_work", "kJ"),
               ("temperature_rise", "max_temperature_rise", "K")]
    return check_constraints([Constraint(name, "start-up, every corner", np.array([h.get(name, math.inf) for h in heads]),
                                         v[limit], "<=", unit, None, f"simulated at the {len(heads)} corner(s)")
                              for name, limit, unit in figures if limit in limits or limit == "max_start_time"],
                             case.start_up.tolerance)


def solve_robust(case: Case, method: str, target: float | None = None, mode: str | None = None,
                 objective: str | None = None, options: SolverOptions = SolverOptions(),
                 samples: int = SAMPLES) -> RobustResult:
    """The robust design of a case with a [scatter] section, beside its nominal design, both checked by Monte Carlo."""
    if not case.scatter:
        raise InputError("--robust", "the case has no [scatter] section: say which quantities scatter and how")
    coupling = get_coupling(case.coupling)
    base = coupling.formulation(mode or case.options.get("mode"))
    objective = objective or case.options.get("objective", "mass")
    structure = Structure.of(case) if case.start_up is not None else None
    shown = problem_for(base, objective, options, structure).formulation  # with the start-up's, if any
    nominal = solve_case(case, base.mode, objective, options)
    params = case.params()
    names = tuple(c.name for c in base.constraints(namespace(nominal.design), params))
    if method == WORST_CASE:
        problem = problem_for(_derived(WORST_CASE, base, case, names), objective, options, structure)
        corners, _ = worst_corners(shown, nominal.design, params, case.scatter)
        if case.start_up is not None:
            corners[START_UP] = start_up_corner(case, base.mode, nominal.design, case.scatter)
        solution, settled = None, False
        for _ in range(CORNER_STEPS):
            values = {corner_name(q, c): v for c, corner in corners.items() for q, v in corner.items()}
            solved = replace(case, values={**case.values, **values})
            solution = problem.solve(solved, warm=solution) if solution else problem.solve(solved, start=nominal.design)
            if solution.status not in ("optimal", "unverified"):
                break
            moved, _ = worst_corners(shown, solution.design, params, case.scatter)
            if case.start_up is not None:
                moved[START_UP] = start_up_corner(case, base.mode, solution.design, case.scatter)
            settled = moved == corners
            corners = moved
            if settled:
                break
        checks = corner_checks(shown, solution.design, params, case.scatter)
        nominal_checks = corner_checks(shown, nominal.design, params, case.scatter)
        if case.start_up is not None:
            checks += start_up_checks(case, base.mode, solution.design, case.scatter, corners[START_UP])
            nominal_checks += start_up_checks(case, base.mode, nominal.design, case.scatter, corners[START_UP])
    else:
        from scipy.special import ndtri

        derived = _derived(CHANCE, base, case, names)
        problem = problem_for(derived, objective, options, structure)
        values = {CHANCE_Z: float(ndtri(target)), **{mean_name(s.name): s.mean for s in case.scatter},
                  **{sd_name(s.name): s.sd for s in case.scatter}}
        solution = problem.solve(replace(case, values={**case.values, **values}), start=nominal.design)
        settled, corners = True, {}
        kept = {c.name for c in shown.constraints(namespace(nominal.design), params)}
        checks = list(solution.constraints)  # backed off; a start-up's at the means
        nominal_checks = [c for c in check_constraints(derived.constraints(namespace(nominal.design),
                                                                           _at(params, values))) if c.name in kept]
    failure = failure_probabilities(shown, solution.design, params, case.scatter, samples)
    nominal_failure = failure_probabilities(shown, nominal.design, params, case.scatter, samples)
    result = RobustResult(method, target, solution, nominal, checks, nominal_checks, samples, failure,
                          nominal_failure, tornado(shown, solution.design, params, case.scatter), corners, shown)
    result.status, result.diagnosis = _verdict(result, settled)
    result.solution = replace(solution, status=result.status, diagnosis=result.diagnosis)
    return result


def corner_checks(formulation: Formulation, design: dict, params: SimpleNamespace, scatter) -> list[ConstraintCheck]:
    """Every constraint at every corner, each reported at its worst."""
    return check_constraints(formulation.constraints(namespace(design), _at(params, corner_table(scatter))))


def _verdict(result: RobustResult, settled: bool) -> tuple[str, str | None]:
    solution = result.solution
    if solution.status != "optimal":
        return solution.status, solution.diagnosis
    if result.method == WORST_CASE:
        failing = [c for c in result.checks if not c.feasible]
        if failing or not settled:
            worst = min(result.checks, key=lambda c: c.margin)
            return "unverified", (f"{worst.name} at its worst corner: margin {worst.margin:.3g} (relative)"
                                  + ("" if settled else f"; the worst corners still moved after {CORNER_STEPS} "
                                                        "re-solves"))
        return "optimal", None
    exceeded = [f"{name} fails with probability {p:.3g} ({low:.3g} to {high:.3g}) > {1 - result.target:.3g}"
                for name, (p, low, high) in result.failure.items() if low > 1 - result.target]
    if exceeded:
        return "unverified", "Monte Carlo: " + "; ".join(exceeded) + " (first order is not enough here)"
    return "optimal", None
