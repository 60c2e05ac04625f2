"""Wedge centrifugal friction coupling (Ambartsumyants & Deli, 2015; seed wedge_cfc_ambartsumyants_deli_2015.txt).

z weights, annular sectors of central angle gamma, slide radially on fingers of the driving shaft. Centrifugal
force pushes each weight's trapezoidal top (flanks inclined alpha to the radial direction, between radii r1 and
r2 = lambda r1) into a V-groove of the driven half-coupling; friction on the two flanks carries the torque.

Equation numbers are the paper's. Where the printed equation is inconsistent the consistent form is used here
and the printed one is kept as ``paper_eq*`` for comparison; see docs/errata.md (W1-W6).

Two posed problems:
- ``paper``: the paper's geometry (r1, lambda, h_r, z, alpha, gamma) is given, r_c = r2 - 2/3 h_r (11);
  free: weight mass m_r and finger diameter d_n.
- ``geometry``: the weight is a real body (annular sector r_in..r2, axial width b, trapezoidal top) whose mass
  and exact centroid follow from its geometry; free: r1, lambda, h_r, gamma, b, d_n (alpha and z if freed).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import SimpleNamespace
from typing import Any

from clutchopt.backend import arctan, cbrt, cos, sin, tan
from clutchopt.formulations.duty import DUTY_QUANTITIES, centrifugal_force, required_torque
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

# --- Quantity table: what a wedge case gives (TOML section.key, unit, paper symbol, meaning) -------------------
Q = Quantity
QUANTITIES = DUTY_QUANTITIES + (
    Q("friction_coefficient", "", "flank friction coefficient", "f", "material", above=0, at_most=1),
    Q("allowable_pressure", "MPa", "allowable flank pressure (wear)", "[p]", "material", above=0),
    Q("allowable_bending_stress", "MPa", "allowable bending stress of the finger", "[sigma]", "material", above=0),
    Q("density", "kg/m^3", "density of weights and fingers", "rho", "material", "7850 kg/m^3", above=0),
    Q("flank_inner_radius", "mm", "inner radius of the flanks (paper mode; start in geometry mode)", "r_1",
      "geometry", above=0),
    Q("radius_ratio", "", "lambda = r2/r1 (paper: 1.1 to 1.35)", "lambda", "geometry", above=1),
    Q("weight_height", "mm", "radial height of a weight", "h_r", "geometry", above=0),
    Q("weight_count", "", "number of weights", "z", "geometry", at_least=1, integer=True),
    Q("flank_angle", "deg", "flank half-angle of the wedge, from the radial direction", "alpha", "geometry",
      above=0, below=math.pi / 2),
    Q("sector_angle", "deg", "central angle of a weight", "gamma", "geometry", above=0, below=2 * math.pi),
    Q("weight_width", "mm", "axial width of a weight at the flank base (geometry-mode start)", "b", "geometry",
      None, above=0),
    Q("outer_diameter_max", "mm", "largest outer diameter of the coupling", "D_max", "limits", above=0),
    Q("shell_thickness", "mm", "radial wall of the driven half-coupling outside r2", "s", "limits", at_least=0),
    Q("hub_radius", "mm", "radius the weights must clear inside (shaft, spring seats)", "r_hub", "limits",
      at_least=0),
    Q("sector_clearance", "deg", "angular gap kept between neighbouring weights", "", "limits", "2 deg",
      at_least=0),
    Q("self_locking_margin", "deg", "flank angle kept above the self-locking limit atan f", "", "limits",
      "2 deg", at_least=0),
    Q("min_top_width", "mm", "smallest width of the trapezoid's top land", "", "limits", "2 mm", at_least=0),
    Q("finger_fit_ratio", "", "finger diameter / weight width (or chord) at most", "", "limits", 0.5,
      above=0, at_most=1),
    Q("guide_length_ratio", "", "weight height / finger diameter at least (sliding guide, no jamming)", "",
      "limits", 1.5, above=0),
    Q("material_price", "EUR/kg", "price of weight and finger material", "", "cost", "2.5 EUR/kg", at_least=0),
    Q("part_cost", "EUR", "machining and handling per weight with its finger", "", "cost", "12 EUR", at_least=0),
    Q("flank_finish_cost", "EUR/cm^2", "grinding cost per flank area", "", "cost", "0.05 EUR/cm^2", at_least=0),
    Q("printed_weight_mass", "kg", "m_r as printed in the paper's example", "m_r", "paper", None, above=0),
    Q("printed_finger_diameter", "mm", "d_n as printed in the paper's example", "d_n", "paper", None, above=0),
)

# --- What a case may take from the material library (clutchopt materials) ----------------------------------------
MATERIALS = (
    MaterialRole("material", "materials", "weights and fingers",
                 {"density": "density", "allowable_bending": "allowable_bending_stress", "price": "material_price"}),
    MaterialRole("friction_pair", "friction_pairs", "flanks of the weights in the groove of the driven half",
                 {"friction_coefficient": "friction_coefficient", "allowable_pressure": "allowable_pressure",
                  "price": "flank_finish_cost"}),
)


# --- Equations ---------------------------------------------------------------------------------------------------
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


def flank_pressure(centrifugal, flank_angle, sector_angle, r1, r2):
    """q = N / A_flank = F_u cot(alpha) / (gamma (r2^2 - r1^2)), eqs. (9), (12), (13) for one weight (errata W3)."""
    return flank_normal_force(centrifugal, flank_angle) / flank_area(sector_angle, r1, r2, flank_angle)


def finger_bending_stress(friction, finger_length, finger_diameter):
    """sigma = F_fr h_n / (pi d_n^3 / 32), cantilever finger, eq. (19) (errata W4)."""
    return 32.0 * friction * finger_length / (math.pi * finger_diameter**3)


def finger_mass(density, finger_diameter, finger_length):
    """Steel finger of length h_n = d_cp / 2 (text below eq. 18)."""
    return density * math.pi * finger_diameter**2 / 4.0 * finger_length


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


def cost(p, total_mass, weight_count, flank_area_one_side):
    """Material at a price per kg, a fixed cost per weight-and-finger part, grinding per flank area."""
    return (p.material_price * total_mass + weight_count * p.part_cost
            + p.flank_finish_cost * weight_count * 2.0 * flank_area_one_side)


# --- The paper's printed forms, kept for comparison (docs/errata.md) ----------------------------------------------
def paper_eq27_first_form(p):
    """m_r = 2 T_max sin(alpha) / (f z (1 + lambda) r1 w^2 (lambda r1 - 2/3 h_r)), eq. (27), first form."""
    r1, lam, w = p.flank_inner_radius, p.radius_ratio, p.speed
    t_max = required_torque(p.inertia, w, p.acceleration_time, p.resisting_torque)
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


# --- The state of a set of weights, shared by both modes ----------------------------------------------------------
@dataclass(frozen=True)
class WeightSet:
    """z weights at speed: where the modes differ is only how this is obtained (given geometry or real bodies)."""

    count: Any
    r1: Any
    r2: Any
    flank_angle: Any
    sector_angle: Any
    weight_mass: Any
    centroid_radius: Any
    finger_diameter: Any
    speed: Any
    friction_coefficient: Any

    @property
    def centrifugal(self):
        return centrifugal_force(self.weight_mass, self.speed, self.centroid_radius)

    @property
    def friction(self):
        return friction_force(self.friction_coefficient, self.centrifugal, self.flank_angle)


def _duty_constraints(w: WeightSet, p):
    """Torque (15)-(16), wear (13) and finger bending (19): the paper's three requirements."""
    return [
        at_least("torque", friction_torque(w.count, w.friction, w.r1, w.r2),
                 required_torque(p.inertia, p.speed, p.acceleration_time, p.resisting_torque),
                 equation="(15)-(16)", unit="N*m", description="friction torque covers T_max",
                 constant_acceleration=True),
        at_most("flank_pressure", flank_pressure(w.centrifugal, w.flank_angle, w.sector_angle, w.r1, w.r2),
                p.allowable_pressure, equation="(13)", unit="MPa", description="flank pressure within [p]"),
        at_most("finger_bending", finger_bending_stress(w.friction, mean_flank_radius(w.r1, w.r2), w.finger_diameter),
                p.allowable_bending_stress, equation="(19)", unit="MPa", description="finger bending within [sigma]"),
    ]


def _total_mass(w: WeightSet, p):
    return w.count * (w.weight_mass + finger_mass(p.density, w.finger_diameter, mean_flank_radius(w.r1, w.r2)))


def _cost(w: WeightSet, p):
    return cost(p, _total_mass(w, p), w.count, flank_area(w.sector_angle, w.r1, w.r2, w.flank_angle))


def _duty_outputs(w: WeightSet, p):
    return {
        "required_torque": Output(required_torque(p.inertia, p.speed, p.acceleration_time, p.resisting_torque),
                                  "N*m", "T_max, eqs. (5), (17)"),
        "torque": Output(friction_torque(w.count, w.friction, w.r1, w.r2), "N*m", "friction torque, eq. (15)"),
        "flank_pressure": Output(flank_pressure(w.centrifugal, w.flank_angle, w.sector_angle, w.r1, w.r2), "MPa",
                                 "q, eq. (13)"),
        "weight_mass": Output(w.weight_mass, "kg", "m_r, one weight"),
        "centroid_radius": Output(w.centroid_radius, "mm", "r_c of a weight"),
        "centrifugal_force": Output(w.centrifugal, "N", "F_u per weight, eq. (10)"),
        "total_mass": Output(_total_mass(w, p), "kg", "z (m_r + finger)"),
        "cost": Output(_cost(w, p), "EUR", "material + parts + flank grinding"),
    }


def _speed_law(weight_set) -> SpeedLaw:
    """T = K w_a^2 with K the friction torque (15) of the weights at 1 rad/s; each weight's centrifugal force is
    m_r r_c w_a^2 (10), against which springs and gravity act."""
    def torque_coefficient(x, p):
        w = replace(weight_set(x, p), speed=1.0)
        return friction_torque(w.count, w.friction, w.r1, w.r2)

    def mass_radius(x, p):
        w = weight_set(x, p)
        return w.weight_mass * w.centroid_radius

    return SpeedLaw(torque_coefficient, mass_radius, lambda x, p: weight_set(x, p).weight_mass)


def _formulation(mode, title, variables, weight_set, extra_constraints=lambda w, x, p: [],
                 extra_outputs=lambda w, x, p: {}):
    """A wedge formulation from the way its mode obtains the weight set."""
    return Formulation(
        coupling="wedge",
        mode=mode,
        title=title,
        quantities=QUANTITIES,
        variables=variables,
        constraints=lambda x, p: _duty_constraints(w := weight_set(x, p), p) + extra_constraints(w, x, p),
        objectives=(
            Objective("mass", "kg", "weights and fingers, z (m_r + m_finger)", lambda x, p: _total_mass(weight_set(x, p), p)),
            Objective("cost", "EUR", "material, parts and flank grinding", lambda x, p: _cost(weight_set(x, p), p)),
        ),
        outputs=lambda x, p: {**_duty_outputs(w := weight_set(x, p), p), **extra_outputs(w, x, p)},
        speed_law=_speed_law(weight_set),
    )


# --- Paper mode: geometry given, r_c = r2 - 2/3 h_r, m_r and d_n free ----------------------------------------------
PAPER_VARIABLES = (
    Variable("weight_mass", "kg", "mass of one weight", "m_r", lower=1e-6, upper=1e4, above=0),
    Variable("finger_diameter", "mm", "finger diameter", "d_n", lower=si(0.1, "mm"), upper=si(500, "mm"), above=0),
)


def _paper_weight_set(x, p):
    r1 = p.flank_inner_radius
    r2 = p.radius_ratio * r1
    return WeightSet(p.weight_count, r1, r2, p.flank_angle, p.sector_angle, x.weight_mass,
                     paper_centroid_radius(r2, p.weight_height), x.finger_diameter, p.speed, p.friction_coefficient)


PAPER = _formulation("paper", "Wedge CFC, paper assumptions: geometry given, m_r and d_n free", PAPER_VARIABLES,
                     _paper_weight_set)


# --- Geometry mode: weights as real bodies -------------------------------------------------------------------------
V = Variable
GEOMETRY_VARIABLES = (
    V("flank_inner_radius", "mm", "inner radius of the flanks", "r_1", lower=si(5, "mm"), upper=si(2000, "mm"), above=0),
    V("radius_ratio", "", "lambda = r2/r1", "lambda", lower=1.1, upper=1.35, above=1),
    V("weight_height", "mm", "radial height of a weight", "h_r", lower=si(1, "mm"), upper=si(1000, "mm"), above=0),
    V("sector_angle", "deg", "central angle of a weight", "gamma", lower=si(5, "deg"), upper=si(170, "deg"),
      above=0, below=2 * math.pi),
    V("weight_width", "mm", "axial width of a weight", "b", lower=si(2, "mm"), upper=si(1000, "mm"), above=0),
    V("finger_diameter", "mm", "finger diameter", "d_n", lower=si(0.5, "mm"), upper=si(300, "mm"), above=0),
    V("flank_angle", "deg", "flank half-angle", "alpha", lower=si(5, "deg"), upper=si(45, "deg"), above=0,
      below=math.pi / 2, fixed_unless_freed=True),
    V("weight_count", "", "number of weights", "z", lower=2, upper=12, at_least=1, integer=True, fixed_unless_freed=True),
)


def _geometry_weight_set(x, p):
    r1 = x.flank_inner_radius
    r2 = x.radius_ratio * r1
    mass, r_c = weight_body(r2 - x.weight_height, r1, r2, x.weight_width, x.flank_angle, x.sector_angle, p.density)
    return WeightSet(x.weight_count, r1, r2, x.flank_angle, x.sector_angle, mass, r_c, x.finger_diameter, p.speed,
                     p.friction_coefficient)


def _constructive_constraints(w: WeightSet, x, p):
    """Rules that make the optimum a part one can build: (26), fit round the shaft, release, housing, fits."""
    r_in, b = w.r2 - x.weight_height, x.weight_width
    return [
        at_least("weight_covers_flank", x.weight_height, w.r2 - w.r1, equation="(26)", unit="mm", scale=w.r1,
                 description="h_r >= r2 - r1"),
        at_most("sectors_fit", w.count * (w.sector_angle + p.sector_clearance), 2 * math.pi, equation="below (23)",
                unit="deg", description="z (gamma + clearance) <= 2 pi"),
        at_least("not_self_locking", w.flank_angle, self_locking_angle(p.friction_coefficient) + p.self_locking_margin,
                 equation="above (24)", unit="deg", description="alpha >= atan f + margin"),
        at_most("outer_diameter", 2 * (w.r2 + p.shell_thickness), p.outer_diameter_max, equation="case", unit="mm",
                description="2 (r2 + shell) <= D_max"),
        at_least("top_land_width", b - 2 * (w.r2 - w.r1) * tan(w.flank_angle), p.min_top_width, equation="geometry",
                 unit="mm", scale=b, description="trapezoid top b - 2 (r2 - r1) tan(alpha) >= min"),
        at_least("hub_clearance", r_in, p.hub_radius, equation="fig. 2", unit="mm", scale=w.r1,
                 description="inner edge r2 - h_r clears the hub"),
        at_most("finger_fits_width", w.finger_diameter, p.finger_fit_ratio * b, equation="geometry", unit="mm",
                scale=b, description="d_n <= ratio * b"),
        at_least("finger_guide_length", x.weight_height, p.guide_length_ratio * w.finger_diameter,
                 equation="geometry", unit="mm", scale=w.r1, description="h_r >= ratio * d_n"),
        at_most("finger_fits_chord", w.finger_diameter, p.finger_fit_ratio * 2 * r_in * sin(w.sector_angle / 2),
                equation="geometry", unit="mm", scale=w.r1, description="d_n <= ratio * chord at r_in"),
    ]


def _geometry_outputs(w: WeightSet, x, p):
    return {
        "paper_centroid_radius": Output(paper_centroid_radius(w.r2, x.weight_height), "mm", "r2 - 2/3 h_r, eq. (11)"),
        "outer_flank_radius": Output(w.r2, "mm", "r2 = lambda r1"),
        "inner_weight_radius": Output(w.r2 - x.weight_height, "mm", "r2 - h_r"),
    }


GEOMETRY = _formulation("geometry", "Wedge CFC, weights as real bodies: geometry free", GEOMETRY_VARIABLES,
                        _geometry_weight_set, _constructive_constraints, _geometry_outputs)


# --- Closed forms of the consistent model (paper assumptions) -------------------------------------------------------
def closed_form_weight_mass(p):
    """m_r = 2 T_max sin(alpha) / (f z (r1 + r2) w^2 r_c): eq. (27) from the consistent (15)-(16)."""
    per_kg = _paper_weight_set(SimpleNamespace(weight_mass=1.0, finger_diameter=math.nan), p)
    t_max = required_torque(p.inertia, p.speed, p.acceleration_time, p.resisting_torque)
    return t_max / friction_torque(per_kg.count, per_kg.friction, per_kg.r1, per_kg.r2)


def closed_form_finger_diameter(p, weight_mass):
    """d_n = cbrt(32 F_fr h_n / (pi [sigma])): eq. (28) from the consistent (19)."""
    w = _paper_weight_set(SimpleNamespace(weight_mass=weight_mass, finger_diameter=math.nan), p)
    return cbrt(32.0 * w.friction * mean_flank_radius(w.r1, w.r2) / (math.pi * p.allowable_bending_stress))


# --- Comparison: paper as printed, paper formulas, consistent closed form, NLP -------------------------------------
ROWS = (
    ComparisonRow("weight_mass", "kg", "m_r, mass of one weight"),
    ComparisonRow("finger_diameter", "mm", "d_n"),
    ComparisonRow("flank_pressure", "MPa", "q of that design, consistent (13)"),
    ComparisonRow("torque", "N*m", "friction torque of that design, consistent (15)"),
    ComparisonRow("weight_count", "", "z"),
    ComparisonRow("total_mass", "kg", "z (m_r + finger)"),
)


def _paper_design_rows(p, weight_mass, finger_diameter):
    """Rows for a design at the paper's geometry, evaluated with the consistent model."""
    outputs = PAPER.outputs(SimpleNamespace(weight_mass=weight_mass, finger_diameter=finger_diameter), p)
    return {"weight_mass": weight_mass, "finger_diameter": finger_diameter,
            "flank_pressure": outputs["flank_pressure"].value, "torque": outputs["torque"].value,
            "weight_count": p.weight_count, "total_mass": outputs["total_mass"].value}


def _references(p):
    columns = {}
    if not math.isnan(p.printed_weight_mass):
        printed_dn = p.printed_finger_diameter
        columns["paper_printed"] = _paper_design_rows(p, p.printed_weight_mass, printed_dn)
    for column, form in (("paper_eq27_first_form", paper_eq27_first_form),
                         ("paper_eq27_second_form", paper_eq27_second_form)):
        mass = form(p)
        columns[column] = _paper_design_rows(p, mass, paper_eq28(p, mass))
    mass = closed_form_weight_mass(p)
    columns["closed_form"] = _paper_design_rows(p, mass, closed_form_finger_diameter(p, mass))
    return columns


def _rows_from_design(mode, design, outputs, p):
    return {"weight_mass": outputs["weight_mass"],
            "finger_diameter": design["finger_diameter"],
            "flank_pressure": outputs["flank_pressure"], "torque": outputs["torque"],
            "weight_count": design.get("weight_count", p.weight_count), "total_mass": outputs["total_mass"]}


COMPARISON = Comparison(
    rows=ROWS,
    references=_references,
    solves=(("nlp_paper", "paper", "mass"), ("nlp_geometry", "geometry", "mass")),
    rows_from_design=_rows_from_design,
    baseline="closed_form",
    column_notes={
        "paper_printed": "the paper's example as printed (m_r = 0.235 kg, d_n = 3.1 mm)",
        "paper_eq27_first_form": "eq. (27) first form, d_n by eq. (28) read as mm",
        "paper_eq27_second_form": "eq. (27) second form (T_c t_p for I_n w/t_p), d_n by eq. (28)",
        "closed_form": "consistent closed form of the paper-mode model",
        "nlp_paper": "IPOPT, paper mode, minimum mass",
        "nlp_geometry": "IPOPT, geometry mode, minimum mass (weights as real bodies)",
    },
)


def _check_case(case):
    """Contradictions a single field cannot show."""
    from clutchopt.errors import InputError

    v = case.values
    r2 = v["radius_ratio"] * v["flank_inner_radius"]
    if paper_centroid_radius(r2, v["weight_height"]) <= 0:
        raise InputError("geometry.weight_height", "too large: r_c = r2 - 2/3 h_r must stay positive")
    if v["weight_count"] * v["sector_angle"] > 2 * math.pi:
        raise InputError("geometry.sector_angle", "z weights of this angle do not fit round the shaft (z gamma > 2 pi)")
    if 2 * v["shell_thickness"] >= v["outer_diameter_max"]:
        raise InputError("limits.outer_diameter_max", "leaves no room inside the shell")


COUPLING = Coupling(
    name="wedge",
    title="Wedge centrifugal friction coupling",
    source="Ambartsumyants & Deli (2015), wedge_cfc_ambartsumyants_deli_2015.txt",
    quantities=QUANTITIES,
    formulations={"paper": PAPER, "geometry": GEOMETRY},
    default_mode="paper",
    comparison=COMPARISON,
    case_checks=(_check_case,),
    materials=MATERIALS,
)
