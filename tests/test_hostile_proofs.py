"""Hostile cases for the drive's proofs (clutchopt/optimise/proofs.py): a proof may claim `infeasible` only where no
design exists. Each case here has a design (found by a solve with the proofs switched off, the command in the
docstring) or is checked against the hand numbers of the proof."""

import math
import tomllib

import pytest

from clutchopt.cases import parse_case
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.proofs import start_up_proofs
from clutchopt.start_up.equations import kloss_torque
from tests.conftest import CASES

RPM = math.pi / 30


def _wedge_with_profile(over: str, points: list[str], torque: list[str]):
    """cases/wedge_motor_start.toml (T_k 37 N m at s_k 0.2, w_s 1000 rpm, w_L,min 900 rpm, t_max 10 s) driving a
    machine whose load follows a profile."""
    data = tomllib.loads((CASES / "wedge_motor_start.toml").read_text())
    data["start_up"]["driven"] = {"load_profile": {"over": over, "points": points, "torque": torque}}
    return parse_case(data)


def test_the_motor_at_lock_up_by_hand():
    """Kloss T = 2 T_k s s_k / (s^2 + s_k^2) at 900 rpm (s = 0.1): 2 * 37 * 0.1 * 0.2 / (0.01 + 0.04) = 29.6 N m."""
    assert float(kloss_torque(900 * RPM, 1000 * RPM, 37.0, 0.2)) == pytest.approx(29.6, rel=1e-12)


def test_a_load_rising_after_the_start_is_no_proof():
    """A time profile at 5 N m until 10.5 s (after max_start_time 10 s), 33 N m from 20 s: the drive locks up by
    10 s against 5 N m, and 33 N m stays below T_k = 37 N m (motor_breakdown_torque met). The proof compared the
    motor's 29.6 N m at 900 rpm with the profile's largest value, 33 N m, and said `infeasible`; with the proofs off
    the solve finds an optimal design (0.7997 kg; /tmp: `clutchopt solve` of this case with start_up_proofs -> [])."""
    case = _wedge_with_profile("time", ["0 s", "10.5 s", "20 s"], ["5 N*m", "5 N*m", "33 N*m"])
    assert start_up_proofs(case) == []
    solution = case_problem(case).solve(case)
    assert solution.status == "optimal"  # every limit met by the float64 check of the simulated start
    assert min(c.margin for c in solution.constraints) >= -1e-6
    assert float(solution.start_up["start_time_simulated"]) <= 10.0 * (1 + 1e-6)


def test_a_breakaway_below_the_lock_up_speed_is_no_proof():
    """A speed profile of 30 N m at rest falling to 5 N m by 100 rpm: at or above 900 rpm the machine asks 5 N m,
    well within the motor's 29.6 N m there; 30 N m <= T_k = 37 N m. No proof from the drive's torque."""
    case = _wedge_with_profile("speed", ["0 rpm", "100 rpm", "990 rpm"], ["30 N*m", "5 N*m", "5 N*m"])
    assert not any("the motor gives at most" in proof for proof in start_up_proofs(case))


def test_a_load_above_the_motor_within_the_lock_up_window_is_still_proven():
    """The profile 33 N m from 4 s on (inside t_max 10 s) over time, or from 850 rpm on over speed: whenever the
    drive locks (t <= 10 s, w >= 900 rpm) the machine asks 33 N m > 29.6 N m; and a profile whose largest value
    (40 N m, after the start) passes T_k = 37 N m fails motor_breakdown_torque whatever the design."""
    over_time = _wedge_with_profile("time", ["0 s", "4 s", "20 s"], ["33 N*m", "33 N*m", "33 N*m"])
    assert any("29.6 N*m" in proof and "33 N*m" in proof for proof in start_up_proofs(over_time))
    over_speed = _wedge_with_profile("speed", ["0 rpm", "850 rpm", "990 rpm"], ["5 N*m", "33 N*m", "33 N*m"])
    assert any("29.6 N*m" in proof and "33 N*m" in proof for proof in start_up_proofs(over_speed))
    late = _wedge_with_profile("time", ["0 s", "10.5 s", "20 s"], ["5 N*m", "5 N*m", "40 N*m"])
    assert any("breakdown_torque 37 N*m" in proof and "40 N*m" in proof for proof in start_up_proofs(late))


def test_a_lining_proof_just_over_its_edge_shows_its_two_numbers_apart():
    """A constant-speed start (no motor_curve, no load) releases J w^2 / 2 = 0.25 (1000 pi / 30)^2 = 2741.556778 J
    whatever the design: max_friction_work 5e-7 below it read "at least 2741.56 J, above its limit 2741.56 J". The
    pair is now shown with the digits that tell its two numbers apart (7 here: 2741.557 and 2741.555)."""
    data = tomllib.loads((CASES / "wedge_motor_start.toml").read_text())
    data["start_up"]["effects"].remove("motor_curve")
    del data["start_up"]["driver"]
    data["start_up"]["driven"] = {"resisting_torque": "0 N*m"}
    work = 0.25 * (1000 * RPM) ** 2
    data["start_up"]["limits"]["max_friction_work"] = f"{work * (1 - 5e-7)!r} J"
    proof = next(p for p in start_up_proofs(parse_case(data)) if p.startswith("friction_work"))
    assert "at least 2741.557 J, above its limit 2741.555 J" in proof
