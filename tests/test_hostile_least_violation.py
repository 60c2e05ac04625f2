"""The newest short-cuts of sweeps and start-up solves checked against the slow way they replace:

- an integer combination that a batched sweep declares without a design by its least largest violation
  (clutchopt/optimise/feasibility.py: a verified KKT point of the feasibility problem above 1e-6) is one that
  ``solve`` of that point alone, with the combination fixed, also finds without a design (IPOPT's verdict);
- the start-up loop's ``unsettled`` rule (clutchopt/optimise/problem.py: the integers decided again from the
  relaxation after a coarse mesh) gives the design the loop gives without it.

No hand calculation: the references are solves of the same values (tests/test_sweep_agrees.py's contract), and each
test asserts that the short-cut was taken, so that it cannot pass by not being exercised."""

from dataclasses import replace

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import batch, problem, solve_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from conftest import CASES


def test_every_combination_a_sweep_leaves_without_a_design_has_none_by_ipopt(monkeypatch):
    # ball_crusher 250-1000 kW: each row count carries the torque k_s P / w up to a power, then the least violation
    # of its rows (torque, contact stress, the outer diameter together) stays above 1e-6: 4.4e-4 to 5e-3 relative on
    # this sweep (13 combinations, 17 settled by SQP on the feasibility problem, 4 of them unverified and left to
    # IPOPT). Each claim, solved alone with the rows fixed (IPOPT, cold), is Infeasible_Problem_Detected as well
    claims = []
    original = batch.BatchSweep._least_violation

    def spied(self, start, k, lower, upper, seed):
        found, seconds = original(self, start, k, lower, upper, seed)
        claims.append((k, float(lower[self.integer][0]), found))
        return found, seconds

    monkeypatch.setattr(batch.BatchSweep, "_least_violation", spied)
    case = load_case(CASES / "ball_crusher.toml")
    sweep = Sweep(case, [parse_vary("power=250:1000:40", case.coupling)])
    sweep.run(progress=False)
    without = [(k, rows, found) for k, rows, found in claims if found.without_design]
    assert len(without) >= 10, "the least violation was not exercised"
    for k, rows, found in without:
        assert found.violation > 1e-6
        point = sweep.case.with_values(**sweep.points[k])
        alone = solve_case(replace(point, bounds={**point.bounds, "ball_rows": (rows, rows)}))
        assert alone.status == "infeasible", (k, rows, found.violation, alone.status)


@pytest.mark.parametrize("inertia", [360.0, 390.0])
def test_the_unsettled_rule_changes_no_start_up_design(inertia, monkeypatch):
    # ball_motor_start with its driven inertia at 360 and 390 kg m^2: a row count one away from the kept one is
    # feasible within the first mesh's collocation error (the rule fires), and the design is the one the loop finds
    # with the rule disabled: 24 rows, 981.0203 kg at 360; 26 rows, 1073.0735 kg at 390 (both the same to the bit)
    fired = []
    original = problem.unsettled
    monkeypatch.setattr(problem, "unsettled", lambda solution, error: fired.append(original(solution, error))
                        or fired[-1])
    case = load_case(CASES / "ball_motor_start.toml").with_values(driven_inertia=inertia)
    with_rule = solve_case(case)
    assert any(fired), "the unsettled rule did not fire"
    monkeypatch.setattr(problem, "unsettled", lambda solution, error: False)
    without_rule = solve_case(case)
    assert with_rule.status == without_rule.status == "optimal"
    assert with_rule.design["ball_rows"] == without_rule.design["ball_rows"]
    assert with_rule.objective == pytest.approx(without_rule.objective, rel=1e-9, abs=0)
