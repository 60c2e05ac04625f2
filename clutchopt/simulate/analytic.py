"""Closed forms of the start-up transient (Simionescu & Oproescu; seed friction_transient_simionescu_oproescu.txt).

Constant driving speed w0, driven inertia J, constant resisting torque M_r, friction torque of the slip
w_r = w0 - w (1):  M_fr = k (1 + e^{a w_r}) (6);  J dw/dt = M_fr - M_r (3).

Evaluated stably: with u = a w_r, m = M_r / k and c = 1 - m, the time from rest (slip w0) to slip w_r is
t = J/(k a) int du / (c + e^u), written with ``expm1``/``exprel``/``log1p`` in whichever of two equivalent forms
cannot overflow for the sign of a, so |a w0| up to 1e3, a -> 0 and M_r close to the friction torque all work.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.integrate import quad
from scipy.special import exprel

NO_LOCKUP = "no lock-up"


@dataclass(frozen=True)
class PaperTransient:
    """The paper's start-up: J, k, a, M_r, w0 in SI (a in s/rad: 1 / slip speed)."""

    inertia: float
    k: float
    a: float
    resisting_torque: float
    speed: float

    @property
    def m(self) -> float:
        return self.resisting_torque / self.k

    def lockup_failure(self) -> str | None:
        """Why the driven part never reaches w0 (M_fr - M_r must stay positive on 0..w0), or None if it does."""
        k, a, w0, mr = self.k, self.a, self.speed, self.resisting_torque
        if a < 0 and mr >= k * (1.0 + math.exp(a * w0)):
            return (f"{NO_LOCKUP}: the driven part does not start, M_fr(w0) = {k * (1 + math.exp(a * w0)):.6g} N*m "
                    f"<= M_r = {mr:.6g} N*m")
        if mr >= 2.0 * k:
            slip = math.log(mr / k - 1.0) / a if a > 0 else math.inf
            return (f"{NO_LOCKUP}: M_r = {mr:.6g} N*m >= M_fr(0) = 2k = {2 * k:.6g} N*m; the slip tends to "
                    f"{slip:.6g} rad/s where M_fr = M_r")
        return None

    def time_to_slip(self, slip: float) -> float:
        """t(w_r) from rest (slip w0) to slip w_r, eq. (8) in an overflow-free form; inf without lock-up."""
        if not 0.0 <= slip <= self.speed:
            raise ValueError(f"slip {slip!r} outside 0 .. w0 = {self.speed!r}")
        if self.lockup_failure() and slip <= self._asymptotic_slip():
            return math.inf
        k, a, w0 = self.k, self.a, self.speed
        c, c2 = (k - self.resisting_torque) / k, (2.0 * k - self.resisting_torque) / k  # 1 - m, 2 - m
        dw, u0, u1 = w0 - slip, a * w0, a * slip
        d = u0 - u1
        if a <= 0:  # z = expm1(d) / (e^u0 + c); ln(num/den) = d + ln(e^u1 + c) - ln(e^u0 + c)
            den = _c_plus_exp(c, c2, u0)
            z_over_a = dw * exprel(d) / den
            log_ratio = d + math.log(_c_plus_exp(c, c2, u1)) - math.log(den)
        else:  # z = e^{-u1} (1 - e^{-d}) / (1 + c e^{-u0}); 1 + c e^{-u} = -expm1(-u) + (2 - m) e^{-u}, both >= 0
            den = -math.expm1(-u0) + c2 * math.exp(-u0)
            z_over_a = dw * math.exp(-u1) * exprel(-d) / den
            log_ratio = math.log((-math.expm1(-u1) + c2 * math.exp(-u1)) / den)
        y = c * z_over_a * a  # ln(num/den) = log1p(y)
        factor = 1.0 if y == 0 else (math.log1p(y) / y if abs(y) < 0.5 else log_ratio / y)
        return self.inertia / k * z_over_a * factor

    def _asymptotic_slip(self) -> float:
        k, a, mr = self.k, self.a, self.resisting_torque
        if a < 0 and mr >= k * (1.0 + math.exp(a * self.speed)):
            return self.speed
        return math.log(mr / k - 1.0) / a if a > 0 else math.inf

    def start_time(self) -> float:
        """t_c, eq. (9) as corrected (errata T1): eq. (8) at w_r = 0; inf without lock-up."""
        return math.inf if self.lockup_failure() else self.time_to_slip(0.0)

    def start_time_printed(self) -> float:
        """t_c as printed in (9): denominator k e^{a w0} + k M_r (dimensionally wrong; errata T1)."""
        k, a, w0, mr = self.k, self.a, self.speed, self.resisting_torque
        return self.inertia / (a * (k - mr)) * (a * w0 + math.log((2 * k - mr) / (k * math.exp(a * w0) + k * mr)))

    def source_work(self) -> float:
        """L_s, eq. (14): J w0 int M_fr / (M_fr - M_r) dw_r = J w0^2 + M_r w0 t_c exactly (t_c from eq. 9)."""
        t_c = self.start_time()
        if math.isinf(t_c):
            return math.inf
        return self.inertia * self.speed**2 + (self.resisting_torque * self.speed * t_c if self.resisting_torque else 0.0)

    def friction_work(self) -> float:
        """L, eq. (11): J int_0^w0 M_fr w_r / (M_fr - M_r) dw_r by quadrature in s = w_r / w0.
        L = J w0^2 / 2 when M_r = 0 (12)."""
        if self.lockup_failure():
            return math.inf
        m, aw0 = self.m, self.a * self.speed
        if m == 0:
            return 0.5 * self.inertia * self.speed**2
        breaks = [b for b in (1e-3 / abs(aw0), 1e-1 / abs(aw0), 1 / abs(aw0), 10 / abs(aw0)) if 0 < b < 1] if aw0 else []
        c = (self.k - self.resisting_torque) / self.k  # c and 2 - m from the inputs: no cancellation near 2k or k
        c2 = (2.0 * self.k - self.resisting_torque) / self.k

        def ratio(s):
            """M_fr / (M_fr - M_r) at u = a w0 s, in a form that neither overflows nor cancels."""
            u = aw0 * s
            if u > 1.0:
                return (1.0 + math.exp(-u)) / (1.0 - (m - 1.0) * math.exp(-u))
            return (1.0 + math.exp(u)) / _c_plus_exp(c, c2, u)

        value, _ = quad(lambda s: s * ratio(s), 0.0, 1.0, points=breaks or None, epsabs=0.0, epsrel=1e-13, limit=500)
        return self.inertia * self.speed**2 * value

    def summary(self) -> dict:
        """Headline figures (SI): t_c, L, L_s, the lock-up verdict and the printed (9) for comparison."""
        failure = self.lockup_failure()
        return {"locks_up": failure is None, "reason": failure or "",
                "start_time": self.start_time(), "friction_work": self.friction_work(),
                "source_work": self.source_work(),
                "start_time_printed_eq9": _quiet(self.start_time_printed)}


def _c_plus_exp(c: float, c2: float, u: float) -> float:
    """c + e^u (u <= 1): as (2 - m) + expm1(u) near u = 0 (M_r ~ 2k), as c + e^u below u = -1 (M_r ~ k)."""
    return c2 + math.expm1(u) if u >= -1.0 else c + math.exp(u)


def _quiet(function) -> float:
    """A printed formula that may be undefined (log of a negative, division by zero) for these inputs: NaN."""
    try:
        value = function()
    except (ValueError, ZeroDivisionError, OverflowError):
        return math.nan
    return value if isinstance(value, float) else math.nan
