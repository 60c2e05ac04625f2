"""The drive's start-time proof by momentum (clutchopt/optimise/proofs.py, docs/start_up.md "A start no coupling can
make in time: a proof"): d(J_m w_a + J w)/dt = T_m - T_r <= T_k - T_r, so the start takes at least
((J + J_m) w_L,min - J_m w_s) / (T_k - T_c,min); a proven case is `infeasible` without a start-up solve."""

import math

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.proofs import shortest_start, start_up_proofs
from tests.conftest import CASES

RPM = math.pi / 30


def _wedge_bound() -> float:
    """cases/wedge_motor_start.toml: J 0.5, J_m 0.012 kg m^2, w_L,min 900 rpm (90 % of w_s 1000 rpm), T_k 37 N m,
    T_c 5 N m: (0.512 * 94.24778 - 0.012 * 104.71976) / 32 = (48.25486 - 1.25664) / 32 = 1.468694 s, against the
    energy bound 0.512 * 94.24778^2 / 2 / P_peak (P_peak about 3.5 kW: 0.65 s) and momentum without the load
    0.512 * 94.24778 / 37 = 1.304 s."""
    return (0.512 * 900 * RPM - 0.012 * 1000 * RPM) / (37.0 - 5.0)


def test_the_momentum_bound_by_hand():
    case = load_case(CASES / "wedge_motor_start.toml")
    v = case.values
    shortest, how = shortest_start(v["driven_inertia"], v["motor_inertia"], v["min_lock_up_speed"],
                                   v["synchronous_speed"], v["breakdown_torque"], v["breakdown_slip"], v["load_torque"])
    assert shortest == pytest.approx(_wedge_bound(), rel=1e-12)
    assert shortest == pytest.approx(1.468694, abs=1e-6)
    assert "less the machine's least load 5 N*m" in how
    # a load that drives the machine (T_c,min < 0): the momentum bound without the load, (J + J_m) w_L / (T_k + 3)
    driving, _ = shortest_start(0.5, 0.012, 900 * RPM, 1000 * RPM, 37.0, v["breakdown_slip"], -3.0)
    assert driving == pytest.approx(0.512 * 900 * RPM / 40.0, rel=1e-12)


def test_a_start_just_outside_the_bound_is_proven_without_a_start_up_solve_and_one_inside_is_not():
    case = load_case(CASES / "wedge_motor_start.toml")
    problem = case_problem(case)
    bound = _wedge_bound()
    outside = case.with_values(max_start_time=0.999 * bound)
    solution = problem.solve(outside)
    assert solution.status == "infeasible"
    assert solution.diagnosis.startswith("proven infeasible: bringing 0.512 kg*m^2 to 900 rpm takes at least 1.469 s "
                                         "by momentum")
    assert solution.diagnosis == "proven infeasible: " + start_up_proofs(outside)[0]  # said once, no retry
    assert solution.starts == ()
    assert solution.solver.name == "proof" and solution.solver.solves == 1  # the papers' sizing, shown as the design
    assert solution.start_up is None and solution.design["spring_preload"] >= 0
    assert not start_up_proofs(case.with_values(max_start_time=1.001 * bound))


def test_a_design_found_starts_no_faster_than_the_bound():
    """The wedge's shortest start is about 2.05-2.5 s (its overload_torque and engagement window bind, measured):
    at 2.5 s a design is found, and its simulated start locks up at w_L >= 900 rpm no sooner than the bound at
    its own lock-up speed."""
    case = load_case(CASES / "wedge_motor_start.toml").with_values(max_start_time=2.5)
    solution = case_problem(case).solve(case)
    assert solution.status == "optimal"
    figures = solution.start_up
    w_l = float(figures["lock_up_speed_simulated"])
    assert w_l >= 900 * RPM * (1 - 1e-6)
    at_own = (0.512 * w_l - 0.012 * 1000 * RPM) / 32.0
    assert float(figures["start_time_simulated"]) >= at_own == pytest.approx(1.5077, abs=1e-3)


def test_a_load_that_drives_the_machine_bounds_the_start_by_momentum_alone():
    """J = 10, J_m = 0.1 kg m^2 to w_L = 150 rad/s, T_k = 100 N m at s_k = 0.2 (w_s = 157 rad/s), the load down to
    -200 N m (driving the machine): it puts in energy of its own, so the motor's peak power (12.9 kW: an 8.8 s bound)
    bounds nothing; momentum does, 10.1 x 150 / (100 + 200) = 5.05 s (with the rotor's own momentum taken off,
    (1515 - 15.7) / 300 = 5.00 s, less)."""
    shortest, how = shortest_start(10.0, 0.1, 150.0, 157.0, 100.0, 0.2, -200.0)
    assert shortest == pytest.approx(10.1 * 150.0 / 300.0, rel=1e-12) and "peak power" not in how
    assert shortest_start(10.0, 0.1, 150.0, 157.0, 100.0, 0.2, 0.0)[0] == pytest.approx(10.1 * 150.0 / 100.0)


def test_a_point_the_drive_proves_is_not_followed_by_continuation(monkeypatch):
    """wedge_motor_start swept over max_start_time 3, 1.4, 1.3 s: the momentum bound (1.469 s) proves the last two
    before any solve; continuation from the first point's design towards them (start-up solves whose result the
    proof makes moot, uncounted) was still run, about 0.1-0.2 s a point."""
    import clutchopt.optimise.sweep as sweep_module
    from clutchopt.optimise.sweep import Sweep
    from clutchopt.optimise.sweep_grid import parse_vary

    followed = []
    real = sweep_module.continued
    monkeypatch.setattr(sweep_module, "continued", lambda *args: followed.append(args[3]) or real(*args))
    case = load_case(CASES / "wedge_motor_start.toml")
    result = Sweep(case, [parse_vary("max_start_time=3,1.4,1.3", case.coupling, case.quantities)]).run(progress=False)
    assert result.frame["status"].tolist() == ["optimal", "infeasible", "infeasible"]
    assert followed == []


def test_through_an_elastic_link_the_rotor_s_inertia_is_not_counted():
    """The cable's start ends when the machine reaches w_L, the rotor at any speed w_a >= 0 and the link twisted:
    momentum J w_L + J_m w_a <= (T_k - T_c,min) t (+ J_m w_s gathered at rest) bounds the start by J alone. J = 10,
    J_m = 2 kg m^2, w_L = 150 rad/s, T_k = 100 N m, s_k = 0.2, w_s = 157 rad/s, load 0: rigid (10 + 2) x 150 / 100 =
    18 s; elastic 10 x 150 / 100 = 15 s (the energy bound, 0.5 x 10 x 150^2 / 12,872 W = 8.7 s, is less)."""
    assert shortest_start(10.0, 2.0, 150.0, 157.0, 100.0, 0.2, 0.0)[0] == pytest.approx(18.0, rel=1e-12)
    assert shortest_start(10.0, 2.0, 150.0, 157.0, 100.0, 0.2, 0.0, rigid=False)[0] == pytest.approx(15.0, rel=1e-12)
    cable = load_case(CASES / "cable_motor_start.toml")
    proofs = start_up_proofs(cable.with_values(breakdown_torque=0.5 * cable.values["load_torque"]))
    assert not any("less than the machine's" in proof for proof in proofs)  # no torque proof through a link
