"""Lever centrifugal friction coupling (Ambartsumyants & Deli; seed lever_cfc_ambartsumyants_deli.txt).

Construction (the paper's figure a): each of z toggles is two links 1, 2 of length l_2, pinned to each other
through a weight 4 (the knee) and, at their other ends, to two pressure discs 3 that slide axially on the
driving shaft. A tension spring of free length l_pr ties each weight to a flange of diameter d_phi on the shaft.
At speed the centrifugal force pulls the knee outwards, the toggle straightens and pushes the two discs apart
against the two inner faces of the driven housing 5, which encloses them: two friction surfaces, linings of
thickness delta.

Geometry (figure b; the paper has no equation numbers, so relations are named by their symbol): gamma is the
angle of a link to the shaft axis. With new linings the discs touch at gamma_0, the weight sitting at
R_0 = d_b/2 + (d_phi - d_b)/4 + l_pr (spring at its free length) and the disc pins at d_cp/2 = R_0 + S_ov,
S_ov = l_2 sin gamma_0. As the linings wear by delta the discs move out by delta and the angle falls towards
gamma_pr: l_2 (cos gamma_pr - cos gamma_0) >= delta.

Statics of the knee (derived here, docs/lever.md): F = m w^2 r_w outwards, each link in compression
S = F / (2 sin gamma), each link pushes its disc axially with F / (2 tan gamma). z toggles press each disc with
N = z F / (2 tan gamma); i = 2 lined faces at mean radius d_cp/2 carry T = i f N d_cp / 2. Hence the
characteristic number m z = 4 T_max tan(gamma_0) / (i f w^2 R_0 d_cp); the printed 32/(k (4 l_2 sin gamma_0 + k))
form is this with i = 1 (errata L1).

Two states bound the life of the linings: new (gamma_0, weight at R_0, spring slack: least push, the torque
requirement) and worn (gamma_pr, weight at R_0 + l_2 (sin gamma_0 - sin gamma_pr), spring stretched: largest
push, the lining pressure and link strength checks).

Two posed problems:
- ``paper``: the paper's method: gamma_0, gamma_pr, z, d_phi given, l_2 at the paper's minimum, lining width
  B_cp = 2 (S_ov + a delta); free: weight mass m and link diameter d_l.
- ``design``: free l_2, gamma_0, gamma_pr, z (integer), d_phi, lining width b, m, d_l within the housing
  (outer diameter, toggle span) and the paper's angle ranges.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace
from typing import Any

from clutchopt.backend import cbrt, cos, sin, sqrt, tan
from clutchopt.errors import InputError
from clutchopt.formulations.duty import DUTY_QUANTITIES, GRAVITY, centrifugal_force, required_torque
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

# --- Quantity table: what a lever case gives (TOML section.key, unit, paper symbol, meaning) -------------------
Q = Quantity
QUANTITIES = DUTY_QUANTITIES + (  # I_M, n_b, t_p, T_p: the same duty as the wedge
    Q("friction_coefficient", "", "friction coefficient of the linings on the housing faces", "f", "material",
      above=0, at_most=1),
    Q("allowable_pressure", "MPa", "allowable lining pressure (wear)", "[p]", "material", above=0),
    Q("allowable_link_stress", "MPa", "allowable compressive stress of a link", "[sigma]", "material", above=0),
    Q("elastic_modulus", "GPa", "Young's modulus of the links", "E", "material", "210 GPa", above=0),
    Q("buckling_safety_factor", "", "safety factor of a link against Euler buckling", "n_b", "material", 3.0,
      at_least=1),
    Q("allowable_pin_shear", "MPa", "allowable shear stress of the link pins (pin size is reported)", "[tau]",
      "material", above=0),
    Q("density", "kg/m^3", "density of weights and links", "rho", "material", "7850 kg/m^3", above=0),
    Q("lining_density", "kg/m^3", "density of the friction lining", "rho_l", "material", "2000 kg/m^3", above=0),
    Q("shaft_diameter", "mm", "diameter of the coupled shafts", "d_b", "geometry", above=0),
    Q("flange_diameter", "mm", "flange carrying the spring eyes (paper mode; start in design mode)", "d_phi",
      "geometry", above=0),
    Q("flange_thickness", "mm", "axial thickness of the spring flange (counted in the mass)", "", "geometry",
      "10 mm", above=0),
    Q("lining_thickness", "mm", "lining thickness = wear the levers must follow", "delta", "geometry", above=0),
    Q("engagement_angle", "deg", "link angle to the axis when new linings touch (paper: at most 15 deg)",
      "gamma_0", "geometry", above=0, at_most=math.radians(15)),
    Q("limit_angle", "deg", "link angle when the linings are worn by delta (paper: 1.5 to 3 deg)", "gamma_pr",
      "geometry", at_least=math.radians(1.5), at_most=math.radians(3)),
    Q("weight_count", "", "number of weights (toggles)", "z", "geometry", at_least=1, integer=True),
    Q("friction_surfaces", "", "lined faces in contact (two discs, one face each)", "i", "geometry", 2,
      at_least=1, integer=True),
    Q("width_allowance", "", "a in the paper's lining width B_cp = 2 (S_ov + a delta), a = 1.5 to 2", "a",
      "geometry", 1.5, at_least=1.5, at_most=2),
    Q("spring_free_length", "mm", "free length of the return spring", "l_pr", "spring", above=0),
    Q("disc_retraction_force", "N", "axial force that slides one pressure disc back at standstill", "W_ax",
      "spring", at_least=0),
    Q("outer_diameter_max", "mm", "largest outer diameter of the housing", "D_max", "limits", above=0),
    Q("shell_thickness", "mm", "radial wall of the housing outside the linings", "s", "limits", at_least=0),
    Q("toggle_span_max", "mm", "largest axial span of a toggle, 2 l_2 cos gamma_pr", "L_max", "limits", above=0),
    Q("flange_hub_ratio", "", "flange diameter / shaft diameter at least", "", "limits", 1.6, above=1),
    Q("weight_packing", "", "share of the circle at R_0 the z weights (cubes) may fill", "", "limits", 0.6,
      above=0, at_most=1),
    Q("material_price", "EUR/kg", "price of weight and link material", "", "cost", "2.5 EUR/kg", at_least=0),
    Q("part_cost", "EUR", "machining per toggle: weight, two links, three pins", "", "cost", "15 EUR", at_least=0),
    Q("lining_price", "EUR/cm^2", "friction lining, bonded, per area", "", "cost", "0.02 EUR/cm^2", at_least=0),
)

# --- What a case may take from the material library (clutchopt materials) ----------------------------------------
MATERIALS = (
    MaterialRole("material", "materials", "weights, links, pins and spring flange",
                 {"density": "density", "elastic_modulus": "elastic_modulus",
                  "allowable_normal": "allowable_link_stress", "allowable_shear": "allowable_pin_shear",
                  "price": "material_price"}),
    MaterialRole("friction_pair", "friction_pairs", "linings of the pressure discs on the housing faces",
                 {"friction_coefficient": "friction_coefficient", "allowable_pressure": "allowable_pressure",
                  "density": "lining_density", "price": "lining_price"}),
)


# --- Equations of the paper -----------------------------------------------------------------------------------------
def minimum_lever_length(lining_thickness, limit_angle, engagement_angle):
    """l_2 >= delta / (cos gamma_pr - cos gamma_0): the discs can follow the lining wear delta (paper, l_2 rule)."""
    return lining_thickness / (cos(limit_angle) - cos(engagement_angle))


def lever_offset(lever_length, engagement_angle):
    """S_ov = l_2 sin gamma_0: radial offset of the disc pins above the weight at engagement (paper, d_cp)."""
    return lever_length * sin(engagement_angle)


def start_radius(shaft_diameter, flange_diameter, spring_free_length):
    """R_0 = d_b/2 + (d_phi - d_b)/4 + l_pr: the weight at engagement, its spring at free length (paper, d_cp)."""
    return shaft_diameter / 2.0 + (flange_diameter - shaft_diameter) / 4.0 + spring_free_length


def mean_diameter(offset, radius):
    """d_cp = 2 (S_ov + R_0): diameter of the disc pins = mean diameter of the linings (paper, d_cp)."""
    return 2.0 * (offset + radius)


def paper_k(shaft_diameter, flange_diameter, spring_free_length):
    """k = d_b + d_phi + 4 l_pr (paper, under the characteristic number); k = 4 R_0."""
    return shaft_diameter + flange_diameter + 4.0 * spring_free_length


def paper_mean_width(offset, lining_thickness, allowance):
    """B_cp ~ 2 [S_ov + (1.5..2) delta] (paper, last relation); read here as the radial width of the linings."""
    return 2.0 * (offset + allowance * lining_thickness)


def paper_characteristic_number(torque, friction_coefficient, speed, engagement_angle, lever_length, k):
    """m z = 32 T_max tan(gamma_0) / (f w^2 k (4 l_2 sin gamma_0 + k)), as printed (errata L1: one surface)."""
    return (32.0 * torque * tan(engagement_angle)
            / (friction_coefficient * speed**2 * k * (4.0 * lever_length * sin(engagement_angle) + k)))


def paper_spring_stiffness(mean_length, lining_thickness, count, lever_length, engagement_angle, limit_angle):
    """c = pi l_cp^2 delta g tan(gamma_0) / (z l_2 (sin gamma_0 - sin gamma_pr)), as printed (paper, c).

    Not a stiffness: in SI it is m^3/s^2, a density short of N/m (errata L2). l_cp is not defined in the paper.
    """
    return (math.pi * mean_length**2 * lining_thickness * GRAVITY * tan(engagement_angle)
            / (count * lever_length * (sin(engagement_angle) - sin(limit_angle))))


# --- Equations derived here: statics of the toggle, wear, strength, spring ----------------------------------------
def weight_travel(lever_length, engagement_angle, angle):
    """Radial travel of the weight from gamma_0 to gamma: l_2 (sin gamma_0 - sin gamma) = spring stretch."""
    return lever_length * (sin(engagement_angle) - sin(angle))


def link_force(radial_force, angle):
    """S = F / (2 sin gamma): compression in each link of a toggle whose knee carries F radially."""
    return radial_force / (2.0 * sin(angle))


def disc_push(radial_force, angle):
    """S cos gamma = F / (2 tan gamma): axial push of one toggle on each disc."""
    return radial_force / (2.0 * tan(angle))


def disc_friction_torque(surfaces, friction_coefficient, push, diameter):
    """T = i f N d_cp / 2: i lined faces, each pressed by N, friction at d_cp/2 (exact under uniform wear)."""
    return surfaces * friction_coefficient * push * diameter / 2.0


def characteristic_number(torque, friction_coefficient, speed, engagement_angle, radius, diameter, surfaces):
    """m z = 4 T_max tan(gamma_0) / (i f w^2 R_0 d_cp): T = i f (z m w^2 R_0 / (2 tan gamma_0)) d_cp / 2 solved."""
    return 4.0 * torque * tan(engagement_angle) / (surfaces * friction_coefficient * speed**2 * radius * diameter)


def lining_pressure(push, diameter, width):
    """p = N / (pi d_cp b): lining ring of mean diameter d_cp and radial width b, centred on the disc pins."""
    return push / (math.pi * diameter * width)


def return_spring_force(weight_mass, retraction_force, count, engagement_angle):
    """c * l_2 (sin gamma_0 - sin gamma_pr) = m g + 2 W_ax tan(gamma_0) / z.

    At standstill with worn linings the stretched spring must lift the weight at the bottom of its circle (m g)
    and, through the toggle at its least favourable angle gamma_0, slide each disc back against W_ax
    (radial knee force per toggle 2 (W_ax / z) tan gamma): the paper's choice of states, made dimensionally
    consistent (errata L2).
    """
    return weight_mass * GRAVITY + 2.0 * retraction_force * tan(engagement_angle) / count


def euler_stress(elastic_modulus, diameter, length):
    """sigma_E = pi^2 E / (l / i)^2 with i = d/4: pinned-pinned solid round link."""
    return math.pi**2 * elastic_modulus * diameter**2 / (16.0 * length**2)


def link_stress(force, diameter):
    """sigma = 4 S / (pi d_l^2): compression of a solid round link."""
    return 4.0 * force / (math.pi * diameter**2)


def pin_diameter(force, allowable_shear):
    """d_pin = sqrt(2 |S| / (pi [tau])): pin in double shear (fork joints) under the link force S, pushing or
    pulling (a worn toggle at low speed pulls)."""
    return sqrt(2.0 * abs(force) / (math.pi * allowable_shear))


def rod_mass(density, diameter, length):
    return density * math.pi * diameter**2 / 4.0 * length


def flange_mass(density, flange_diameter, shaft_diameter, thickness):
    """Spring flange: annular disc d_b..d_phi of the given thickness."""
    return density * math.pi * (flange_diameter**2 - shaft_diameter**2) / 4.0 * thickness


def lining_mass(lining_density, surfaces, diameter, width, thickness):
    """i lining rings of mean diameter d_cp, width b, thickness delta."""
    return surfaces * lining_density * math.pi * diameter * width * thickness


def weight_size(weight_mass, density):
    """Edge of a cube of mass m: how much of the circle at R_0 a weight takes."""
    return cbrt(weight_mass / density)


def toggle_span(lever_length, limit_angle):
    """Axial span of a toggle at its longest (gamma_pr): 2 l_2 cos gamma_pr."""
    return 2.0 * lever_length * cos(limit_angle)


# --- The state of a set of toggles, shared by both modes ------------------------------------------------------------
@dataclass(frozen=True)
class Toggles:
    """z toggles at speed; the modes differ only in how this is obtained (paper rules or free variables)."""

    p: Any
    count: Any
    weight_mass: Any
    lever_length: Any
    engagement_angle: Any
    limit_angle: Any
    flange_diameter: Any
    lining_width: Any
    link_diameter: Any

    @property
    def start_radius(self):
        return start_radius(self.p.shaft_diameter, self.flange_diameter, self.p.spring_free_length)

    @property
    def offset(self):
        return lever_offset(self.lever_length, self.engagement_angle)

    @property
    def mean_diameter(self):
        return mean_diameter(self.offset, self.start_radius)

    @property
    def travel(self):
        return weight_travel(self.lever_length, self.engagement_angle, self.limit_angle)

    @property
    def spring_force(self):
        return return_spring_force(self.weight_mass, self.p.disc_retraction_force, self.count, self.engagement_angle)

    @property
    def new_radial_force(self):
        """Linings new: weight at R_0, spring slack."""
        return centrifugal_force(self.weight_mass, self.p.speed, self.start_radius)

    @property
    def worn_radial_force(self):
        """Linings worn by delta: weight at R_0 + travel, spring stretched by the travel."""
        return centrifugal_force(self.weight_mass, self.p.speed, self.start_radius + self.travel) - self.spring_force

    @property
    def new_push(self):
        return self.count * disc_push(self.new_radial_force, self.engagement_angle)

    @property
    def worn_push(self):
        return self.count * disc_push(self.worn_radial_force, self.limit_angle)

    def torque(self, push):
        return disc_friction_torque(self.p.friction_surfaces, self.p.friction_coefficient, push, self.mean_diameter)

    @property
    def worn_link_force(self):
        return link_force(self.worn_radial_force, self.limit_angle)

    @property
    def worn_link_stress(self):
        return link_stress(self.worn_link_force, self.link_diameter)

    @property
    def steel_mass(self):
        """Weights, two links per toggle and the spring flange."""
        p = self.p
        toggles = self.count * (self.weight_mass + 2.0 * rod_mass(p.density, self.link_diameter, self.lever_length))
        return toggles + flange_mass(p.density, self.flange_diameter, p.shaft_diameter, p.flange_thickness)

    @property
    def lining_mass(self):
        p = self.p
        return lining_mass(p.lining_density, p.friction_surfaces, self.mean_diameter, self.lining_width,
                           p.lining_thickness)

    @property
    def total_mass(self):
        return self.steel_mass + self.lining_mass

    @property
    def cost(self):
        p = self.p
        lining_area = p.friction_surfaces * math.pi * self.mean_diameter * self.lining_width
        return p.material_price * self.steel_mass + self.count * p.part_cost + p.lining_price * lining_area


def _t_max(p):
    return required_torque(p.inertia, p.speed, p.acceleration_time, p.resisting_torque)


def _duty_constraints(t: Toggles):
    """Torque with new linings, wear and link strength with worn ones, weights that fit: both modes."""
    p = t.p
    return [
        at_least("torque", t.torque(t.new_push), _t_max(p), equation="m z (statics)", unit="N*m",
                 description="friction torque at gamma_0, new linings, covers T_max", constant_acceleration=True),
        at_most("lining_pressure", lining_pressure(t.worn_push, t.mean_diameter, t.lining_width),
                p.allowable_pressure, equation="B_cp, statics", unit="MPa",
                description="lining pressure at gamma_pr (worn: largest push) within [p]"),
        at_most("link_buckling", t.worn_link_stress,
                euler_stress(p.elastic_modulus, t.link_diameter, t.lever_length) / p.buckling_safety_factor,
                equation="Euler", unit="MPa", description="link stress at gamma_pr within sigma_E / n_b"),
        at_most("link_compression", t.worn_link_stress, p.allowable_link_stress, equation="statics", unit="MPa",
                description="link stress at gamma_pr within [sigma]"),
        at_most("weights_fit", t.count * weight_size(t.weight_mass, p.density),
                p.weight_packing * 2.0 * math.pi * t.start_radius, equation="geometry", unit="mm",
                description="z cube edges fit round the circle at R_0"),
    ]


def _duty_outputs(t: Toggles):
    p = t.p
    new_torque, worn_torque = t.torque(t.new_push), t.torque(t.worn_push)
    return {
        "required_torque": Output(_t_max(p), "N*m", "T_max = I w / t_p + T_p"),
        "torque": Output(new_torque, "N*m", "friction torque with new linings (gamma_0)"),
        "worn_torque": Output(worn_torque, "N*m", "friction torque with worn linings (gamma_pr)"),
        "torque_growth": Output(worn_torque / new_torque, "", "worn / new torque over the lining life"),
        "lining_pressure": Output(lining_pressure(t.worn_push, t.mean_diameter, t.lining_width), "MPa",
                                  "p at gamma_pr (worn)"),
        "new_lining_pressure": Output(lining_pressure(t.new_push, t.mean_diameter, t.lining_width), "MPa",
                                      "p at gamma_0 (new)"),
        "weight_mass": Output(t.weight_mass, "kg", "m, one weight"),
        "characteristic_number": Output(t.count * t.weight_mass, "kg", "m z"),
        "lever_length": Output(t.lever_length, "mm", "l_2"),
        "lever_offset": Output(t.offset, "mm", "S_ov = l_2 sin gamma_0"),
        "start_radius": Output(t.start_radius, "mm", "R_0, weight at engagement"),
        "mean_diameter": Output(t.mean_diameter, "mm", "d_cp = 2 (S_ov + R_0)"),
        "lining_width": Output(t.lining_width, "mm", "b, radial width of the linings"),
        "weight_travel": Output(t.travel, "mm", "l_2 (sin gamma_0 - sin gamma_pr), spring stretch when worn"),
        "disc_push": Output(t.new_push, "N", "axial push on each disc, new linings"),
        "worn_disc_push": Output(t.worn_push, "N", "axial push on each disc, worn linings"),
        "link_force": Output(t.worn_link_force, "N", "S at gamma_pr, largest link compression"),
        "pin_diameter": Output(pin_diameter(t.worn_link_force, p.allowable_pin_shear), "mm",
                               "pin in double shear under S"),
        "spring_stiffness": Output(t.spring_force / t.travel, "N/m", "consistent return-spring stiffness c"),
        "paper_spring_stiffness": Output(
            paper_spring_stiffness(t.mean_diameter / 2.0, p.lining_thickness, t.count, t.lever_length,
                                   t.engagement_angle, t.limit_angle),
            "m^3/s^2", "c as printed with l_cp = d_cp/2 (not a stiffness: errata L2)"),
        "toggle_span": Output(toggle_span(t.lever_length, t.limit_angle), "mm", "2 l_2 cos gamma_pr"),
        "outer_diameter": Output(t.mean_diameter + t.lining_width + 2.0 * p.shell_thickness, "mm",
                                 "d_cp + b + 2 s"),
        "total_mass": Output(t.total_mass, "kg", "weights, links, spring flange, linings"),
        "cost": Output(t.cost, "EUR", "material, parts, linings"),
    }


def _speed_law(toggles) -> SpeedLaw:
    """T = K w_a^2, K the friction torque with new linings (gamma_0, weight at R_0, spring slack) at 1 rad/s; each
    weight's centrifugal force is m R_0 w_a^2, against which a spring preload and gravity act."""
    def at_one_radian_per_second(x, p):
        return toggles(x, SimpleNamespace(**{**vars(p), "speed": 1.0}))

    def torque_coefficient(x, p):
        t = at_one_radian_per_second(x, p)
        return t.torque(t.new_push)

    def mass_radius(x, p):
        t = toggles(x, p)
        return t.weight_mass * t.start_radius

    return SpeedLaw(torque_coefficient, mass_radius, lambda x, p: toggles(x, p).weight_mass)


def _formulation(mode, title, variables, toggles, extra_constraints=lambda t: []):
    """A lever formulation from the way its mode obtains the toggles."""
    return Formulation(
        coupling="lever",
        mode=mode,
        title=title,
        quantities=QUANTITIES,
        variables=variables,
        constraints=lambda x, p: _duty_constraints(t := toggles(x, p)) + extra_constraints(t),
        objectives=(
            Objective("mass", "kg", "weights, links, spring flange and linings", lambda x, p: toggles(x, p).total_mass),
            Objective("cost", "EUR", "material, parts per toggle, linings", lambda x, p: toggles(x, p).cost),
        ),
        outputs=lambda x, p: _duty_outputs(toggles(x, p)),
        speed_law=_speed_law(toggles),
    )


# --- Paper mode: the paper's rules fix the geometry; m and d_l free -------------------------------------------------
V = Variable
WEIGHT_MASS = V("weight_mass", "kg", "mass of one weight", "m", lower=1e-4, upper=100.0, above=0)
LINK_DIAMETER = V("link_diameter", "mm", "diameter of a (solid round) link", "d_l", lower=si(0.5, "mm"),
                  upper=si(100, "mm"), above=0)
PAPER_VARIABLES = (WEIGHT_MASS, LINK_DIAMETER)


def paper_geometry(p):
    """(l_2, B_cp): the shortest levers of the l_2 rule and the paper's lining width."""
    lever = minimum_lever_length(p.lining_thickness, p.limit_angle, p.engagement_angle)
    width = paper_mean_width(lever_offset(lever, p.engagement_angle), p.lining_thickness, p.width_allowance)
    return lever, width


def _paper_toggles(x, p):
    lever, width = paper_geometry(p)
    return Toggles(p, p.weight_count, x.weight_mass, lever, p.engagement_angle, p.limit_angle, p.flange_diameter,
                   width, x.link_diameter)


PAPER = _formulation("paper", "Lever CFC, paper method: l_2 and B_cp by the paper's rules, m and d_l free",
                     PAPER_VARIABLES, _paper_toggles)


# --- Design mode: geometry free within the housing ------------------------------------------------------------------
DESIGN_VARIABLES = (
    WEIGHT_MASS,
    V("lever_length", "mm", "link length", "l_2", lower=si(10, "mm"), upper=si(2000, "mm"), above=0),
    V("engagement_angle", "deg", "link angle to the axis, new linings", "gamma_0", lower=si(4, "deg"),
      upper=si(15, "deg"), above=0, at_most=math.radians(15)),
    V("limit_angle", "deg", "link angle to the axis, worn linings", "gamma_pr", lower=si(1.5, "deg"),
      upper=si(3, "deg"), at_least=math.radians(1.5), at_most=math.radians(3)),
    V("weight_count", "", "number of weights (toggles)", "z", lower=3, upper=12, at_least=1, integer=True),
    V("flange_diameter", "mm", "spring flange diameter", "d_phi", lower=si(10, "mm"), upper=si(1000, "mm"), above=0),
    V("lining_width", "mm", "radial width of the linings", "b", lower=si(2, "mm"), upper=si(500, "mm"), above=0),
    LINK_DIAMETER,
)


def _design_toggles(x, p):
    return Toggles(p, x.weight_count, x.weight_mass, x.lever_length, x.engagement_angle, x.limit_angle,
                   x.flange_diameter, x.lining_width, x.link_diameter)


def _housing_constraints(t: Toggles):
    """The l_2 rule and what makes the toggles fit a housing and a shaft."""
    p = t.p
    return [
        at_least("lever_length", t.lever_length * (cos(t.limit_angle) - cos(t.engagement_angle)),
                 p.lining_thickness, equation="l_2 rule", unit="mm",
                 description="l_2 (cos gamma_pr - cos gamma_0) >= delta"),
        at_most("outer_diameter", t.mean_diameter + t.lining_width + 2.0 * p.shell_thickness, p.outer_diameter_max,
                equation="case", unit="mm", description="d_cp + b + 2 s <= D_max"),
        at_most("toggle_span", toggle_span(t.lever_length, t.limit_angle), p.toggle_span_max, equation="case",
                unit="mm", description="2 l_2 cos gamma_pr <= L_max"),
        at_least("lining_clears_flange", t.mean_diameter - t.lining_width, t.flange_diameter, equation="geometry",
                 unit="mm", description="inner lining diameter d_cp - b >= d_phi"),
        at_least("flange_over_shaft", t.flange_diameter, p.flange_hub_ratio * p.shaft_diameter, equation="geometry",
                 unit="mm", description="d_phi >= ratio * d_b"),
    ]


DESIGN = _formulation("design", "Lever CFC, geometry free: l_2, angles, z, d_phi, b, m, d_l",
                      DESIGN_VARIABLES, _design_toggles, _housing_constraints)


# --- Closed forms of the consistent model (paper mode) ----------------------------------------------------------------
def closed_form_characteristic_number(p):
    """m z from the torque requirement at gamma_0 with the paper's geometry (consistent form of the paper's m z)."""
    lever, _ = paper_geometry(p)
    radius = start_radius(p.shaft_diameter, p.flange_diameter, p.spring_free_length)
    diameter = mean_diameter(lever_offset(lever, p.engagement_angle), radius)
    return characteristic_number(_t_max(p), p.friction_coefficient, p.speed, p.engagement_angle, radius, diameter,
                                 p.friction_surfaces)


def closed_form_link_diameter(p, weight_mass):
    """d_l = max((64 n_b S l_2^2 / (pi^3 E))^(1/4), (4 S / (pi [sigma]))^(1/2)) at the worn-state link force S;
    NaN where S <= 0 (the worn toggle does not press the linings at this duty)."""
    t = _paper_toggles(SimpleNamespace(weight_mass=weight_mass, link_diameter=math.nan), p)
    force, length = t.worn_link_force, t.lever_length
    if not force > 0:  # at this duty the worn toggle no longer presses: the paper's sizing has no link to size
        return math.nan
    buckling = (64.0 * p.buckling_safety_factor * force * length**2 / (math.pi**3 * p.elastic_modulus)) ** 0.25
    compression = math.sqrt(4.0 * force / (math.pi * p.allowable_link_stress))
    return max(buckling, compression)


# --- Comparison: the paper's printed formula, the consistent closed form, the NLP -----------------------------------
ROWS = (
    ComparisonRow("characteristic_number", "kg", "m z"),
    ComparisonRow("weight_mass", "kg", "m, one weight"),
    ComparisonRow("weight_count", "", "z"),
    ComparisonRow("lever_length", "mm", "l_2"),
    ComparisonRow("engagement_angle", "deg", "gamma_0"),
    ComparisonRow("limit_angle", "deg", "gamma_pr"),
    ComparisonRow("mean_diameter", "mm", "d_cp"),
    ComparisonRow("lining_width", "mm", "b"),
    ComparisonRow("link_diameter", "mm", "d_l"),
    ComparisonRow("torque", "N*m", "torque of that design with new linings, consistent statics"),
    ComparisonRow("worn_torque", "N*m", "torque of that design with worn linings"),
    ComparisonRow("lining_pressure", "MPa", "p of that design, worn linings"),
    ComparisonRow("spring_stiffness", "N/m", "return spring c, consistent"),
    ComparisonRow("total_mass", "kg", "weights, links, spring flange, linings"),
)


def _rows(design, outputs, p):
    return {
        **{name: outputs[name] for name in ("characteristic_number", "weight_mass", "lever_length", "mean_diameter",
                                            "lining_width", "torque", "worn_torque", "lining_pressure",
                                            "spring_stiffness", "total_mass")},
        "weight_count": design.get("weight_count", p.weight_count),
        "engagement_angle": design.get("engagement_angle", p.engagement_angle),
        "limit_angle": design.get("limit_angle", p.limit_angle),
        "link_diameter": design["link_diameter"],
    }


def _paper_design_rows(p, weight_mass, link_diameter):
    """Rows of a design at the paper's geometry, evaluated with the consistent model."""
    design = {"weight_mass": weight_mass, "link_diameter": link_diameter}
    outputs = {name: out.value for name, out in PAPER.outputs(SimpleNamespace(**design), p).items()}
    return _rows(design, outputs, p)


def _references(p):
    lever, _ = paper_geometry(p)
    printed = paper_characteristic_number(_t_max(p), p.friction_coefficient, p.speed, p.engagement_angle, lever,
                                          paper_k(p.shaft_diameter, p.flange_diameter, p.spring_free_length))
    mass = closed_form_characteristic_number(p) / p.weight_count
    return {
        "paper_formula": _paper_design_rows(p, printed / p.weight_count, math.nan),
        "closed_form": _paper_design_rows(p, mass, closed_form_link_diameter(p, mass)),
    }


COMPARISON = Comparison(
    rows=ROWS,
    references=_references,
    solves=(("nlp_paper", "paper", "mass"), ("nlp_design", "design", "mass")),
    rows_from_design=lambda mode, design, outputs, p: _rows(design, outputs, p),
    baseline="closed_form",
    column_notes={
        "paper_formula": "m z by the printed formula (32 ...) at the paper's geometry; the paper sizes no link",
        "closed_form": "consistent closed form of the paper-mode model (two friction surfaces)",
        "nlp_paper": "IPOPT, paper mode, minimum mass",
        "nlp_design": "IPOPT, design mode (geometry free), minimum mass",
    },
)


def _check_case(case):
    """Contradictions a single field cannot show."""
    v = case.values
    if v["limit_angle"] >= v["engagement_angle"]:
        raise InputError("geometry.engagement_angle", "must exceed the limit angle gamma_pr: the toggle straightens "
                                                      "as the linings wear")
    if v["flange_diameter"] <= v["shaft_diameter"]:
        raise InputError("geometry.flange_diameter", "must exceed the shaft diameter d_b")
    if 2 * v["shell_thickness"] >= v["outer_diameter_max"]:
        raise InputError("limits.outer_diameter_max", "leaves no room inside the shell")


COUPLING = Coupling(
    name="lever",
    title="Lever centrifugal friction coupling",
    source="Ambartsumyants & Deli, lever_cfc_ambartsumyants_deli.txt",
    quantities=QUANTITIES,
    formulations={"paper": PAPER, "design": DESIGN},
    default_mode="paper",
    comparison=COMPARISON,
    case_checks=(_check_case,),
    materials=MATERIALS,
)
