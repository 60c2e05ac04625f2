"""The z toggles at a design, as both modes obtain them, and what both read off them: the torque with new
linings, wear and link strength with worn ones, the mass and cost, the outputs, the speed law of a start-up."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import SimpleNamespace
from typing import Any

from clutchopt.formulations.common import CouplingModel, centrifugal_speed_law, duty_torque, rod_mass
from clutchopt.formulations.duty import centrifugal_force
from clutchopt.formulations.envelope import disc_mass, housing_length, housing_mass
from clutchopt.formulations.lever.equations import (
    disc_friction_torque,
    disc_push,
    euler_stress,
    flange_mass,
    lever_offset,
    link_force,
    link_stress,
    lining_area,
    lining_mass,
    lining_pressure,
    mean_diameter,
    pin_diameter,
    return_spring_force,
    start_radius,
    toggle_span,
    weight_size,
    weight_travel,
)
from clutchopt.formulations.lever.paper import paper_spring_stiffness
from clutchopt.formulations.lever.quantities import QUANTITIES
from clutchopt.model import Envelope, Output, Part, at_least, at_most


@dataclass(frozen=True)
class Toggles:
    """z toggles at speed; the modes differ only in how this is obtained (paper rules or free variables)."""

    p: Any
    count: Any
    weight_mass: Any
    lever_length: Any
    engagement_angle: Any
    limit_angle: Any
    flange_diameter: Any
    lining_width: Any
    link_diameter: Any

    @property
    def start_radius(self):
        return start_radius(self.p.shaft_diameter, self.flange_diameter, self.p.spring_free_length)

    @property
    def offset(self):
        return lever_offset(self.lever_length, self.engagement_angle)

    @property
    def mean_diameter(self):
        return mean_diameter(self.offset, self.start_radius)

    @property
    def travel(self):
        return weight_travel(self.lever_length, self.engagement_angle, self.limit_angle)

    @property
    def spring_force(self):
        return return_spring_force(self.weight_mass, self.p.disc_retraction_force, self.count, self.engagement_angle)

    @property
    def new_radial_force(self):
        """Linings new: weight at R_0, spring slack."""
        return centrifugal_force(self.weight_mass, self.p.speed, self.start_radius)

    @property
    def worn_radial_force(self):
        """Linings worn by delta: weight at R_0 + travel, spring stretched by the travel."""
        return centrifugal_force(self.weight_mass, self.p.speed, self.start_radius + self.travel) - self.spring_force

    @property
    def new_push(self):
        return self.count * disc_push(self.new_radial_force, self.engagement_angle)

    @property
    def worn_push(self):
        return self.count * disc_push(self.worn_radial_force, self.limit_angle)

    def torque(self, push):
        return disc_friction_torque(self.p.friction_surfaces, self.p.friction_coefficient, push, self.mean_diameter)

    @property
    def worn_link_force(self):
        return link_force(self.worn_radial_force, self.limit_angle)

    @property
    def worn_link_stress(self):
        return link_stress(self.worn_link_force, self.link_diameter)

    @property
    def steel_mass(self):
        """Weights, two links per toggle and the spring flange."""
        p = self.p
        toggles = self.count * (self.weight_mass + 2.0 * rod_mass(p.density, self.link_diameter, self.lever_length))
        return toggles + flange_mass(p.density, self.flange_diameter, p.shaft_diameter, p.flange_thickness)

    @property
    def lining_mass(self):
        p = self.p
        return lining_mass(p.lining_density, p.friction_surfaces, self.mean_diameter, self.lining_width,
                           p.lining_thickness)

    @property
    def lining_area(self):
        return lining_area(self.p.friction_surfaces, self.mean_diameter, self.lining_width)

    @property
    def total_mass(self):
        return self.steel_mass + self.lining_mass

    @property
    def cost(self):
        p = self.p
        return p.material_price * self.steel_mass + self.count * p.part_cost + p.lining_price * self.lining_area


def _duty_constraints(t: Toggles, x, p):
    """Torque with new linings, wear and link strength with worn ones, weights that fit: both modes."""
    return [
        at_least("torque", t.torque(t.new_push), duty_torque(p), equation="m z (statics)", unit="N*m",
                 description="friction torque at gamma_0, new linings, covers T_max", constant_acceleration=True),
        at_most("lining_pressure", lining_pressure(t.worn_push, t.mean_diameter, t.lining_width),
                p.allowable_pressure, equation="B_cp, statics", unit="MPa",
                description="lining pressure at gamma_pr (worn: largest push) within [p]"),
        at_most("link_buckling", t.worn_link_stress,
                euler_stress(p.elastic_modulus, t.link_diameter, t.lever_length) / p.buckling_safety_factor,
                equation="Euler", unit="MPa", description="link stress at gamma_pr within sigma_E / n_b"),
        at_most("link_compression", t.worn_link_stress, p.allowable_link_stress, equation="statics", unit="MPa",
                description="link stress at gamma_pr within [sigma]"),
        at_most("weights_fit", t.count * weight_size(t.weight_mass, p.density),
                p.weight_packing * 2.0 * math.pi * t.start_radius, equation="geometry", unit="mm",
                description="z cube edges fit round the circle at R_0"),
    ]


def _duty_outputs(t: Toggles, x, p):
    new_torque, worn_torque = t.torque(t.new_push), t.torque(t.worn_push)
    return {
        "required_torque": Output(duty_torque(p), "N*m", "T_max = I w / t_p + T_p"),
        "torque": Output(new_torque, "N*m", "friction torque with new linings (gamma_0)"),
        "worn_torque": Output(worn_torque, "N*m", "friction torque with worn linings (gamma_pr)"),
        "torque_growth": Output(worn_torque / new_torque, "", "worn / new torque over the lining life"),
        "lining_pressure": Output(lining_pressure(t.worn_push, t.mean_diameter, t.lining_width), "MPa",
                                  "p at gamma_pr (worn)"),
        "new_lining_pressure": Output(lining_pressure(t.new_push, t.mean_diameter, t.lining_width), "MPa",
                                      "p at gamma_0 (new)"),
        "weight_mass": Output(t.weight_mass, "kg", "m, one weight"),
        "characteristic_number": Output(t.count * t.weight_mass, "kg", "m z"),
        "lever_length": Output(t.lever_length, "mm", "l_2"),
        "lever_offset": Output(t.offset, "mm", "S_ov = l_2 sin gamma_0"),
        "start_radius": Output(t.start_radius, "mm", "R_0, weight at engagement"),
        "mean_diameter": Output(t.mean_diameter, "mm", "d_cp = 2 (S_ov + R_0)"),
        "lining_width": Output(t.lining_width, "mm", "b, radial width of the linings"),
        "weight_travel": Output(t.travel, "mm", "l_2 (sin gamma_0 - sin gamma_pr), spring stretch when worn"),
        "disc_push": Output(t.new_push, "N", "axial push on each disc, new linings"),
        "worn_disc_push": Output(t.worn_push, "N", "axial push on each disc, worn linings"),
        "link_force": Output(t.worn_link_force, "N", "S at gamma_pr, largest link compression"),
        "pin_diameter": Output(pin_diameter(t.worn_link_force, p.allowable_pin_shear), "mm",
                               "pin in double shear under S"),
        "spring_stiffness": Output(t.spring_force / t.travel, "N/m", "consistent return-spring stiffness c"),
        "paper_spring_stiffness": Output(
            paper_spring_stiffness(t.mean_diameter / 2.0, p.lining_thickness, t.count, t.lever_length,
                                   t.engagement_angle, t.limit_angle),
            "m^3/s^2", "c as printed with l_cp = d_cp/2 (not a stiffness: errata L2)"),
        "toggle_span": Output(toggle_span(t.lever_length, t.limit_angle), "mm", "2 l_2 cos gamma_pr"),
        "outer_diameter": Output(t.mean_diameter + t.lining_width + 2.0 * p.shell_thickness, "mm",
                                 "d_cp + b + 2 s"),
        "total_mass": Output(t.total_mass, "kg", "weights, links, spring flange, linings"),
        "cost": Output(t.cost, "EUR", "material, parts, linings"),
    }


def _envelope(t: Toggles, x, p):
    """The lever coupling beside the others (docs/envelope.md): D = d_cp + b + 2 s, and L = 2 l_2 cos gamma_pr + 2
    delta + i s + 2 s, the toggle at its longest between the i pressure discs, their linings and the housing's two end
    walls.

    halves: the spring flange, i pressure discs (d_b .. d_cp + b, as thick as the housing wall s) and the driven
    housing 5, a drum of inner radius (d_cp + b) / 2 and wall s round them, closed at both ends; moving parts: z
    weights and 2 z links; springs: none sized (the model gives the return springs' stiffness, not their wire);
    linings: the i lining rings.
    """
    s, surfaces = p.shell_thickness, p.friction_surfaces
    outer_radius = (t.mean_diameter + t.lining_width) / 2.0
    inner = toggle_span(t.lever_length, t.limit_angle) + 2.0 * p.lining_thickness + surfaces * s
    flange = flange_mass(p.density, t.flange_diameter, p.shaft_diameter, p.flange_thickness)
    halves = (flange + surfaces * disc_mass(p.density, outer_radius, p.shaft_diameter / 2.0, s)
              + housing_mass(p.density, outer_radius, s, inner, ends=2))
    return Envelope(2.0 * (outer_radius + s), housing_length(inner, s, ends=2), {
        "halves": Part(halves, "spring flange, i pressure discs (wall s thick), housing round them (two end walls)"),
        "moving_parts": Part(t.steel_mass - flange, "z weights and 2 z links"),
        "springs": Part(0.0, "none sized by the model (stiffness only)"),
        "linings": Part(t.lining_mass, "i lining rings"),
    })


def _speed_law(toggles):
    """T = K w_a^2, K the friction torque with new linings (gamma_0, weight at R_0, spring slack) at 1 rad/s; each
    weight's centrifugal force is m R_0 w_a^2, against which a spring preload and gravity act. Worn (gamma_pr, weight
    at R_0 + dr, the return spring stretched by dr): T = i f z (m w^2 (R_0 + dr) - c dr - F) d_cp / (4 tan gamma_pr),
    F the radial force of preload and gravity (docs/lever.md, "Worn linings on the drive")."""
    def worn_torque(x, p, speed, radial_force):
        t = toggles(x, SimpleNamespace(**{**vars(p), "speed": speed}))
        return t.torque(t.count * disc_push(t.worn_radial_force - radial_force, t.limit_angle))

    law = centrifugal_speed_law(toggles, lambda t, p: t.torque(t.new_push), lambda t: t.weight_mass,
                                lambda t: t.start_radius, lambda t: t.lining_area)
    return replace(law, worn_torque=worn_torque)


MODEL = CouplingModel(
    coupling="lever",
    quantities=QUANTITIES,
    mass=("weights, links, spring flange and linings", lambda t, p: t.total_mass),
    cost=("material, parts per toggle, linings", lambda t, p: t.cost),
    outputs=_duty_outputs,
    speed_law=_speed_law,
    constraints=_duty_constraints,
    envelope=_envelope,
    outputs_once=True,
)
