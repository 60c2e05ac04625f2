"""The motor's run-up to the weights' engagement, in closed form (clutchopt/simulate/motor_phases.py)."""

import math
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from clutchopt.simulate.engine import Model, simulate
from clutchopt.simulate.laws import CentrifugalFriction, InductionMotor, Load

MOTOR = InductionMotor(synchronous_speed=104.71975511965977, breakdown_torque=37.0, breakdown_slip=0.2, inertia=0.012)
EFFECTS = ("slip_friction", "motor_curve", "spring_preload", "gravity", "lockup", "friction_heat")


def _wedge_start(**changes) -> Model:
    """wedge_motor_start's drive and a design of its sweep (engaging at 36.65 rad/s), at the check's rtol."""
    model = Model(CentrifugalFriction(0.000983933079943879, 1343.3628213416189), 0.5, Load(5.0), EFFECTS,
                  motor=MOTOR, heat_capacity=1400.0, conductance=4.0, rtol=1e-6)
    return replace(model, **changes)


def _time_to(speed: float) -> float:
    """J_m times the integral of dw / T_m(w) from rest: the motor's own run-up, by quadrature."""
    return MOTOR.inertia * quad(lambda w: 1.0 / MOTOR(w), 0.0, speed, epsabs=0.0, epsrel=1e-13, limit=200)[0]


def test_the_run_up_to_engagement_is_the_motor_s_own_to_rounding():
    # LSODA at the check's rtol (1e-7) put the engagement 4e-10 off; the closed form is the quadrature's to rounding
    model = _wedge_start()
    engagement = math.sqrt(model.law.engagement_squared)
    columns = simulate(model).columns
    run_up = columns["w_driver"] <= engagement
    k = int(np.flatnonzero(run_up)[-1])
    assert columns["w_driver"][k] == engagement
    assert columns["t"][k] == pytest.approx(_time_to(engagement), rel=1e-14, abs=0.0)
    for j in np.linspace(1, k - 1, 7).astype(int):  # every sample on the way: the time the quadrature gives its speed
        assert columns["t"][j] == pytest.approx(_time_to(columns["w_driver"][j]), rel=1e-12, abs=0.0)
    assert np.array_equal(columns["slip"][:k + 1], columns["w_driver"][:k + 1])  # the driven half at rest
    for name in ("friction_work", "source_work", "temperature_rise"):
        assert not columns[name][:k + 1].any(), name
    assert not columns["friction_torque"][columns["w_driver"] < engagement].any()  # (at w_e: K (w_e^2 - w_e^2))


def test_a_start_with_its_run_up_in_closed_form_is_lsoda_s_to_its_tolerance():
    # the same start integrated by LSODA throughout (an integrator forced: no closed form), both at rtol 1e-12
    model = _wedge_start(rtol=1e-12)
    closed, integrated = simulate(model).headline, simulate(replace(model, integrator="LSODA")).headline
    for name in ("start_time", "friction_work", "lock_up_speed", "temperature_rise"):
        assert closed[name] == pytest.approx(integrated[name], rel=1e-11), name
    assert closed["locks_up"] and integrated["locks_up"]


def test_a_start_the_load_does_not_hold_at_rest_is_integrated():
    # without a load the driven half breaks away at once: the run-up is a slipping phase, not the motor's alone
    model = _wedge_start(load=Load(0.0))
    head = simulate(model).headline
    reference = simulate(replace(model, integrator="LSODA")).headline
    assert head["start_time"] == reference["start_time"] and head["friction_work"] == reference["friction_work"]


def test_the_locked_drive_is_the_motor_s_against_the_load_to_rounding():
    # (J + J_m) dw/dt = T_m(w) - L after lock-up: time, work from the driving half and the cooling by quadrature
    model = _wedge_start()
    columns = simulate(model).columns
    locked = np.flatnonzero(columns["phase"] == "stick")
    first = locked[0]
    t0, w0, source0, rise0 = (columns[name][first] for name in ("t", "w_driver", "source_work", "temperature_rise"))
    inertia, load = model.inertia + MOTOR.inertia, model.load.torque
    accelerating = locked[MOTOR(columns["w_driver"][locked]) - load > 0.05 * (MOTOR(w0) - load)]  # (nearer the
    for j in np.linspace(locked[1], accelerating[-1], 7).astype(int):  # steady speed the quadrature is the worse)
        w = columns["w_driver"][j]  # (a speed to rounding: a time to 1e-15 s)
        time = quad(lambda v: inertia / (MOTOR(v) - load), w0, w, epsabs=0.0, epsrel=1e-13, limit=200)[0]
        carried = quad(lambda v: (load + model.inertia * (MOTOR(v) - load) / inertia) * v * inertia / (MOTOR(v) - load),
                       w0, w, epsabs=0.0, epsrel=1e-13, limit=200)[0]
        assert columns["t"][j] - t0 == pytest.approx(time, rel=1e-11, abs=1e-15)
        assert columns["source_work"][j] - source0 == pytest.approx(carried, rel=1e-11, abs=1e-11)
        cooled = rise0 * math.exp(-model.conductance / model.heat_capacity * (columns["t"][j] - t0))
        assert columns["temperature_rise"][j] == pytest.approx(cooled, rel=1e-14)
    assert not columns["slip"][locked].any()
    assert np.all(columns["friction_work"][locked] == columns["friction_work"][first])
    tight = replace(model, rtol=1e-13)  # its end, near the steady speed, against LSODA's (both starts at 1e-13)
    closed, integrated = simulate(tight).columns, simulate(replace(tight, integrator="LSODA")).columns
    for name, rel in (("t", 1e-13), ("w_driver", 1e-13), ("source_work", 1e-12), ("temperature_rise", 1e-11)):
        assert closed[name][-1] == pytest.approx(integrated[name][-1], rel=rel), name


@pytest.mark.parametrize("share", [1e-9, 1e-3])
def test_a_locked_drive_at_a_light_load_keeps_its_accuracy(share):
    # review: at L = 1e-9 T_k the closed form's terms (s - s_0 and k s_2 log1p(x), s_2 ~ 2 s_k T_k / L) cancelled to
    # 4e-8 of w_s; a load that light is left to LSODA. Against DOP853 at rtol 1e-13 on the same samples.
    from scipy.integrate import solve_ivp

    motor = InductionMotor(100.0, 100.0, 0.2, 0.05)
    model = Model(CentrifugalFriction(3 * 100.0 / (100.0**2 - 50.0**2), 50.0**2), 0.5, Load(share * 100.0),
                  EFFECTS[:3] + EFFECTS[4:], motor=motor, heat_capacity=1000.0, conductance=1.0, rtol=1e-11)
    columns = simulate(model).columns
    stick = np.flatnonzero(columns["phase"] == "stick")
    t, w = columns["t"][stick], columns["w_driver"][stick]
    load, inertia = model.load.torque, model.inertia + motor.inertia
    exact = solve_ivp(lambda _, y: [(motor(y[0]) - load) / inertia], (t[0], t[-1]), [w[0]], t_eval=t, rtol=1e-13,
                      atol=1e-12, method="DOP853").y[0]
    assert len(stick) > 10 and np.max(np.abs(w - exact)) / motor.synchronous_speed < 1e-9


def test_a_locked_drive_whose_samples_cross_an_event_is_left_to_the_integrator():
    from clutchopt.simulate.engine import _Run
    from clutchopt.simulate.motor_phases import locked

    model = _wedge_start()
    run = _Run(model)
    y0 = np.array([95.0, 0.0, 6000.0, 9000.0, 3.0])
    quiet = lambda t, y: y[0] - 200.0  # noqa: E731 - never reached
    quiet.terminal, quiet.direction = True, 1
    phase = locked(run, 10.0, y0, 12.0, 1e-3, [quiet])
    assert phase.status == "end" and phase.t[-1] == 12.0 and 95.0 < phase.y[0, -1] < MOTOR.synchronous_speed
    crossed = lambda t, y: y[0] - 0.5 * (95.0 + phase.y[0, -1])  # noqa: E731 - crosses halfway
    crossed.terminal, crossed.direction = True, 1
    assert locked(run, 10.0, y0, 12.0, 1e-3, [crossed]) is None
    assert locked(run, 10.0, y0 * [1.0, 0.0, 1.0, 1.0, 1.0] + [0.0, 1e-3, 0.0, 0.0, 0.0], 12.0, 1e-3, [quiet]) is None


def test_newton_stops_where_its_steps_are_rounding():
    # a time whose residual is rounding above the roots' own (the locked drive's is a sum of larger terms) stops
    # once its steps no longer shrink, not after NEWTON_STEPS (the lever's locked drive took 60, 0.5 ms)
    from clutchopt.simulate.motor_phases import NEWTON_STEPS, _newton

    calls = []

    def time_at(x):
        calls.append(1)
        return -x + 3e-15 * np.sin(1e16 * x)  # falls (concave but for noise of the last bits), 3e-15 at most

    targets = np.linspace(0.0, 0.9, 50)
    roots = _newton(time_at, lambda x: np.ones_like(x), targets, 0.0)
    assert np.all(np.abs(roots + targets) <= 1e-14)
    assert len(calls) <= 5 < NEWTON_STEPS
