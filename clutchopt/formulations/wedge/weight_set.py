"""The z weights at a design, as both modes obtain them, and what both read off them: the paper's three
requirements, the mass and cost, the outputs, the speed law of a start-up."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from clutchopt.formulations.common import CouplingModel, centrifugal_speed_law, duty_torque
from clutchopt.formulations.duty import centrifugal_force
from clutchopt.formulations.envelope import disc_mass, housing_length, housing_mass
from clutchopt.formulations.wedge.equations import (
    cost,
    finger_bending_stress,
    finger_mass,
    flank_area,
    flank_area_total,
    flank_pressure,
    friction_force,
    friction_torque,
    mean_flank_radius,
)
from clutchopt.formulations.wedge.quantities import QUANTITIES
from clutchopt.model import Envelope, Output, Part, at_least, at_most


@dataclass(frozen=True)
class WeightSet:
    """z weights at speed: where the modes differ is only how this is obtained (given geometry or real bodies)."""

    count: Any
    r1: Any
    r2: Any
    flank_angle: Any
    sector_angle: Any
    weight_mass: Any
    centroid_radius: Any
    finger_diameter: Any
    speed: Any
    friction_coefficient: Any
    height: Any = None  # h_r, radial height of a weight (its inner edge at r2 - h_r)
    width: Any = None  # b, axial width of a weight

    @property
    def centrifugal(self):
        return centrifugal_force(self.weight_mass, self.speed, self.centroid_radius)

    @property
    def friction(self):
        return friction_force(self.friction_coefficient, self.centrifugal, self.flank_angle)

    @property
    def torque(self):
        """T_fr, eq. (15)."""
        return friction_torque(self.count, self.friction, self.r1, self.r2)

    @property
    def friction_area(self):
        return flank_area_total(self.count, self.sector_angle, self.r1, self.r2, self.flank_angle)


def _duty_constraints(w: WeightSet, x, p):
    """Torque (15)-(16), wear (13) and finger bending (19): the paper's three requirements."""
    return [
        at_least("torque", w.torque, duty_torque(p), equation="(15)-(16)", unit="N*m",
                 description="friction torque covers T_max", constant_acceleration=True),
        at_most("flank_pressure", flank_pressure(w.centrifugal, w.flank_angle, w.sector_angle, w.r1, w.r2),
                p.allowable_pressure, equation="(13)", unit="MPa", description="flank pressure within [p]"),
        at_most("finger_bending", finger_bending_stress(w.friction, mean_flank_radius(w.r1, w.r2), w.finger_diameter),
                p.allowable_bending_stress, equation="(19)", unit="MPa", description="finger bending within [sigma]"),
    ]


def _total_mass(w: WeightSet, p):
    """z (m_r + m_finger), the finger h_n = d_cp / 2 long."""
    return w.count * (w.weight_mass + finger_mass(p.density, w.finger_diameter, mean_flank_radius(w.r1, w.r2)))


def _cost(w: WeightSet, p):
    return cost(p, _total_mass(w, p), w.count, flank_area(w.sector_angle, w.r1, w.r2, w.flank_angle))


def _duty_outputs(w: WeightSet, x, p):
    return {
        "required_torque": Output(duty_torque(p), "N*m", "T_max, eqs. (5), (17)"),
        "torque": Output(w.torque, "N*m", "friction torque, eq. (15)"),
        "flank_pressure": Output(flank_pressure(w.centrifugal, w.flank_angle, w.sector_angle, w.r1, w.r2), "MPa",
                                 "q, eq. (13)"),
        "weight_mass": Output(w.weight_mass, "kg", "m_r, one weight"),
        "centroid_radius": Output(w.centroid_radius, "mm", "r_c of a weight"),
        "centrifugal_force": Output(w.centrifugal, "N", "F_u per weight, eq. (10)"),
        "total_mass": Output(_total_mass(w, p), "kg", "z (m_r + finger)"),
        "cost": Output(_cost(w, p), "EUR", "material + parts + flank grinding"),
    }


def _envelope(w: WeightSet, x, p):
    """The wedge coupling beside the others (docs/envelope.md): D = 2 (r2 + s), L = b + s.

    halves: the driving hub, a solid disc of the hub radius r_hub over the weights' width b, and the driven
    half-coupling, a drum of inner radius r2 (the groove's outer flank radius), wall s, over b, closed at one end;
    moving parts: z (m_r + finger); springs: none sized (the return springs of a start-up are a preload only);
    linings: none (steel flanks in a steel groove).
    """
    halves = (disc_mass(p.density, p.hub_radius, 0.0, w.width)
              + housing_mass(p.density, w.r2, p.shell_thickness, w.width))
    return Envelope(2.0 * (w.r2 + p.shell_thickness), housing_length(w.width, p.shell_thickness), {
        "halves": Part(halves, "driving hub (r_hub over b) and driven drum (r2, wall s, over b, one end wall)"),
        "moving_parts": Part(_total_mass(w, p), "z weights and z fingers"),
        "springs": Part(0.0, "none sized by the model"),
        "linings": Part(0.0, "none: steel flanks"),
    })


def _speed_law(weight_set):
    """T = K w_a^2 with K the friction torque (15) of the weights at 1 rad/s; each weight's centrifugal force is
    m_r r_c w_a^2 (10), against which springs and gravity act."""
    return centrifugal_speed_law(weight_set, lambda w, p: w.torque, lambda w: w.weight_mass,
                                 lambda w: w.centroid_radius, lambda w: w.friction_area)


MODEL = CouplingModel(
    coupling="wedge",
    quantities=QUANTITIES,
    mass=("weights and fingers, z (m_r + m_finger)", _total_mass),
    cost=("material, parts and flank grinding", _cost),
    outputs=_duty_outputs,
    speed_law=_speed_law,
    constraints=_duty_constraints,
    envelope=_envelope,
)
