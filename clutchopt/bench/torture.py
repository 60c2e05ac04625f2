"""Hard cases, generated systematically over every registered coupling, and the judge of their outcomes.

Each :class:`TortureCase` runs to a :class:`Verdict`; a case passes when it ends in
- ``optimal``: the optimum re-checked in float64 (worst relative violation <= 1e-8), no better than the closed
  form (a relaxation of the posed problem, so a lower bound) and equal to it (1e-7 relative) where the closed
  form's design is feasible and within the bounds;
- ``infeasible``: a diagnosis naming the conflicting constraints or bounds, and a closed form (where there is
  one) that is indeed infeasible or out of bounds (else the solver missed a feasible design);
- ``rejected``: an InputError naming the field (a contradictory case, refused before any solve);
- ``verified``: for a standalone family's own check (the transient against its closed form).
Anything else (solver failure, unverified, a wrong answer, an exception) is a failure.

Families are functions ``(base case) -> list[TortureCase]`` in :data:`FAMILIES`, applied to every case file of
every registered coupling; a family needing no base case (the simulator's transient family) goes in
:data:`STANDALONE_FAMILIES` as ``() -> list[TortureCase]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Callable

import numpy as np

from clutchopt.bench.reference import closed_form, coupling_cases, reference_mode, search_box
from clutchopt.cases import Case, load_case
from clutchopt.errors import InputError
from clutchopt.formulations import MODULES, get_coupling
from clutchopt.optimise.problem import PROVEN, problem_for
from clutchopt.optimise.solution import Solution
from clutchopt.units import ureg

MATCH_TOL = 1e-7  # objective against the closed form, relative
NEAR = 1e-6  # "within 1e-6 of the optimum"


@dataclass(frozen=True)
class Verdict:
    kind: str  # optimal | infeasible | rejected | verified (a non-optimisation result checked) pass; failed
    detail: str

    @property
    def passed(self) -> bool:
        return self.kind in ("optimal", "infeasible", "rejected", "verified")


@dataclass(frozen=True)
class TortureCase:
    name: str
    family: str
    run: Callable[[], Verdict]

    def verdict(self) -> Verdict:
        """The outcome; never raises."""
        try:
            return self.run()
        except InputError as exc:
            return Verdict("rejected", str(exc)) if exc.field else Verdict("failed", f"unnamed InputError: {exc}")
        except Exception as exc:  # noqa: BLE001 - any other exception is the failure this suite looks for
            return Verdict("failed", f"{type(exc).__name__}: {exc}")


# --- Judging one solve --------------------------------------------------------------------------------------------
def judge(case: Case, mode: str) -> Verdict:
    """Solve ``case`` in ``mode`` and judge it; the closed form applies in the reference mode only."""
    formulation = get_coupling(case.coupling).formulation(mode)
    solution = problem_for(formulation).solve(case)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        reference = closed_form(case) if mode == reference_mode(case.coupling) else None
    return judge_solution(solution, reference, formulation)


def judge_solution(solution: Solution, reference, formulation) -> Verdict:
    """The verdict on a solution, ``reference`` its closed form (:class:`ClosedForm`) or None."""
    if solution.status == "optimal":
        if any(-c.margin > c.tolerance for c in solution.constraints):  # 1e-8; a start-up's: its case's tolerance
            return Verdict("failed", f"optimal but violates by {solution.worst_violation:.3g}")
        if reference is not None and math.isfinite(reference.objective):
            gap = (solution.objective - reference.objective) / abs(reference.objective)
            if gap < -MATCH_TOL:
                return Verdict("failed", f"objective {solution.objective:.10g} below the closed form's "
                                         f"{reference.objective:.10g}: the optimum cannot beat its relaxation")
            if reference.feasible and gap > MATCH_TOL:
                return Verdict("failed", f"objective {solution.objective:.10g} above the feasible closed form's "
                                         f"{reference.objective:.10g} (gap {gap:.3g})")
        return Verdict("optimal", f"{solution.objective:.10g} {solution.objective_unit}")
    if solution.status in ("infeasible", "not_found"):  # proven or not: a verdict that names its constraints
        names = [c.name for c in solution.constraints] + [v.name for v in formulation.variables]
        if solution.solver.name == PROVEN:  # a proof from the case's values alone: it names the fields it rests on
            names += [q.name for q in formulation.quantities]
        if not solution.diagnosis or not any(name in solution.diagnosis for name in names):
            return Verdict("failed", f"infeasible without naming a constraint: {solution.diagnosis!r}")
        if reference is not None and reference.feasible:
            return Verdict("failed", f"reported infeasible, yet the closed form is feasible ({solution.diagnosis})")
        return Verdict("infeasible", solution.diagnosis)
    return Verdict("failed", f"{solution.status}: {solution.diagnosis}")


def _solve(case_of: Callable[[], Case], mode: str) -> Callable[[], Verdict]:
    """Build the case (its cross-field checks too, as for a case file), then solve and judge it."""
    def run() -> Verdict:
        case = case_of()
        get_coupling(case.coupling).check_case(case)
        return judge(case, mode)

    return run


def _label(case: Case) -> str:
    """A case's name in torture-case names: its file's stem (``wedge_paper``)."""
    return Path(case.path).stem


def _other_modes(case: Case) -> list[str]:
    return [mode for mode in get_coupling(case.coupling).formulations if mode != reference_mode(case.coupling)]


def _base_solution(case: Case, mode: str) -> Solution:
    return problem_for(get_coupling(case.coupling).formulation(mode)).solve(case)


def _dimension(unit: str):
    return ureg.Quantity(1.0, unit).dimensionality


# --- Families -----------------------------------------------------------------------------------------------------
TORQUES = (1.0, 10.0, 1e2, 1e3, 1e4, 1e5, 1e6)  # N*m


def torque_quantities(case: Case) -> list[str]:
    """The duty quantities (first section) of torque, inertia or power dimension: scaled alike at a fixed speed,
    they scale the required torque (T_max = I w / t_p + T_c, T itself, or k_s P / w)."""
    coupling = get_coupling(case.coupling)
    duty = coupling.quantities[0].section
    return [q.name for q in coupling.quantities if q.section == duty and q.name in case.values
            and _dimension(q.unit) in (_dimension("N*m"), _dimension("kg*m^2"), _dimension("W"))]


def torque_range(case: Case) -> list[TortureCase]:
    """The required torque from 1 N*m to 1 MN*m (:func:`torque_quantities` scaled). Reference mode at every
    torque, the other modes at 1, 1e3 and 1e6 N*m."""
    scaled = torque_quantities(case)
    base = _base_solution(case, reference_mode(case.coupling))
    torque = base.outputs["required_torque"].value if "required_torque" in base.outputs else case.values.get("torque")
    if not scaled or not torque:
        return []
    cases = []
    for target in TORQUES:
        factor = target / torque
        values = {name: case.values[name] * factor for name in scaled}
        for mode in [reference_mode(case.coupling)] + (_other_modes(case) if target in (1.0, 1e3, 1e6) else []):
            cases.append(TortureCase(f"{_label(case)}-{mode}-torque-{target:.0e}Nm", "torque",
                                     _solve(lambda v=values: case.with_values(**v), mode)))
    return cases


def speed_range(case: Case) -> list[TortureCase]:
    """Driving speeds 100 to 10,000 rpm, torque held (duty quantities untouched), reference mode."""
    if "speed" not in case.values:
        return []
    return [TortureCase(f"{_label(case)}-speed-{rpm}rpm", "speed",
                        _solve(lambda r=rpm: case.with_values(speed=r * math.pi / 30), reference_mode(case.coupling)))
            for rpm in (100, 300, 1000, 3000, 10000)]


def stress_extremes(case: Case) -> list[TortureCase]:
    """Every allowable stress or pressure at 1e-3 and 1e3 times its case value."""
    names = [q.name for q in get_coupling(case.coupling).quantities
             if q.name.startswith("allowable_") and q.name in case.values and _dimension(q.unit) == _dimension("Pa")]
    return [TortureCase(f"{_label(case)}-{name}-x{factor:g}", "stress",
                        _solve(lambda n=name, f=factor: case.with_values(**{n: case.values[n] * f}),
                               reference_mode(case.coupling)))
            for name in names for factor in (1e-3, 1e3)]


def _limit_quantities(case: Case, solution: Solution) -> list[tuple[str, str, float]]:
    """(constraint, quantity, value at the optimum) for each constraint whose limit is a case quantity itself."""
    coupling = get_coupling(case.coupling)
    found = []
    for check in solution.constraints:
        names = [q.name for q in coupling.quantities if not q.integer and case.values.get(q.name) == check.limit]
        if len(names) == 1 and check.value > 0:
            found.append((check.name, names[0], check.value))
    return found


def near_limits(case: Case) -> list[TortureCase]:
    """A limit moved to within 1e-6 (relative) of the value its constraint takes at the optimum, on both sides:
    near-infeasible specifications (for an inactive constraint the feasible set shrinks to a sliver or vanishes)."""
    mode = reference_mode(case.coupling)
    cases = []
    for constraint, quantity, value in _limit_quantities(case, _base_solution(case, mode)):
        for side in (+1, -1):
            limit = value * (1 + side * NEAR)
            cases.append(TortureCase(f"{_label(case)}-{constraint}-limit-{'+' if side > 0 else '-'}1e-6", "near",
                                     _solve(lambda q=quantity, v=limit: case.with_values(**{q: v}), mode)))
    return cases


def pinned_angles(case: Case) -> list[TortureCase]:
    """A design quantity fixed unless freed (the wedge's alpha, a thread's lead angle), kept fixed, within 1e-6 of
    the limit a constraint puts on it (the self-locking limit), on both sides, in every mode that has it."""
    cases = []
    for mode, formulation in get_coupling(case.coupling).formulations.items():
        for v in formulation.variables:
            if not v.fixed_unless_freed or v.integer:
                continue
            fixed = replace(case, free=tuple(name for name in case.free if name != v.name))
            solution = _base_solution(fixed, mode)
            for check in solution.constraints:
                if check.value != solution.design[v.name] or not check.limit > 0:
                    continue
                for side in (+1, -1):
                    value = check.limit * (1 + side * NEAR)
                    cases.append(TortureCase(
                        f"{_label(case)}-{mode}-{v.name}-at-{check.name}-{'+' if side > 0 else '-'}1e-6", "pinned",
                        _solve(lambda c=fixed, n=v.name, x=value: c.with_values(**{n: x}), mode)))
    return cases


def _near_bounds(quantity) -> list[float]:
    """Values within 1e-6 of each end of a quantity's declared valid range."""
    values = []
    for bound, inside in ((quantity.above, +1), (quantity.at_least, 0), (quantity.below, -1), (quantity.at_most, 0)):
        if bound is not None:
            values.append(bound + inside * NEAR * max(1.0, abs(bound)))
    return values


def degenerate_geometry(case: Case) -> list[TortureCase]:
    """Angles and ratios of the case's geometry at the ends of their valid ranges (lambda -> 1, alpha -> 0 or
    90 deg, ...): each within 1e-6 of the end, reference mode."""
    coupling = get_coupling(case.coupling)
    mode = reference_mode(case.coupling)
    cases = []
    for q in coupling.quantities:
        if q.integer or q.name not in case.values or q.section in ("cost", "paper", "limits"):
            continue
        if q.unit not in ("deg", "rad", ""):
            continue
        for value in _near_bounds(q):
            cases.append(TortureCase(f"{_label(case)}-{q.name}={value:.9g}", "degenerate",
                                     _solve(lambda n=q.name, v=value: case.with_values(**{n: v}), mode)))
    return cases


def excluded_optimum(case: Case) -> list[TortureCase]:
    """Infeasible by construction: each free variable's upper bound set to half its closed-form value."""
    mode = reference_mode(case.coupling)
    reference = closed_form(case)
    if reference is None:
        return []
    formulation = get_coupling(case.coupling).formulation(mode)
    box = search_box(formulation, case)
    cases = []
    for v in formulation.variables:
        lo, hi = box[v.name]
        value = reference.design[v.name]
        if lo < hi and not v.integer and lo < value / 2:
            bounded = replace(case, bounds={**case.bounds, v.name: (lo, value / 2)})
            cases.append(TortureCase(f"{_label(case)}-{v.name}-below-half-optimum", "excluded",
                                     _solve(lambda c=bounded: c, mode)))
    return cases


def _start_up_solve(case_of: Callable[[], Case]) -> Callable[[], Verdict]:
    def run() -> Verdict:
        from clutchopt.optimise.problem import case_problem

        case = case_of()
        problem = case_problem(case)
        return judge_solution(problem.solve(case), None, problem.formulation)

    return run


def start_up_limits(case: Case) -> list[TortureCase]:
    """Cases with a [start_up]: engagement windows 1e-3 and 1e-6 wide (relative) at 1.1 times the optimum's
    engagement speed, heat limits binding at 0.99 and 0.9 of the optimum's friction work and temperature rise, the
    start time 1e-6 either side of the optimum's, a motor whose breakdown torque is below the load; an elastic link's
    stress limit at 0.9 and 1.1 of the optimum's."""
    if case.start_up is None:
        return []
    from clutchopt.optimise.problem import solve_case

    start = solve_case(case).start_up
    variants: dict[str, dict[str, float]] = {}
    if start["engagement_speed"] > 0:
        for width in (1e-3, 1e-6):
            centre = 1.1 * start["engagement_speed"]
            variants[f"engagement-window-{width:g}"] = {"min_engagement_speed": centre * (1 - width / 2),
                                                       "max_engagement_speed": centre * (1 + width / 2)}
    for share in (0.99, 0.9) if "locked" not in start["phases"] else ():  # an elastic link has no friction heat
        variants[f"friction-work-x{share:g}"] = {"max_friction_work": share * start["friction_work_simulated"]}
        if start["temperature_rise"] is not None:
            variants[f"temperature-x{share:g}"] = {"max_temperature_rise": share * start["temperature_rise_simulated"]}
    if "peak_link_stress_simulated" in start:  # an elastic link: its stress binding below and above the optimum's
        for share in (0.9, 1.1):
            variants[f"link-stress-x{share:g}"] = {"max_link_stress": share * start["peak_link_stress_simulated"]}
    for side in (+1, -1):
        variants[f"start-time-{'+' if side > 0 else '-'}1e-6"] = {"max_start_time": start["start_time"] * (1 + side * NEAR)}
    if case.start_up.has("motor_curve"):
        variants["motor-below-load"] = {"breakdown_torque": 0.9 * case.values["load_torque"]}
    cases = []
    for name, values in variants.items():
        limits = tuple(sorted(set(case.start_up.limits) | {n for n in values if n.startswith(("max_", "min_"))}))
        edited = replace(case, start_up=replace(case.start_up, limits=limits))
        cases.append(TortureCase(f"{_label(case)}-{name}", "start_up",
                                 _start_up_solve(lambda c=edited, v=values: c.with_values(**v))))
    return cases


FAMILIES: tuple[Callable[[Case], list[TortureCase]], ...] = (
    torque_range, speed_range, stress_extremes, near_limits, pinned_angles, degenerate_geometry, excluded_optimum,
    start_up_limits)


# --- The start-up transient: closed forms against the simulation ----------------------------------------------
TRANSIENT_A_W0 = (0.0, 1e-6, 1.0, 30.0, 300.0, 1000.0)  # |a w0|, both signs
TRANSIENT_LOAD_RATIOS = (0.0, 0.5, 0.999, 1.001)  # M_r / 2k: no load, half, just below and just above lock-up
TRANSIENT_AGREEMENT = 1e-9  # relative, t_c, L and L_s


def _transient(a_w0: float, ratio: float) -> Callable[[], Verdict]:
    def run() -> Verdict:
        from clutchopt.simulate.paper import paper_start_up

        inertia, k, speed = 2.0, 50.0, 157.07963267948966  # the paper scene's J, k, w0 (1500 rpm)
        both = paper_start_up(inertia, k, a_w0 / speed, ratio * 2 * k, speed)
        exact, simulated = both["analytic"], both["simulated"]
        if exact["locks_up"] != simulated["locks_up"]:
            return Verdict("failed", f"lock-up: closed form {exact['locks_up']}, simulation {simulated['locks_up']}")
        if not exact["locks_up"]:
            named = exact["reason"].startswith("no lock-up") and simulated["reason"].startswith("no lock-up")
            return Verdict("verified" if named else "failed", f"no lock-up: {simulated['reason']}")
        errors = {key: abs(simulated[key] - exact[key]) / abs(exact[key])
                  for key in ("start_time", "friction_work", "source_work")}
        worst = max(errors, key=errors.get)
        kind = "verified" if errors[worst] <= TRANSIENT_AGREEMENT else "failed"
        return Verdict(kind, f"worst relative difference {errors[worst]:.1e} ({worst})")
    return run


def transient_family() -> list[TortureCase]:
    """The paper's start-up over |a w0| up to 1e3 (both signs) and M_r up to just above the lock-up limit 2k."""
    return [TortureCase(f"transient-a_w0={sign * a_w0:g}-Mr={ratio:g}x2k", "transient", _transient(sign * a_w0, ratio))
            for a_w0 in TRANSIENT_A_W0 for sign in (1, -1) for ratio in TRANSIENT_LOAD_RATIOS]


STANDALONE_FAMILIES: tuple[Callable[[], list[TortureCase]], ...] = (transient_family,)


def torture_cases() -> list[TortureCase]:
    """Every family over every case file of every registered coupling, then the standalone families."""
    files = [path for name in MODULES for path in coupling_cases(name)]
    cases = [tc for path in files for family in FAMILIES for tc in family(load_case(path))]
    return cases + [tc for family in STANDALONE_FAMILIES for tc in family()]
