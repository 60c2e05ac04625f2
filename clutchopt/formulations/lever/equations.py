"""The lever coupling's equations: the paper's geometric rules (it numbers no equation, so each is named by its
symbol) and the statics of the toggle, wear, strength and spring derived here (docs/lever.md). Generic over
floats and CasADi symbols."""

from __future__ import annotations

import math

from clutchopt.backend import cbrt, cos, sin, sqrt, tan
from clutchopt.formulations.duty import GRAVITY


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


def paper_mean_width(offset, lining_thickness, allowance):
    """B_cp ~ 2 [S_ov + (1.5..2) delta] (paper, last relation); read here as the radial width of the linings."""
    return 2.0 * (offset + allowance * lining_thickness)


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


def flange_mass(density, flange_diameter, shaft_diameter, thickness):
    """Spring flange: annular disc d_b..d_phi of the given thickness."""
    return density * math.pi * (flange_diameter**2 - shaft_diameter**2) / 4.0 * thickness


def lining_area(surfaces, diameter, width):
    """A = i pi d_cp b: the friction area of i lining rings of mean diameter d_cp and width b (what wears)."""
    return surfaces * math.pi * diameter * width


def lining_mass(lining_density, surfaces, diameter, width, thickness):
    """i lining rings of mean diameter d_cp, width b, thickness delta."""
    return lining_density * lining_area(surfaces, diameter, width) * thickness


def weight_size(weight_mass, density):
    """Edge of a cube of mass m: how much of the circle at R_0 a weight takes."""
    return cbrt(weight_mass / density)


def toggle_span(lever_length, limit_angle):
    """Axial span of a toggle at its longest (gamma_pr): 2 l_2 cos gamma_pr."""
    return 2.0 * lever_length * cos(limit_angle)
