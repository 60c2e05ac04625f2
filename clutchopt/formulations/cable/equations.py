"""The cable coupling's equations, by the paper's numbers (Strilets 2013): the hub and weight threads, the
cables, clamps and fingers, the masses; where the printed equation is inconsistent, the consistent form
(docs/errata.md, C1-C9). Generic over floats and CasADi symbols."""

from __future__ import annotations

import math

from clutchopt.backend import arctan, cos, sqrt, tan
from clutchopt.formulations.common import rod_bending_stress, rod_mass
from clutchopt.formulations.duty import centrifugal_force


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
    return rod_bending_stress(finger_force(p.torque, finger_count, p.finger_circle_diameter), p.finger_length / 2.0,
                              diameter)


def torsional_stiffness(torque, twist_angle):
    """C_phi = T / phi_3, eq. (23), with phi_3 = phi the design twist under T."""
    return torque / twist_angle


def hardware_mass(p, cable_count, finger_diameter, screw_diameter):
    """z fingers (d_n x l_n) and 2 z clamp screws (d_1 x screw length) as steel cylinders."""
    finger = rod_mass(p.density, finger_diameter, p.finger_length)
    screw = rod_mass(p.density, screw_diameter, p.clamp_screw_length)
    return cable_count * (finger + 2.0 * screw)


def total_mass(p, half_coupling, weight, cable_count, finger_diameter, screw_diameter):
    """m + z m_rv + fingers + clamp screws (the hardware's own inertia force is neglected: conservative)."""
    return half_coupling + cable_count * weight + hardware_mass(p, cable_count, finger_diameter, screw_diameter)


def cost(p, mass, cable_count):
    """Material at a price per kg and a fixed cost per cable set."""
    return p.material_price * mass + cable_count * p.cable_set_cost
