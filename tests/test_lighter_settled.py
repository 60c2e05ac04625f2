"""A start-up sweep's point of an elastic link whose every lighter count has its verdict there already is not probed
as ``solve`` would (``start_up_sweep.as_solve_would``, ``Problem.lighter_settled``)."""

from dataclasses import replace
from types import SimpleNamespace

import clutchopt.optimise.start_up_sweep as start_up_sweep
from clutchopt.cases import load_case
from clutchopt.optimise.own_shift import ForeignShifts, carried_by
from clutchopt.optimise.problem import Problem, case_problem
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from tests.conftest import CASES

CABLE = load_case(CASES / "cable_motor_start.toml")


def swept(monkeypatch, settled: bool = True, vary: str = "driven_inertia=0.2,0.21") -> tuple[list[dict], list]:
    """cable_motor_start swept (``vary``; default over driven_inertia 0.2, 0.21 kg m^2): its records, and each
    (problem, case, solution) ``as_solve_would`` was handed; ``settled=False``: every point probed (main before the
    rule)."""
    handed, probe = [], start_up_sweep.as_solve_would

    def spied(problem, case, solution, sized, alone=None):
        handed.append((problem, case, solution))
        return probe(problem, case, solution, sized, alone)

    with monkeypatch.context() as patched:
        patched.setattr(start_up_sweep, "as_solve_would", spied)
        if not settled:
            patched.setattr(Problem, "lighter_settled", lambda *args: False)
        return Sweep(CABLE, [parse_vary(vary, "cable", CABLE.quantities)]).run(progress=False).solutions, handed


def test_a_point_whose_lighter_counts_are_settled_is_not_probed_the_same_design(monkeypatch):
    """At 0.21 kg m^2, warm from 0.2's 8 cables at the stress limit 7 cables' start moved there: 8 cables kept, 7
    solved through their own loop from the case's limit (``unverified``), the sizing's 6 refuted by the link's least
    stress at the case's limit. The probe solved the relaxation and 7 cables again, to end on them ``unverified``: two
    solver calls fewer, the point's status, count and objective the same to the bit."""
    before, _ = swept(monkeypatch, settled=False)
    after, handed = swept(monkeypatch)
    problem, case, solution = handed[-1]
    sevens = [e["status"] for e in solution.integer_search if e["cable_count"] == 7]
    assert sevens[-1] == "own accuracy loop: unverified"
    assert problem.sized_design(case)["cable_count"] == 6.0
    assert problem._link_refutes(case, case, solution, [(6.0,)])
    assert problem.lighter_settled(case, solution)
    assert after[1]["solver"]["solves"] == before[1]["solver"]["solves"] - 2
    assert after[0]["solver"]["solves"] == before[0]["solver"]["solves"]  # (cold: solve's own)
    for old, new in zip(before, after):
        assert new["status"] == old["status"] == "optimal"
        assert new["design"]["cable_count"] == old["design"]["cable_count"] == 8.0
        assert new["objective"]["value"] == old["objective"]["value"]


def test_a_lighter_count_without_its_verdict_leaves_the_point_probed(monkeypatch):
    """The same point's solution without 7 cables' own loop in its search: 7 cables have a design of the NLP at the
    case's limit (not refuted), so their verdict is not had and the point is probed; nor is a solution settled that is
    not ``optimal``, nor one of a problem without an elastic link (the ball)."""
    _, handed = swept(monkeypatch)
    problem, case, solution = handed[-1]
    unlooped = replace(solution, integer_search=[e for e in solution.integer_search
                                                 if not e["status"].startswith("own accuracy loop")],
                       unverified_at_the_case=frozenset())
    assert not problem._link_refutes(case, case, solution, [(7.0,)])
    assert not problem.lighter_settled(case, unlooped)
    assert not problem.lighter_settled(case, replace(solution, status="unverified"))
    ball = load_case(CASES / "ball_motor_start.toml")
    assert not case_problem(ball).lighter_settled(ball, solution)


def test_a_lighter_count_its_loop_simulated_at_the_case_s_limits_is_settled(monkeypatch):
    """cable_motor_start over max_start_time 2, 2.1 s: at 2.1 s, warm from 2 s's 8 cables at the case's limits, the
    loop's first solve keeps 7 cables (lighter), whose simulated start misses the stress limit; 8 cables solved first
    at the case's limit are kept (``Problem._one_up_first``), 7 never looped on their own. Their design of the NLP at
    the case's own limits was simulated, unverified: settled (the probe solved the relaxation and 7 cables again, to
    end on them ``unverified``), two solver calls fewer, the same design to the bit."""
    vary = "max_start_time=2,2.1"
    before, _ = swept(monkeypatch, settled=False, vary=vary)
    after, handed = swept(monkeypatch, vary=vary)
    problem, case, solution = handed[-1]
    assert solution.unverified_at_the_case == frozenset({(7.0,)})
    assert not any(e["status"].startswith("own accuracy loop") for e in solution.integer_search
                   if e["cable_count"] == 7)
    said = [e for e in after[1]["integer_search"] if e["status"] == "simulated at the case's limits: unverified"]
    assert [(e["cable_count"], e["feasible"]) for e in said] == [(7, False)]  # (its record says why: review h18b)
    assert said[0]["objective"] < after[1]["objective"]["value"]  # (lighter, its start missing a limit)
    assert problem.lighter_settled(case, solution)
    assert not problem.lighter_settled(case, replace(solution, unverified_at_the_case=frozenset()))
    assert after[1]["solver"]["solves"] == before[1]["solver"]["solves"] - 2
    for old, new in zip(before, after):
        assert new["status"] == old["status"] == "optimal"
        assert new["design"]["cable_count"] == old["design"]["cable_count"] == 8.0
        assert new["objective"]["value"] == old["objective"]["value"]


def test_only_a_design_at_the_case_s_own_limits_is_recorded_unverified_there():
    """``ForeignShifts.seen``: an unverified design is recorded at the case's own limits only while no choice's start
    has moved them (nor a shift carried from another point)."""
    unverified = SimpleNamespace(status="unverified", design={"cable_count": 7.0}, objective=3.49, integer_search=[])
    at_the_case = ForeignShifts(["cable_count"])
    at_the_case.seen(unverified)
    assert set(at_the_case.unverified_at_the_case) == {(7.0,)}
    moved = ForeignShifts(["cable_count"])
    moved.corrected(unverified)
    moved.seen(unverified)
    carried = ForeignShifts(["cable_count"], carried_by(None))
    carried.seen(unverified)
    assert moved.unverified_at_the_case == carried.unverified_at_the_case == {}
    assert (7.0,) in moved.unverified and (7.0,) in carried.unverified
    moved.simulated_at_the_case(SimpleNamespace(status="optimal", design={"cable_count": 8.0}))
    moved.simulated_at_the_case(SimpleNamespace(status="unverified", design={"cable_count": 9.0}))
    assert set(moved.unverified_at_the_case) == {(9.0,)}  # (the caller's word that it was solved at the case's limits)


def test_the_count_one_up_solved_first_and_left_unverified_is_settled(monkeypatch):
    """cable_motor_start over damping_ratio 0.05, 0.0553: at the second point the loop's first solve keeps 7 cables at
    the case's limits (unverified), 8 cables solved first there (``Problem._one_up_first``) start with more stress
    than allowed too, never looped on their own (the search at the moved limit then keeps 15, and the own loops walk
    down to 10, 9 unverified): 7 and 8 were simulated at the case's own limits, so the point is not probed (it solved
    the relaxation and 7 cables again), two solver calls fewer, the same design to the bit."""
    vary = "damping_ratio=0.05,0.0553"
    before, _ = swept(monkeypatch, settled=False, vary=vary)
    after, handed = swept(monkeypatch, vary=vary)
    problem, case, solution = handed[-1]
    assert solution.unverified_at_the_case == frozenset({(7.0,), (8.0,)})
    assert ("8", "solved first at the case's limits: unverified") in [
        (str(e["cable_count"]), e["status"]) for e in solution.integer_search]
    assert problem.lighter_settled(case, solution)
    assert after[1]["solver"]["solves"] == before[1]["solver"]["solves"] - 2
    for old, new in zip(before, after):
        assert new["status"] == old["status"] == "optimal"
        assert new["design"]["cable_count"] == old["design"]["cable_count"]
        assert new["objective"]["value"] == old["objective"]["value"]
    assert [r["design"]["cable_count"] for r in after] == [11.0, 10.0]
