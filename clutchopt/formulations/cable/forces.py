"""The forces, thread loads and stresses of a cable-coupling design, and what both modes read off them: the
constraints, the mass and cost, the outputs."""

from __future__ import annotations

from clutchopt.backend import cbrt, fmax
from clutchopt.formulations.cable.equations import (
    back_driven_torque,
    cable_diameter,
    cable_stress,
    cable_tension,
    cable_wire_area,
    clamp_screw_stress,
    cost,
    finger_bending_stress,
    hub_axial_force,
    hub_thread_load,
    inertia_force,
    length_ratio,
    reduced_friction_angle,
    required_cable_count,
    thread_pitch,
    thread_pressure,
    torsional_stiffness,
    total_mass,
    turns_in_nut,
    weight_thread_diameter,
)
from clutchopt.formulations.cable.quantities import QUANTITIES
from clutchopt.formulations.cable.speed_law import ELASTIC_LAW
from clutchopt.formulations.common import CouplingModel
from clutchopt.formulations.envelope import disc_mass
from clutchopt.model import Envelope, Output, Part, at_least, at_most, si


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


def _constraints(c: CableCoupling, x, p):
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


def _outputs(c: CableCoupling, x, p):
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


def _envelope(c: CableCoupling, x, p):
    """The cable coupling beside the others (docs/envelope.md). D = 2 max(R_rv + a_w / 2, D/2 + d_n / 2), the
    weights (a_w the edge of a steel cube of mass m_rv) or the fingers on their circle, whichever reaches further;
    L = l + H + l_n, the free cable span, the cup's hub (the engaged length of thread 5) and the driven half.

    halves: the driving cup m (a design variable) and the driven half-coupling 8, which the paper does not size: a
    steel disc of the finger circle D, l_n thick (our proportion); moving parts: z weights, z fingers, 2 z clamp
    screws and the z cables (steel wire of area A_s, eq. (18), over the span l); springs: none sized (the return
    spring 6 is given by its stiffness); linings: none.
    """
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    wire = cable_wire_area(p.area_ratio, cable_diameter(p.finger_circle_diameter, ratio, p.cable_coefficient,
                                                         p.twist_angle))
    cables = c.z * p.density * wire * p.span
    weight_edge = cbrt(x.weight_mass / p.density)
    radius = fmax(p.weight_radius + weight_edge / 2.0, p.finger_circle_diameter / 2.0 + x.finger_diameter / 2.0)
    driven = disc_mass(p.density, p.finger_circle_diameter / 2.0, 0.0, p.finger_length)
    return Envelope(2.0 * radius, p.span + p.nut_height + p.finger_length, {
        "halves": Part(x.half_coupling_mass + driven, "driving cup m and driven half 8 (disc of D, l_n thick)"),
        "moving_parts": Part(c.mass - x.half_coupling_mass + cables,
                             "z weights, fingers, 2 z clamp screws, z cables (A_s over l)"),
        "springs": Part(0.0, "none sized by the model (stiffness only)"),
        "linings": Part(0.0, "none: the cables carry the torque"),
    })


MODEL = CouplingModel(
    coupling="cable",
    quantities=QUANTITIES,
    mass=("half-coupling, weights, fingers and clamp screws", lambda c, p: c.mass),
    cost=("material and cable sets", lambda c, p: c.cost),
    outputs=_outputs,
    speed_law=lambda state: ELASTIC_LAW,
    constraints=_constraints,
    envelope=_envelope,
)
