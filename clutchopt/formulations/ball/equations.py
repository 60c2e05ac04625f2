"""The ball clutch's equations, by the paper's numbers (Tasev): the ball layer, its torque, masses and loads;
where the printed equation is inconsistent, the consistent form (docs/errata.md, B1-B8). The contact stress (9)
is in ``contact``. Generic over floats and CasADi symbols."""

from __future__ import annotations

import math

from clutchopt.backend import arcsinh, sinh, sqrt
from clutchopt.formulations.duty import rated_torque


ROW_MARGIN = 1.1  # the paper's factor in (6)


def required(p):
    """M_c = k_s P / w_n: the torque the clutch must carry at the motor's nominal speed."""
    return rated_torque(p.power, p.speed, p.service_factor)


def filling_coefficient(construction_density, packing_density):
    """K2 = R_1 / R_a: the real root of K2^3 + 3 K2 (Psi_c / Psi_n + 1) - 4 = 0, eq. (1).

    The cubic t^3 + p t - 4 (p > 0) rises monotonically from -4 at 0 to 3 Psi_c / Psi_n > 0 at 1: one real root,
    in (0, 1), written without cancellation as t = 2 sqrt(p/3) sinh(asinh((6/p) sqrt(3/p)) / 3).
    """
    p = 3.0 * (construction_density / packing_density + 1.0)
    return 2.0 * sqrt(p / 3.0) * sinh(arcsinh(6.0 / p * sqrt(3.0 / p)) / 3.0)


def layer_force_coefficient(filling):
    """(1 - K2^3) / 3: the layer's centrifugal force per unit drum area over rho Psi_n w^2 R_a^2 (behind (4), (8))."""
    return (1.0 - filling**3) / 3.0


def leading_torque(friction, density, packing, speed, width, radius, filling):
    """M = (2 pi / 3) f rho Psi_n w^2 l R_a^4 (1 - K2^3): the friction of the layer's centrifugal force on the
    cylinder, the first term of (8) and the torque behind (4)."""
    return 2.0 * math.pi / 3.0 * friction * density * packing * speed**2 * width * radius**4 * (1.0 - filling**3)


def paper_active_radius(torque, friction, density, packing, speed, width_ratio, filling):
    """R_a = (3 M_c / (2 pi rho Psi_n f w^2 K5 (1 - K2^3)))^(1/5), eq. (4): (the leading torque at l = K5 R_a) = M_c."""
    return (3.0 * torque / (2.0 * math.pi * density * packing * friction * speed**2 * width_ratio
                            * (1.0 - filling**3))) ** 0.2


def paper_ball_rows(width, ball_radius):
    """n_p = 1.1 l / (sqrt(3) r_c), eq. (6), rounded up."""
    return float(math.ceil(ROW_MARGIN * width / (math.sqrt(3.0) * ball_radius) - 1e-9))


def width_from_rows(rows, ball_radius):
    """l_a = sqrt(3) r_c (n_p - 1) + 2 r_c, eq. (7): n_p rows sqrt(3) r_c apart (close packing)."""
    return math.sqrt(3.0) * ball_radius * (rows - 1.0) + 2.0 * ball_radius


def clutch_torque(p, radius, width, filling):
    """M = 6 w^2 f rho Psi_n l_a R_a^4 {pi/9 (1 - K2^3) - (z_s/6) K1/2 (1 - K2^2)
    + R_a / (l_a sqrt 6) [pi/45 (2 - 5 K2^3 + 3 K2^5) - (z_s/6) K1/4 (1 - K2^2)^2]}, eq. (8) made consistent:
    cylinder plus two end faces (side pressure 1/sqrt 6 of the radial one), z_s shovels of thickness K1 R_a
    taking their volume out of the layer (errata B3, B4)."""
    k, k1, shovels = filling, p.shovel_ratio, p.shovel_count / 6.0
    cylinder = math.pi / 9.0 * (1.0 - k**3) - shovels * k1 / 2.0 * (1.0 - k**2)
    faces = math.pi / 45.0 * (2.0 - 5.0 * k**3 + 3.0 * k**5) - shovels * k1 / 4.0 * (1.0 - k**2) ** 2
    return (6.0 * p.speed**2 * p.friction_coefficient * p.density * p.packing_density * width * radius**4
            * (cylinder + radius / (width * math.sqrt(6.0)) * faces))


def ball_mass(p, radius, width, filling):
    """m_n = rho Psi_n l_a R_a^2 [pi (1 - K2^2) - z_s K1 (1 - K2)], eq. (2) with the z_s shovels of (8) (errata B2)."""
    return (p.density * p.packing_density * width * radius**2
            * (math.pi * (1.0 - filling**2) - p.shovel_count * p.shovel_ratio * (1.0 - filling)))


def body_mass(p, radius, width):
    """G_c = pi rho Psi_c R_a^2 l_a, eq. (13)."""
    return math.pi * p.density * p.construction_density * radius**2 * width


def cost(p, balls, body):
    """Balls and body priced per kg."""
    return p.ball_price * balls + p.body_price * body


def wall_pressure(p, radius, filling):
    """p_w = rho Psi_n w^2 R_a^2 (1 - K2^3) / 3: the layer's centrifugal force per unit drum area, as in (4), (8), (9)."""
    return p.density * p.packing_density * p.speed**2 * radius**2 * layer_force_coefficient(filling)


def ball_load(p, radius, filling, ball_radius):
    """F = p_w 2 sqrt(3) r_c^2: the outer layer's balls sit in grooves sqrt(3) r_c apart (11), 2 r_c apart along one."""
    return wall_pressure(p, radius, filling) * 2.0 * math.sqrt(3.0) * ball_radius**2
