"""The optimum of paper mode by hand: m z from the torque requirement, d_l from buckling and compression."""

from __future__ import annotations

import math
from types import SimpleNamespace

from clutchopt.formulations.common import duty_torque
from clutchopt.formulations.lever.equations import characteristic_number, lever_offset, mean_diameter, start_radius
from clutchopt.formulations.lever.modes import paper_toggles
from clutchopt.formulations.lever.paper import paper_geometry


def closed_form_characteristic_number(p):
    """m z from the torque requirement at gamma_0 with the paper's geometry (consistent form of the paper's m z)."""
    lever, _ = paper_geometry(p)
    radius = start_radius(p.shaft_diameter, p.flange_diameter, p.spring_free_length)
    diameter = mean_diameter(lever_offset(lever, p.engagement_angle), radius)
    return characteristic_number(duty_torque(p), p.friction_coefficient, p.speed, p.engagement_angle, radius, diameter,
                                 p.friction_surfaces)


def closed_form_link_diameter(p, weight_mass):
    """d_l = max((64 n_b S l_2^2 / (pi^3 E))^(1/4), (4 S / (pi [sigma]))^(1/2)) at the worn-state link force S;
    NaN where S <= 0 (the worn toggle does not press the linings at this duty)."""
    t = paper_toggles(SimpleNamespace(weight_mass=weight_mass, link_diameter=math.nan), p)
    force, length = t.worn_link_force, t.lever_length
    if not force > 0:  # at this duty the worn toggle no longer presses: the paper's sizing has no link to size
        return math.nan
    buckling = (64.0 * p.buckling_safety_factor * force * length**2 / (math.pi**3 * p.elastic_modulus)) ** 0.25
    compression = math.sqrt(4.0 * force / (math.pi * p.allowable_link_stress))
    return max(buckling, compression)
