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
- A ``[start_up]``'s start is designed at one corner, where its simulated figures bind, and each of its
  constraints evaluated at its own (a scattered limit at its strict end): of the ends of the ranges (worst case) or
  of the quantiles (chance), re-solved until the corners settle; then simulated at every such corner (each start-up
  limit at its worst) and by ``starts`` simulated starts of Monte Carlo.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.formulations import get_coupling
from clutchopt.model import Formulation, namespace
from clutchopt.optimise.problem import problem_for
from clutchopt.optimise.robust_models import (
    CHANCE_Z,
    CONFIDENCE,
    SAMPLES,
    START_UP,
    at_values,
    chance_formulation,
    corner_name,
    corner_checks,
    corner_table,
    failure_probabilities,
    mean_name,
    sd_name,
    tornado,
    worst_case_formulation,
    worst_corners,
)
from clutchopt.optimise.robust_start_up import (
    MAX_START_CORNERS,
    START_SAMPLES,
    StartUpCorners,
    corner_points,
    start_up_checks,
    start_up_corners,
    start_up_failures,
)
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.optimise.verify import DESIGN_STATUSES, ConstraintCheck, check_constraints
from clutchopt.start_up.drive import Structure

WORST_CASE = "worst-case"
CHANCE = "chance"
MAX_SAMPLES = 1_000_000  # vectorised in float64: about 100 MB for the widest formulation
CORNER_STEPS = 8  # re-solves while the worst corners move
MAX_STARTS = 100_000


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


def _derived(kind: str, base: Formulation, case: Case, names: tuple[str, ...],
             start_up_names: tuple[str, ...]) -> Formulation:
    scattered = tuple(s.name for s in case.scatter)
    follows = tuple(sorted(case.follows.items()))
    key = (kind, base.coupling, base.mode, base.variant, scattered, names, start_up_names, follows)
    if key not in _DERIVED:
        declared = {q.name: q for q in case.quantities}
        _DERIVED[key] = (worst_case_formulation(base, scattered, names, declared, follows, start_up_names)
                         if kind == WORST_CASE else chance_formulation(base, scattered, declared, follows,
                                                                       start_up_names))
    return _DERIVED[key]


# --- Solving ------------------------------------------------------------------------------------------------------
def solve_robust(case: Case, method: str, target: float | None = None, mode: str | None = None,
                 objective: str | None = None, options: SolverOptions = SolverOptions(),
                 samples: int = SAMPLES, starts: int = START_SAMPLES, base: Formulation | None = None) -> RobustResult:
    """The robust design of a case with a [scatter] section, beside its nominal design, both checked by Monte Carlo
    (``samples``). A [start_up] is designed at its corners (worst case: of the ranges; chance: of the quantiles),
    re-solved until they settle, then simulated at every such corner and by ``starts`` Monte Carlo starts.
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

    def corners_at(design: dict) -> tuple[dict, StartUpCorners | None]:
        """Each constraint's worst corner (worst case; a start-up's constraints' and its start's, both methods),
        and the start-up's ends, corners and bars there."""
        corners = worst_corners(shown, design, params, case.scatter)[0] if method == WORST_CASE else {}
        start_up = start_up_corners(case, base.mode, design, case.scatter, target) if structure else None
        return ({**corners, **start_up.corners}, start_up) if start_up else (corners, None)

    corners, start_up = corners_at(nominal.design)
    start_up_names = tuple(name for name in corners if name not in names and name != START_UP)
    derived = _derived(method, base, case, names, start_up_names)
    fixed = {}
    if method == CHANCE:
        from scipy.special import ndtri

        fixed = {CHANCE_Z: float(ndtri(target)), **{mean_name(s.name): s.mean for s in case.scatter},
                 **{sd_name(s.name): s.sd for s in case.scatter}}
    problem = problem_for(derived, objective, options, structure)
    solution, settled = None, False
    for _ in range(CORNER_STEPS):
        values = {**fixed, **{corner_name(q, c): v for c, corner in corners.items() for q, v in corner.items()}}
        solved = replace(case, values={**case.values, **values})  # NLP parameters, not case quantities
        solution = problem.solve(solved, warm=solution) if solution else problem.solve(solved, start=nominal.design)
        if solution.status not in DESIGN_STATUSES:
            break
        moved, start_up = corners_at(solution.design)
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
                                                                           at_values(params, values))) if c.name in kept]
    failure = failure_probabilities(shown, solution.design, params, case.scatter, samples,
                                    correlation=case.correlation)
    nominal_failure = failure_probabilities(shown, nominal.design, params, case.scatter, samples,
                                            correlation=case.correlation)
    result = RobustResult(method, target, solution, nominal, checks, nominal_checks, samples, failure,
                          nominal_failure, {**tornado(shown, solution.design, params, case.scatter),
                                            **(start_up.bars if start_up else {})}, corners, shown, settled=settled)
    if structure and solution.status in DESIGN_STATUSES:
        result.start_up_points = (corner_points(corner_table(case.scatter, start_up.ends))
                                  if len(case.scatter) <= MAX_START_CORNERS
                                  else _distinct([corners[name] for name in (START_UP, *start_up_names)]))
        result.checks += start_up_checks(case, base.mode, solution.design, result.start_up_points)
        result.nominal_checks += start_up_checks(case, base.mode, nominal.design, result.start_up_points)
        result.start_up_samples = starts
        result.start_up_failure = start_up_failures(case, base.mode, solution.design, case.scatter, starts)
    result.status, result.diagnosis = verdict(result)
    result.solution = replace(solution, status=result.status, diagnosis=result.diagnosis)
    result.verification = verification(result, case)
    return result


def _distinct(points: list[dict[str, float]]) -> list[dict[str, float]]:
    return [point for i, point in enumerate(points) if point not in points[:i]]


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
