"""The ball paper's printed forms of (2), (8), (9), (10), (11) and (12), kept for comparison (docs/errata.md)."""

from __future__ import annotations

import math

from clutchopt.backend import cbrt


def paper_eq2(p, radius, width, filling):
    """m_n = pi rho Psi_n l_a R_a^2 [(1 - K2^2) - K1 (1 - K2)], eq. (2) as printed."""
    k1 = p.shovel_ratio
    return math.pi * p.density * p.packing_density * width * radius**2 * ((1 - filling**2) - k1 * (1 - filling))


def paper_eq8(p, radius, width, approximate_width, filling):
    """M_c of eq. (8) as printed: the end-face term divided by the approximate width l of (5), K1/2 in both terms."""
    k, k1 = filling, p.shovel_ratio
    return (6 * p.speed**2 * p.friction_coefficient * p.density * p.packing_density * width * radius**4
            * (math.pi / 9 * (1 - k**3) - k1 / 2 * (1 - k**2)
               + radius / (approximate_width * math.sqrt(6))
               * (math.pi / 45 * (2 - 5 * k**3 + 3 * k**5) - k1 / 2 * (1 - 2 * k**2 + k**4))))


def reduced_modulus(p):
    """E' = 2 E_1 E_2 / (E_1 + E_2), the "reduced modulus" of the Russian-language contact tables (our reading of
    E' in (9); it is E for equal materials)."""
    return 2.0 * p.ball_modulus * p.drum_modulus / (p.ball_modulus + p.drum_modulus)


def paper_eq9(p, radius, filling, n_a, n_b):
    """p_0 = 1.5 / (pi n_a n_b) ((E' R_a w / 3)^2 rho Psi_n (1 - K2^3))^(1/3), eq. (9) as printed."""
    inner = (reduced_modulus(p) * radius * p.speed / 3) ** 2 * p.density * p.packing_density * (1 - filling**3)
    return 1.5 / (math.pi * n_a * n_b) * cbrt(inner)


def paper_eq10(p, radius, filling, conformity):
    """p_0 = 175e8 (beta - 1)^0.185 (w R_a)^0.67 (1 - K2^3) Pa, eq. (10) as printed (errata B6)."""
    return 175e8 * (conformity - 1) ** 0.185 * (p.speed * radius) ** 0.67 * (1 - filling**3)


def paper_eq12_balls(p, radius, width, filling):
    """6 Q_kam, Q_kam = pi/6 rho Psi_c l_a R_a [(1 - K2^2) - K1 (1 - K2)], eq. (12) as printed (errata B2)."""
    k1 = p.shovel_ratio
    return 6 * math.pi / 6 * p.density * p.construction_density * width * radius * ((1 - filling**2)
                                                                                     - k1 * (1 - filling))


def paper_groove_depth(p, radius, ball_radius, conformity):
    """h = 1.2 r_c [1 - w 0.005 (w R_a)^(2/3) / (beta - 1)^0.38], eq. (11) second line, as printed (errata B7)."""
    return 1.2 * ball_radius * (1 - p.speed * 0.005 * (p.speed * radius) ** (2 / 3) / (conformity - 1) ** 0.38)
