"""The page's verification block: what was checked of the design and what each check found, read from the
solution (its solver figures, its float64 constraint checks, the simulated start it carries), from the simulator's
check of a start at constant driving speed, and from the robust result where the design is robust."""

from __future__ import annotations

from dataclasses import dataclass

from clutchopt.records import DESIGN_STATUSES, lock_up_verdict, target_text

PASSED, FAILED, NOT_DONE = "passed", "failed", "not done"


def robust_label(robust) -> str:
    """The robust method of a RobustResult as the page names it: "worst-case", "chance 0.999"."""
    return robust.method + (f" {target_text(robust.target)}" if robust.target else "")


@dataclass(frozen=True)
class Check:
    what: str
    how: str
    found: str
    verdict: str  # PASSED, FAILED or NOT_DONE


def verification(case, solution, robust=None, nominal_failure: tuple[str, float, int] | None = None) -> list[Check]:
    """The checks of ``solution`` (the robust design's where ``robust`` is given); ``nominal_failure``: (constraint,
    probability, samples) of the nominal design's likeliest failure, where the page shows the nominal design of a
    case with a [scatter]."""
    return [solver_check(solution), float64_check(solution), start_up_check(case, solution),
            scatter_check(case, solution, robust, nominal_failure)]


def solver_check(solution) -> Check:
    info = solution.solver
    iterations = "" if info.iterations is None else f", {info.iterations} iterations"
    how = f"{info.name.upper()} returned {info.status}{iterations} in {info.solves} solve(s), {info.time_s:.3g} s"
    if solution.status == "optimal":
        return Check("solver", how, f"status {solution.status}: converged and confirmed by the float64 check",
                     PASSED)
    return Check("solver", how, f"status {solution.status}: {solution.diagnosis or 'no design'}", FAILED)


def float64_check(solution) -> Check:
    checks = solution.constraints
    if not checks:
        return Check("float64 re-check", "no constraint to re-evaluate", "-", NOT_DONE)
    tolerances = sorted({c.tolerance for c in checks})
    how = (f"all {len(checks)} constraints re-evaluated in float64 outside the solver (the same equations, no "
           f"CasADi); a violation counts above {' or '.join(f'{t:g}' for t in tolerances)} (relative)")
    failed = [c for c in checks if not c.feasible]
    if failed:
        return Check("float64 re-check", how, "violated: " + ", ".join(f"{c.name} by {-c.margin:.3g}" for c in failed),
                     FAILED)
    smallest = min((c for c in checks if not c.active), key=lambda c: c.margin, default=None)
    active = [c.name for c in checks if c.active]
    found = f"all {len(checks)} met; active: {', '.join(active) or 'none'}"
    if smallest is not None:
        found += f"; smallest margin of the others {smallest.margin:.3g} ({smallest.name})"
    return Check("float64 re-check", how, found, PASSED)


def start_up_check(case, solution) -> Check:
    """The start of the design's drive simulated independently of the NLP; a case sized for constant acceleration
    is started at constant driving speed."""
    what = "independent simulation"
    if solution.status not in DESIGN_STATUSES:  # (a last point's start is no design's: review 29)
        return Check(what, "not simulated", f"no design to start (status {solution.status})", NOT_DONE)
    start = solution.start_up
    if start is not None:
        how = (f"the start on the case's drive ({', '.join(start['effects'])}) integrated by SciPy (LSODA where "
               f"stiff) in float64, beside the NLP's Radau collocation ({start['intervals']} intervals per phase); the "
               "start-up's constraints above are checked with the simulated figures")
        if not start["locks_up"]:
            return Check(what, how, f"{'no lock-up' if lock_up_verdict(start) == 'no' else 'not decided'}: "
                                    f"{start['reason']}", FAILED)
        errors = start["discretisation_error"]
        return Check(what, how, f"lock-up after {start['start_time_simulated']:.6g} s (NLP {start['start_time']:.6g} "
                                f"s, {errors['start_time']:+.1e}); friction work {start['friction_work_simulated']:.6g}"
                                f" J (NLP {errors['friction_work']:+.1e})", PASSED)
    from clutchopt.simulate import verify

    check = verify(case, solution)
    if "sized_acceleration_time" not in check:
        return Check(what, "not simulated", check["reason"], NOT_DONE)
    how = f"the start simulated by SciPy (DOP853) in float64 at {check['assumption']}"
    if not check["verified"]:
        return Check(what, how, f"the design does not start up: {check['reason']}", FAILED)
    return Check(what, how, f"reaches speed in {check['simulated_acceleration_time']:.6g} s against t_p = "
                            f"{check['sized_acceleration_time']:.6g} s ({check['relative_difference']:+.1e}); "
                            f"friction work {check['friction_work']:.6g} J", PASSED)


def scatter_check(case, solution, robust, nominal_failure: tuple[str, float, int] | None) -> Check:
    what = "corners and Monte Carlo"
    if robust is None and case.scatter and solution.status not in DESIGN_STATUSES:
        return Check(what, "the nominal design under the case's [scatter]", "no design to check", NOT_DONE)
    if robust is not None:
        return Check(what, f"robust design ({robust_label(robust)}) for the case's [scatter]", robust.verification,
                     PASSED if robust.status == "optimal" else FAILED)
    if nominal_failure is not None:
        name, p, samples = nominal_failure
        start_up = case.start_up is not None
        unsampled = "; its start-up limits not sampled" if start_up else ""  # (review 29: not said)
        return Check(what, f"the nominal design under the case's [scatter], {samples} Monte Carlo samples (section "
                           "Scatter); it is not designed for the scatter",
                     f"largest failure probability {p:.3g} ({name}){unsampled}",
                     FAILED if p > 0 else NOT_DONE if start_up else PASSED)
    return Check(what, "the case has no [scatter]", "-", NOT_DONE)
