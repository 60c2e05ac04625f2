"""What a wedge case gives: the quantity table, the material-library roles, the contradictions a single field
cannot show."""

from __future__ import annotations

import math

from clutchopt.errors import InputError
from clutchopt.formulations.duty import DUTY_QUANTITIES
from clutchopt.formulations.wedge.equations import paper_centroid_radius
from clutchopt.model import MaterialRole, Quantity


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


# --- Contradictory requirements a single field cannot show ----------------------------------------------------------
def check_case(case):
    """z weights of the paper's geometry fit round the shaft with a positive centroid radius."""
    v = case.values
    r2 = v["radius_ratio"] * v["flank_inner_radius"]
    if paper_centroid_radius(r2, v["weight_height"]) <= 0:
        raise InputError("geometry.weight_height", "too large: r_c = r2 - 2/3 h_r must stay positive")
    if v["weight_count"] * v["sector_angle"] > 2 * math.pi:
        raise InputError("geometry.sector_angle", "z weights of this angle do not fit round the shaft (z gamma > 2 pi)")
