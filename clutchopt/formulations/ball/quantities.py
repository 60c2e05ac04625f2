"""What a ball-clutch case gives: the quantity table, the material-library roles, the contradictions a single
field cannot show."""

from __future__ import annotations

import math

from clutchopt.errors import InputError
from clutchopt.formulations.ball.equations import filling_coefficient
from clutchopt.formulations.duty import POWER_DUTY_QUANTITIES
from clutchopt.model import MaterialRole, Quantity


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


# --- Contradictory requirements a single field cannot show ----------------------------------------------------------
def check_width_ratios(case):
    """The range of K5 = l_a / R_a is not empty."""
    v = case.values
    if v["width_ratio_min"] >= v["width_ratio_max"]:
        raise InputError("limits.width_ratio_max", f"must exceed limits.width_ratio_min ({v['width_ratio_min']:g})")


def check_shovels(case):
    """The shovels leave room for balls in the layer of K2 from (1), eq. (2)."""
    v = case.values
    layer = 1 - float(filling_coefficient(v["construction_density"], v["packing_density"]))
    if v["shovel_count"] * v["shovel_ratio"] * layer >= math.pi * (1 - (1 - layer) ** 2):
        raise InputError("body.shovel_ratio", "the shovels fill the whole ball layer (eq. 2 gives no balls)")
