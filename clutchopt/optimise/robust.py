"""Designs that hold under scatter (a case's ``[scatter]`` section; docs/robust.md).

- ``worst-case``: every constraint holds at its own worst corner of the scattered quantities' ranges. The NLP is the
  mode's formulation with each constraint evaluated at a corner of its own (the corner values are NLP parameters,
  so a new assignment re-solves the built problem); the worst corner of each constraint is found by evaluating all
  2^n corners in float64 at the design (vectorised), the problem re-solved until the assignment settles, and the
  optimum checked at every corner.
- ``chance=P``: each constraint fails with probability at most 1 - P, ``system_chance=P``: the design (any
  constraint) does. The same NLP with each constraint at its performance point (PMA: the values of the scattered
  quantities where its limit state is smallest on the sphere ||u|| = beta of the standard normal space, mapped
  exactly), re-solved until the points settle (SORA); then beta corrected per constraint, a 1-D root find, until
  importance sampling at the design point meets the target (FORM is exact only for a limit state linear in u).
  For the system the betas are NLP variables whose shares of 1 - P the NLP splits
  (``clutchopt.optimise.risk_allocation``).
- Both are then checked by Monte Carlo: ``samples`` draws of the distributions (a range: uniform over it),
  evaluated vectorised in float64 by the formulation's own equations; each constraint's failure probability with
  its Clopper-Pearson interval, for the robust and for the nominal design; and by FORM, SORM and importance sampling
  at each constraint's design point, and the system's (``robust_reliability``).
- A ``[start_up]``'s start is designed at one point, where its simulated figures bind, and each of its
  constraints evaluated at its own (a scattered limit at its strict end): worst case at the ends of the ranges,
  re-solved until the corners settle, then simulated at every corner (each start-up limit at its worst); chance at
  each limit's performance point on the beta-sphere, its limit state the simulated start
  (``start_up_reliability``), re-solved until the points settle, each limit checked at its own and its failure
  probability estimated by importance sampling of simulated starts at its design point; both by ``starts``
  simulated starts of Monte Carlo.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.formulations import get_coupling
from clutchopt.model import Formulation, namespace
from clutchopt.optimise.problem import problem_for
from clutchopt.optimise.chance_refutation import VERIFIED_FACTOR, MonteCarloAbove, monte_carlo_above
from clutchopt.optimise.reliability import IS_SAMPLES, Estimate, generalised_beta
from clutchopt.optimise.robust_models import (
    CONFIDENCE,
    SAMPLES,
    START_UP,
    at_values,
    corner_name,
    corner_checks,
    corner_table,
    failure_probabilities,
    tornado,
    worst_case_formulation,
    worst_corners,
)
from clutchopt.optimise.risk_allocation import (AIM_BELOW, SYSTEM_SAMPLES, RiskAllocation, allocation_formulation,
                                                beta_name)
from clutchopt.optimise.robust_reliability import (
    Reliability,
    performance_corners,
    performance_points,
    reliability_at,
    union_bound,
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
from clutchopt.optimise.start_up_reliability import StartUpPerformancePoints
from clutchopt.records import DESIGN_STATUSES
from clutchopt.optimise.verify import ConstraintCheck, check_constraints
from clutchopt.records import target_text
from clutchopt.start_up.drive import Structure

WORST_CASE = "worst-case"
CHANCE = "chance"
SYSTEM_CHANCE = "system_chance"
CHANCES = (CHANCE, SYSTEM_CHANCE)
BETA_STEPS = 12  # corrections of the chance design's betas until importance sampling meets the target
ACTIVE = 1e-6  # relative margin at its performance point below which a constraint shapes the design
SETTLED = 1e-7  # relative: a performance point that moves less has settled
MAX_SAMPLES = 1_000_000  # vectorised in float64: about 100 MB for the widest formulation
CORNER_STEPS = 8  # re-solves while the worst corners move
MONTE_CARLO = "Monte Carlo (Clopper-Pearson interval)"  # estimator of the samples' and simulated starts' [p, low, high]
MAX_STARTS = 100_000


def parse_method(text: str) -> tuple[str, float | None]:
    """``worst-case``, ``chance=P`` or ``system_chance=P`` (0.5 < P < 1) from the command line."""
    if text == WORST_CASE:
        return WORST_CASE, None
    name, sep, value = text.partition("=")
    if name in CHANCES and sep:
        try:
            probability = float(value)
        except ValueError:
            probability = math.nan
        if 0.5 < probability < 1.0 and probability <= 1.0 - 1e-9:
            return name, probability
        raise InputError("--robust", f"{name}=P needs 0.5 < P <= 1 - 1e-9 (e.g. {name}=0.999), got {value!r}")
    raise InputError("--robust", f"expected worst-case, chance=P or system_chance=P (e.g. chance=0.999), got "
                                 f"{text!r}")


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
    reliability: Reliability | None = None  # the robust design's constraints and system: FORM, SORM, importance
    nominal_reliability: Reliability | None = None  # sampling, design points; the nominal design's
    betas: dict[str, float] = field(default_factory=dict)  # chance: each constraint's beta of its performance point
    allocation: RiskAllocation | None = None  # system chance: how 1 - P was split between the constraints
    start_up_beta: float | None = None  # chance: the beta of the start-up limits' performance points
    start_up_share: float | None = None  # system chance: each moved start-up limit's share of 1 - P
    start_up_fallbacks: tuple[str, ...] = ()  # chance: start-up limits at their quantile corners (no settled point)

    def design_failure(self) -> Estimate:
        """P(the design fails: any constraint or start-up limit): the closed-form constraints' system (importance
        sampling), plus each start-up limit's estimate where the design has a start-up (a union bound: their overlap
        is not subtracted, so the sum is at or above the system's; the interval from the largest lower end to the
        sum of the upper ends)."""
        static = self.reliability.system
        limits = [c.best for name, c in self.reliability.constraints.items() if name in self.start_up_failure]
        if not limits:
            return static
        return union_bound([static, *limits],
                           f"the constraints' {static.estimator} plus each start-up limit's estimate (union bound)")

    def monte_carlo_above(self) -> tuple[list[MonteCarloAbove], list[MonteCarloAbove]]:
        """A chance design's Monte Carlo intervals wholly above 1 - P, of the constraints and of the simulated starts,
        each beside the more accurate estimate that decides it where there is one (``chance_refutation``)."""
        if self.target is None:
            return [], []
        allowed = 1 - self.target
        best = {name: c.best for name, c in self.reliability.constraints.items()} if self.reliability else {}
        return (monte_carlo_above(self.failure, self.samples, best, SYSTEM_SAMPLES if self.allocation else IS_SAMPLES,
                                  allowed),
                monte_carlo_above(self.start_up_failure, self.start_up_samples, best, self.start_up_samples, allowed))

    def as_dict(self) -> dict:
        return {
            "method": self.method, "target": self.target, "status": self.status, "diagnosis": self.diagnosis,
            "samples": self.samples, "confidence": CONFIDENCE,
            "failure_probability_estimator": MONTE_CARLO,
            "failure_probability": self.failure, "nominal_failure_probability": self.nominal_failure,
            "monte_carlo_above_target": [c.as_dict() for above in self.monte_carlo_above() for c in above],
            "corners": self.corners,
            "checks": [c.as_dict() for c in self.checks],
            "nominal_checks": [c.as_dict() for c in self.nominal_checks],
            "nominal_objective": {"name": self.nominal.objective_name, "value": self.nominal.objective,
                                  "unit": self.nominal.objective_unit},
            "nominal_design": self.nominal.design,
            "margin_sensitivity": self.bars,
            "verification": self.verification,
            "reliability": self.reliability.as_dict() if self.reliability else None,
            "nominal_reliability": self.nominal_reliability.as_dict() if self.nominal_reliability else None,
            "performance_point_beta": self.betas or None,
            "system_allocation": self.allocation.as_dict() if self.allocation else None,
            "system_failure_probability": self.design_failure().as_dict() if self.reliability else None,
            "start_up_verification": {"corners": self.start_up_points, "simulations": self.start_up_samples,
                                      "failure_probability": self.start_up_failure,
                                      "failure_probability_estimator": MONTE_CARLO,
                                      "performance_point_beta": self.start_up_beta,
                                      "share_of_target": self.start_up_share,
                                      "at_quantile_corners": list(self.start_up_fallbacks)}
            if self.start_up_points else None,
        }


_DERIVED: dict[tuple, Formulation] = {}


def _derived(base: Formulation, case: Case, names: tuple[str, ...], start_up_names: tuple[str, ...]) -> Formulation:
    """The mode's formulation with each constraint at a corner of its own (worst case: of the ranges; chance: its
    performance point), built once per scatter."""
    scattered = tuple(s.name for s in case.scatter)
    follows = tuple(sorted(case.follows.items()))
    key = (base.coupling, base.mode, base.variant, scattered, names, start_up_names, follows)
    if key not in _DERIVED:
        declared = {q.name: q for q in case.quantities}
        _DERIVED[key] = worst_case_formulation(base, scattered, names, declared, follows, start_up_names)
    return _DERIVED[key]


# --- Solving ------------------------------------------------------------------------------------------------------
def solve_robust(case: Case, method: str, target: float | None = None, mode: str | None = None,
                 objective: str | None = None, options: SolverOptions = SolverOptions(),
                 samples: int = SAMPLES, starts: int = START_SAMPLES, base: Formulation | None = None) -> RobustResult:
    """The robust design of a case with a [scatter] section, beside its nominal design, both checked by Monte Carlo
    (``samples``) and by the reliability methods (FORM, SORM, importance sampling; the system). Worst case: each
    constraint at its worst corner of the ranges; chance: at its performance point on the beta-sphere (PMA, SORA),
    beta corrected until importance sampling meets the target (:func:`_next_betas`). A [start_up] is designed at
    its corners (worst case: of the ranges; chance: each limit's performance point, the simulated start its limit
    state), re-solved until they settle, then simulated at every such point, by ``starts`` Monte Carlo starts and
    (chance) by importance sampling of ``starts`` simulated starts at each limit's design point.
    ``base``: the formulation to make robust, if not the mode's own (a Pareto point's, with its cost cap)."""
    if not case.scatter:
        raise InputError("--robust", "the case has no [scatter] section: say which quantities scatter and how")
    base = base or get_coupling(case.coupling).formulation(case.mode_of(mode))
    objective = case.objective_of(objective)
    structure = Structure.of(case) if case.start_up is not None else None
    shown = problem_for(base, objective, options, structure).formulation  # with the start-up's, if any
    nominal = problem_for(base, objective, options, structure).solve(case)
    params = case.params()
    names = tuple(c.name for c in base.constraints(namespace(nominal.design), params))
    chance = method in CHANCES
    # each constraint's failure probability to start from: 1 - P (chance), or an equal share of it (the system: the
    # NLP then chooses the split, clutchopt.optimise.risk_allocation)
    betas = (dict.fromkeys(names, generalised_beta((1.0 - target) / (len(names) if method == SYSTEM_CHANCE else 1)))
             if chance else {})
    allocation = None
    start_up_points = (StartUpPerformancePoints(case, base.mode, target, case.correlation) if structure and chance
                       else None)  # a start-up's limits at their performance points

    def corners_at(design: dict) -> tuple[dict, StartUpCorners | None]:
        """Each constraint's worst corner (worst case) or performance point (chance; the system's allocation
        aimed along them), and a start-up's ends, corners and bars there."""
        if method == WORST_CASE:
            corners = worst_corners(shown, design, params, case.scatter)[0]
        else:
            points = performance_points(shown, design, params, case.scatter, betas, case.correlation)
            corners = performance_corners(shown, design, params, case.scatter, betas, case.correlation, points)
            if allocation is not None:
                allocation.aim({name: points[name] for name in allocation.names})
        start_up = ((start_up_points.at(design) if start_up_points else
                     start_up_corners(case, base.mode, design, case.scatter, target)) if structure else None)
        return ({**corners, **start_up.corners}, start_up) if start_up else (corners, None)

    if method == SYSTEM_CHANCE:  # the constraints the scatter moves share 1 - P, as the NLP chooses
        points = performance_points(shown, nominal.design, params, case.scatter, betas, case.correlation)
        moved = {name: betas[name] for name in names if np.linalg.norm(points[name]) > 0}
        budget = (start_up_points.take_shares(nominal.design, len(moved), 1.0 - target) if start_up_points
                  else 1.0 - target)  # the start-up limits the scatter moves take their shares first
        allocation = RiskAllocation(budget, case.scatter, case.correlation, moved) if moved else None  # (none: the
        # scatter moves only the start-up's limits, which took their shares; review 30: a lever start-up case's
        # empty allocation, its budget 0, had divided by zero)
    corners, start_up = corners_at(nominal.design)
    start_up_names = tuple(name for name in corners if name not in names and name != START_UP)
    derived = _derived(base, case, names, start_up_names)
    if allocation is not None:
        derived = allocation_formulation(derived, base, case.scatter, names, allocation.names)
    problem = problem_for(derived, objective, options, structure)
    with_betas = (lambda design: {**design, **allocation.variables()}) if allocation else (lambda design: design)
    solution, settled, history = None, False, {name: [] for name in names}
    sampled = None  # (the solution the loop last sampled, its reliability)
    for _ in range(BETA_STEPS if chance else 1):
        for _ in range(CORNER_STEPS):
            values = {corner_name(q, c): v for c, corner in corners.items() for q, v in corner.items()}
            values.update(allocation.parameters() if allocation else {})
            solved = replace(case, values={**case.values, **values})  # NLP parameters, not case quantities
            solution = (problem.solve(solved, warm=solution) if solution else
                        problem.solve(solved, start=with_betas(nominal.design)))
            if solution.status not in DESIGN_STATUSES:
                break
            if allocation is not None:
                betas.update(allocation.read(solution.design))
            moved, start_up = corners_at(solution.design)
            settled, corners = _same(moved, corners), moved
            if settled:
                break
        if not chance or solution.status not in DESIGN_STATUSES or not settled:
            break
        reliability = reliability_at(shown, solution.design, params, case.scatter, case.correlation, names,
                                     SYSTEM_SAMPLES if allocation else None)
        sampled = solution, reliability
        if allocation is not None:
            if not allocation.step(reliability, {c.name: c.margin for c in solution.constraints}, ACTIVE):
                break
        elif not _next_betas(betas, history, reliability, solution, 1.0 - target):
            break
        corners, start_up = corners_at(solution.design)
    kept = {c.name for c in shown.constraints(namespace(nominal.design), params)}
    # the design's reliability: the loop's where it sampled the design it ended on (the same samples and seed)
    reliability = sampled[1] if sampled is not None and sampled[0] is solution else None
    if method == WORST_CASE:
        checks = corner_checks(shown, solution.design, params, case.scatter)
        nominal_checks = corner_checks(shown, nominal.design, params, case.scatter)
    else:  # each at its performance point
        checks = [c for c in solution.constraints if c.name in kept]
        nominal_checks = [c for c in check_constraints(derived.constraints(namespace(with_betas(nominal.design)),
                                                                           at_values(params, values))) if c.name in kept]
        solution = _without(solution, [beta_name(name) for name in allocation.names] if allocation else [])
    failure = failure_probabilities(shown, solution.design, params, case.scatter, samples,
                                    correlation=case.correlation)
    nominal_failure = failure_probabilities(shown, nominal.design, params, case.scatter, samples,
                                            correlation=case.correlation)
    result = RobustResult(method, target, solution, nominal, checks, nominal_checks, samples, failure,
                          nominal_failure, {**tornado(shown, solution.design, params, case.scatter),
                                            **(start_up.bars if start_up else {})}, corners, shown, settled=settled)
    if solution.status in DESIGN_STATUSES:
        result.reliability = reliability or reliability_at(shown, solution.design, params, case.scatter,
                                                           case.correlation, names,
                                                           SYSTEM_SAMPLES if allocation else None)
        result.nominal_reliability = reliability_at(shown, nominal.design, params, case.scatter, case.correlation,
                                                    names)
        result.betas = dict(betas)
        result.allocation = allocation
    if start_up_points and solution.status in DESIGN_STATUSES:  # each limit at its performance point
        fallbacks = sorted(start_up_points.fallbacks)
        quantile_points = _distinct([corners[name] for name in fallbacks])
        result.start_up_points = _distinct(start_up_points.distinct_points() + quantile_points)
        result.checks += start_up_points.checks() + [
            c for c in start_up_checks(case, base.mode, solution.design, quantile_points) if c.name in fallbacks]
        result.nominal_checks += start_up_checks(case, base.mode, nominal.design, result.start_up_points)
        result.reliability.constraints.update(start_up_points.reliability(starts))
        result.start_up_beta, result.start_up_fallbacks = start_up_points.beta, tuple(fallbacks)
        result.start_up_share = start_up_points.share
    elif structure and solution.status in DESIGN_STATUSES:
        result.start_up_points = (corner_points(corner_table(case.scatter, start_up.ends))
                                  if len(case.scatter) <= MAX_START_CORNERS
                                  else _distinct([corners[name] for name in (START_UP, *start_up_names)]))
        result.checks += start_up_checks(case, base.mode, solution.design, result.start_up_points)
        result.nominal_checks += start_up_checks(case, base.mode, nominal.design, result.start_up_points)
    if structure and solution.status in DESIGN_STATUSES:
        result.start_up_samples = starts
        result.start_up_failure = start_up_failures(case, base.mode, solution.design, case.scatter, starts)
    result.status, result.diagnosis = verdict(result)
    result.solution = replace(solution, status=result.status, diagnosis=result.diagnosis)
    result.verification = verification(result, case)
    return result


def _without(solution: Solution, variables: list[str]) -> Solution:
    """The solution without the allocation's beta variables: its design is the coupling's (the betas are the
    allocation's, ``RobustResult.allocation``)."""
    if not variables:
        return solution
    return replace(solution, design={k: v for k, v in solution.design.items() if k not in variables},
                   bounds={k: v for k, v in solution.bounds.items() if k not in variables},
                   design_units={k: v for k, v in solution.design_units.items() if k not in variables})


def _same(moved: dict, corners: dict) -> bool:
    """The corners (constraint -> quantity -> value) stopped moving: equal, a performance point to SETTLED."""
    return moved.keys() == corners.keys() and all(
        moved[c].keys() == corners[c].keys() and all(math.isclose(v, corners[c][q], rel_tol=SETTLED, abs_tol=1e-300)
                                                     for q, v in moved[c].items()) for c in moved)


def _next_betas(betas: dict[str, float], history: dict[str, list], reliability, solution, allowed: float) -> bool:
    """A step of the 1-D root find, per constraint, of the beta whose performance-point design meets the ``allowed``
    failure probability (1 - P) by importance sampling: the generalised index -Phi^-1(p) it reaches minus the one it should,
    zero by the secant method (common random numbers: the estimate is a smooth function of the design), aimed
    AIM_BELOW under it, until the allowed probability lies within the estimate's interval (FORM's beta is kept
    where importance sampling does not refute it: exact where the limit state is linear in u). Only an
    active constraint that depends on the scatter is corrected (an inactive one fails less than allowed whatever
    its beta). False when nothing moves."""
    margins = {c.name: c.margin for c in solution.constraints}
    shown = reliability.constraints
    movable = [name for name in betas if name in shown and shown[name].point.found
               and margins.get(name, 1.0) <= ACTIVE and shown[name].best.probability > 0]
    moved = False
    for name in movable:
        best = shown[name].best
        miss = generalised_beta(best.probability) - generalised_beta(allowed * (1 - AIM_BELOW))
        history[name].append((betas[name], miss))
        corrected = history[name][0][0] != betas[name]
        if (best.probability if corrected else best.low) <= allowed <= best.high:
            continue  # met: at or below once corrected; FORM's beta where sampling does not refute it (exact there)
        (b0, m0), (b1, m1) = history[name][-2:] if len(history[name]) > 1 else ((None, None), history[name][-1])
        betas[name] = b1 - m1 * (b1 - b0) / (m1 - m0) if b0 is not None and m1 != m0 else b1 - m1
        moved = True
    return moved


def _distinct(points: list[dict[str, float]]) -> list[dict[str, float]]:
    return [point for i, point in enumerate(points) if point not in points[:i]]


def verdict(result: RobustResult) -> tuple[str, str | None]:
    """(status, diagnosis): ``optimal`` only when the robust solve is, its corners settled, every check holds (at
    its worst corner, backed off, a start-up's at its worst simulated corner) and, for a chance design, no Monte
    Carlo interval (of the constraints, of the simulated starts) lies above 1 - P unless the more accurate estimate
    of the same probability decides (``chance_refutation``: importance sampling at the design point, in agreement
    with the Monte Carlo; it refuses where its own interval lies above 1 - P)."""
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
    reasons = []
    if result.reliability is not None:
        shown = ({"the system": result.design_failure()} if result.method == SYSTEM_CHANCE else
                 {name: c.best for name, c in result.reliability.constraints.items()})
        if missed := [f"{name} fails with probability {e.probability:.3g} ({e.low:.3g} to {e.high:.3g}, "
                      f"{e.estimator})" for name, e in shown.items()
                      if e.low > allowed or e.high > VERIFIED_FACTOR * allowed]:
            reasons.append(f"not shown within {VERIFIED_FACTOR:g} x {allowed:.3g}: " + "; ".join(missed))
    static, start = ([c.text(allowed) for c in above if c.refused] for above in result.monte_carlo_above())
    if static:
        reasons.append("Monte Carlo: " + "; ".join(static))
    if start:
        reasons.append(f"{result.start_up_samples} simulated starts: " + "; ".join(start)
                       + ("" if result.start_up_beta is not None else
                          " (the start is not monotone in the scatter: its quantile corner is not enough)"))
    return ("unverified", "; ".join(reasons)) if reasons else ("optimal", None)


def verification(result: RobustResult, case: Case) -> str:
    """One line: what was verified and how (which corners, how many samples and simulated starts, the intervals)."""
    if result.status not in DESIGN_STATUSES:
        return f"not verified: there is no robust design ({result.status})"
    quantities = {q.name: q for q in case.quantities}
    n = len(case.scatter)
    parts = [f"constraints at all {2 ** n} corners of the ranges" if result.method == WORST_CASE else
             f"constraints at their performance points for {result.method} P = {target_text(result.target)}, "
             + (result.allocation.claim() if result.allocation else "beta corrected by importance sampling"),
             f"{result.samples} Monte Carlo samples: {_largest(result.failure)}"]
    if result.reliability is not None:
        parts.append(f"importance sampling at the design points: {_largest_estimate(result, static=True)}, system "
                     f"{result.reliability.system.probability:.3g} ({result.reliability.system.low:.3g} to "
                     f"{result.reliability.system.high:.3g})")
    if result.method == SYSTEM_CHANCE and result.start_up_failure and result.reliability is not None:
        system = result.design_failure()
        share = result.start_up_share
        parts.append((f"each start-up limit the scatter moves designed for its share {share:.3g} of "
                      f"{1 - result.target:.3g}, " if share else "")
                     + f"the system with the start-up limits {system.probability:.3g} ({system.low:.3g} to "
                       f"{system.high:.3g}; {system.estimator})")
    if result.start_up_fallbacks:
        parts.append("start-up limits at their quantile corners (their performance point did not settle): "
                      + ", ".join(result.start_up_fallbacks))
    if result.start_up_points:
        by_points = result.start_up_beta is not None
        kind = ("point(s)" if by_points else
                "corner(s) of the ranges" if result.method == WORST_CASE else "quantile corner(s)")
        where = "; ".join(_shown(point, quantities) for point in result.start_up_points)
        missed = [c.name for c in result.checks if c.name in result.start_up_failure and not c.feasible]
        parts += [(f"start-up designed at its performance point ({_shown(result.corners[START_UP], quantities)}; "
                   f"beta {result.start_up_beta:.4g}), each limit simulated at its own, the "
                   if by_points else
                   f"start-up designed at ({_shown(result.corners[START_UP], quantities)}), simulated at the ")
                  + f"{len(result.start_up_points)} {kind} ({where}): "
                  + (f"{', '.join(missed)} missed" if missed else "every limit met"),
                  *([f"importance sampling of {result.start_up_samples} simulated starts at the start-up's design "
                     f"points: {_largest_estimate(result, static=False)}"] if by_points else []),
                  f"{result.start_up_samples} simulated starts: {_largest(result.start_up_failure)}"]
        if result.method == CHANCE and max(high for _, _, high in result.start_up_failure.values()) > 1 - result.target:
            parts[-1] += (f" (too few to show P(fail) <= {1 - result.target:.3g} alone; importance sampling shows it)"
                          if by_points else f" (too few to show P(fail) <= {1 - result.target:.3g} alone; the "
                                            "quantile corners show it for a start monotone in each quantity)")
    parts += [c.text(1 - result.target) for above in result.monte_carlo_above() for c in above if not c.refused]
    return "verified: " + "; ".join(parts)


def _largest_estimate(result: RobustResult, static: bool) -> str:
    """The constraint (``static``) or start-up limit most likely to fail by its estimate, with its interval."""
    shown = [(name, c.best) for name, c in result.reliability.constraints.items()
             if (name in result.start_up_failure) != static]
    if not shown:
        return "none sampled"
    name, best = max(shown, key=lambda item: item[1].probability)
    return (f"largest P(fail) {best.probability:.3g} ({name}; {best.estimator}, 95% interval {best.low:.3g} to "
            f"{best.high:.3g})" if not static else
            f"largest P(fail) {best.probability:.3g} ({name}; 95% interval {best.low:.3g} to {best.high:.3g})")


def _shown(values: dict, quantities: dict) -> str:
    return ", ".join(f"{q} {quantities[q].show(v, 5)}" for q, v in values.items())


def _largest(failure: dict[str, list[float]]) -> str:
    """The constraint most likely to fail, with its interval."""
    name, (p, low, high) = max(failure.items(), key=lambda item: (item[1][0], item[1][2]))
    return f"largest P(fail) {p:.3g} ({name}; {CONFIDENCE:.0%} interval {low:.2g} to {high:.2g})"
