"""The wedge coupling's equations, by the paper's numbers (Ambartsumyants & Deli 2015); where the printed
equation is inconsistent, the consistent form (docs/errata.md, W1-W6). Generic over floats and CasADi symbols."""

from __future__ import annotations

from clutchopt.backend import arctan, cos, sin, tan
from clutchopt.formulations.common import rod_bending_stress, rod_mass


def paper_centroid_radius(r2, weight_height):
    """r_c ~ r2 - 2/3 h_r, the paper's approximation below eq. (10) (see errata W5)."""
    return r2 - 2.0 / 3.0 * weight_height


def flank_normal_force(centrifugal, flank_angle):
    """N = F_u / (2 sin alpha) on each flank, eq. (12)."""
    return centrifugal / (2.0 * sin(flank_angle))


def friction_force(friction_coefficient, centrifugal, flank_angle):
    """F_fr = 2 f N = f F_u / sin alpha per weight, eq. (14) made consistent with (12) (errata W1)."""
    return 2.0 * friction_coefficient * flank_normal_force(centrifugal, flank_angle)


def mean_flank_radius(r1, r2):
    """d_cp / 2 = (r1 + r2) / 2: the friction radius (exact under uniform wear), eqs. (15), (25)."""
    return (r1 + r2) / 2.0


def friction_torque(weight_count, friction, r1, r2):
    """T_fr = z F_fr d_cp / 2, eq. (15) (errata W1)."""
    return weight_count * friction * mean_flank_radius(r1, r2)


def flank_area(sector_angle, r1, r2, flank_angle):
    """Area of one conical flank of one weight, gamma (r2^2 - r1^2) / (2 cos alpha); eqs. (6)-(7) give both."""
    return sector_angle * (r2**2 - r1**2) / (2.0 * cos(flank_angle))


def flank_area_total(weight_count, sector_angle, r1, r2, flank_angle):
    """2 z A_flank: both conical flanks of every weight rub in the groove, the friction area that wears."""
    return 2.0 * weight_count * flank_area(sector_angle, r1, r2, flank_angle)


def flank_pressure(centrifugal, flank_angle, sector_angle, r1, r2):
    """q = N / A_flank = F_u cot(alpha) / (gamma (r2^2 - r1^2)), eqs. (9), (12), (13) for one weight (errata W3)."""
    return flank_normal_force(centrifugal, flank_angle) / flank_area(sector_angle, r1, r2, flank_angle)


def finger_bending_stress(friction, finger_length, finger_diameter):
    """sigma = F_fr h_n / (pi d_n^3 / 32), cantilever finger, eq. (19) (errata W4)."""
    return rod_bending_stress(friction, finger_length, finger_diameter)


def finger_mass(density, finger_diameter, finger_length):
    """Steel finger of length h_n = d_cp / 2 (text below eq. 18)."""
    return rod_mass(density, finger_diameter, finger_length)


def self_locking_angle(friction_coefficient):
    """The wedge jams (does not release when the speed drops) for tan(alpha) <= f."""
    return arctan(friction_coefficient)


def weight_body(r_in, r1, r2, width, flank_angle, sector_angle, density):
    """Mass and exact centroid radius of a weight: annular sector r_in..r2 of angle gamma, axial width b below
    r1 and the trapezoidal top b - 2 (r - r1) tan(alpha) between r1 and r2.

    m = rho gamma int w(r) r dr;  r_c = 2 sin(gamma/2) / gamma * int w r^2 dr / int w r dr.
    """
    t = tan(flank_angle)
    top = width + 2.0 * r1 * t  # w(r) = top - 2 t r on r1..r2
    first = width * (r1**2 - r_in**2) / 2.0 + top * (r2**2 - r1**2) / 2.0 - 2.0 * t * (r2**3 - r1**3) / 3.0
    second = width * (r1**3 - r_in**3) / 3.0 + top * (r2**3 - r1**3) / 3.0 - t * (r2**4 - r1**4) / 2.0
    mass = density * sector_angle * first
    centroid = 2.0 * sin(sector_angle / 2.0) / sector_angle * second / first
    return mass, centroid


def weight_base_width(weight_mass, r_in, r1, r2, flank_angle, sector_angle, density):
    """b of the weight of ``weight_body`` that has mass m_r: its mass is affine in b, so b(m_r) is closed form.

    With t = tan(alpha), the width w(r) = b on r_in..r1 and b - 2 t (r - r1) on r1..r2, weight_body's
    m = rho gamma int w r dr = rho gamma [b (r2^2 - r_in^2)/2 + r1 t (r2^2 - r1^2) - 2 t (r2^3 - r1^3)/3], so
        b = (m_r / (rho gamma) - t (r1 (r2^2 - r1^2) - 2/3 (r2^3 - r1^3))) / ((r2^2 - r_in^2) / 2).
    The trapezoid's term is negative (the top narrows), so b exceeds the width 2 m_r / (rho gamma (r2^2 - r_in^2))
    of a rectangular sector of that mass. By hand, the paper's example (r_in 40, r1 50, r2 60 mm, alpha 15 deg,
    gamma 0.785, rho 7850, m_r 0.156873 kg): m_r / (rho gamma) = 2.54571e-5 m^3, the trapezoid's term
    -1.51838e-6 m^3, (r2^2 - r_in^2)/2 = 1e-3 m^2: b = 26.976 mm (a rectangular sector: 25.457 mm).
    Paper mode's weight (m_r free, geometry given) has this width: its envelope and its width rules read it.
    """
    t = tan(flank_angle)
    trapezoid = t * (r1 * (r2**2 - r1**2) - 2.0 * (r2**3 - r1**3) / 3.0)
    return (weight_mass / (density * sector_angle) - trapezoid) / ((r2**2 - r_in**2) / 2.0)


def cost(p, total_mass, weight_count, flank_area_one_side):
    """Material at a price per kg, a fixed cost per weight-and-finger part, grinding per flank area."""
    return (p.material_price * total_mass + weight_count * p.part_cost
            + p.flank_finish_cost * weight_count * 2.0 * flank_area_one_side)
