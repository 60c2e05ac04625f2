"""Centrifugal ball clutch of high power (Tasev; seed ball_clutch_tasev.txt).

Balls of radius r_c fill the six chambers of a six-shovel rotor (shovel thickness a_n = K1 R_a). At speed they
form a layer, packing density Psi_n, from R_1 = K2 R_a out to the drum's active radius R_a over the active width
l_a; their centrifugal force presses them, with friction f, on the drum's cylinder (grooves of radius
r_groove = beta r_c, pitch sqrt(3) r_c) and on its two end faces.

Equation numbers are the paper's. Where the printed equation is inconsistent the consistent form is used here
and the printed one is kept as ``paper_eq*`` for comparison; see docs/errata.md (B1-B8) and docs/ball.md.

Two posed problems:
- ``paper``: the paper's simplifying assumptions: leading-order torque (no shovels, no end faces), K2 from (1),
  width continuous, l_a / R_a at least the case's K5; free: R_a, l_a. Its optimum is the fifth root (4).
- ``design``: the consistent torque (8), Hertz contact stress (9) with exact n_a, n_b, ball rows n_p integer with
  l_a from (7); free: R_a, K2, r_c, beta, n_p within the paper's ranges, the housing and the stress limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

from clutchopt.backend import arcsinh, cbrt, ellipke, exp, fmax, fmin, log, sinh, sqrt
from clutchopt.errors import InputError
from clutchopt.formulations.duty import POWER_DUTY_QUANTITIES, rated_torque
from clutchopt.model import (
    Comparison,
    ComparisonRow,
    Coupling,
    Formulation,
    MaterialRole,
    Objective,
    Output,
    Quantity,
    SpeedLaw,
    Variable,
    at_least,
    at_most,
    si,
)

SIDE_PRESSURE_RATIO = 1.0 / math.sqrt(6.0)  # axial over radial pressure of the ball layer, implied by (8)
ROW_MARGIN = 1.1  # the paper's factor in (6)
CLOSE_PACKING = math.pi / (3.0 * math.sqrt(2.0))  # densest packing of equal spheres, 0.7405

# --- Quantity table: what a ball case gives (TOML section.key, unit, paper symbol, meaning) -------------------
Q = Quantity
QUANTITIES = POWER_DUTY_QUANTITIES + (
    Q("density", "kg/m^3", "density of steel (balls and body)", "rho", "balls", "7850 kg/m^3", above=0),
    Q("packing_density", "", "packing density of the ball filling (paper ~0.55)", "Psi_n", "balls", 0.55, above=0,
      below=CLOSE_PACKING),
    Q("friction_coefficient", "", "friction coefficient of the balls on the drum (paper ~0.04)", "f", "balls",
      above=0, at_most=1),
    Q("ball_radius", "mm", "ball radius (paper procedure; start of the NLP)", "r_c", "balls", above=0),
    Q("groove_conformity", "", "beta = r_groove / r_c (paper 1.005 to 1.05; paper procedure, NLP start)", "beta",
      "balls", above=1, at_most=2),
    Q("ball_modulus", "GPa", "Young's modulus of the balls", "E_1", "balls", "210 GPa", above=0),
    Q("ball_poisson", "", "Poisson's ratio of the balls", "nu_1", "balls", 0.3, at_least=0, below=0.5),
    Q("construction_density", "", "Psi_c, density of the clutch body by its construction (paper 0.6 to 1.2)",
      "Psi_c", "body", above=0),
    Q("shovel_ratio", "", "K1 = a_n / R_a, shovel thickness over active radius (paper ~0.05)", "K1", "body", 0.05,
      at_least=0, below=0.5),
    Q("shovel_count", "", "number of shovels (chambers) of the rotor", "", "body", 6, at_least=1, integer=True),
    Q("drum_modulus", "GPa", "Young's modulus of the drum", "E_2", "body", "210 GPa", above=0),
    Q("drum_poisson", "", "Poisson's ratio of the drum", "nu_2", "body", 0.3, at_least=0, below=0.5),
    Q("width_ratio", "", "K5 = l / R_a of the paper procedure (paper: 0.4 low speed to 0.8 high speed)", "K5",
      "paper", above=0),
    Q("torque_tolerance", "", "the paper's 10 %: |M(8) / M_c - 1| accepted by the K2 loop", "", "paper", 0.10,
      above=0, below=1),
    Q("allowable_contact_stress", "GPa", "largest Hertz contact stress of ball on drum (paper 0.5 GPa)", "[p_0]",
      "limits", "0.5 GPa", above=0),
    Q("width_ratio_min", "", "smallest K5 = l_a / R_a (paper range 0.4 to 0.8)", "", "limits", 0.4, above=0),
    Q("width_ratio_max", "", "largest K5 = l_a / R_a (paper range 0.4 to 0.8)", "", "limits", 0.8, above=0),
    Q("outer_diameter_max", "mm", "largest outer diameter of the clutch", "D_max", "limits", above=0),
    Q("shell_thickness", "mm", "radial wall of the drum outside R_a", "s", "limits", at_least=0),
    Q("min_ball_layers", "", "ball diameters the layer R_a - R_1 must hold at least (continuum model)", "",
      "limits", 3.0, above=0),
    Q("ball_price", "EUR/kg", "price of the balls", "", "cost", above=0, needed_by="cost"),
    Q("body_price", "EUR/kg", "price of the clutch body (drum, rotor), machined", "", "cost", above=0,
      needed_by="cost"),
)

# --- What a case may take from the material library (clutchopt materials) ----------------------------------------
MATERIALS = (
    MaterialRole("ball_material", "materials", "balls; their density is the body's too (the model has one density)",
                 {"density": "density", "elastic_modulus": "ball_modulus", "poisson": "ball_poisson",
                  "price": "ball_price"}),
    MaterialRole("body_material", "materials", "drum and rotor; the drum's surface sets the contact-stress limit",
                 {"elastic_modulus": "drum_modulus", "poisson": "drum_poisson",
                  "allowable_contact": "allowable_contact_stress"}),  # body_price is machined, not raw material
    MaterialRole("friction_pair", "friction_pairs", "balls on the drum", {"friction_coefficient": "friction_coefficient"}),
)


# --- Equations ---------------------------------------------------------------------------------------------------
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


def contact_modulus(p):
    """E* = 1 / ((1 - nu_1^2) / E_1 + (1 - nu_2^2) / E_2), the Hertz contact modulus (our reading of E' in (9))."""
    return 1.0 / ((1.0 - p.ball_poisson**2) / p.ball_modulus + (1.0 - p.drum_poisson**2) / p.drum_modulus)


def wall_pressure(p, radius, filling):
    """p_w = rho Psi_n w^2 R_a^2 (1 - K2^3) / 3: the layer's centrifugal force per unit drum area, as in (4), (8), (9)."""
    return p.density * p.packing_density * p.speed**2 * radius**2 * layer_force_coefficient(filling)


def ball_load(p, radius, filling, ball_radius):
    """F = p_w 2 sqrt(3) r_c^2: the outer layer's balls sit in grooves sqrt(3) r_c apart (11), 2 r_c apart along one."""
    return wall_pressure(p, radius, filling) * 2.0 * math.sqrt(3.0) * ball_radius**2


def curvatures(radius, ball_radius, conformity):
    """Relative principal curvatures of ball on grooved drum: around the drum 1/r_c - 1/R_a, across the groove
    1/r_c - 1/(beta r_c). Returns (sum rho, B/A >= 1) with B/A the larger over the smaller (beta r_c < R_a)."""
    around = 1.0 / ball_radius - 1.0 / radius
    across = (1.0 - 1.0 / conformity) / ball_radius
    return around + across, around / across


KAPPA_RANGE = (math.log(1.01), math.log(1e5))  # ln(B/A) over which the Newton start is fitted
KAPPA_START = (0.6195049581568469, -0.04819203413574859, 0.017114963528664155, -0.0010213762429290012,
               -0.005777536213994348, 0.0075816120696768595, -0.0072777845352428585, 0.003622163387927758,
               0.0015625642464741274, -0.002686491922902393, 0.0008446148249083446)
# ln(a/b) / ln(B/A) as a polynomial in t = (2 ln(B/A) - lo - hi) / (hi - lo): the degree-10 Chebyshev fit to the
# exact solution at 400 Chebyshev points of KAPPA_RANGE (scipy ellipk/ellipe and brentq); within 4e-6 of ln(a/b)
# there (tests/test_ball_closed_forms.py refits it)
NEWTON_STEPS = 1  # from the fitted start (4e-6): float64 accuracy, value and derivatives alike


def kappa_start(ratio):
    """ln(a/b) of the contact ellipse to 4e-6 for 1.01 <= B/A <= 1e5 (KAPPA_START); beyond, the fit at its ends."""
    lo, hi = KAPPA_RANGE
    log_ratio = log(ratio)
    t = fmin(fmax((2.0 * log_ratio - lo - hi) / (hi - lo), -1.0), 1.0)
    value = 0.0
    for coefficient in reversed(KAPPA_START):  # Horner
        value = value * t + coefficient
    return log_ratio * value


def _curvature_ratio(m):
    """B/A = ((1/(1 - m)) E - K) / (K - E) of the contact ellipse, e^2 = m = 1 - (b/a)^2, and d(B/A)/dm; K, E."""
    k, e = ellipke(m)
    num, den = e / (1.0 - m) - k, k - e
    de, dk = (e - k) / (2.0 * m), (e - (1.0 - m) * k) / (2.0 * m * (1.0 - m))
    dnum, dden = e / (1.0 - m) ** 2 + de / (1.0 - m) - dk, dk - de
    return num / den, (dnum * den - num * dden) / den**2, k, e


def hertz_coefficients(ratio):
    """Hertz's n_a, n_b (Timoshenko's m, n) of an elliptic contact with curvature ratio B/A = ``ratio`` >= 1.01:
    a = n_a (3F / (2 E* sum rho))^(1/3), b = n_b (...)^(1/3).

    Solves B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e)) for kappa = ln(a/b) by Newton (NEWTON_STEPS) from a
    fitted start (:func:`kappa_start`) with K, E by the AGM (:func:`clutchopt.backend.ellipke`); then
    n_a^3 = 2 (K - E) (1 + B/A) / (pi e^2), n_b = n_a b/a. Differentiable in CasADi; agrees with the exact
    solution (:func:`hertz_coefficients_exact`) to 1e-10 for 1.01 <= B/A <= 1e5 (tested).
    """
    kappa = kappa_start(ratio)
    for _ in range(NEWTON_STEPS):
        m = 1.0 - exp(-2.0 * kappa)
        r, dr, _, _ = _curvature_ratio(m)
        kappa = kappa - (log(r) - log(ratio)) * r / (dr * 2.0 * (1.0 - m))
    m = 1.0 - exp(-2.0 * kappa)
    k, e = ellipke(m)
    n_a = cbrt(2.0 * (k - e) * (1.0 + ratio) / (math.pi * m))
    return n_a, n_a * sqrt(1.0 - m)


def hertz_coefficients_exact(ratio):
    """n_a, n_b by bracketing the exact elliptic-integral equation (scipy ellipk/ellipe); floats only, reference."""
    m = brentq(lambda m: (ellipe(m) / (1 - m) - ellipk(m)) / (ellipk(m) - ellipe(m)) - ratio, 1e-9, 1 - 1e-15,
               xtol=1e-300, rtol=1e-15)
    n_a = (2 * (ellipk(m) - ellipe(m)) * (1 + ratio) / (math.pi * m)) ** (1 / 3)
    return n_a, n_a * math.sqrt(1 - m)


def hertz_peak_pressure(load, curvature_sum, modulus, n_a, n_b):
    """p_0 = 3F / (2 pi a b) = 1.5 / (pi n_a n_b) (F (2 E* sum rho / 3)^2)^(1/3): the Hertz form behind (9)."""
    return 1.5 / (math.pi * n_a * n_b) * cbrt(load * (2.0 * modulus * curvature_sum / 3.0) ** 2)


def contact_stress(p, radius, filling, ball_radius, conformity):
    """p_0 of the outer balls on the drum, eq. (9) made consistent (errata B5): Hertz with the ball load and the
    contact's own curvatures, n_a, n_b from the elliptic integrals."""
    total, ratio = curvatures(radius, ball_radius, conformity)
    n_a, n_b = hertz_coefficients(ratio)
    return hertz_peak_pressure(ball_load(p, radius, filling, ball_radius), total, contact_modulus(p), n_a, n_b)


# --- The paper's printed forms, kept for comparison (docs/errata.md) ----------------------------------------------
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


# --- The clutch at a design, shared by both modes -------------------------------------------------------------------
@dataclass(frozen=True)
class BallClutch:
    """R_a, l_a, K2, r_c, beta, n_p of one design: where the modes differ is how they are obtained."""

    radius: Any
    width: Any
    filling: Any
    ball_radius: Any
    conformity: Any
    rows: Any

    def balls(self, p):
        return ball_mass(p, self.radius, self.width, self.filling)

    def body(self, p):
        return body_mass(p, self.radius, self.width)

    def mass(self, p):
        return self.balls(p) + self.body(p)

    def cost(self, p):
        return cost(p, self.balls(p), self.body(p))

    def torque(self, p):
        return clutch_torque(p, self.radius, self.width, self.filling)

    def contact_stress(self, p):
        return contact_stress(p, self.radius, self.filling, self.ball_radius, self.conformity)


def required(p):
    """M_c = k_s P / w_n: the torque the clutch must carry at the motor's nominal speed."""
    return rated_torque(p.power, p.speed, p.service_factor)


def _outputs(c: BallClutch, p):
    total, ratio = curvatures(c.radius, c.ball_radius, c.conformity)
    n_a, n_b = hertz_coefficients(ratio)
    return {
        "required_torque": Output(required(p), "N*m", "M_c = k_s P / w_n"),
        "torque": Output(c.torque(p), "N*m", "torque of the design, eq. (8) consistent"),
        "leading_torque": Output(leading_torque(p.friction_coefficient, p.density, p.packing_density, p.speed,
                                                c.width, c.radius, c.filling), "N*m",
                                 "cylinder term only, the torque behind (4)"),
        "active_width": Output(c.width, "mm", "l_a"),
        "width_ratio": Output(c.width / c.radius, "", "K5 = l_a / R_a, eq. (3)"),
        "filling_radius": Output(c.filling * c.radius, "mm", "R_1 = K2 R_a"),
        "contact_stress": Output(c.contact_stress(p), "MPa", "p_0, Hertz, eq. (9) consistent"),
        "contact_stress_eq9": Output(paper_eq9(p, c.radius, c.filling, n_a, n_b), "MPa", "p_0, eq. (9) as printed"),
        "contact_stress_eq10": Output(paper_eq10(p, c.radius, c.filling, c.conformity), "MPa",
                                      "p_0, eq. (10) as printed"),
        "hertz_n_a": Output(n_a, "", "n_a of the contact"),
        "hertz_n_b": Output(n_b, "", "n_b of the contact"),
        "curvature_ratio": Output(ratio, "", "B/A of the contact"),
        "ball_load": Output(ball_load(p, c.radius, c.filling, c.ball_radius), "N", "F on one outer ball"),
        "ball_mass": Output(c.balls(p), "kg", "balls, eq. (2) consistent"),
        "ball_count": Output(c.balls(p) / (p.density * 4.0 / 3.0 * math.pi * c.ball_radius**3), "",
                             "number of balls, m_n / (rho 4/3 pi r_c^3)"),
        "body_mass": Output(c.body(p), "kg", "G_c, eq. (13)"),
        "total_mass": Output(c.mass(p), "kg", "balls + body"),
        "cost": Output(c.cost(p), "EUR", "balls and body priced per kg"),
        "outer_diameter": Output(2 * (c.radius + p.shell_thickness), "mm", "2 (R_a + s)"),
    }


def _speed_law(clutch_of) -> SpeedLaw:
    """T = K w_a^2: the torque (8) of the ball layer, which rides on the driving rotor, at 1 rad/s. The balls have
    no springs, and their weight does not hold the layer in once it has formed, so neither effect applies."""
    def torque_coefficient(x, p):
        return clutch_of(x, p).torque(SimpleNamespace(**{**vars(p), "speed": 1.0}))

    return SpeedLaw(torque_coefficient)


def _formulation(mode, title, variables, clutch_of, constraints_of):
    return Formulation(
        coupling="ball",
        mode=mode,
        title=title,
        quantities=QUANTITIES,
        variables=variables,
        constraints=lambda x, p: constraints_of(clutch_of(x, p), p),
        objectives=(
            Objective("mass", "kg", "balls and body, eqs. (2), (13)", lambda x, p: clutch_of(x, p).mass(p)),
            Objective("cost", "EUR", "balls and body priced per kg", lambda x, p: clutch_of(x, p).cost(p)),
        ),
        outputs=lambda x, p: _outputs(clutch_of(x, p), p),
        speed_law=_speed_law(clutch_of),
    )


V = Variable
RADIUS = V("active_radius", "mm", "active friction radius", "R_a", lower=si(50, "mm"), upper=si(2000, "mm"), above=0)


# --- Paper mode: the paper's simplifying assumptions; the optimum is the fifth root (4) ---------------------------
PAPER_VARIABLES = (
    RADIUS,
    V("active_width", "mm", "active width (continuous, no whole rows)", "l", lower=si(10, "mm"), upper=si(2000, "mm"),
      above=0),
)


def _paper_clutch(x, p):
    return BallClutch(x.active_radius, x.active_width, filling_coefficient(p.construction_density, p.packing_density),
                      p.ball_radius, p.groove_conformity, x.active_width / (math.sqrt(3.0) * p.ball_radius))


def _paper_constraints(c: BallClutch, p):
    return [
        at_least("torque", leading_torque(p.friction_coefficient, p.density, p.packing_density, p.speed, c.width,
                                          c.radius, c.filling), required(p), equation="(4)", unit="N*m",
                 description="leading-order torque (cylinder, no shovels) covers M_c"),
        at_least("width_ratio", c.width / c.radius, p.width_ratio, equation="(3), (5)",
                 description="K5 = l / R_a at least the case's K5"),
    ]


PAPER = _formulation("paper", "Ball clutch, the paper's assumptions: leading-order torque, K2 from (1); R_a, l free",
                     PAPER_VARIABLES, _paper_clutch, _paper_constraints)


# --- Design mode: consistent torque, Hertz stress, whole ball rows --------------------------------------------------
DESIGN_VARIABLES = (  # K2 bounds: (1) gives 0.41 to 0.60 over the paper's Psi_c = 0.6 to 1.2
    RADIUS,
    V("filling", "", "K2 = R_1 / R_a, filling of the chambers", "K2",
      lower=0.41, upper=0.60, above=0, below=1),
    V("ball_radius", "mm", "ball radius", "r_c", lower=si(4, "mm"), upper=si(20, "mm"), above=0),
    V("groove_conformity", "", "beta = r_groove / r_c", "beta", lower=1.005, upper=1.05, above=1),
    V("ball_rows", "", "number of ball rows across the width", "n_p", lower=2, upper=80, at_least=1, integer=True),
)


def _design_clutch(x, p):
    return BallClutch(x.active_radius, width_from_rows(x.ball_rows, x.ball_radius), x.filling, x.ball_radius,
                      x.groove_conformity, x.ball_rows)


def _design_constraints(c: BallClutch, p):
    k5 = c.width / c.radius
    return [
        at_least("torque", c.torque(p), required(p), equation="(8)", unit="N*m",
                 description="torque of cylinder and end faces covers M_c"),
        at_most("contact_stress", c.contact_stress(p), p.allowable_contact_stress, equation="(9)", unit="MPa",
                description="Hertz stress of the outer balls within [p_0]"),
        at_least("width_ratio_min", k5, p.width_ratio_min, equation="(3)", description="K5 = l_a / R_a in range"),
        at_most("width_ratio_max", k5, p.width_ratio_max, equation="(3)", description="K5 = l_a / R_a in range"),
        at_most("outer_diameter", 2 * (c.radius + p.shell_thickness), p.outer_diameter_max, equation="case",
                unit="mm", description="2 (R_a + s) <= D_max"),
        at_least("ball_layers", c.radius * (1 - c.filling), p.min_ball_layers * 2 * c.ball_radius, equation="model",
                 unit="mm", scale=c.radius, description="the layer R_a - R_1 holds several balls"),
    ]


DESIGN = _formulation("design", "Ball clutch, consistent model: R_a, K2, r_c, beta, n_p free",
                      DESIGN_VARIABLES, _design_clutch, _design_constraints)


# --- The paper's procedure, as printed, step by step ---------------------------------------------------------------
def _procedure_pass(p, filling, geometry=None):
    """Eqs. (4)-(8) at one K2; with ``geometry`` (a previous pass) R_a, l, n_p and l_a are kept."""
    if geometry is None:
        radius = paper_active_radius(required(p), p.friction_coefficient, p.density, p.packing_density, p.speed,
                                     p.width_ratio, filling)
        approximate = p.width_ratio * radius
        rows = paper_ball_rows(approximate, p.ball_radius)
        geometry = {"active_radius": radius, "approximate_width": approximate, "ball_rows": rows,
                    "active_width": width_from_rows(rows, p.ball_radius)}
    torque = paper_eq8(p, geometry["active_radius"], geometry["active_width"], geometry["approximate_width"], filling)
    return {"filling": filling, **{k: geometry[k] for k in ("active_radius", "approximate_width", "ball_rows",
                                                             "active_width")},
            "torque_eq8": torque, "torque_ratio": torque / required(p)}


def paper_procedure(p, rule: str = "refill", max_passes: int = 60):
    """The paper's sizing as printed: K2 (1), R_a (4), l (5), n_p (6) up, l_a (7), M (8); while M (8) is off M_c
    by more than the tolerance (10 %), change K2 and calculate again; then p_0 (9), (10), masses (2), (12), (13).

    The paper does not say how to change K2. Our rule (``refill``, the default): keep the machined geometry
    (R_a, l, n_p, l_a of the first pass) and change only the filling K2 by bisection on (0, 1): too much torque,
    K2 up (fewer balls); too little, K2 down; the first K2 within the tolerance is kept. ``restart`` is the
    literal reading, every pass again from (4) with the new K2: (4) then rescales R_a to hold the leading torque
    at M_c, the excess of (8) (end faces, rounding up) only fades as K2 -> 1, and the bisection ends at a layer
    one ball thick in a drum several times larger (docs/ball.md). Returns every intermediate value and the passes.
    """
    if rule not in ("refill", "restart"):
        raise ValueError(f"rule must be 'refill' or 'restart', got {rule!r}")
    low, high = 0.0, 1.0
    filling = float(filling_coefficient(p.construction_density, p.packing_density))
    passes = [_procedure_pass(p, filling)]
    geometry = passes[0] if rule == "refill" else None
    while abs(passes[-1]["torque_ratio"] - 1) > p.torque_tolerance and len(passes) < max_passes:
        low, high = (filling, high) if passes[-1]["torque_ratio"] > 1 else (low, filling)
        filling = (low + high) / 2
        passes.append(_procedure_pass(p, filling, geometry))
    final = dict(passes[-1])
    radius, width, filling = final["active_radius"], final["active_width"], final["filling"]
    clutch = BallClutch(radius, width, filling, p.ball_radius, p.groove_conformity, final["ball_rows"])
    total, ratio = curvatures(radius, p.ball_radius, p.groove_conformity)
    n_a, n_b = hertz_coefficients_exact(ratio)
    final.update({
        "filling_eq1": passes[0]["filling"],
        "converged": abs(final["torque_ratio"] - 1) <= p.torque_tolerance,
        "passes": passes,
        "required_torque": required(p),
        "width_ratio": width / radius,
        "torque": float(clutch.torque(p)),
        "hertz_n_a": n_a, "hertz_n_b": n_b, "curvature_ratio": ratio,
        "contact_stress": float(clutch.contact_stress(p)),
        "contact_stress_eq9": paper_eq9(p, radius, filling, n_a, n_b),
        "contact_stress_eq10": paper_eq10(p, radius, filling, p.groove_conformity),
        "groove_pitch": math.sqrt(3) * p.ball_radius,
        "groove_depth_eq11": paper_groove_depth(p, radius, p.ball_radius, p.groove_conformity),
        "ball_mass_eq2": paper_eq2(p, radius, width, filling),
        "ball_mass_eq12": paper_eq12_balls(p, radius, width, filling),
        "ball_mass": float(clutch.balls(p)),
        "body_mass": float(clutch.body(p)),
        "total_mass": float(clutch.mass(p)),
        "cost": float(clutch.cost(p)),
        "ball_radius": p.ball_radius, "groove_conformity": p.groove_conformity,
        "outer_diameter": 2 * (radius + p.shell_thickness),
    })
    return final


# --- Comparison: the paper's procedure beside the NLP optima --------------------------------------------------------
ROWS = (
    ComparisonRow("active_radius", "mm", "R_a"),
    ComparisonRow("active_width", "mm", "l_a, eq. (7)"),
    ComparisonRow("width_ratio", "", "K5 = l_a / R_a"),
    ComparisonRow("ball_rows", "", "n_p"),
    ComparisonRow("filling", "", "K2 = R_1 / R_a"),
    ComparisonRow("ball_radius", "mm", "r_c"),
    ComparisonRow("groove_conformity", "", "beta"),
    ComparisonRow("torque", "N*m", "torque of the design, eq. (8) consistent"),
    ComparisonRow("contact_stress", "MPa", "p_0, Hertz (9) consistent"),
    ComparisonRow("contact_stress_eq10", "MPa", "p_0, eq. (10) as printed"),
    ComparisonRow("ball_mass", "kg", "balls, eq. (2) consistent"),
    ComparisonRow("body_mass", "kg", "body, eq. (13)"),
    ComparisonRow("total_mass", "kg", "balls + body"),
    ComparisonRow("cost", "EUR", "balls and body priced per kg"),
)
_OUTPUT_ROWS = ("active_width", "width_ratio", "torque", "contact_stress", "contact_stress_eq10", "ball_mass",
                "body_mass", "total_mass", "cost")


def _references(p):
    procedure = paper_procedure(p)
    return {"paper_procedure": {row.name: procedure[row.name] for row in ROWS}}


def _rows_from_design(mode, design, outputs, p):
    return {**design, **{name: outputs[name] for name in _OUTPUT_ROWS}}


COMPARISON = Comparison(
    rows=ROWS,
    references=_references,
    solves=(("nlp_mass", "design", "mass"), ("nlp_cost", "design", "cost")),
    rows_from_design=_rows_from_design,
    baseline="paper_procedure",
    column_notes={
        "paper_procedure": "the paper's procedure: K2 (1), fifth root (4), rows (6)-(7), K2 loop on (8) to 10 %; "
                           "evaluated with the consistent model",
        "nlp_mass": "IPOPT, design mode, minimum mass (balls + body)",
        "nlp_cost": "IPOPT, design mode, minimum cost (balls and body per kg)",
    },
)


# --- Contradictory requirements a single field cannot show ----------------------------------------------------------
def _check_ranges(case):
    v = case.values
    if v["width_ratio_min"] >= v["width_ratio_max"]:
        raise InputError("limits.width_ratio_max", f"must exceed limits.width_ratio_min ({v['width_ratio_min']:g})")
    if 2 * v["shell_thickness"] >= v["outer_diameter_max"]:
        raise InputError("limits.outer_diameter_max", "leaves no room inside the shell")
    layer = 1 - float(filling_coefficient(v["construction_density"], v["packing_density"]))
    if v["shovel_count"] * v["shovel_ratio"] * layer >= math.pi * (1 - (1 - layer) ** 2):
        raise InputError("body.shovel_ratio", "the shovels fill the whole ball layer (eq. 2 gives no balls)")


COUPLING = Coupling(
    name="ball",
    title="Centrifugal ball clutch",
    source="Tasev, ball_clutch_tasev.txt",
    quantities=QUANTITIES,
    formulations={"design": DESIGN, "paper": PAPER},
    default_mode="design",
    comparison=COMPARISON,
    case_checks=(_check_ranges,),
    materials=MATERIALS,
)
