"""The wedge coupling's two posed problems: the paper's geometry given, or the weights as real bodies."""

from __future__ import annotations

import math

from clutchopt.backend import sin, tan
from clutchopt.formulations.wedge.equations import (
    paper_centroid_radius,
    self_locking_angle,
    weight_base_width,
    weight_body,
)
from clutchopt.formulations.wedge.weight_set import MODEL, WeightSet
from clutchopt.model import Output, Variable, at_least, at_most, si


# --- Paper mode: geometry given, r_c = r2 - 2/3 h_r, m_r and d_n free ----------------------------------------------
PAPER_VARIABLES = (
    Variable("weight_mass", "kg", "mass of one weight", "m_r", lower=1e-6, upper=1e4, above=0),
    Variable("finger_diameter", "mm", "finger diameter", "d_n", lower=si(0.1, "mm"), upper=si(500, "mm"), above=0),
)


def paper_weight_set(x, p):
    """The weights of the paper's geometry, r_c = r2 - 2/3 h_r (11); the width b that a real weight of that geometry
    (``weight_body``) has at mass m_r (``weight_base_width``)."""
    r1 = p.flank_inner_radius
    r2 = p.radius_ratio * r1
    width = weight_base_width(x.weight_mass, r2 - p.weight_height, r1, r2, p.flank_angle, p.sector_angle, p.density)
    return WeightSet(p.weight_count, r1, r2, p.flank_angle, p.sector_angle, x.weight_mass,
                     paper_centroid_radius(r2, p.weight_height), x.finger_diameter, p.speed, p.friction_coefficient,
                     p.weight_height, width)


def constructive_constraints(w: WeightSet, x, p):
    """Rules that make a design a part one can build, posed in both modes (one definition, one name): (26), the
    sectors round the shaft (below (23)), release (above (24)), the housing's D_max, the trapezoid's top land, the
    hub, and the finger in its weight.

    In geometry mode they bound the free geometry. In paper mode the geometry is given and only m_r and d_n move:
    the rows that read neither (26, sectors, release, housing, hub) are fixed by the case (one it breaks is
    infeasible whatever the design); the finger's guide and chord read d_n. The top land and the finger's fit
    read the weight's width b, in paper mode that of the real weight of mass m_r on the given geometry
    (``weight_base_width``): exact, as in geometry mode."""
    r_in, b = w.r2 - w.height, w.width
    return [
        at_least("weight_covers_flank", w.height, w.r2 - w.r1, equation="(26)", unit="mm", scale=w.r1,
                 description="h_r >= r2 - r1"),
        at_most("sectors_fit", w.count * (w.sector_angle + p.sector_clearance), 2 * math.pi, equation="below (23)",
                unit="deg", description="z (gamma + clearance) <= 2 pi"),
        at_least("not_self_locking", w.flank_angle, self_locking_angle(p.friction_coefficient) + p.self_locking_margin,
                 equation="above (24)", unit="deg", description="alpha >= atan f + margin"),
        at_most("outer_diameter", 2 * (w.r2 + p.shell_thickness), p.outer_diameter_max, equation="case", unit="mm",
                description="2 (r2 + shell) <= D_max"),
        at_least("top_land_width", b - 2 * (w.r2 - w.r1) * tan(w.flank_angle), p.min_top_width, equation="geometry",
                 unit="mm", scale=b, description="trapezoid top b - 2 (r2 - r1) tan(alpha) >= min"),
        at_least("hub_clearance", r_in, p.hub_radius, equation="fig. 2", unit="mm", scale=w.r1,
                 description="inner edge r2 - h_r clears the hub"),
        at_most("finger_fits_width", w.finger_diameter, p.finger_fit_ratio * b, equation="geometry", unit="mm",
                scale=b, description="d_n <= ratio * b"),
        at_least("finger_guide_length", w.height, p.guide_length_ratio * w.finger_diameter,
                 equation="geometry", unit="mm", scale=w.r1, description="h_r >= ratio * d_n"),
        at_most("finger_fits_chord", w.finger_diameter, p.finger_fit_ratio * 2 * r_in * sin(w.sector_angle / 2),
                equation="geometry", unit="mm", scale=w.r1, description="d_n <= ratio * chord at r_in"),
    ]


def _paper_outputs(w: WeightSet, x, p):
    return {"weight_width": Output(w.width, "mm", "b of the real weight of mass m_r (weight_base_width)")}


PAPER = MODEL.formulation("paper", "Wedge CFC, paper assumptions: geometry given, m_r and d_n free",
                          PAPER_VARIABLES, paper_weight_set, constructive_constraints, _paper_outputs)


# --- Geometry mode: weights as real bodies -------------------------------------------------------------------------
V = Variable
GEOMETRY_VARIABLES = (
    V("flank_inner_radius", "mm", "inner radius of the flanks", "r_1", lower=si(5, "mm"), upper=si(2000, "mm"), above=0),
    V("radius_ratio", "", "lambda = r2/r1", "lambda", lower=1.1, upper=1.35, above=1),
    V("weight_height", "mm", "radial height of a weight", "h_r", lower=si(1, "mm"), upper=si(1000, "mm"), above=0),
    V("sector_angle", "deg", "central angle of a weight", "gamma", lower=si(5, "deg"), upper=si(170, "deg"),
      above=0, below=2 * math.pi),
    V("weight_width", "mm", "axial width of a weight", "b", lower=si(2, "mm"), upper=si(1000, "mm"), above=0),
    V("finger_diameter", "mm", "finger diameter", "d_n", lower=si(0.5, "mm"), upper=si(300, "mm"), above=0),
    V("flank_angle", "deg", "flank half-angle", "alpha", lower=si(5, "deg"), upper=si(45, "deg"), above=0,
      below=math.pi / 2, fixed_unless_freed=True),
    V("weight_count", "", "number of weights", "z", lower=2, upper=12, at_least=1, integer=True, fixed_unless_freed=True),
)


def _geometry_weight_set(x, p):
    """The weights as real bodies (annular sector r2 - h_r .. r2 with a trapezoidal top): mass, exact centroid."""
    r1 = x.flank_inner_radius
    r2 = x.radius_ratio * r1
    mass, r_c = weight_body(r2 - x.weight_height, r1, r2, x.weight_width, x.flank_angle, x.sector_angle, p.density)
    return WeightSet(x.weight_count, r1, r2, x.flank_angle, x.sector_angle, mass, r_c, x.finger_diameter, p.speed,
                     p.friction_coefficient, x.weight_height, x.weight_width)


def _geometry_outputs(w: WeightSet, x, p):
    return {
        "paper_centroid_radius": Output(paper_centroid_radius(w.r2, x.weight_height), "mm", "r2 - 2/3 h_r, eq. (11)"),
        "outer_flank_radius": Output(w.r2, "mm", "r2 = lambda r1"),
        "inner_weight_radius": Output(w.r2 - x.weight_height, "mm", "r2 - h_r"),
    }


GEOMETRY = MODEL.formulation("geometry", "Wedge CFC, weights as real bodies: geometry free", GEOMETRY_VARIABLES,
                             _geometry_weight_set, constructive_constraints, _geometry_outputs)
