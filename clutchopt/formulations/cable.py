"""Inertial-centrifugal cable coupling (Strilets, Fedoruk, Strilets & Kovalchuk, 2013; seed
cable_coupling_strilets_2013.txt).

The driving cup-shaped half-coupling 1 sits on the driving shaft on a non-self-locking thread 5 (lead angle
beta) against a return spring 6. z radial cables 10 are clamped in the driven half-coupling 8 and in z moving
weights 14; each cable passes through a radial hole of a finger 2 of the cup (finger circle D). At start-up the
cup's inertia force screws it along thread 5: the fingers deflect the cables transversely and compress the
spring. At speed the weights, each on its own non-self-locking thread 16 (lead angle beta_w, radial axis),
move outwards and turn: they stretch the cables (x_2) and twist them (phi_1).

Equation numbers are the paper's. Where the printed equation is inconsistent the consistent form is used here
and the printed one is kept as ``paper_eq*`` for comparison; see docs/errata.md (C1-C9) and docs/cable.md.

Two posed problems:
- ``paper``: the case's threads (beta, beta_w) are given, as in the paper's sizing; free: half-coupling mass m,
  weight mass m_w, cable count z (integer), finger and clamp-screw diameters. ``options.free`` may free either
  lead angle. The optimum is the consistent closed form (``closed_form``).
- ``threads``: both lead angles free as well. The hub thread goes to its non-self-locking limit; the weight
  thread to the best screw efficiency 45 deg + phi'/2 unless its wear or its smallest diameter stops it first.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

from scipy.optimize import brentq

from clutchopt.backend import arctan, cbrt, cos, fmax, sin, sqrt, tan
from clutchopt.errors import InputError
from clutchopt.formulations.duty import GRAVITY, centrifugal_force
from clutchopt.model import (
    Comparison,
    ComparisonRow,
    Coupling,
    Formulation,
    MaterialRole,
    Objective,
    Output,
    Quantity,
    Variable,
    ElasticLaw,
    at_least,
    at_most,
    si,
)

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


# --- Equations -----------------------------------------------------------------------------------------------------
def inertia_force(mass, centroid_radius, speed, gravity):
    """F_i = m (R_m w^2 - g), eq. (1); with R_rv and m_rv also the weight's force of eq. (8) (errata C4)."""
    return centrifugal_force(mass, speed, centroid_radius) - mass * gravity


def reduced_friction_angle(friction_coefficient, flank_angle):
    """phi' = atan(f / cos alpha_1), eq. (14)."""
    return arctan(friction_coefficient / cos(flank_angle))


def hub_axial_force(inertia, lead_angle, friction_angle):
    """F_a = F_i / tan(beta + phi'): the circumferential F_i screws the nut against F_a, eqs. (12)-(13) (errata C2)."""
    return inertia / tan(lead_angle + friction_angle)


def cable_transverse_force(cable_count, transverse_stiffness, deflection):
    """F_nk = z c_k x, eq. (3)."""
    return cable_count * transverse_stiffness * deflection


def spring_force(stiffness, compression):
    """F_pr = c_pr x_1, eq. (4)."""
    return stiffness * compression


def hub_thread_load(p, cable_count):
    """F_a needed = F_nk + F_pr, eq. (2)."""
    return (cable_transverse_force(cable_count, p.transverse_stiffness, p.transverse_deflection)
            + spring_force(p.spring_stiffness, p.spring_compression))


def half_coupling_mass(load, lead_angle, friction_angle, mass_radius, speed, gravity):
    """m = (z c_k x + c_pr x_1) tan(beta + phi') / (R_m w^2 - g), eq. (7) from (1), (2), (5) (errata C2)."""
    return load * tan(lead_angle + friction_angle) / (mass_radius * speed**2 - gravity)


def weight_thread_diameter(elongation, cable_twist, weight_lead_angle):
    """d_2w = 2 x_2 / (phi_1 tan beta_w): a turn phi_1 of the weight moves it x_2 = phi_1 (d_2w / 2) tan beta_w."""
    return 2.0 * elongation / (cable_twist * tan(weight_lead_angle))


def back_driven_torque(axial_force, pitch_diameter, lead_angle, friction_angle):
    """M = F_a (d_2 / 2) tan(beta - phi'): the torque an axial force turns a non-self-locking thread with,
    eq. (12) with the friction reversed (the load drives); negative for beta < phi' (self-locking)."""
    return axial_force * pitch_diameter / 2.0 * tan(lead_angle - friction_angle)


def weight_mass(p, weight_lead_angle, friction_angle):
    """m_rv = (c_kn x_2 + 2 c_kk phi_1 / (d_2w tan(beta_w - phi'))) / (R_rv w^2 - g), eq. (9) made consistent:
    the cable's twist moment reaches the weight through thread 16 (errata C3, C4)."""
    d_2w = weight_thread_diameter(p.elongation, p.cable_twist, weight_lead_angle)
    twist_force = 2.0 * p.torsional_stiffness * p.cable_twist / (d_2w * tan(weight_lead_angle - friction_angle))
    return (p.longitudinal_stiffness * p.elongation + twist_force) / (p.weight_radius * p.speed**2 - p.gravity)


def thread_pitch(pitch_diameter, lead_angle, starts):
    """p = pi d_2 tan(beta) / n_s: lead over starts."""
    return math.pi * pitch_diameter * tan(lead_angle) / starts


def turns_in_nut(nut_height, pitch):
    """z_e = H / p, below eq. (16)."""
    return nut_height / pitch


def thread_pressure(axial_force, pitch_diameter, working_height, turns):
    """q = F_a / (pi d_2 h z_e), eq. (16)."""
    return axial_force / (math.pi * pitch_diameter * working_height * turns)


def length_ratio(span, finger_circle_diameter):
    """psi_lD = l / D, below eq. (17)."""
    return span / finger_circle_diameter


def cable_diameter(finger_circle_diameter, ratio, coefficient, twist_angle):
    """d_k = D psi_lD^2 / (k sqrt(12 psi_lD^2 + 3 phi^2)), eq. (17)."""
    return finger_circle_diameter * ratio**2 / (coefficient * sqrt(12.0 * ratio**2 + 3.0 * twist_angle**2))


def cable_wire_area(area_ratio, diameter):
    """A_s = psi_s 0.785 d_k^2, the paper's definition of psi_s below eq. (18)."""
    return area_ratio * 0.785 * diameter**2


def cable_tension(torque, ratio, twist_angle, span, cable_count):
    """N = T (4 psi_lD^2 + phi^2) / (l phi z): the tension per cable behind eq. (18)."""
    return torque * (4.0 * ratio**2 + twist_angle**2) / (span * twist_angle * cable_count)


def cable_stress(p, cable_count):
    """sigma_pk = N / A_s = T (4 psi^2 + phi^2) / (0.785 l phi psi_s d_k^2 z), eq. (18) solved for the stress."""
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    d_k = cable_diameter(p.finger_circle_diameter, ratio, p.cable_coefficient, p.twist_angle)
    return (cable_tension(p.torque, ratio, p.twist_angle, p.span, cable_count)
            / cable_wire_area(p.area_ratio, d_k))


def required_cable_count(p):
    """z = T (4 psi^2 + phi^2) / (0.785 l phi psi_s d_k^2 [sigma_pk]), eq. (18) (not yet rounded up)."""
    return cable_stress(p, 1.0) / p.allowable_cable_stress


def clamp_screw_force(tension, clamp_friction):
    """F_s = N / (2 f): friction on both faces of the cable (screw tip and bore) holds its tension (errata C6)."""
    return tension / (2.0 * clamp_friction)


def screw_equivalent_stress(screw_force, core_diameter):
    """sigma_E = 1.3 F_s / (pi d_1^2 / 4): tension with the torsion of tightening, eq. (20) (errata C6)."""
    return 1.3 * screw_force / (math.pi * core_diameter**2 / 4.0)


def clamp_screw_stress(p, cable_count, core_diameter):
    """sigma_E of a clamp screw holding the cable tension of eq. (18), eq. (20) made consistent."""
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    tension = cable_tension(p.torque, ratio, p.twist_angle, p.span, cable_count)
    return screw_equivalent_stress(clamp_screw_force(tension, p.clamp_friction), core_diameter)


def finger_force(torque, finger_count, finger_circle_diameter):
    """F = 2 T / (z_n D): the fingers carry the torque at radius D / 2 (one finger per cable, z_n = z)."""
    return 2.0 * torque / (finger_count * finger_circle_diameter)


def finger_bending_stress(p, finger_count, diameter):
    """sigma_F = 32 F (l_n / 2) / (pi d_n^3) = 32 T l_n / (pi d_n^3 z_n D), eq. (22) made consistent (errata C7):
    the cable crosses the finger at mid-length."""
    arm = p.finger_length / 2.0
    return 32.0 * finger_force(p.torque, finger_count, p.finger_circle_diameter) * arm / (math.pi * diameter**3)


def torsional_stiffness(torque, twist_angle):
    """C_phi = T / phi_3, eq. (23), with phi_3 = phi the design twist under T."""
    return torque / twist_angle


def hardware_mass(p, cable_count, finger_diameter, screw_diameter):
    """z fingers (d_n x l_n) and 2 z clamp screws (d_1 x screw length) as steel cylinders."""
    finger = p.density * math.pi / 4.0 * finger_diameter**2 * p.finger_length
    screw = p.density * math.pi / 4.0 * screw_diameter**2 * p.clamp_screw_length
    return cable_count * (finger + 2.0 * screw)


def total_mass(p, half_coupling, weight, cable_count, finger_diameter, screw_diameter):
    """m + z m_rv + fingers + clamp screws (the hardware's own inertia force is neglected: conservative)."""
    return half_coupling + cable_count * weight + hardware_mass(p, cable_count, finger_diameter, screw_diameter)


def cost(p, mass, cable_count):
    """Material at a price per kg and a fixed cost per cable set."""
    return p.material_price * mass + cable_count * p.cable_set_cost


# --- Start-up: the cables as a tension-stiffened link (docs/cable.md, "Start-up") -----------------------------------
def cable_pretension(transverse_stiffness, span):
    """N_0 = c_k l / 4: a cable of span l under tension N_0 has the transverse stiffness 4 N_0 / l at mid-span
    (the case's c_k, eq. 3, is read as that pretension's)."""
    return transverse_stiffness * span / 4.0


def weight_stiffness(p, weight_lead_angle, friction_angle):
    """k_w = c_kn + 4 c_kk / (d_2w^2 tan beta_w tan(beta_w - phi')): the radial force per metre of travel that a
    weight meets, its cable's stretch plus the cable's twist through thread 16 (x_2 = phi_1 (d_2w / 2) tan beta_w,
    the moment c_kk phi_1 back-driving the thread: eq. (9) made consistent, errata C3)."""
    d_2w = weight_thread_diameter(p.elongation, p.cable_twist, weight_lead_angle)
    return p.longitudinal_stiffness + 4.0 * p.torsional_stiffness / (
        d_2w**2 * tan(weight_lead_angle) * tan(weight_lead_angle - friction_angle))


def weight_travel(weight, radius, speed, gravity, stiffness):
    """x_2 = m_rv (R_rv w^2 - g)^+ / k_w: how far the weights have moved out at the driving speed w (eq. 8-9);
    none while their centrifugal force is below their own weight."""
    return fmax(inertia_force(weight, radius, speed, gravity), 0.0) / stiffness


def twist_stretch(longitudinal_stiffness, span, ratio, twist):
    """c_kn l (sqrt(1 + theta^2 / (4 psi^2)) - 1): a twist theta of the halves lengthens each cable from l to
    (D / 2) sqrt(4 psi^2 + theta^2), the geometry of eq. (18)."""
    return longitudinal_stiffness * span * (sqrt(1.0 + twist**2 / (4.0 * ratio**2)) - 1.0)


def link_tension(x, p, speed, twist):
    """N = N_0 + c_kn x_2(w) + c_kn (lengthening by the twist): the tension of one cable in a start-up."""
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    travel = weight_travel(x.weight_mass, p.weight_radius, speed, p.gravity,
                           weight_stiffness(p, x.weight_lead_angle, phi))
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    return (cable_pretension(p.transverse_stiffness, p.span) + p.longitudinal_stiffness * travel
            + twist_stretch(p.longitudinal_stiffness, p.span, ratio, twist))


def link_torque(x, p, speed, twist):
    """T = z N l theta / (4 psi^2 + theta^2): eq. (18) read the other way, the torque z cables of tension N
    carry at the twist theta."""
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    return x.cable_count * link_tension(x, p, speed, twist) * p.span * twist / (4.0 * ratio**2 + twist**2)


def link_stress(x, p, speed, twist):
    """sigma = N / A_s, the cable stress of eq. (18) with the tension of the start."""
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    area = cable_wire_area(p.area_ratio, cable_diameter(p.finger_circle_diameter, ratio, p.cable_coefficient,
                                                        p.twist_angle))
    return link_tension(x, p, speed, twist) / area


def link_stiffness(x, p, speed):
    """dT/dtheta at theta = 0: z N l / (4 psi^2), N without stretch."""
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    return x.cable_count * link_tension(x, p, speed, 0.0) * p.span / (4.0 * ratio**2)


def largest_twist(x, p):
    """2 psi: up to this twist the leaning cables' torque z N l theta / (4 psi^2 + theta^2) grows (N held);
    beyond it they are past square to the halves, a start that no longer holds together."""
    return 2.0 * length_ratio(p.span, p.finger_circle_diameter)


ELASTIC_LAW = ElasticLaw(link_torque, link_stress, link_stiffness, lambda x, p: p.damping_ratio, largest_twist,
                         "allowable_cable_stress")


# --- The paper's printed forms, kept for comparison (docs/errata.md) ------------------------------------------------
def paper_eq5(inertia, lead_angle, friction_angle):
    """F_a = F_i tan(beta + phi'), eq. (5) as printed."""
    return inertia * tan(lead_angle + friction_angle)


def paper_eq7(p, cable_count):
    """m = (z c_k x + c_pr x_1) / ((R_m w^2 - g) tan(beta + phi')), eq. (7) as printed."""
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    return hub_thread_load(p, cable_count) / ((p.mass_radius * p.speed**2 - p.gravity) * tan(p.lead_angle + phi))


def paper_eq9(p):
    """m_rv = (c_kn x_2 + c_kk phi_1) / (R_rv w^2 tan(beta + phi')), eq. (9) as printed, with beta = beta_w.

    Adds a force (N) and a moment (N m): the number is the SI reading of the printed line (errata C3)."""
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    return ((p.longitudinal_stiffness * p.elongation + p.torsional_stiffness * p.cable_twist)
            / (p.weight_radius * p.speed**2 * tan(p.weight_lead_angle + phi)))


def paper_eq19(p, cable_count):
    """d_1 = sqrt(3.31 T l / (f z D^2 tan(phi) [sigma_cm])), eq. (19) as printed."""
    return sqrt(3.31 * p.torque * p.span / (p.clamp_friction * cable_count * p.finger_circle_diameter**2
                                            * tan(p.twist_angle) * p.allowable_screw_stress))


def paper_eq20(p, cable_count, core_diameter):
    """sigma_E = 3.31 T l / (d_1^2 f z D^2 sin(phi)), eq. (20) as printed."""
    return 3.31 * p.torque * p.span / (core_diameter**2 * p.clamp_friction * cable_count
                                       * p.finger_circle_diameter**2 * sin(p.twist_angle))


def paper_eq21(p, finger_count):
    """d_n = cbrt(10 T l_n / (D z_n [sigma_F])), eq. (21) as printed."""
    return cbrt(10.0 * p.torque * p.finger_length / (p.finger_circle_diameter * finger_count
                                                     * p.allowable_finger_stress))


def paper_eq22(p, finger_count, diameter):
    """sigma_F = 10 T l_n / (d_n^3 z_n D^2), eq. (22) as printed: a stress per metre (errata C7)."""
    return 10.0 * p.torque * p.finger_length / (diameter**3 * finger_count * p.finger_circle_diameter**2)


# --- The coupling at a design: one state shared by constraints, objectives and outputs -----------------------------
class CableCoupling:
    """Forces, thread loads and stresses of one design (x: design variables, p: case)."""

    def __init__(self, x, p):
        self.x, self.p = x, p
        self.z = x.cable_count
        self.friction_angle = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
        self.load = hub_thread_load(p, self.z)
        self.inertia = inertia_force(x.half_coupling_mass, p.mass_radius, p.speed, p.gravity)
        self.axial_force = hub_axial_force(self.inertia, x.lead_angle, self.friction_angle)
        self.hub_pitch = thread_pitch(p.pitch_diameter, x.lead_angle, p.starts)
        self.hub_turns = turns_in_nut(p.nut_height, self.hub_pitch)
        self.hub_pressure = thread_pressure(self.axial_force, p.pitch_diameter, p.height_ratio * self.hub_pitch,
                                            self.hub_turns)
        self.weight_force = inertia_force(x.weight_mass, p.weight_radius, p.speed, p.gravity)
        self.weight_thread_force = self.weight_force - p.longitudinal_stiffness * p.elongation
        self.weight_diameter = weight_thread_diameter(p.elongation, p.cable_twist, x.weight_lead_angle)
        self.weight_torque = back_driven_torque(self.weight_thread_force, self.weight_diameter, x.weight_lead_angle,
                                                self.friction_angle)
        self.weight_pitch = thread_pitch(self.weight_diameter, x.weight_lead_angle, p.weight_thread_starts)
        self.weight_turns = turns_in_nut(p.weight_nut_height, self.weight_pitch)
        self.weight_pressure = thread_pressure(self.weight_thread_force, self.weight_diameter,
                                               p.height_ratio * self.weight_pitch, self.weight_turns)

    @property
    def mass(self):
        x = self.x
        return total_mass(self.p, x.half_coupling_mass, x.weight_mass, self.z, x.finger_diameter, x.screw_diameter)

    @property
    def cost(self):
        return cost(self.p, self.mass, self.z)


def _not_self_locking(name, lead_angle, c: CableCoupling, which):
    limit = c.friction_angle + c.p.self_locking_margin
    return at_least(name, lead_angle, limit, equation="below (14)", unit="deg", scale=fmax(limit, si(1, "deg")),
                    description=f"{which} thread does not self-lock: beta > phi' + margin")


def _constraints(x, p):
    c = CableCoupling(x, p)
    pull = p.longitudinal_stiffness * p.elongation
    return [
        at_least("hub_thread_drive", c.axial_force, c.load, equation="(1)-(7)", unit="N",
                 description="F_a = F_i / tan(beta + phi') covers F_nk + F_pr"),
        _not_self_locking("hub_thread_not_self_locking", x.lead_angle, c, "hub"),
        at_most("hub_thread_wear", c.hub_pressure, p.allowable_thread_pressure, equation="(15)-(16)", unit="MPa",
                description="flank pressure of the hub thread within [q]"),
        at_least("hub_thread_turns", c.hub_turns, p.min_engaged_turns, equation="below (16)",
                 description="z_e = H / p turns engaged in the hub"),
        at_least("weight_pulls_cable", c.weight_force, pull, equation="(8)-(9)", unit="N",
                 scale=pull + 2.0 * p.torsional_stiffness * p.cable_twist / c.weight_diameter,
                 description="F_c exceeds the cable's pull c_kn x_2: thread 16 is driven outwards"),
        at_least("weight_turns_cable", c.weight_torque, p.torsional_stiffness * p.cable_twist, equation="(8)-(9), (12)",
                 unit="N*m", description="torque thread 16 turns the weight with covers c_kk phi_1"),
        _not_self_locking("weight_thread_not_self_locking", x.weight_lead_angle, c, "weight"),
        at_most("weight_thread_wear", c.weight_pressure, p.allowable_thread_pressure, equation="(15)-(16)",
                unit="MPa", description="flank pressure of the weight thread within [q]"),
        at_least("weight_thread_turns", c.weight_turns, p.min_engaged_turns, equation="below (16)",
                 description="z_e = H_w / p_w turns engaged in a weight"),
        at_least("weight_thread_diameter", c.weight_diameter, p.min_weight_thread_diameter, equation="kinematics",
                 unit="mm", description="d_2w = 2 x_2 / (phi_1 tan beta_w) not below the smallest"),
        at_most("cable_stress", cable_stress(p, c.z), p.allowable_cable_stress, equation="(18)", unit="MPa",
                description="cable tension over wire area within [sigma_pk]"),
        at_most("clamp_screw_stress", clamp_screw_stress(p, c.z, x.screw_diameter), p.allowable_screw_stress,
                equation="(20)", unit="MPa", description="clamp screw holding the cable within [sigma_cm]"),
        at_most("finger_bending", finger_bending_stress(p, c.z, x.finger_diameter), p.allowable_finger_stress,
                equation="(22)", unit="MPa", description="finger bending within [sigma_F]"),
    ]


def _outputs(x, p):
    c = CableCoupling(x, p)
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    d_k = cable_diameter(p.finger_circle_diameter, ratio, p.cable_coefficient, p.twist_angle)
    return {
        "friction_angle": Output(c.friction_angle, "deg", "phi' = atan(f / cos alpha_1), eq. (14)"),
        "hub_thread_load": Output(c.load, "N", "F_nk + F_pr the hub thread must push, eq. (2)"),
        "inertia_force": Output(c.inertia, "N", "F_i = m (R_m w^2 - g), eq. (1)"),
        "hub_axial_force": Output(c.axial_force, "N", "F_a = F_i / tan(beta + phi'), eq. (5) consistent"),
        "hub_thread_pressure": Output(c.hub_pressure, "MPa", "q of the hub thread, eq. (16)"),
        "hub_thread_turns": Output(c.hub_turns, "", "z_e = H / p of the hub thread"),
        "hub_thread_pitch": Output(c.hub_pitch, "mm", "p = pi d_2 tan(beta) / n_s"),
        "weight_force": Output(c.weight_force, "N", "m_rv (R_rv w^2 - g) per weight, eq. (8)"),
        "weight_thread_diameter": Output(c.weight_diameter, "mm", "d_2w = 2 x_2 / (phi_1 tan beta_w)"),
        "weight_thread_force": Output(c.weight_thread_force, "N", "axial force on thread 16: F_c - c_kn x_2"),
        "weight_thread_pressure": Output(c.weight_pressure, "MPa", "q of the weight thread, eq. (16)"),
        "weight_thread_turns": Output(c.weight_turns, "", "z_e of the weight thread"),
        "cable_diameter": Output(d_k, "mm", "d_k, eq. (17)"),
        "cable_tension": Output(cable_tension(p.torque, ratio, p.twist_angle, p.span, c.z), "N",
                                "tension per cable at T, eq. (18)"),
        "required_cable_count": Output(required_cable_count(p), "", "z of eq. (18) before rounding up"),
        "torsional_stiffness": Output(torsional_stiffness(p.torque, p.twist_angle), "N*m/rad", "C_phi = T / phi, eq. (23)"),
        "total_mass": Output(c.mass, "kg", "m + z m_rv + fingers + clamp screws"),
        "cost": Output(c.cost, "EUR", "material + cable sets"),
    }


V = Variable
MASS_AND_SIZE_VARIABLES = (
    V("half_coupling_mass", "kg", "mass of the driving half-coupling", "m", lower=1e-6, upper=1e4, above=0),
    V("weight_mass", "kg", "mass of one moving weight", "m_rv", lower=1e-6, upper=1e3, above=0),
    V("cable_count", "", "number of cables (and of fingers and weights)", "z", lower=2, upper=48, at_least=1,
      integer=True),
    V("finger_diameter", "mm", "finger diameter", "d_n", lower=si(0.2, "mm"), upper=si(200, "mm"), above=0),
    V("screw_diameter", "mm", "core diameter of the clamp screws", "d_1", lower=si(0.2, "mm"), upper=si(100, "mm"),
      above=0),
)
LEAD_ANGLE_BOUNDS = {"lead_angle": (si(1, "deg"), si(45, "deg")), "weight_lead_angle": (si(1, "deg"), si(60, "deg"))}


def _lead_angles(fixed_unless_freed: bool):
    return tuple(
        V(name, "deg", description, symbol, lower=LEAD_ANGLE_BOUNDS[name][0], upper=LEAD_ANGLE_BOUNDS[name][1],
          above=0, below=math.pi / 2, fixed_unless_freed=fixed_unless_freed)
        for name, description, symbol in (("lead_angle", "lead angle of the hub thread 5", "beta"),
                                          ("weight_lead_angle", "lead angle of the weight thread 16", "beta_w"))
    )


def _formulation(mode, title, fixed_unless_freed):
    return Formulation(
        coupling="cable",
        mode=mode,
        title=title,
        quantities=QUANTITIES,
        variables=MASS_AND_SIZE_VARIABLES + _lead_angles(fixed_unless_freed),
        constraints=_constraints,
        objectives=(
            Objective("mass", "kg", "half-coupling, weights, fingers and clamp screws",
                      lambda x, p: CableCoupling(x, p).mass),
            Objective("cost", "EUR", "material and cable sets", lambda x, p: CableCoupling(x, p).cost),
        ),
        outputs=_outputs,
        speed_law=ELASTIC_LAW,
    )


PAPER = _formulation("paper", "Cable coupling, the paper's sizing: threads given, masses, z, d_n, d_1 free", True)
THREADS = _formulation("threads", "Cable coupling, threads designed: both lead angles free as well", False)


# --- Closed forms of the consistent model ---------------------------------------------------------------------------
def hub_lead_angle_optimum(p, bounds=LEAD_ANGLE_BOUNDS["lead_angle"]):
    """m grows with tan(beta + phi'): the lightest hub thread is the flattest one that does not self-lock."""
    return max(bounds[0], reduced_friction_angle(p.friction_coefficient, p.flank_angle) + p.self_locking_margin)


def _weight_wear_interval(p, friction_angle):
    """(lowest, highest) beta_w at which the weight thread's pressure at the optimum is within [q]; None if none.

    With the weight's drive active the thread carries 2 c_kk phi_1 / (d_2w tan(beta_w - phi')) on
    d_2w = 2 x_2 / (phi_1 tan beta_w), so with s = tan(beta_w - phi'), u = tan phi' and
    K = c_kk phi_1^3 / (2 pi x_2^2 (h/p) H_w), eq. (16) reads q = K (u + s)^2 / (s (1 - u s)^2) on 0 < s < 1/u.
    q <= [q] where P(s) = [q] s (1 - u s)^2 - K (u + s)^2 >= 0: a cubic, negative at both ends for u > 0, whose
    local maximum is the smaller root of a quadratic; a root on each side of it bounds the interval.
    """
    k = p.torsional_stiffness * p.cable_twist**3 / (2 * math.pi * p.elongation**2 * p.height_ratio * p.weight_nut_height)
    u, q = math.tan(friction_angle), p.allowable_thread_pressure

    def excess(s):
        return q * s * (1 - u * s) ** 2 - k * (u + s) ** 2

    a, b, c = 3 * q * u**2, -2 * (2 * q * u + k), q - 2 * k * u  # P'(s) = a s^2 + b s + c
    if c <= 0:
        return None
    s_max = 2 * c / (-b + math.sqrt(b * b - 4 * a * c))  # the smaller root, stable as a -> 0
    if excess(s_max) < 0:
        return None
    s_low = brentq(excess, 0.0, s_max, xtol=1e-300, rtol=1e-15) if u > 0 else 0.0
    s_high = brentq(excess, s_max, 1 / u, xtol=1e-300, rtol=1e-15) if u > 0 else q / k
    return friction_angle + math.atan(s_low), friction_angle + math.atan(s_high)


def weight_lead_angle_optimum(p, bounds=LEAD_ANGLE_BOUNDS["weight_lead_angle"]):
    """beta_w minimising tan(beta_w) / tan(beta_w - phi') (the weight's mass), i.e. 45 deg + phi'/2, kept within the
    non-self-locking limit, the wear interval, the smallest thread diameter and the bounds; None if they exclude
    each other."""
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    wear = _weight_wear_interval(p, phi)
    if wear is None:
        return None
    lead = 2 * math.pi * p.elongation / p.cable_twist
    lower = max(bounds[0], phi + p.self_locking_margin, wear[0])
    upper = min(bounds[1], math.atan(lead / (math.pi * p.min_weight_thread_diameter)), wear[1])
    if lower > upper:
        return None
    return min(max(math.pi / 4 + phi / 2, lower), upper)


def closed_form(p, lead_angle=None, weight_lead_angle=None, count_bounds=(2, 48)):
    """The consistent optimum with the given lead angles (default: the case's): every sizing constraint active.

    z = (18) rounded up; m = (7) and m_rv = (9) consistent; d_1 from (20), d_n from (22) with that z."""
    beta = p.lead_angle if lead_angle is None else lead_angle
    beta_w = p.weight_lead_angle if weight_lead_angle is None else weight_lead_angle
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    z = float(min(max(math.ceil(required_cable_count(p) - 1e-9), count_bounds[0]), count_bounds[1]))
    m = half_coupling_mass(hub_thread_load(p, z), beta, phi, p.mass_radius, p.speed, p.gravity)
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    tension = cable_tension(p.torque, ratio, p.twist_angle, p.span, z)
    d_1 = math.sqrt(1.3 * clamp_screw_force(tension, p.clamp_friction) / (math.pi / 4 * p.allowable_screw_stress))
    d_n = (32 * finger_force(p.torque, z, p.finger_circle_diameter) * p.finger_length / 2
           / (math.pi * p.allowable_finger_stress)) ** (1 / 3)
    return {"half_coupling_mass": m, "weight_mass": weight_mass(p, beta_w, phi), "cable_count": z,
            "finger_diameter": d_n, "screw_diameter": d_1, "lead_angle": beta, "weight_lead_angle": beta_w}


def closed_form_threads(p):
    """The consistent optimum of ``threads`` mode (default bounds): both lead angles at their optimum."""
    beta_w = weight_lead_angle_optimum(p)
    if beta_w is None:
        return None
    return closed_form(p, hub_lead_angle_optimum(p), beta_w)


# --- Comparison: paper formulas, consistent closed forms, NLP -------------------------------------------------------
ROWS = (
    ComparisonRow("lead_angle", "deg", "beta, hub thread 5"),
    ComparisonRow("weight_lead_angle", "deg", "beta_w, weight thread 16"),
    ComparisonRow("cable_count", "", "z, eq. (18) rounded up"),
    ComparisonRow("cable_diameter", "mm", "d_k, eq. (17)"),
    ComparisonRow("half_coupling_mass", "kg", "m, eq. (7)"),
    ComparisonRow("hub_axial_force", "N", "F_a that half-coupling produces, consistent (5)"),
    ComparisonRow("hub_thread_load", "N", "F_a needed, eq. (2)"),
    ComparisonRow("weight_mass", "kg", "m_rv, eq. (9)"),
    ComparisonRow("weight_thread_diameter", "mm", "d_2w = 2 x_2 / (phi_1 tan beta_w)"),
    ComparisonRow("finger_diameter", "mm", "d_n, eqs. (21)-(22)"),
    ComparisonRow("screw_diameter", "mm", "d_1, eqs. (19)-(20)"),
    ComparisonRow("total_mass", "kg", "m + z m_rv + fingers + clamp screws"),
)


def _design_rows(p, design):
    """Rows for a design, evaluated with the consistent model."""
    outputs = _outputs(SimpleNamespace(**design), p)
    return {**design, **{name: outputs[name].value for name in
                         ("cable_diameter", "hub_axial_force", "hub_thread_load", "weight_thread_diameter",
                          "total_mass")}}


def paper_design(p):
    """The paper's formulas at the case's threads: z by (18) rounded up, m by (7), m_rv by (9), d_1 by (19),
    d_n by (21), as printed."""
    z = float(max(math.ceil(required_cable_count(p) - 1e-9), 1))  # at least one cable, however strong
    return {"half_coupling_mass": paper_eq7(p, z), "weight_mass": paper_eq9(p), "cable_count": z,
            "finger_diameter": paper_eq21(p, z), "screw_diameter": paper_eq19(p, z), "lead_angle": p.lead_angle,
            "weight_lead_angle": p.weight_lead_angle}


def _references(p):
    columns = {"paper_formulas": _design_rows(p, paper_design(p)), "closed_form": _design_rows(p, closed_form(p))}
    threads = closed_form_threads(p)
    if threads is not None:
        columns["closed_form_threads"] = _design_rows(p, threads)
    return columns


def _rows_from_design(mode, design, outputs, p):
    return {**design, **{name: outputs[name] for name in
                         ("cable_diameter", "hub_axial_force", "hub_thread_load", "weight_thread_diameter",
                          "total_mass")}}


COMPARISON = Comparison(
    rows=ROWS,
    references=_references,
    solves=(("nlp_paper", "paper", "mass"), ("nlp_threads", "threads", "mass")),
    rows_from_design=_rows_from_design,
    baseline="closed_form",
    column_notes={
        "paper_formulas": "the paper's printed (7), (9), (18), (19), (21) at the case's threads (no worked example)",
        "closed_form": "consistent closed form at the case's threads (paper mode)",
        "closed_form_threads": "consistent closed form with both lead angles optimal (default bounds)",
        "nlp_paper": "IPOPT, paper mode, minimum mass",
        "nlp_threads": "IPOPT, threads mode, minimum mass",
    },
)


# --- Contradictory requirements a single field cannot show ----------------------------------------------------------
def _check_drives(case):
    v = case.values
    speed = v["speed"]
    for name, what in (("mass_radius", "half-coupling"), ("weight_radius", "weights")):
        if v[name] * speed**2 <= v["gravity"]:
            raise InputError(f"geometry.{name}", f"R w^2 = {v[name] * speed**2:.4g} m/s^2 does not exceed "
                                                 f"g = {v['gravity']:.4g} m/s^2: the {what} cannot drive (eq. 1)")


def _check_threads(case):
    v = case.values
    phi = float(reduced_friction_angle(v["friction_coefficient"], v["flank_angle"]))
    limit = phi + v["self_locking_margin"]
    for name, symbol in (("lead_angle", "beta"), ("weight_lead_angle", "beta_w")):
        if v[name] <= limit:
            raise InputError(f"thread.{name}", (
                f"self-locking thread: {symbol} = {math.degrees(v[name]):.4g} deg must exceed phi' = "
                f"{math.degrees(phi):.4g} deg (atan(f / cos alpha_1), eq. 14) plus limits.self_locking_margin "
                f"{math.degrees(v['self_locking_margin']):.4g} deg, i.e. {math.degrees(limit):.4g} deg"))


COUPLING = Coupling(
    name="cable",
    title="Inertial-centrifugal cable coupling",
    source="Strilets, Fedoruk, Strilets & Kovalchuk (2013), cable_coupling_strilets_2013.txt",
    quantities=QUANTITIES,
    formulations={"paper": PAPER, "threads": THREADS},
    default_mode="paper",
    comparison=COMPARISON,
    case_checks=(_check_drives, _check_threads),
    materials=MATERIALS,
)
