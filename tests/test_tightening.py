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
