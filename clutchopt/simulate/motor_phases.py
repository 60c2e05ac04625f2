"""The phases of a start in which only the induction motor moves the drive, in closed form: the motor's run-up to
the weights' engagement and the locked drive after lock-up (a constant load).

Kloss's curve T_m = 2 T_k s s_k / (s^2 + s_k^2) at slip s = 1 - w / w_s makes both separable:

- *run-up*: below its engagement speed a centrifugal coupling passes no torque, so while the driven half stands and
  the weights have not engaged, J_m dw/dt = T_m(w); the works and the temperature rise stay zero. With u = ln s,
  t(u) = J_m w_s / (2 T_k s_k) [(1 - e^{2u}) / 2 - s_k^2 u];
- *locked*: (J + J_m) dw/dt = T_m(w) - L, the load L constant. T_m - L = L (s - s_1)(s_2 - s) / (s^2 + s_k^2),
  s_1,2 = s_k (T_k / L -+ sqrt((T_k / L)^2 - 1)) (s_1 s_2 = s_k^2); between them the drive speeds up towards
  s_1, its steady slip. With F(s) = -s + (s_1 + s_2) / (s_2 - s_1) [s_1 ln(s - s_1) - s_2 ln(s_2 - s)],
  t(s) = (J + J_m) w_s / L [F(s_0) - F(s)], in v = ln(s - s_1). The clutch carries L + J dw/dt, so the work from
  the driving half grows by L int w dt + J (w^2 - w_0^2) / 2, int w dt = (J + J_m) w_s^2 / L [G(s_0) - G(s)],
  G = int (1 - s)(s^2 + s_k^2) / ((s - s_1)(s_2 - s)) ds in partial fractions; the temperature rise decays as
  e^{-G t / C} and the friction work stays.

In both, t is concave and falls with the variable (u, v), so Newton's method from the phase's start (t = 0) stays at
or right of each root and converges to it monotonically: the speed at each sample time to rounding. The samples are
at the times LSODA's spans take (:func:`clutchopt.simulate.spans.sample_times`), so the mesh the next solve adapts
to them sees the phases as before, and the phase's events are evaluated on them as on a span's: a locked drive whose
samples show the clutch breaking loose is integrated by LSODA after all. LSODA took 190-370 steps for the run-up and
90-160 for the locked drive (a fifth and a seventh of a check, docs/start_up.md) for what this gives to rounding.
"""

from __future__ import annotations

import math

import numpy as np

from clutchopt.simulate.laws import CentrifugalFriction
from clutchopt.simulate.spans import _crossings, _values, sample_times
from clutchopt.simulate.stepping import EPS, Phase

NEWTON_STEPS = 60  # at most (monotone and quadratic near the root: 4-7 from the phase's start on the cases)
STALLS = 1e-8  # steps below this that no longer shrink are rounding (from here quadratic convergence is 1e-16 away)
LIGHTEST_LOAD = 1e-3  # of the breakdown torque: below it the locked drive's terms cancel to eps T_k / L (1e-13 here)


def in_closed_form(run, y, rate_floor: float) -> bool:
    """Whether the rest phase from state ``y`` before the weights engage is the motor's run-up alone: a centrifugal
    coupling (no torque below engagement) on an induction motor, the driven half at rest and a load that keeps it
    there (positive at every time), no work or heat yet, an engagement speed the motor reaches above ``y``'s speed,
    and its acceleration above ``rate_floor`` (relative, the steady event's) all the way (Kloss's curve has one
    maximum, so at both ends)."""
    law, motor, load = run.m.law, run.motor, run.m.load
    if not (type(law) is CentrifugalFriction and law.torque_coefficient > 0.0 and _motor_alone(run)
            and y[1] == y[0] and not any(y[2:])):
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
    start = math.log1p(-y0[0] / w_s)
    origin = float(time_at(start))
    end = t0 + float(time_at(math.log1p(-engagement / w_s))) - origin
    last, status = (end, "event") if end <= bound else (bound, "end")
    times = np.concatenate([[t0], sample_times(t0, last, bound, span), [last]])
    u = _newton(time_at, lambda u: scale * (np.exp(2.0 * u) + s_k * s_k), times - t0 + origin, start)
    speeds = w_s * -np.expm1(u)
    speeds[0] = y0[0]
    if status == "event":
        speeds[-1] = engagement
    states = np.zeros((5, len(times)))
    states[0] = states[1] = speeds
    return Phase(times, states, status, event if status == "event" else None)


def locked(run, t0: float, y0: np.ndarray, bound: float, span: float, events: list) -> Phase | None:
    """The locked drive from (t0, y0) to ``bound`` (status ``end``), sampled as LSODA's spans would be; None where it
    is not in closed form (no motor, a load that varies, a drive that does not speed up towards the motor's steady
    slip, a load under LIGHTEST_LOAD of the breakdown torque: its time and work are differences of terms T_k / L times
    larger, s_2 growing with T_k / L) or one of ``events`` crosses zero on its samples (the clutch breaks loose: LSODA locates it)."""
    motor, load, model = run.motor, run.m.load, run.m
    if not (_motor_alone(run) and not load.over and LIGHTEST_LOAD * motor.breakdown_torque <= load.torque
            < motor.breakdown_torque and y0[1] == 0.0):
        return None
    s_k, w_s, torque = motor.breakdown_slip, motor.synchronous_speed, load.torque
    ratio = motor.breakdown_torque / torque
    s_2 = s_k * (ratio + math.sqrt((ratio - 1.0) * (ratio + 1.0)))
    s_1 = s_k * s_k / s_2
    s_0 = 1.0 - y0[0] / w_s
    if not s_1 < s_0 < s_2:
        return None
    inertia = model.inertia + run.driver_inertia
    scale, k = inertia * w_s / torque, (s_1 + s_2) / (s_2 - s_1)
    start = math.log(s_0 - s_1)

    def time_at(v):  # t(v) = scale (F(s_0) - F(s)), the logarithms' differences formed as such
        s = s_1 + np.exp(v)
        return scale * ((s - s_0) + k * (s_1 * (start - v) - s_2 * np.log1p((s - s_0) / (s_2 - s))))

    def rate_at(v):  # -dt/dv
        s = s_1 + np.exp(v)
        return scale * (s * s + s_k * s_k) / (s_2 - s)

    times = np.concatenate([[t0], sample_times(t0, bound, bound, span), [bound]])
    v = _newton(time_at, rate_at, times - t0, start)
    v[0], s = start, s_1 + np.exp(v)
    s[0] = s_0
    speeds = w_s * (1.0 - s)
    speeds[0] = y0[0]
    polynomial = lambda x: (1.0 - x) * (x * x + s_k * s_k)  # noqa: E731 - (1 - s)(s^2 + s_k^2) / ((s - s_1)(s_2 - s))
    left, right = polynomial(s_1) / (s_2 - s_1), polynomial(s_2) / (s_2 - s_1)  # its partial fractions
    grown = ((s_0 - s) * (0.5 * (s_0 + s) + s_1 + s_2 - 1.0)  # G(s_0) - G(s)
             - left * (v - start) - right * np.log1p((s - s_0) / (s_2 - s)))  # (v: s - s_1 near the steady slip)
    states = np.empty((5, len(times)))
    states[0], states[1], states[2] = speeds, 0.0, y0[2]
    states[3] = y0[3] + inertia * w_s * w_s * grown + 0.5 * model.inertia * (speeds - y0[0]) * (speeds + y0[0])
    states[4] = y0[4] * np.exp(-model.conductance / model.heat_capacity * (times - t0)) if run.heat else y0[4]
    states[:, 0] = y0
    if any(_crossings(event, _values(event, times, states)).any() for event in events):
        return None
    return Phase(times, states, "end")


def _motor_alone(run) -> bool:
    """An induction motor drives and the integrator is the engine's choice (a benchmark's forced one integrates)."""
    return run.motor is not None and run.m.integrator == "auto"


def _newton(time_at, rate_at, targets: np.ndarray, start: float) -> np.ndarray:
    """x with time_at(x) = each target (>= 0; time_at(start) = 0, concave and falling, rate_at = -its slope), by
    Newton's method from ``start``: until the steps are within rounding of x, or small and no longer shrinking (the
    residual is rounding: the locked drive's time is a sum of terms larger than it)."""
    x, last = np.full_like(targets, start), np.inf
    for _ in range(NEWTON_STEPS):
        step = (time_at(x) - targets) / rate_at(x)
        x = x + step
        largest = float(np.max(np.abs(step), initial=0.0))
        if not np.any(np.abs(step) > 4.0 * EPS * np.maximum(np.abs(x), 1.0)) or STALLS > largest >= last:
            break
        last = largest
    return x
