"""Whether a sweep's step only tightens the constraints (clutchopt/optimise/tightening.py): the ball clutch in design
mode, whose torque row is T(design) >= k_s P / w (eq. (8))."""

import numpy as np

from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.problem import Problem
from clutchopt.optimise.tightening import tightening
from pathlib import Path

CASES = Path(__file__).resolve().parents[1] / "cases"


def _values(problem, case, **factors):
    """The case's values (SI, the formulation's order), those named multiplied by their factors."""
    params = problem.posed.params(case)
    return np.array([getattr(params, q.name) * factors.get(q.name, 1.0) for q in problem.formulation.quantities])


def test_a_limit_of_case_values_alone_tightens_or_loosens():
    case = load_case(CASES / "ball_compressor.toml")
    problem = Problem(get_coupling("ball").formulation("design"))
    base = _values(problem, case)
    # the power enters the torque row's limit alone: k_s P / w at 1.1 P is 1.1 times the rated torque, a higher
    # floor for every design (at_least): tightened; back down to P: loosened
    power = tightening(problem.posed, ["power"])
    assert power.known
    assert power.tightened(base, _values(problem, case, power=1.1))
    assert not power.tightened(_values(problem, case, power=1.1), base)
    assert power.tightened(base, base)  # (no step: the same constraints)
    # the allowable contact stress is the contact-stress row's ceiling (at_most, eq. (9)): lower is tighter
    stress = tightening(problem.posed, ["allowable_contact_stress"])
    assert stress.tightened(base, _values(problem, case, allowable_contact_stress=0.9))
    assert not stress.tightened(base, _values(problem, case, allowable_contact_stress=1.1))
    # the speed enters the torque the design carries (the balls' centrifugal force, the value side) and the rated
    # torque: what a step does depends on the design, nothing is concluded
    speed = tightening(problem.posed, ["speed"])
    assert not speed.known and not speed.tightened(base, _values(problem, case, speed=0.9))


def test_the_limits_of_every_point_at_once_give_the_same_verdicts():
    # a sweep evaluates the limits of all its points in one mapped call (Tightening.limits): the torque row's limit
    # k_s P / w (eq. (8)) at P, 1.1 P and 0.9 P is the base limit times 1, 1.1 and 0.9; a step to a higher power
    # tightens, a step down loosens, as point by point
    case = load_case(CASES / "ball_compressor.toml")
    problem = Problem(get_coupling("ball").formulation("design"))
    power = tightening(problem.posed, ["power"])
    points = np.array([_values(problem, case, power=f) for f in (1.0, 1.1, 0.9)])
    limits, scales = power.limits(points)
    assert limits.shape == (1, 3)
    np.testing.assert_allclose(limits[0] / limits[0, 0], [1.0, 1.1, 0.9], rtol=1e-12)
    for j in range(3):
        for k in range(3):
            verdict = power.holds(limits[:, j], scales[:, j], limits[:, k], scales[:, k])
            assert verdict == power.tightened(points[j], points[k]) == (j == k or (j, k) in ((0, 1), (2, 0), (2, 1)))
