"""The torture suite: hard cases over every coupling end in a verified optimum, a named infeasibility or a
rejected input naming its field; never a silent wrong answer or an exception."""

from collections import Counter
from dataclasses import replace

import pytest

from clutchopt.bench.reference import bench_cases, closed_form, coupling_cases
from clutchopt.bench.torture import FAMILIES, TortureCase, judge_solution, torque_quantities, torture_cases
from clutchopt.formulations import MODULES, get_coupling
from clutchopt.optimise import problem_for

CASES = torture_cases()
VERDICTS: dict[str, object] = {}


@pytest.mark.parametrize("torture", CASES, ids=[tc.name for tc in CASES])
def test_hard_case(torture):
    verdict = torture.verdict()
    VERDICTS[torture.name] = verdict
    assert verdict.passed, verdict.detail


def test_coverage():
    assert len(CASES) >= 400 and len({tc.name for tc in CASES}) == len(CASES)
    files = {tc.name.split("-")[0] for tc in CASES if tc.family != "transient"}
    assert files == {path.stem for name in MODULES for path in coupling_cases(name)}
    assert {name for name in MODULES if coupling_cases(name)} >= {"wedge", "lever", "cable", "ball"}
    optimisation = {"torque", "speed", "stress", "near", "pinned", "degenerate", "excluded"}
    assert {family(bench_cases()[0])[0].family for family in FAMILIES[:-1]} == optimisation
    assert {tc.family for tc in CASES} == optimisation | {"start_up", "transient"}
    start_up = {tc.name for tc in CASES if tc.family == "start_up"}
    assert {"wedge_motor_start-engagement-window-1e-06", "lever_motor_start-temperature-x0.99",
            "ball_motor_start-motor-below-load"} <= start_up
    transient = [tc.name for tc in CASES if tc.family == "transient"]
    assert len(transient) == 48 and "transient-a_w0=1000-Mr=1.001x2k" in transient and "transient-a_w0=-1000-Mr=0x2k" in transient


def test_outcomes_are_mixed_and_named():
    kinds = Counter(v.kind for v in (VERDICTS.get(tc.name) or tc.verdict() for tc in CASES))
    assert kinds["optimal"] >= 200 and kinds["infeasible"] >= 100 and kinds["rejected"] >= 10
    assert kinds["failed"] == 0


def _named(name):
    return next(tc for tc in CASES if tc.name == name).verdict()


def test_known_outcomes():
    # within 1e-6 of the wedge's flank-pressure limit: just feasible at the same optimum, just infeasible below
    above = _named("wedge_centrifuge-flank_pressure-limit-+1e-6")
    below = _named("wedge_centrifuge-flank_pressure-limit--1e-6")
    assert above.kind == "optimal" and below.kind == "infeasible"
    assert "torque" in below.detail and "flank_pressure" in below.detail
    # alpha within 1e-6 of the self-locking limit (atan f + margin), geometry mode with alpha fixed
    assert _named("wedge_centrifuge-geometry-flank_angle-at-not_self_locking-+1e-6").kind == "optimal"
    locked = _named("wedge_centrifuge-geometry-flank_angle-at-not_self_locking--1e-6")
    assert locked.kind == "infeasible" and "not_self_locking" in locked.detail
    # lambda -> 1: no flank area left
    assert _named("wedge_centrifuge-radius_ratio=1.000001").kind == "infeasible"
    # the cable's thread below its self-locking limit is refused by the case check, naming the field
    refused = _named("cable_conveyor-paper-lead_angle-at-hub_thread_not_self_locking--1e-6")
    assert refused.kind == "rejected" and refused.detail.startswith("thread.lead_angle: self-locking thread")
    # the transient at |a w0| = 1e3: agreement without overflow; just above the lock-up limit: no lock-up, said so
    assert _named("transient-a_w0=1000-Mr=0.999x2k").kind == "verified"
    assert _named("transient-a_w0=-1000-Mr=0x2k").detail.startswith("worst relative difference")
    assert "no lock-up" in _named("transient-a_w0=30-Mr=1.001x2k").detail


def _wedge():
    case = bench_cases()[0]
    formulation = get_coupling("wedge").formulation("paper")
    return case, formulation, problem_for(formulation).solve(case), closed_form(case)


def test_judge_catches_a_wrong_optimum():
    case, formulation, solution, reference = _wedge()
    assert judge_solution(solution, reference, formulation).kind == "optimal"
    assert judge_solution(replace(solution, objective=solution.objective * (1 + 1e-5)), reference,
                          formulation).kind == "failed"
    assert judge_solution(replace(solution, objective=solution.objective * (1 - 1e-5)), reference,
                          formulation).kind == "failed"
    violated = [replace(c, margin=-1e-7) if c.name == "torque" else c for c in solution.constraints]
    assert judge_solution(replace(solution, constraints=violated), reference, formulation).kind == "failed"


def test_judge_catches_a_false_infeasibility():
    case, formulation, solution, reference = _wedge()
    false_alarm = replace(solution, status="infeasible", diagnosis="infeasible: cannot satisfy torque")
    assert reference.feasible
    assert judge_solution(false_alarm, reference, formulation).kind == "failed"
    unnamed = replace(solution, status="infeasible", diagnosis="infeasible")
    assert judge_solution(unnamed, None, formulation).kind == "failed"


def test_an_exception_is_a_failure_not_a_crash():
    def explode():
        raise ZeroDivisionError("float division by zero")

    verdict = TortureCase("x", "x", explode).verdict()
    assert verdict.kind == "failed" and "ZeroDivisionError" in verdict.detail


@pytest.mark.parametrize("k", [1e-9, 1e-6, 1e-3, 1e3, 1e6, 1e9])
def test_ipopt_behaves_the_same_at_every_scale(k):
    # torque, allowables and density scaled by k: every mass scales by k, every normalised constraint is unchanged,
    # so the nondimensionalised NLP is the same one: same iterations, same optimum over k
    case = bench_cases()[0]
    problem = problem_for(get_coupling(case.coupling).formulation("paper"))

    def solve(factor):
        names = torque_quantities(case) + ["allowable_pressure", "allowable_bending_stress", "density"]
        scaled = replace(case.with_values(**{n: case.values[n] * factor for n in names}),
                         bounds={"weight_mass": (1e-6 * factor, 1e4 * factor)})
        return problem.solve(scaled, start={"weight_mass": 0.05 * factor, "finger_diameter": 0.005})

    base, scaled = solve(1.0), solve(k)
    assert base.status == scaled.status == "optimal"
    assert scaled.solver.iterations == base.solver.iterations
    assert scaled.objective / k == pytest.approx(base.objective, rel=1e-12)
    assert scaled.design["finger_diameter"] == pytest.approx(base.design["finger_diameter"], rel=1e-12)
