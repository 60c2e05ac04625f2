"""A start-up's first mesh is graded by the case it solves (``drive.graded_part``), not by the case its problem was
built from: a sweep's point starts where ``solve`` of it alone starts (review 24)."""

from pathlib import Path

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise.problem import case_problem, solve_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import Vary
from clutchopt.start_up.drive import graded_part

CASES = Path(__file__).resolve().parents[1] / "cases"


def test_the_graded_part_is_the_motor_s_knee_time_twenty_times_over_rounded_up():
    case = load_case(CASES / "ball_motor_start.toml")
    v = case.values
    knee = 20 * v["motor_inertia"] * v["synchronous_speed"] / v["breakdown_torque"]  # s: the knee, 20 times over
    for start_time in (8.0, 16.0, 40.0):
        share = knee / start_time
        expected = next((part for part in (0.05, 0.1, 0.2, 0.4) if part >= share), 0.4)
        assert graded_part(case.start_up, {**v, "max_start_time": start_time}) == expected
    assert graded_part(case.start_up, {**v, "max_start_time": 8.0}) != graded_part(case.start_up,
                                                                                    {**v, "max_start_time": 16.0})


def test_a_sweep_point_of_another_graded_part_is_solve_s_alone_and_shares_its_problem():
    # ball_motor_start at 16 s: graded by 8 s's part (the case's), the sweep had kept 950.755 kg (23 rows) where
    # ``solve`` alone keeps 957.546 kg (25 rows): the two local optima of docs/start_up.md, each from its own first
    # mesh; at 12 s both keep 950.755 kg
    case = load_case(CASES / "ball_motor_start.toml")
    quantity = next(q for q in case.quantities if q.name == "max_start_time")
    result = Sweep(case, [Vary(quantity, (16.0, 12.0))]).run(progress=False)
    for value, point in zip((16.0, 12.0), result.solutions):
        alone = solve_case(case.with_values(max_start_time=value))
        assert point["status"] == alone.status == "optimal"
        assert point["design"]["ball_rows"] == alone.design["ball_rows"]
        assert point["objective"]["value"] == pytest.approx(alone.objective, rel=1e-6)
        assert "solve_alone" not in point
        assert case_problem(case.with_values(max_start_time=value)) is case_problem(case)  # (one NLP, one build)
