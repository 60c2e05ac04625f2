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
- A ``[start_up]`` is designed at one corner, where its simulated figures bind: of the ends of the ranges (worst
  case) or of the quantiles (chance), re-solved until the corner settles; then simulated at every such corner
  (each start-up limit at its worst) and by ``starts`` simulated starts of Monte Carlo.
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
from clutchopt.model import Constraint, Formulation, Quantity, followed, namespace
from clutchopt.optimise.problem import problem_for
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.optimise.verify import (
    DESIGN_STATUSES,
    FEASIBILITY_TOL,
    ConstraintCheck,
    check_constraints,
    constraint_table,
)
from clutchopt.scatter import Scatter, _within
from clutchopt.start_up.drive import Structure

WORST_CASE = "worst-case"
CHANCE = "chance"
SAMPLES = 10_000
MAX_SAMPLES = 1_000_000  # vectorised in float64: about 100 MB for the widest formulation
CONFIDENCE = 0.95  # of the failure probabilities' intervals
CORNER_STEPS = 8  # re-solves while the worst corners move
SEED = 20261123
START_SAMPLES = 200  # simulated starts of a start-up's Monte Carlo (about 30 ms of CPU each)
MAX_STARTS = 100_000
START_RTOL = 1e-9  # of the simulated starts: far inside a start-up's tolerance (1e-6)
MAX_START_CORNERS = 4  # scattered quantities up to which a start-up is simulated at all 2^n corners


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
def _at(params: SimpleNamespace, values: dict) -> SimpleNamespace:
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
    constraints = formulation.constraints(namespace(design), _at(params, table))
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
    constraints = formulation.constraints(namespace(design), _at(params, drawn))
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
    corners: dict[str, dict[str, float]] = field(default_factory=dict)  # constraint (worst case), start_up -> corner
    formulation: Formulation | None = None  # the mode's, as solved nominally: what corners and samples evaluate
    status: str = "optimal"
    diagnosis: str | None = None
    settled: bool = True  # the corners (a start-up's too) stopped moving
    start_up_points: list[dict[str, float]] = field(default_factory=list)  # where the start-up was simulated
    start_up_samples: int = 0  # simulated starts of the Monte Carlo
    start_up_failure: dict[str, list[float]] = field(default_factory=dict)  # start-up limit -> [p, low, high]
    verification: str = ""  # one line: what was verified, and how

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
            "verification": self.verification,
            "start_up_verification": {"corners": self.start_up_points, "simulations": self.start_up_samples,
                                      "failure_probability": self.start_up_failure} if self.start_up_points else None,
        }


_DERIVED: dict[tuple, Formulation] = {}


def _derived(kind: str, base: Formulation, case: Case, names: tuple[str, ...]) -> Formulation:
    scattered = tuple(s.name for s in case.scatter)
    follows = tuple(sorted(case.follows.items()))
    key = (kind, base.coupling, base.mode, base.variant, scattered, names, case.start_up is not None, follows)
    if key not in _DERIVED:
        declared = {q.name: q for q in case.quantities}
        _DERIVED[key] = (worst_case_formulation(base, scattered, names, declared, follows) if kind == WORST_CASE
                         else chance_formulation(base, scattered, declared, follows))
    return _DERIVED[key]


# --- A start-up under scatter: designed at one corner, simulated at every corner and by Monte Carlo -------------------
def quantile(s: Scatter, probability: float, quantity: Quantity) -> float:
    """The value a scattered quantity stays below with ``probability``: a range uniform over it, a normal
    distribution cut where the quantity's valid range ends."""
    from scipy.special import ndtri

    if s.kind == "normal":
        return _within(quantity, s.mean + s.sd * float(ndtri(probability)))
    return s.low + probability * (s.high - s.low)


def start_up_ends(case: Case, mode: str, design: dict, scatter, target: float | None = None) -> dict:
    """Quantity -> (its value at the corner where the design's start-up binds, the other): the ends of its range or,
    with a ``target`` P (chance), its quantiles P_k and 1 - P_k, P_k = P^(1/k) for the k quantities that move the
    start at all (Sidak: start-up figures monotone in each of k independent quantities are worse than at every
    corner of their P_k quantiles only when one of them lies beyond its quantile, with probability
    1 - P_k^k = 1 - P). The binding corner: of all 2^k corners (up to MAX_START_CORNERS quantities), the one where
    the start-up's smallest relative margin is smallest; with more, each quantity at the end where the start takes
    longer, the others nominal (no lock-up counts as longest)."""
    alone = ({s.name: simulated_start_ups(case, mode, design, [{s.name: s.low}, {s.name: s.high}]) for s in scatter}
             if target is not None or len(scatter) > MAX_START_CORNERS else {})
    ends = {s.name: (s.low, s.high) for s in scatter}
    if target is not None:
        moving = sum([c.value for c in low] != [c.value for c in high] for low, high in alone.values())
        share = target ** (1.0 / max(1, moving))
        declared = {q.name: q for q in case.quantities}
        ends = {s.name: (quantile(s, 1.0 - share, declared[s.name]), quantile(s, share, declared[s.name]))
                for s in scatter}
    if len(scatter) <= MAX_START_CORNERS:
        points = _points(corner_table(scatter, ends))
        margins = [min(-math.inf if math.isnan(c.margin) else c.margin for c in run)
                   for run in simulated_start_ups(case, mode, design, points)]
        binding = points[int(np.argmin(margins))]
    else:
        binding = {q: low if _start_time(alone[q][0]) > _start_time(alone[q][1]) else high
                   for q, (low, high) in ends.items()}
    return {q: (binding[q], low if binding[q] == high else high) for q, (low, high) in ends.items()}


def _start_time(run: list[ConstraintCheck]) -> float:
    return next(c.value for c in run if c.name == "start_time")


def _points(table: dict[str, np.ndarray]) -> list[dict[str, float]]:
    """The corners of a corner table, one dict each."""
    return [{q: float(values[i]) for q, values in table.items()} for i in range(len(next(iter(table.values()))))]


def start_up_corner(case: Case, mode: str, design: dict, scatter, target: float | None = None) -> dict[str, float]:
    """The corner a start-up is designed at, where it binds (:func:`start_up_ends`: of the ranges, or with a
    ``target`` of the quantiles)."""
    return {q: slow for q, (slow, _) in start_up_ends(case, mode, design, scatter, target).items()}


def simulated_start_ups(case: Case, mode: str, design: dict, points: list[dict]) -> list[list[ConstraintCheck]]:
    """Every start-up limit of the case (start time, friction work, temperature rise, engagement and lock-up
    speeds, ...) checked with the design's start simulated at each point (scattered quantity -> value, the defaults
    that follow one following it): a list of checks per point, in one order."""
    from clutchopt.start_up.drive import Drive, named_constraints
    from clutchopt.start_up.simulation import run_start_up, start_up_model

    law = get_coupling(case.coupling).formulation(mode).speed_law
    runs = []
    for point in points:
        at = case.with_values(**point)
        structure = Structure.of(at)
        result = run_start_up(start_up_model(at, mode, design, rtol=START_RTOL))
        head = result.headline
        figures = SimpleNamespace(
            start_time=head["start_time"], friction_work=head["friction_work"], lock_up_speed=head["lock_up_speed"],
            temperatures=head.get("temperature_rise", 0.0),
            stresses=result.history["stress"].to_numpy() if structure.elastic and head["locks_up"] else math.inf)
        drive = Drive(structure, law, namespace(design), at.params())
        runs.append(check_constraints(named_constraints(structure, drive, figures), structure.spec.tolerance))
    return runs


def start_up_checks(case: Case, mode: str, design: dict, points: list[dict]) -> list[ConstraintCheck]:
    """The start-up's limits simulated at each point, each reported at its worst."""
    return [min(column, key=lambda c: -math.inf if math.isnan(c.margin) else c.margin)
            for column in zip(*simulated_start_ups(case, mode, design, points))]


def start_up_failures(case: Case, mode: str, design: dict, scatter, starts: int = START_SAMPLES,
                      seed: int = SEED) -> dict[str, list[float]]:
    """Monte Carlo of the simulated start: ``starts`` draws of the distributions (cut where each quantity's valid
    range ends), each start-up limit's failure probability with its Clopper-Pearson interval."""
    rng = np.random.default_rng(seed)
    declared = {q.name: q for q in case.quantities}
    drawn = {s.name: s.sample(rng, starts) for s in scatter}
    points = [{q: _within(declared[q], float(values[i])) for q, values in drawn.items()} for i in range(starts)]
    return {column[0].name: clopper_pearson(sum(not c.feasible for c in column), starts)
            for column in zip(*simulated_start_ups(case, mode, design, points))}


# --- Solving ------------------------------------------------------------------------------------------------------
def solve_robust(case: Case, method: str, target: float | None = None, mode: str | None = None,
                 objective: str | None = None, options: SolverOptions = SolverOptions(),
                 samples: int = SAMPLES, starts: int = START_SAMPLES, base: Formulation | None = None) -> RobustResult:
    """The robust design of a case with a [scatter] section, beside its nominal design, both checked by Monte Carlo
    (``samples``). A [start_up] is designed at its corner (worst case: of the ranges; chance: of the quantiles),
    re-solved until the corner settles, then simulated at every such corner and by ``starts`` Monte Carlo starts.
    ``base``: the formulation to make robust, if not the mode's own (a Pareto point's, with its cost cap)."""
    if not case.scatter:
        raise InputError("--robust", "the case has no [scatter] section: say which quantities scatter and how")
    base = base or get_coupling(case.coupling).formulation(mode or case.options.get("mode"))
    objective = objective or case.options.get("objective", "mass")
    structure = Structure.of(case) if case.start_up is not None else None
    shown = problem_for(base, objective, options, structure).formulation  # with the start-up's, if any
    nominal = problem_for(base, objective, options, structure).solve(case)
    params = case.params()
    names = tuple(c.name for c in base.constraints(namespace(nominal.design), params))
    if method == WORST_CASE:
        derived, fixed = _derived(WORST_CASE, base, case, names), {}
    else:
        from scipy.special import ndtri

        derived = _derived(CHANCE, base, case, names)
        fixed = {CHANCE_Z: float(ndtri(target)), **{mean_name(s.name): s.mean for s in case.scatter},
                 **{sd_name(s.name): s.sd for s in case.scatter}}

    def corners_at(design: dict) -> tuple[dict, dict]:
        """Each constraint's worst corner (worst case) and the start-up's, and the start-up's ends there."""
        corners = worst_corners(shown, design, params, case.scatter)[0] if method == WORST_CASE else {}
        ends = start_up_ends(case, base.mode, design, case.scatter, target) if structure else {}
        if ends:
            corners[START_UP] = {q: slow for q, (slow, _) in ends.items()}
        return corners, ends

    problem = problem_for(derived, objective, options, structure)
    corners, ends = corners_at(nominal.design)
    solution, settled = None, False
    for _ in range(CORNER_STEPS):
        values = {**fixed, **{corner_name(q, c): v for c, corner in corners.items() for q, v in corner.items()}}
        solved = replace(case, values={**case.values, **values})  # NLP parameters, not case quantities
        solution = problem.solve(solved, warm=solution) if solution else problem.solve(solved, start=nominal.design)
        if solution.status not in DESIGN_STATUSES:
            break
        moved, ends = corners_at(solution.design)
        settled, corners = moved == corners, moved
        if settled:
            break
    if method == WORST_CASE:
        checks = corner_checks(shown, solution.design, params, case.scatter)
        nominal_checks = corner_checks(shown, nominal.design, params, case.scatter)
    else:
        kept = {c.name for c in shown.constraints(namespace(nominal.design), params)}
        checks = [c for c in solution.constraints if c.name in kept]  # backed off
        nominal_checks = [c for c in check_constraints(derived.constraints(namespace(nominal.design),
                                                                           _at(params, values))) if c.name in kept]
    failure = failure_probabilities(shown, solution.design, params, case.scatter, samples)
    nominal_failure = failure_probabilities(shown, nominal.design, params, case.scatter, samples)
    result = RobustResult(method, target, solution, nominal, checks, nominal_checks, samples, failure,
                          nominal_failure, tornado(shown, solution.design, params, case.scatter), corners, shown,
                          settled=settled)
    if structure and solution.status in DESIGN_STATUSES:
        result.start_up_points = (_points(corner_table(case.scatter, ends)) if len(case.scatter) <= MAX_START_CORNERS
                                  else [corners[START_UP]])
        result.checks += start_up_checks(case, base.mode, solution.design, result.start_up_points)
        result.nominal_checks += start_up_checks(case, base.mode, nominal.design, result.start_up_points)
        result.start_up_samples = starts
        result.start_up_failure = start_up_failures(case, base.mode, solution.design, case.scatter, starts)
    result.status, result.diagnosis = verdict(result)
    result.solution = replace(solution, status=result.status, diagnosis=result.diagnosis)
    result.verification = verification(result, case)
    return result


def corner_checks(formulation: Formulation, design: dict, params: SimpleNamespace, scatter) -> list[ConstraintCheck]:
    """Every constraint at every corner, each reported at its worst."""
    return check_constraints(formulation.constraints(namespace(design), _at(params, corner_table(scatter))))


def verdict(result: RobustResult) -> tuple[str, str | None]:
    """(status, diagnosis): ``optimal`` only when the robust solve is, its corners settled, every check holds (at
    its worst corner, backed off, a start-up's at its worst simulated corner) and, for a chance design, no Monte
    Carlo interval (of the constraints, of the simulated starts) lies above 1 - P."""
    solution = result.solution
    if solution.status != "optimal":
        return solution.status, solution.diagnosis
    failing = [c for c in result.checks if not c.feasible]
    if failing or not result.settled:
        worst = min(failing or result.checks, key=lambda c: c.margin)
        return "unverified", (f"{worst.name} at its worst corner: margin {worst.margin:.3g} (relative)"
                              + ("" if result.settled else f"; the worst corners still moved after {CORNER_STEPS} "
                                                           "re-solves"))
    if result.method == WORST_CASE:
        return "optimal", None
    allowed = 1 - result.target

    def exceeded(failure: dict) -> list[str]:
        return [f"{name} fails with probability {p:.3g} ({low:.3g} to {high:.3g}) > {allowed:.3g}"
                for name, (p, low, high) in failure.items() if low > allowed]

    reasons = []
    if static := exceeded(result.failure):
        reasons.append("Monte Carlo: " + "; ".join(static) + " (first order is not enough here)")
    if start := exceeded(result.start_up_failure):
        reasons.append(f"{result.start_up_samples} simulated starts: " + "; ".join(start)
                       + " (the start is not monotone in the scatter: its quantile corner is not enough)")
    return ("unverified", "; ".join(reasons)) if reasons else ("optimal", None)


def verification(result: RobustResult, case: Case) -> str:
    """One line: what was verified and how (which corners, how many samples and simulated starts, the intervals)."""
    if result.status not in DESIGN_STATUSES:
        return f"not verified: there is no robust design ({result.status})"
    quantities = {q.name: q for q in case.quantities}
    n = len(case.scatter)
    parts = [f"constraints at all {2 ** n} corners of the ranges" if result.method == WORST_CASE else
             f"constraints backed off to first order for P = {result.target:g}",
             f"{result.samples} Monte Carlo samples: {_largest(result.failure)}"]
    if result.start_up_points:
        kind = "corner(s) of the ranges" if result.method == WORST_CASE else "quantile corner(s)"
        where = "; ".join(_shown(point, quantities) for point in result.start_up_points)
        missed = [c.name for c in result.checks if c.name in result.start_up_failure and not c.feasible]
        parts += [f"start-up designed at ({_shown(result.corners[START_UP], quantities)}), simulated at the "
                  f"{len(result.start_up_points)} {kind} ({where}): "
                  + (f"{', '.join(missed)} missed" if missed else "every limit met"),
                  f"{result.start_up_samples} simulated starts: {_largest(result.start_up_failure)}"]
        if result.method == CHANCE and max(high for _, _, high in result.start_up_failure.values()) > 1 - result.target:
            parts[-1] += (f" (too few to show P(fail) <= {1 - result.target:.3g} alone; the quantile corners show it "
                          "for a start monotone in each quantity)")
    return "verified: " + "; ".join(parts)


def _shown(values: dict, quantities: dict) -> str:
    return ", ".join(f"{q} {quantities[q].show(v, 5)}" for q, v in values.items())


def _largest(failure: dict[str, list[float]]) -> str:
    """The constraint most likely to fail, with its interval."""
    name, (p, low, high) = max(failure.items(), key=lambda item: (item[1][0], item[1][2]))
    return f"largest P(fail) {p:.3g} ({name}; {CONFIDENCE:.0%} interval {low:.2g} to {high:.2g})"
