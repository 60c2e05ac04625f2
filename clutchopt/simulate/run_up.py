"""The motor's run-up to the weights' engagement, in closed form.

Below its engagement speed a centrifugal coupling passes no torque, so while the driven half stands and the weights
have not engaged, the only motion is the motor's own, J_m dw/dt = T_m(w), Kloss's T_m = 2 T_k s s_k / (s^2 + s_k^2)
at slip s = 1 - w / w_s; the works and the temperature rise stay zero (no slip power, nothing to conduct away). With
u = ln s this is separable:

    t(u) = J_m w_s / (2 T_k s_k) [(1 - e^{2u}) / 2 - s_k^2 u],

so the engagement time is exact, and the speed at each sample time is the root of t(u) = tau, found by Newton's
method from u = 0: t is concave and falls with u, so each iterate stays at or right of the root and converges to
it monotonically. LSODA took 190-370 steps (a fifth of a check, docs/start_up.md) for what this gives to rounding.
The samples are at the times LSODA's spans take (:func:`clutchopt.simulate.spans.sample_times`), so the mesh the
next solve adapts to them sees the phase as before.
"""

from __future__ import annotations

import math

import numpy as np

from clutchopt.simulate.laws import CentrifugalFriction
from clutchopt.simulate.spans import sample_times
from clutchopt.simulate.stepping import EPS, Phase

NEWTON_STEPS = 60  # at most (monotone and quadratic near the root: 5-8 from u = 0 on the cases)


def in_closed_form(run, y, rate_floor: float) -> bool:
    """Whether the rest phase from state ``y`` before the weights engage is the motor's run-up alone: a centrifugal
    coupling (no torque below engagement) on an induction motor, the driven half at rest and a load that keeps it
    there (positive at every time), no work or heat yet, an engagement speed the motor reaches above ``y``'s speed,
    and its acceleration above ``rate_floor`` (relative, the steady event's) all the way (Kloss's curve has one
    maximum, so at both ends)."""
    law, motor, load, model = run.m.law, run.motor, run.m.load, run.m
    if not (type(law) is CentrifugalFriction and law.torque_coefficient > 0.0 and motor is not None
            and model.integrator == "auto" and y[1] == y[0] and not any(y[2:])):
        return False
    if min(load.values) <= 0.0 if load.over else load.torque <= 0.0:
        return False
    engagement = math.sqrt(law.engagement_squared)
    if not 0.0 <= y[0] < engagement < motor.synchronous_speed:
        return False
    scale = run.time_scale / (run.w_ref * motor.inertia)
    return min(motor(y[0]), motor(engagement)) * scale > rate_floor


def run_up(run, t0: float, y0: np.ndarray, bound: float, span: float, event: int) -> Phase:
    """The run-up from (t0, y0) to the engagement (status ``event``, the terminal event ``event``) or to ``bound``
    (``end``), sampled as LSODA's spans would be from ``t0`` (``span``: their first FIRST_SAMPLES samples' time)."""
    motor = run.motor
    s_k, w_s = motor.breakdown_slip, motor.synchronous_speed
    scale = motor.inertia * w_s / (2.0 * motor.breakdown_torque * s_k)

    def time_at(u):
        return scale * (-0.5 * np.expm1(2.0 * u) - s_k * s_k * u)

    engagement = math.sqrt(run.m.law.engagement_squared)
    origin = float(time_at(math.log1p(-y0[0] / w_s)))
    end = t0 + float(time_at(math.log1p(-engagement / w_s))) - origin
    last, status = (end, "event") if end <= bound else (bound, "end")
    times = np.concatenate([[t0], sample_times(t0, last, bound, span), [last]])
    speeds = w_s * -np.expm1(_roots(time_at, times - t0 + origin, scale, s_k))
    speeds[0] = y0[0]
    if status == "event":
        speeds[-1] = engagement
    states = np.zeros((5, len(times)))
    states[0] = states[1] = speeds
    return Phase(times, states, status, event if status == "event" else None)


def _roots(time_at, targets: np.ndarray, scale: float, s_k: float) -> np.ndarray:
    """u with time_at(u) = each target (>= 0), by Newton's method from u = 0 (time_at' = -scale (e^{2u} + s_k^2))."""
    u = np.zeros_like(targets)
    for _ in range(NEWTON_STEPS):
        step = (time_at(u) - targets) / (scale * (np.exp(2.0 * u) + s_k * s_k))
        u = u + step
        if not np.any(np.abs(step) > 4.0 * EPS * np.maximum(np.abs(u), 1.0)):
            break
    return u
