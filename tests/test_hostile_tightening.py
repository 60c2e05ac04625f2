"""The tightening rule of sweeps (clutchopt/optimise/tightening.py, used by optimise/batch.py to rule out an integer
combination without a solve while a sweep only tightens) where its assumptions are strained: a sweep going back and
forth across the ball's infeasible region, and a grid of two quantities that move the same limit in opposite senses.
Every point's status is that of `solve` of that point alone, its objective too where it has a design (a point without
one that a region's proof covers shows the design of the last point without one, not its own failed solve's:
tests/test_sweep_agrees.py's contract), and the rule is exercised (combinations are ruled out), not bypassed."""

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import batch, solve_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from conftest import CASES

STATIC_RTOL = 1e-9


@pytest.mark.parametrize("texts", [
    # ball_crusher has no design from about 560 kW: 450 kW designed, 700 infeasible, back to 450 (the rows ruled out
    # at 700 must not be ruled out at 450: the torque floor k_s P / w is lower there), and so on
    ("power=450,700,450,700,500,650",),
    # power up and service factor down move the torque row's floor k_s P / w in opposite senses: ruled out only where
    # the product grew (1.5 x 450 = 675 > 1.2 x 520 = 624 kW: the step 450 -> 520 at k_s 1.5 -> 1.2 loosens)
    ("power=450,520,600,680", "service_factor=1.5,1.2,1.0"),
])
def test_a_sweep_that_tightens_and_loosens_agrees_with_solves(texts, monkeypatch):
    ruled = []
    original = batch.BatchSweep._ruled_out
    monkeypatch.setattr(batch.BatchSweep, "_ruled_out",
                        lambda self, combo, k: ruled.append(original(self, combo, k)) or ruled[-1])
    case = load_case(CASES / "ball_crusher.toml")
    sweep = Sweep(case, [parse_vary(text, case.coupling) for text in texts])
    records = list(sweep.run(progress=False).solutions)
    assert any(ruled), "no combination was ruled out: the rule was not exercised"
    for record, point in zip(records, sweep.points):
        solved = solve_case(sweep.case.with_values(**point))
        assert record["status"] == solved.status, point
        if solved.status == "infeasible":
            assert record["diagnosis"].startswith("proven infeasible"), point
            continue
        assert record["objective"]["value"] == pytest.approx(solved.objective, rel=STATIC_RTOL, abs=0), point
