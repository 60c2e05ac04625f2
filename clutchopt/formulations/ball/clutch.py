"""The ball clutch at a design, as both modes obtain it, and what both read off it: the mass and cost, the
outputs, the speed law of a start-up."""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from clutchopt.formulations.ball.contact import contact_stress, curvatures, hertz_coefficients
from clutchopt.formulations.ball.equations import (
    ball_load,
    ball_mass,
    body_mass,
    clutch_torque,
    cost,
    leading_torque,
    required,
)
from clutchopt.formulations.ball.paper import paper_eq9, paper_eq10
from clutchopt.formulations.ball.quantities import QUANTITIES
from clutchopt.formulations.common import CouplingModel, centrifugal_speed_law
from clutchopt.model import Envelope, Output, Part


@dataclass(frozen=True)
class BallClutch:
    """R_a, l_a, K2, r_c, beta, n_p of one design: where the modes differ is how they are obtained."""

    radius: Any
    width: Any
    filling: Any
    ball_radius: Any
    conformity: Any
    rows: Any

    @cached_property
    def width_ratio(self):
        """K5 = l / R_a (3): one expression for every row that reads it."""
        return self.width / self.radius

    def balls(self, p):
        return ball_mass(p, self.radius, self.width, self.filling)

    def body(self, p):
        return body_mass(p, self.radius, self.width)

    def mass(self, p):
        return self.balls(p) + self.body(p)

    def cost(self, p):
        return cost(p, self.balls(p), self.body(p))

    def torque(self, p):
        return clutch_torque(p, self.radius, self.width, self.filling)

    def contact_stress(self, p):
        return contact_stress(p, self.radius, self.filling, self.ball_radius, self.conformity)


def _outputs(c: BallClutch, x, p):
    total, ratio = curvatures(c.radius, c.ball_radius, c.conformity)
    n_a, n_b = hertz_coefficients(ratio)
    return {
        "required_torque": Output(required(p), "N*m", "M_c = k_s P / w_n"),
        "torque": Output(c.torque(p), "N*m", "torque of the design, eq. (8) consistent"),
        "leading_torque": Output(leading_torque(p.friction_coefficient, p.density, p.packing_density, p.speed,
                                                c.width, c.radius, c.filling), "N*m",
                                 "cylinder term only, the torque behind (4)"),
        "active_width": Output(c.width, "mm", "l_a"),
        "width_ratio": Output(c.width / c.radius, "", "K5 = l_a / R_a, eq. (3)"),
        "filling_radius": Output(c.filling * c.radius, "mm", "R_1 = K2 R_a"),
        "contact_stress": Output(c.contact_stress(p), "MPa", "p_0, Hertz, eq. (9) consistent"),
        "contact_stress_eq9": Output(paper_eq9(p, c.radius, c.filling, n_a, n_b), "MPa", "p_0, eq. (9) as printed"),
        "contact_stress_eq10": Output(paper_eq10(p, c.radius, c.filling, c.conformity), "MPa",
                                      "p_0, eq. (10) as printed"),
        "hertz_n_a": Output(n_a, "", "n_a of the contact"),
        "hertz_n_b": Output(n_b, "", "n_b of the contact"),
        "curvature_ratio": Output(ratio, "", "B/A of the contact"),
        "ball_load": Output(ball_load(p, c.radius, c.filling, c.ball_radius), "N", "F on one outer ball"),
        "ball_mass": Output(c.balls(p), "kg", "balls, eq. (2) consistent"),
        "ball_count": Output(c.balls(p) / (p.density * 4.0 / 3.0 * math.pi * c.ball_radius**3), "",
                             "number of balls, m_n / (rho 4/3 pi r_c^3)"),
        "body_mass": Output(c.body(p), "kg", "G_c, eq. (13)"),
        "total_mass": Output(c.mass(p), "kg", "balls + body"),
        "cost": Output(c.cost(p), "EUR", "balls and body priced per kg"),
        "outer_diameter": Output(2 * (c.radius + p.shell_thickness), "mm", "2 (R_a + s)"),
    }


def _envelope(c: BallClutch, x, p):
    """The ball clutch beside the others (docs/envelope.md): D = 2 (R_a + s), L = l_a + 2 s (the drum's two end
    faces). halves: the body of eq. (13), rotor and drum by the construction density Psi_c; moving parts: the balls,
    eq. (2); springs and linings: none."""
    return Envelope(2.0 * (c.radius + p.shell_thickness), c.width + 2.0 * p.shell_thickness, {
        "halves": Part(c.body(p), "body, eq. (13): rotor and drum by the construction density"),
        "moving_parts": Part(c.balls(p), "balls, eq. (2)"),
        "springs": Part(0.0, "none: the balls need no springs"),
        "linings": Part(0.0, "none: balls on the steel drum"),
    })


def _speed_law(clutch_of):
    """T = K w_a^2: the torque (8) of the ball layer, which rides on the driving rotor, at 1 rad/s. The balls have
    no springs, and their weight does not hold the layer in once it has formed, so neither effect applies."""
    return centrifugal_speed_law(clutch_of, lambda c, p: c.torque(p))


MODEL = CouplingModel(
    coupling="ball",
    quantities=QUANTITIES,
    mass=("balls and body, eqs. (2), (13)", lambda c, p: c.mass(p)),
    cost=("balls and body priced per kg", lambda c, p: c.cost(p)),
    outputs=_outputs,
    speed_law=_speed_law,
    envelope=_envelope,
)
