"""The wedge paper's printed forms of (27) and (28), kept for comparison (docs/errata.md, W2, W4)."""

from __future__ import annotations

import math

from clutchopt.backend import cbrt, cos, sin
from clutchopt.formulations.common import duty_torque


def paper_eq27_first_form(p):
    """m_r = 2 T_max sin(alpha) / (f z (1 + lambda) r1 w^2 (lambda r1 - 2/3 h_r)), eq. (27), first form."""
    r1, lam, w = p.flank_inner_radius, p.radius_ratio, p.speed
    t_max = duty_torque(p)
    return (2 * t_max * sin(p.flank_angle)
            / (p.friction_coefficient * p.weight_count * (1 + lam) * r1 * w**2 * (lam * r1 - 2 / 3 * p.weight_height)))


def paper_eq27_second_form(p):
    """m_r = 6 (I_n w_a + T_c t_p) sin(alpha) / (f z (1 + lambda) r1 w^2 (3 lambda r1 - 2 h_r)), eq. (27), second form."""
    r1, lam, w = p.flank_inner_radius, p.radius_ratio, p.speed
    return (6 * (p.inertia * w + p.resisting_torque * p.acceleration_time) * sin(p.flank_angle)
            / (p.friction_coefficient * p.weight_count * (1 + lam) * r1 * w**2 * (3 * lam * r1 - 2 * p.weight_height)))


def paper_eq28(p, weight_mass):
    """d_n = cbrt(32 f m_r w^2 (3 lambda r1 - 2 h_r) [p] cos(alpha) / (3 pi gamma (lambda - 1) [sigma])), eq. (28).

    Not dimensionally consistent (its cube is a force); the paper reads the number as millimetres, so it is
    returned here in metres as that number times 1e-3 (errata W4).
    """
    lam = p.radius_ratio
    number = (32 * p.friction_coefficient * weight_mass * p.speed**2 * (3 * lam * p.flank_inner_radius - 2 * p.weight_height)
              * p.allowable_pressure * cos(p.flank_angle)
              / (3 * math.pi * p.sector_angle * (lam - 1) * p.allowable_bending_stress))
    return cbrt(number) * 1e-3
