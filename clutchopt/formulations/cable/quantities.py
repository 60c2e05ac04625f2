"""What a cable case gives: the quantity table, the material-library roles, the contradictions a single field
cannot show."""

from __future__ import annotations

import math

from clutchopt.errors import InputError
from clutchopt.formulations.cable.equations import cable_transverse_force, reduced_friction_angle, spring_force
from clutchopt.formulations.duty import GRAVITY
from clutchopt.model import MaterialRole, Quantity


# --- Quantity table: what a cable case gives (TOML section.key, unit, paper symbol, meaning) ---------------------
Q = Quantity
QUANTITIES = (
    Q("torque", "N*m", "torque the coupling transmits (design value)", "T", "duty", above=0),
    Q("speed", "rpm", "largest driving speed, w_max of eq. (6)", "n", "duty", above=0),
    Q("gravity", "m/s^2", "gravitational acceleration, eq. (1)", "g", "duty", f"{GRAVITY} m/s^2", at_least=0),
    Q("cable_coefficient", "", "experimental coefficient of the cable diameter, eq. (17)", "k", "cables", above=0),
    Q("area_ratio", "", "psi_s = A_s / (0.785 d_k^2), wire area of the cable, eq. (18)", "psi_s", "cables",
      above=0, at_most=1),
    Q("allowable_cable_stress", "MPa", "tensile stress at which k holds and the cable is strong enough", "[sigma_pk]",
      "cables", above=0),
    Q("twist_angle", "deg", "relative twist of the half-couplings under T, eqs. (17)-(20), (23)", "phi", "cables",
      above=0, below=math.pi / 2),
    Q("transverse_stiffness", "N/m", "transverse stiffness of one cable, eq. (3)", "c_k", "cables", at_least=0),
    Q("transverse_deflection", "mm", "transverse deflection of the cables by the fingers, eq. (3)", "x", "cables",
      at_least=0),
    Q("longitudinal_stiffness", "N/m", "longitudinal stiffness of one cable, eq. (9)", "c_kn", "cables", at_least=0),
    Q("elongation", "mm", "longitudinal deformation of a cable = radial travel of its weight, eq. (9)", "x_2",
      "cables", above=0),
    Q("torsional_stiffness", "N*m/rad", "torsional stiffness of one cable, eq. (9)", "c_kk", "cables", above=0),
    Q("cable_twist", "deg", "twist of a cable by its weight, eq. (9)", "phi_1", "cables", above=0),
    Q("spring_stiffness", "N/m", "stiffness of the return spring, eq. (4)", "c_pr", "spring", at_least=0),
    Q("spring_compression", "mm", "compression of the return spring, eq. (4)", "x_1", "spring", at_least=0),
    Q("friction_coefficient", "", "friction coefficient in both threads, eq. (14)", "f", "thread", at_least=0,
      at_most=1),
    Q("flank_angle", "deg", "alpha_1: half the profile angle (trapezoidal 15, buttress 3, square 0), eq. (14)",
      "alpha_1", "thread", at_least=0, below=math.pi / 2),
    Q("lead_angle", "deg", "lead angle of the hub thread 5 (start value when free)", "beta", "thread",
      above=0, below=math.pi / 2),
    Q("weight_lead_angle", "deg", "lead angle of the weight thread 16 (start value when free)", "beta_w", "thread",
      above=0, below=math.pi / 2),
    Q("pitch_diameter", "mm", "pitch diameter of the hub thread 5", "d_2", "thread", above=0),
    Q("starts", "", "number of starts of the hub thread", "", "thread", 1, at_least=1, integer=True),
    Q("weight_thread_starts", "", "number of starts of the weight thread", "", "thread", 1, at_least=1, integer=True),
    Q("height_ratio", "", "h / p, working height of the profile per pitch (trapezoidal 0.5)", "h/p", "thread", 0.5,
      above=0, at_most=1),
    Q("nut_height", "mm", "engaged length of the hub thread (half-coupling hub)", "H", "thread", above=0),
    Q("weight_nut_height", "mm", "engaged length of the weight thread", "H_w", "thread", above=0),
    Q("allowable_thread_pressure", "MPa", "allowable flank pressure of both threads, eq. (15)", "[q]", "thread",
      above=0),
    Q("mass_radius", "mm", "radius of the centre of mass of the driving half-coupling, eq. (1)", "R_m", "geometry",
      above=0),
    Q("weight_radius", "mm", "radius of the centre of mass of the moving weights, eq. (8)", "R_rv", "geometry",
      above=0),
    Q("finger_circle_diameter", "mm", "diameter of the finger circle, eqs. (17)-(22)", "D", "geometry", above=0),
    Q("span", "mm", "distance between the half-couplings (free cable length), eqs. (17)-(20)", "l", "geometry",
      above=0),
    Q("finger_length", "mm", "length of a finger, eq. (21)", "l_n", "geometry", above=0),
    Q("clamp_screw_length", "mm", "length of a clamp screw (its mass only)", "", "geometry", above=0),
    Q("density", "kg/m^3", "density of fingers and clamp screws", "rho", "material", "7850 kg/m^3", above=0),
    Q("clamp_friction", "", "friction coefficient between cable and clamp, eqs. (19)-(20)", "f", "material",
      above=0, at_most=1),
    Q("allowable_screw_stress", "MPa", "allowable compressive stress of the clamp screw", "[sigma_cm]", "material",
      above=0),
    Q("allowable_finger_stress", "MPa", "allowable bending stress of a finger", "[sigma_F]", "material", above=0),
    Q("self_locking_margin", "deg", "lead angle kept above the friction angle phi'", "", "limits", "2 deg",
      at_least=0),
    Q("min_engaged_turns", "", "fewest turns engaged in a nut, z_e = H / p", "", "limits", 1.0, above=0),
    Q("min_weight_thread_diameter", "mm", "smallest pitch diameter of the weight thread", "", "limits", "6 mm",
      above=0),
    Q("material_price", "EUR/kg", "price of half-coupling, weight, finger and screw material", "", "cost",
      "2.5 EUR/kg", at_least=0),
    Q("damping_ratio", "", "equivalent viscous damping ratio of the cables in torsion (start-ups only)", "zeta",
      "cables", 0.1, above=0, below=1),
    Q("cable_set_cost", "EUR", "per cable: rope, two clamps, weight and finger machining", "", "cost", "15 EUR",
      at_least=0),
)


# --- What a case may take from the material library (clutchopt materials) ----------------------------------------
MATERIALS = (
    MaterialRole("material", "materials", "fingers and clamp screws; its price is the half-coupling's and weights' too",
                 {"density": "density", "allowable_bending": "allowable_finger_stress", "price": "material_price"}),
    MaterialRole("thread_pair", "thread_pairs", "hub thread 5 and weight threads 16",
                 {"friction_coefficient": "friction_coefficient", "allowable_pressure": "allowable_thread_pressure"}),
)


# --- Contradictory requirements a single field cannot show ----------------------------------------------------------
def check_drives(case):
    """Half-coupling and weights drive: R w^2 exceeds g, eq. (1)."""
    v = case.values
    speed = v["speed"]
    for name, what in (("mass_radius", "half-coupling"), ("weight_radius", "weights")):
        if v[name] * speed**2 <= v["gravity"]:
            raise InputError(f"geometry.{name}", f"R w^2 = {v[name] * speed**2:.4g} m/s^2 does not exceed "
                                                 f"g = {v['gravity']:.4g} m/s^2: the {what} cannot drive (eq. 1)")


def check_threads(case):
    """Neither thread self-locks: beta and beta_w exceed phi' (14) plus the margin."""
    v = case.values
    phi = float(reduced_friction_angle(v["friction_coefficient"], v["flank_angle"]))
    limit = phi + v["self_locking_margin"]
    for name, symbol in (("lead_angle", "beta"), ("weight_lead_angle", "beta_w")):
        if v[name] <= limit:
            raise InputError(f"thread.{name}", (
                f"self-locking thread: {symbol} = {math.degrees(v[name]):.4g} deg must exceed phi' = "
                f"{math.degrees(phi):.4g} deg (atan(f / cos alpha_1), eq. 14) plus limits.self_locking_margin "
                f"{math.degrees(v['self_locking_margin']):.4g} deg, i.e. {math.degrees(limit):.4g} deg"))


def check_hub_load(case):
    """The hub thread has a load to push, F_nk + F_pr > 0 (eq. 2): with none, eq. (7) sizes no half-coupling and the
    thread's drive requirement has no limit to be measured against."""
    v = case.values
    if cable_transverse_force(1.0, v["transverse_stiffness"], v["transverse_deflection"]) > 0 \
            or spring_force(v["spring_stiffness"], v["spring_compression"]) > 0:
        return
    zero = [key for key in ("cables.transverse_stiffness", "cables.transverse_deflection", "spring.spring_stiffness",
                            "spring.spring_compression") if v[key.split(".")[1]] == 0]
    raise InputError(zero[0], f"is 0, and so is {' and '.join(zero[1:])}: the hub thread pushes nothing (F_nk + "
                              "F_pr = 0, eq. 2), so eq. (7) sizes no half-coupling; give the cables' transverse "
                              "force or the spring's")
