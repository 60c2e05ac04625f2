"""The boxes an iteration of an interval search evaluates at least (clutchopt.optimise.interval_proof._batch): fewer
for a design with integer variables, whose boxes the evaluations between splits empty, cut and round."""

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.optimise import interval_proof
from clutchopt.optimise.interval_proof import _search_problem, searches
from clutchopt.optimise.problem import case_problem


def _ball_at_half_its_contact_stress():
    case = next(c for c in bench_cases() if c.coupling == "ball")
    case = case.with_values(allowable_contact_stress=0.5 * case.values["allowable_contact_stress"])
    posed = case_problem(case, reference_mode("ball")).posed
    return posed, _search_problem(posed, case)


def test_the_ball_s_proof_takes_fewer_boxes_with_fewer_splits_between_evaluations(monkeypatch):
    """The bench's ball at 0.5x its allowable contact stress (a sweep's first point, no design: torque (8) and the
    Hertz stress (9) conflict). Its design has an integer variable (ball rows), so an iteration splits a box
    ceil(log2(32 / boxes)) times, 5 for the first box (32 halves), not 7 (128): the proof took 435 boxes with 128 an
    iteration, 121 with 32; proven either way, resting on the torque and the contact stress."""
    posed, problem = _ball_at_half_its_contact_stress()
    assert posed.integer and interval_proof._batch(posed) == interval_proof.INTEGER_BATCH == 32
    now, = searches(posed, [problem])
    monkeypatch.setattr(interval_proof, "INTEGER_BATCH", interval_proof.BATCH)
    before, = searches(posed, [problem])
    assert (now.proven, now.boxes, before.proven, before.boxes) == (True, 121, True, 435)
    assert {"torque", "contact_stress"} <= set(now.decisive) and {"torque", "contact_stress"} <= set(before.decisive)


def test_searches_led_by_a_point_end_where_its_first_box_decides_it():
    """``searches(..., lead=True)`` (a sweep's point with the runs after it: interval_proof.searched_along): where the
    first search ends at its first evaluation (here by a budget of one box), the others still searching end there,
    given up after their own first box (the ball at 0.5x its allowable contact stress: 1 box, not its proof in 121);
    where it goes on, each search is what it alone gives (121 boxes, proven, with or without a leader)."""
    posed, problem = _ball_at_half_its_contact_stress()
    leader, follower = searches(posed, [problem, problem], [1, interval_proof.MAX_BOXES], lead=True)
    assert (leader.proven, leader.boxes, follower.proven, follower.boxes) == (False, 1, False, 1)
    alone, = searches(posed, [problem])
    led = searches(posed, [problem, problem], lead=True)
    assert [(o.proven, o.boxes, o.decisive) for o in led] == [(alone.proven, alone.boxes, alone.decisive)] * 2
    assert (alone.proven, alone.boxes) == (True, 121)
