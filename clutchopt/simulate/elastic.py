"""The start-up of a coupling that is an elastic link (the cable coupling), simulated with its dynamics.

An induction motor (rotor J_m) drives the machine (J, load T_c) through a link whose torque T(w_a, theta) depends
on the driving speed and the relative twist theta of the halves (``clutchopt.model.ElasticLaw``), with an
equivalent viscous damping c = 2 zeta sqrt(k J_red) (k the link's stiffness at zero twist and the driving speed of
the design, J_red = J J_m / (J + J_m); c = 0 where k <= 0, its limit as k falls to 0):

    J_m dw_a/dt = T_m(w_a) - T(w_a, theta) - c (w_a - w)
    J   dw/dt   = T(w_a, theta) + c (w_a - w) - T_c(w, t)      (the machine rests while that is <= 0 at w = 0)
    dtheta/dt   = w_a - w,    dL/dt = c (w_a - w)^2             (L: the energy the link's damping takes)

The start ends when the machine reaches the start speed (the case's min_lock_up_speed). This is the independent
check of the NLP's start, which takes the link as quasi-static (the twist where T meets the locked drive's torque).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import partial
from types import SimpleNamespace
from typing import Callable

import numpy as np

from clutchopt.backend import where
from clutchopt.model import ElasticLaw
from clutchopt.simulate.engine import FIRST_SPAN, MAX_STEPS, SimulationResult, largest
from clutchopt.simulate.laws import InductionMotor, Load, positive_part
from clutchopt.simulate.on_floats import bound, on_numpy, parametrised
from clutchopt.simulate.spans import integrate_spans
from clutchopt.simulate.stepping import Budget, integrate

SWING_SAMPLES = 96  # samples of a swing at least (of its period at zero twist, some twice the swings' in a start):
# their extremes are found on the samples, not on intervals integrated again
SWING_NODES = 10  # samples an extreme's interpolant runs through (degree 9): with 96 a swing it is as accurate as
# LSODA's own samples at most extremes, whose states are then not integrated again (cable_motor_start: 17 odeint
# runs and 2,966 right-hand sides a check, not 53 and 4,460 with 48 a swing and 6)
STRESS_LAG = 1e-6  # of the start's time scale: the step of the stress rate's central difference (its peak's event)


@dataclass
class ElasticModel:
    """One start of an elastic link, SI."""

    link: ElasticLaw  # the coupling's link: its torque and stress at (design, case, driving speed, twist)
    design: SimpleNamespace  # its design variables
    numbers: SimpleNamespace  # the case's quantities
    damping: float  # c, N*m*s/rad
    inertia: float  # J of the machine
    load: Load
    motor: InductionMotor
    target: float  # start speed of the machine, rad/s
    largest_twist: float  # where the link's torque stops growing: beyond it the cables overturn
    effects: tuple[str, ...] = ()
    rtol: float = 1e-10
    end_time: float | None = None
    integrator: str = "LSODA"  # "DOP853" or "Radau" for a reference run (docs/start_up.md, "The check's tolerance")
    all_extremes: bool = False  # every extreme of the twist and stress sampled, not only those that can be the
    # largest (clutchopt.simulate.spans.PEAK_MARGIN): a start guess's samples are the NLP's initial states

    def torque(self, speed, twist):
        """Torque through the link at a driving speed and a twist (numbers, arrays or symbols alike)."""
        return self.link.torque(self.design, self.numbers, speed, twist)

    def stress(self, speed, twist):
        """Stress of the link's most loaded element (numbers, arrays or symbols alike)."""
        return self.link.stress(self.design, self.numbers, speed, twist)


def _swing_period(m: ElasticModel) -> float:
    """2 pi sqrt(J_red / k): the period of the halves' torsional swing on the link's stiffness at zero twist and
    synchronous speed (the stiffest it is in a start), J_red = J J_m / (J + J_m)."""
    h = 1e-6 * m.largest_twist
    speed = m.motor.synchronous_speed
    stiffness = (m.torque(speed, h) - m.torque(speed, -h)) / (2.0 * h)
    reduced = m.inertia * m.motor.inertia / (m.inertia + m.motor.inertia)
    return 2.0 * math.pi * math.sqrt(reduced / stiffness) if stiffness > 0 else math.inf


def link_rates(m: ElasticModel, wa, w, theta, load) -> list:
    """The rates of (w_a, w, theta, L) (the equations above; ``load`` T_c at the state) at numbers, at samples
    (arrays) or at symbols: the machine at rest (w <= 0) is not driven backwards, the load a reaction up to its
    value."""
    link = m.torque(wa, theta) + m.damping * (wa - w)
    net = link - load
    net = where(w <= 0.0, positive_part(net), net)
    return [(m.motor(wa) - link) / m.motor.inertia, net / m.inertia, wa - w, m.damping * (wa - w) ** 2]


def stress_rate(m: ElasticModel, lag: float, wa, w, theta, load):
    """The stress's rate along the motion as a central difference over +-``lag`` (the stress grows with the
    driving speed too, so its peak lags the twist's: sampled there, it was missed by 1e-5), at numbers, samples or
    symbols."""
    dw, _, dtheta, _ = link_rates(m, wa, w, theta, load)
    return m.stress(wa + lag * dw, theta + lag * dtheta) - m.stress(wa - lag * dw, theta - lag * dtheta)


def _on_floats(m: ElasticModel, lag: float) -> tuple[Callable, Callable]:
    """:func:`link_rates` and :func:`stress_rate` of ``m`` as functions of (w_a, w, theta, T_c) on floats: traced
    once per structure of the model (its numbers, the design's and the case's among them, parameters) and written
    out (clutchopt.simulate.on_floats; the generic equations were two thirds of a check), each compared with its
    equations at probes; the equations where they cannot be traced."""
    w, twist, load = m.motor.synchronous_speed, m.largest_twist, m.motor.breakdown_torque
    probes = [(0.0, 0.0, 0.0, 0.0), (0.0, -1e-3 * w, 0.1 * twist, 0.5 * load), (0.5 * w, 0.4 * w, 0.1 * twist, 0.0),
              (w, 0.9 * w, -0.5 * twist, 0.5 * load), (w, w, twist, load)]  # (at rest, as it swings, beyond)
    made = []
    run_free = replace(m, effects=(), end_time=None, integrator="LSODA", all_extremes=False)  # the run's settings
    # (its end, integrator, samples, the effects it reports) enter no equation: one trace for a guess and a check
    for equations, objects in ((link_rates, (run_free,)), (stress_rate, (run_free, lag))):
        reference = partial(equations, *objects)
        made.append(bound(partial(partial, equations), (0, 0, 0, 0), parametrised(*objects),
                          ("elastic", equations.__name__), reference, probes,
                          fallback=lambda *point, reference=reference: on_numpy(reference, point)))
    return made[0], made[1]


def simulate_elastic(model: ElasticModel) -> SimulationResult:
    """The start from rest by LSODA (its stiff mode takes the link's fast twist where it is stiff), stepped by
    :mod:`clutchopt.simulate.stepping` within the same budget of steps as a slipping coupling's; the twist's
    extremes (relative speed zero) and the stress's (its rate along the motion zero) are sampled where they occur,
    so that the peak stress is not missed: where the samples resolve the swings, only those that can be the largest
    (``all_extremes``: every one)."""
    m = model
    motor = m.motor
    time_scale = (m.inertia + motor.inertia) * m.target / max(motor.breakdown_torque, 1e-300)

    lag = STRESS_LAG * time_scale
    fast_rates, fast_stress = _on_floats(m, lag)

    load = m.load.on_floats()

    def on_state(fast):  # (odeint, which copies the rates at once: ``fast.into``, into one array; not solve_ivp)
        def rates(t, y):
            """At a solver's state, read as numbers (arithmetic on NumPy scalars costs twice)."""
            wa, w, theta, _ = y.tolist()
            return fast(wa, w, theta, load(t, w))
        return rates

    def started(t, y):
        return y[1] - m.target

    def overturned(t, y):
        return np.abs(y[2]) - m.largest_twist

    def twist_extreme(t, y):
        return y[0] - y[1]

    def stress_extreme(t, y):
        """:func:`stress_rate` at a state or at samples."""
        if isinstance(t, np.ndarray):
            return stress_rate(m, lag, y[0], y[1], y[2], m.load(t, y[1]))
        wa, w, theta = float(y[0]), float(y[1]), float(y[2])
        return fast_stress(wa, w, theta, load(t, w))

    started.terminal, started.direction = True, 1
    overturned.terminal, overturned.direction = True, 1
    twist_extreme.terminal, twist_extreme.direction = False, 0
    stress_extreme.terminal, stress_extreme.direction = False, -1
    bound = m.end_time if m.end_time is not None else 1e3 * time_scale
    speed_scale = motor.synchronous_speed
    atol = m.rtol * np.array([speed_scale, speed_scale, m.largest_twist, 1.0 + m.inertia * speed_scale**2])
    swing = _swing_period(m) / SWING_SAMPLES
    if not m.all_extremes and math.isfinite(swing) and swing >= FIRST_SPAN * time_scale:  # samples that resolve
        # the swings: of their extremes only those that can be the largest twist and stress are located
        twist_extreme.figure = lambda y: np.abs(y[2])
        stress_extreme.figure = lambda y: np.asarray(m.stress(y[0], y[2]), dtype=float)
    events = [started, overturned, twist_extreme, stress_extreme]
    if m.integrator == "LSODA":
        out = integrate_spans(on_state(getattr(fast_rates, "into", fast_rates)), None, 0.0, np.zeros(4), bound,
                              events, m.rtol, atol, Budget(MAX_STEPS),
                              FIRST_SPAN * time_scale, max(swing, FIRST_SPAN * time_scale),  # (a swing faster
                              SWING_NODES, extremes_interpolated=True)  # than 96e-3 of the start, as of a rotor
        # of 1e-9 kg m^2, is not sampled: its extremes on zooms)
    else:
        out = integrate(on_state(fast_rates), None, 0.0, np.zeros(4), bound, events, m.integrator, m.rtol, atol,
                        Budget(MAX_STEPS))
    t, y = out.t, out.y
    torque = m.torque(y[0], y[2]) + m.damping * (y[0] - y[1])  # the samples at once, as arrays
    stress = np.asarray(m.stress(y[0], y[2]), dtype=float)
    history = {"t": t, "w_driver": y[0], "w_driven": y[1], "slip": y[0] - y[1], "twist": y[2],
               "friction_torque": np.asarray(torque, dtype=float), "power_lost": m.damping * (y[0] - y[1]) ** 2,
               "friction_work": y[3], "temperature_rise": np.zeros_like(t), "stress": stress,
               "phase": np.full(len(t), "elastic", dtype=object)}
    done = out.status == "event" and out.event == 0
    if done:
        reason = ""
    elif out.status == "event":
        reason = (f"no start: the link twisted past {m.largest_twist:.4g} rad at {t[-1]:.4g} s, where its "
                  "torque stops growing (the cables overturn)")
    elif out.status == "failed":
        reason = f"integration failed: {out.message}"
    elif out.status == "budget":
        reason = (f"stopped after {MAX_STEPS} solver steps at t = {t[-1]:.6g} s, not yet at the start speed: the "
                  f"start is too long or too stiff to simulate (its time scale (J + J_m) w / T_k {time_scale:.3g} s, "
                  f"the motor's time constant {motor.time_constant:.3g} s)")
    else:
        reason = f"no start: the machine did not reach {m.target:.6g} rad/s by {bound:.6g} s"
    end = t[-1]
    headline = {
        "locks_up": done if out.status in ("event", "end") else None, "reason": reason,  # (budget, failed: no
        # verdict)
        "start_time": end if done else math.inf,
        "friction_work": float(y[3, -1]) if done else math.inf,
        "source_work": math.nan,
        "lock_up_speed": m.target if done else math.nan,
        "peak_slip_power": largest(history["power_lost"]),
        "peak_twist": float(np.abs(y[2]).max()),
        "peak_stress": float(stress.max()),
        "end_time": float(end),
        "total_friction_work": float(y[3, -1]),
        "final_driver_speed": float(y[0, -1]),
        "final_driven_speed": float(y[1, -1]),
        "effects": list(m.effects),
    }
    events = [{"time": end, "event": "start speed reached" if done else "stopped", "torque": float(torque[-1])}]
    return SimulationResult(history, headline, events)
