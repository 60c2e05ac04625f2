"""The ball clutch's two posed problems: the paper's simplifying assumptions, or the consistent model."""

from __future__ import annotations

import math

from clutchopt.formulations.ball.clutch import MODEL, BallClutch
from clutchopt.formulations.ball.equations import filling_coefficient, leading_torque, required, width_from_rows
from clutchopt.model import Variable, at_least, at_most, si


V = Variable
RADIUS = V("active_radius", "mm", "active friction radius", "R_a", lower=si(50, "mm"), upper=si(2000, "mm"), above=0)


# --- Paper mode: the paper's simplifying assumptions; the optimum is the fifth root (4) ---------------------------
PAPER_VARIABLES = (
    RADIUS,
    V("active_width", "mm", "active width (continuous, no whole rows)", "l", lower=si(10, "mm"), upper=si(2000, "mm"),
      above=0),
)


def _paper_clutch(x, p):
    return BallClutch(x.active_radius, x.active_width, filling_coefficient(p.construction_density, p.packing_density),
                      p.ball_radius, p.groove_conformity, x.active_width / (math.sqrt(3.0) * p.ball_radius))


def _case_limits(c: BallClutch, x, p):
    """The limits the case names, met in every mode: the Hertz stress p_0 (9) of the outer balls within [p_0] (the
    paper checks it after sizing, docs/ball.md), the longest drum for its radius, K5 = l / R_a at most
    ``width_ratio_max``, and the drum's outer diameter D_max."""
    return [
        at_most("contact_stress", c.contact_stress(p), p.allowable_contact_stress, equation="(9)", unit="MPa",
                description="Hertz stress of the outer balls within [p_0]"),
        at_most("width_ratio_max", c.width_ratio, p.width_ratio_max, equation="(3)",
                description="K5 = l_a / R_a in range"),
        at_most("outer_diameter", 2 * (c.radius + p.shell_thickness), p.outer_diameter_max, equation="case",
                unit="mm", description="2 (R_a + s) <= D_max"),
    ]


def _paper_constraints(c: BallClutch, x, p):
    return [
        at_least("torque", leading_torque(p.friction_coefficient, p.density, p.packing_density, p.speed, c.width,
                                          c.radius, c.filling), required(p), equation="(4)", unit="N*m",
                 description="leading-order torque (cylinder, no shovels) covers M_c"),
        at_least("width_ratio", c.width_ratio, p.width_ratio, equation="(3), (5)",
                 description="K5 = l / R_a at least the case's K5"),
        *_case_limits(c, x, p),
    ]


PAPER = MODEL.formulation("paper",
                          "Ball clutch, the paper's assumptions: leading-order torque, K2 from (1); R_a, l free",
                          PAPER_VARIABLES, _paper_clutch, _paper_constraints)


# --- Design mode: consistent torque, Hertz stress, whole ball rows --------------------------------------------------
DESIGN_VARIABLES = (  # K2 bounds: (1) gives 0.41 to 0.60 over the paper's Psi_c = 0.6 to 1.2
    RADIUS,
    V("filling", "", "K2 = R_1 / R_a, filling of the chambers", "K2",
      lower=0.41, upper=0.60, above=0, below=1),
    V("ball_radius", "mm", "ball radius", "r_c", lower=si(4, "mm"), upper=si(20, "mm"), above=0),
    V("groove_conformity", "", "beta = r_groove / r_c", "beta", lower=1.005, upper=1.05, above=1),
    V("ball_rows", "", "number of ball rows across the width", "n_p", lower=2, upper=80, at_least=1, integer=True),
)


def _design_clutch(x, p):
    return BallClutch(x.active_radius, width_from_rows(x.ball_rows, x.ball_radius), x.filling, x.ball_radius,
                      x.groove_conformity, x.ball_rows)


def _design_constraints(c: BallClutch, x, p):
    stress, *extent = _case_limits(c, x, p)
    return [
        at_least("torque", c.torque(p), required(p), equation="(8)", unit="N*m",
                 description="torque of cylinder and end faces covers M_c"),
        stress,
        at_least("width_ratio_min", c.width_ratio, p.width_ratio_min, equation="(3)",
                 description="K5 = l_a / R_a in range"),
        *extent,
        at_least("ball_layers", c.radius * (1 - c.filling), p.min_ball_layers * 2 * c.ball_radius, equation="model",
                 unit="mm", scale=c.radius, description="the layer R_a - R_1 holds several balls"),
    ]


DESIGN = MODEL.formulation("design", "Ball clutch, consistent model: R_a, K2, r_c, beta, n_p free",
                           DESIGN_VARIABLES, _design_clutch, _design_constraints)
