"""What a lever case gives: the quantity table, the material-library roles, the contradictions a single field
cannot show."""

from __future__ import annotations

import math

from clutchopt.errors import InputError
from clutchopt.formulations.duty import DUTY_QUANTITIES
from clutchopt.model import MaterialRole, Quantity


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


# --- Contradictory requirements a single field cannot show ----------------------------------------------------------
def check_case(case):
    """The toggle straightens as the linings wear, and the spring flange stands above the shaft."""
    v = case.values
    if v["limit_angle"] >= v["engagement_angle"]:
        raise InputError("geometry.engagement_angle", "must exceed the limit angle gamma_pr: the toggle straightens "
                                                      "as the linings wear")
    if v["flange_diameter"] <= v["shaft_diameter"]:
        raise InputError("geometry.flange_diameter", "must exceed the shaft diameter d_b")
