"""Torque laws of a start-up: the clutch's friction torque, the driven machine's load, the driving motor.

Friction laws give the magnitude of the kinetic friction torque as a function of the driving speed w_a and the
slip w_r = w_a - w (>= 0 during a start-up), and the static capacity at zero slip that lock-up must respect:
- ``ConstantFriction``: T (a dry plate clutch with constant pressing force);
- ``PaperFriction``: k (1 + e^{a w_r}), Simionescu & Oproescu eq. (6);
- ``CentrifugalFriction``: K (w_a^2 - w_e^2)^+, proportional to the net radial force of a weight (centrifugal less
  spring preload and, effect ``gravity``, its own weight): the weights ride on the driving half, so the torque
  follows the driving speed, not the slip, and vanishes below the engagement speed; see
  ``clutchopt.start_up.simulation``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from clutchopt.backend import fmax
from clutchopt.simulate.analytic import PaperTransient
from clutchopt.start_up.equations import coupling_torque, kloss_torque, table_segment


class _Law:
    """Defaults of a law: the net torque on the driven half is friction less load; the torque has no slip scale."""

    slip_scale = math.inf
    engagement_squared = 0.0  # w_e^2 below which the torque is zero (a kink the simulator makes a phase boundary)

    def excess(self, driver_speed, slip, load):
        return self.kinetic(driver_speed, slip) - load

    @property
    def own_excess(self) -> bool:
        """Whether the law writes excess() in a form of its own (no cancellation), not the kinetic torque less the
        load."""
        return type(self).excess is not _Law.excess

    def slopes(self, driver_speed, slip) -> tuple[float, float]:
        """(dT/dw_a, dT/dw_r) of the kinetic torque: the simulator's Jacobian."""
        return 0.0, 0.0

    def kinetic_samples(self, driver_speeds: np.ndarray, slips: np.ndarray) -> np.ndarray:
        """The kinetic torque at each sample of a run (its history), as :meth:`kinetic` gives it at each."""
        return np.array([self.kinetic(w, s) for w, s in zip(driver_speeds, slips)], dtype=float)

    def capacity_samples(self, driver_speeds: np.ndarray) -> np.ndarray:
        """The static capacity at each sample, as :meth:`capacity` gives it at each."""
        return np.array([self.capacity(w) for w in driver_speeds], dtype=float)


def positive_part(x):
    """(x)^+ = max(x, 0) at a number, samples (arrays) or a symbol, the one way the simulator writes it: a branch at
    a number (numpy.maximum costs a microsecond there; NaN stays NaN, as numpy.maximum and the traced right-hand
    sides give it), else fmax."""
    return (x if x > 0.0 or x != x else 0.0) if x.__class__ is float else fmax(x, 0.0)


@dataclass(frozen=True)
class ConstantFriction(_Law):
    torque: float
    name: str = "constant"

    def kinetic(self, driver_speed, slip):
        return self.torque

    def capacity(self, driver_speed):
        return self.torque

    def lockup_failure(self, speed, load, inertia):
        """Closed-form verdict at constant driving speed and constant load: None if the start-up locks up."""
        return None if self.torque > load else f"no lock-up: friction torque {self.torque:.6g} N*m <= load {load:.6g} N*m"


@dataclass(frozen=True)
class PaperFriction(_Law):
    k: float
    a: float
    name: str = "paper"

    def kinetic(self, driver_speed, slip):
        """k (1 + e^{a w_r}), eq. (6), exponent capped at 300 (1e130 k: the time spent above it is e^-300 of t_c)."""
        return self.k * (1.0 + math.exp(min(self.a * slip, 300.0)))

    def slopes(self, driver_speed, slip):
        """dT/dw_r = k a e^{a w_r} (zero above the cap)."""
        u = self.a * slip
        return 0.0, self.k * self.a * math.exp(u) if u < 300.0 else 0.0

    def excess(self, driver_speed, slip, load):
        """M_fr - M_r without cancellation: (2k - M_r) + k expm1(a w_r) for a > 0 (M_r ~ 2k near lock-up),
        (k - M_r) + k e^{a w_r} for a <= 0 (M_r ~ k and e^{a w_r} << 1)."""
        u = min(self.a * slip, 300.0)
        return (2.0 * self.k - load) + self.k * math.expm1(u) if self.a > 0 else (self.k - load) + self.k * math.exp(u)

    @property
    def slip_scale(self) -> float:
        """Slip over which the torque changes by a factor e: 1/|a|."""
        return 1.0 / abs(self.a) if self.a else math.inf

    def capacity(self, driver_speed):
        return 2.0 * self.k

    def lockup_failure(self, speed, load, inertia):
        return PaperTransient(inertia, self.k, self.a, load, speed).lockup_failure()


@dataclass(frozen=True)
class CentrifugalFriction(_Law):
    """T = K (w_a^2 - w_e^2)^+: a centrifugal coupling's torque follows its driving speed (clutchopt.formulations.
    start_up). K = dT/d(w_a^2) comes from the coupling's own torque equation (wedge eqs. 10-15, lever statics,
    ball eq. 8); w_e^2 = (F_s + m g) / (m r) holds the listed spring preload and gravity (zero without them)."""

    torque_coefficient: float  # K, N*m*s^2
    engagement_squared: float = 0.0  # w_e^2, (rad/s)^2
    name: str = "centrifugal"

    def kinetic(self, driver_speed, slip):
        """K (w_a^2 - w_e^2) once engaged, else zero (K > 0): at numbers, at samples (arrays) or at symbols (the
        simulator's right-hand side traced, clutchopt.simulate.engine)."""
        return positive_part(coupling_torque(self.torque_coefficient, driver_speed, self.engagement_squared))

    def kinetic_samples(self, driver_speeds, slips):
        """:meth:`kinetic` at each sample, at once (a run has a thousand)."""
        return self.kinetic(driver_speeds, slips)

    def slopes(self, driver_speed, slip):
        """dT/dw_a = 2 K w_a once engaged."""
        engaged = driver_speed * driver_speed > self.engagement_squared
        return (2.0 * self.torque_coefficient * driver_speed if engaged else 0.0), 0.0

    def capacity(self, driver_speed):
        return self.kinetic(driver_speed, 0.0)

    def capacity_samples(self, driver_speeds):
        return self.kinetic_samples(driver_speeds, 0.0)

    def engagement_speed(self) -> float:
        return math.sqrt(self.engagement_squared)

    def lockup_failure(self, speed, load, inertia):
        torque = self.capacity(speed)
        return None if torque > load else (f"no lock-up: coupling torque {torque:.6g} N*m at the driving speed "
                                           f"<= load {load:.6g} N*m")


@dataclass(frozen=True)
class Load:
    """Resisting torque of the driven machine (magnitude, opposes motion): constant, or piecewise linear in the
    driven speed (``over = "speed"``) or in time (``over = "time"``), held constant beyond the table."""

    torque: float = 0.0
    over: str = ""
    points: tuple[float, ...] = ()
    values: tuple[float, ...] = ()

    @property
    def constant(self) -> bool:
        return not self.over

    def __call__(self, t: float, driven_speed: float) -> float:
        """At a number, or at each sample of arrays."""
        if not self.over:
            return self.torque
        x = t if self.over == "time" else driven_speed
        if isinstance(x, np.ndarray):
            return np.interp(x, self.points, self.values)  # (held at both ends, as table_segment)
        return table_segment(x, self.points, self.values)[0]

    def on_floats(self):
        """The load as a function of (t, driven speed) at numbers, for a solver's right-hand side: the table looked
        up by :func:`table_segment` itself, without :meth:`__call__`'s dispatch on the kind of load and argument
        (1.06 -> 0.35 us a call: an elastic start's check calls it some 3,000 times)."""
        if not self.over:
            torque = self.torque
            return lambda t, driven_speed: torque
        points, values = self.points, self.values
        if self.over == "time":
            return lambda t, driven_speed: table_segment(t, points, values)[0]
        return lambda t, driven_speed: table_segment(driven_speed, points, values)[0]

    def slope(self, t: float, driven_speed: float) -> float:
        """d(load)/d(driven speed), for the simulator's Jacobian (a load over time does not depend on the speed)."""
        return table_segment(driven_speed, self.points, self.values)[1] if self.over == "speed" else 0.0

    def largest(self) -> float:
        return max(self.values) if self.over else self.torque


@dataclass(frozen=True)
class InductionMotor:
    """Kloss's torque-speed curve T = 2 T_k / (s / s_k + s_k / s), slip s = (w_sync - w) / w_sync."""

    synchronous_speed: float
    breakdown_torque: float
    breakdown_slip: float
    inertia: float

    @property
    def time_constant(self) -> float:
        """J_m / (dT/dw) at synchronous speed, where the Kloss curve is steepest (dT/dw = 2 T_k / (s_k w_s)):
        the fastest mode the motor adds to a start-up."""
        return self.inertia * self.breakdown_slip * self.synchronous_speed / (2.0 * self.breakdown_torque)

    def __call__(self, speed: float) -> float:
        return kloss_torque(speed, self.synchronous_speed, self.breakdown_torque, self.breakdown_slip)

    def slope(self, speed: float) -> float:
        """dT/dw = -(dT/ds) / w_s, dT/ds = 2 T_k s_k (s_k^2 - s^2) / (s^2 + s_k^2)^2."""
        s, s_k = 1.0 - speed / self.synchronous_speed, self.breakdown_slip
        return -2.0 * self.breakdown_torque * s_k * (s_k * s_k - s * s) / (s * s + s_k * s_k) ** 2 \
            / self.synchronous_speed
