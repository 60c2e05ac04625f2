"""The lever paper's own method and its printed forms: the geometry by its rules, the characteristic number m z
and the spring stiffness c as printed (docs/errata.md, L1, L2)."""

from __future__ import annotations

import math

from clutchopt.backend import sin, tan
from clutchopt.formulations.duty import GRAVITY
from clutchopt.formulations.lever.equations import lever_offset, minimum_lever_length, paper_mean_width


def paper_geometry(p):
    """(l_2, B_cp): the shortest levers of the l_2 rule and the paper's lining width."""
    lever = minimum_lever_length(p.lining_thickness, p.limit_angle, p.engagement_angle)
    width = paper_mean_width(lever_offset(lever, p.engagement_angle), p.lining_thickness, p.width_allowance)
    return lever, width


def paper_k(shaft_diameter, flange_diameter, spring_free_length):
    """k = d_b + d_phi + 4 l_pr (paper, under the characteristic number); k = 4 R_0."""
    return shaft_diameter + flange_diameter + 4.0 * spring_free_length


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
