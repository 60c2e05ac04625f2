"""The lever coupling's two posed problems: the geometry by the paper's rules, or free within the housing."""

from __future__ import annotations

import math

from clutchopt.backend import cos
from clutchopt.formulations.lever.equations import toggle_span
from clutchopt.formulations.lever.paper import paper_geometry
from clutchopt.formulations.lever.toggles import MODEL, Toggles
from clutchopt.model import Variable, at_least, at_most, si

# --- Paper mode: the paper's rules fix the geometry; m and d_l free -------------------------------------------------
V = Variable
WEIGHT_MASS = V("weight_mass", "kg", "mass of one weight", "m", lower=1e-4, upper=100.0, above=0)
LINK_DIAMETER = V("link_diameter", "mm", "diameter of a (solid round) link", "d_l", lower=si(0.5, "mm"),
                  upper=si(100, "mm"), above=0)
PAPER_VARIABLES = (WEIGHT_MASS, LINK_DIAMETER)


def paper_toggles(x, p):
    """The toggles of the paper's method: l_2 and B_cp by its rules, the case's angles, z and d_phi."""
    lever, width = paper_geometry(p)
    return Toggles(p, p.weight_count, x.weight_mass, lever, p.engagement_angle, p.limit_angle, p.flange_diameter,
                   width, x.link_diameter)


def _case_limits(t: Toggles, x, p):
    """The housing limits the case names, met in every mode: the outer diameter D_max and the toggle's axial span
    L_max. In paper mode both are fixed by the paper's rules for l_2 and B_cp at the case's angles: a case that
    breaks one is infeasible whatever m and d_l, which the float64 re-check shows as a row with its margin."""
    return [
        at_most("outer_diameter", t.mean_diameter + t.lining_width + 2.0 * p.shell_thickness, p.outer_diameter_max,
                equation="case", unit="mm", description="d_cp + b + 2 s <= D_max"),
        at_most("toggle_span", toggle_span(t.lever_length, t.limit_angle), p.toggle_span_max, equation="case",
                unit="mm", description="2 l_2 cos gamma_pr <= L_max"),
    ]


def _flange_over_shaft(t: Toggles, p):
    """The case's limits.flange_hub_ratio, met in every mode: the spring flange is that much wider than the shaft."""
    return at_least("flange_over_shaft", t.flange_diameter, p.flange_hub_ratio * p.shaft_diameter,
                    equation="geometry", unit="mm", description="d_phi >= ratio * d_b")


def _lining_clears_flange(t: Toggles):
    """The linings' inner diameter clears the spring flange, in every mode: in paper mode d_cp and B_cp come from the
    paper's rules and d_phi from the case, a row no design variable enters."""
    return at_least("lining_clears_flange", t.mean_diameter - t.lining_width, t.flange_diameter, equation="geometry",
                    unit="mm", description="inner lining diameter d_cp - b >= d_phi")


def _paper_limits(t: Toggles, x, p):
    """Every rule of design mode but the l_2 rule, which paper mode meets by construction (``paper_geometry``
    takes the shortest levers it allows: l_2 (cos gamma_pr - cos gamma_0) = delta exactly)."""
    return [*_case_limits(t, x, p), _lining_clears_flange(t), _flange_over_shaft(t, p)]


PAPER = MODEL.formulation("paper", "Lever CFC, paper method: l_2 and B_cp by the paper's rules, m and d_l free",
                          PAPER_VARIABLES, paper_toggles, _paper_limits)


# --- Design mode: geometry free within the housing ------------------------------------------------------------------
DESIGN_VARIABLES = (
    WEIGHT_MASS,
    V("lever_length", "mm", "link length", "l_2", lower=si(10, "mm"), upper=si(2000, "mm"), above=0),
    V("engagement_angle", "deg", "link angle to the axis, new linings", "gamma_0", lower=si(4, "deg"),
      upper=si(15, "deg"), above=0, at_most=math.radians(15)),
    V("limit_angle", "deg", "link angle to the axis, worn linings", "gamma_pr", lower=si(1.5, "deg"),
      upper=si(3, "deg"), at_least=math.radians(1.5), at_most=math.radians(3)),
    V("weight_count", "", "number of weights (toggles)", "z", lower=3, upper=12, at_least=1, integer=True),
    V("flange_diameter", "mm", "spring flange diameter", "d_phi", lower=si(10, "mm"), upper=si(1000, "mm"), above=0),
    V("lining_width", "mm", "radial width of the linings", "b", lower=si(2, "mm"), upper=si(500, "mm"), above=0),
    LINK_DIAMETER,
)


def _design_toggles(x, p):
    return Toggles(p, x.weight_count, x.weight_mass, x.lever_length, x.engagement_angle, x.limit_angle,
                   x.flange_diameter, x.lining_width, x.link_diameter)


def _housing_constraints(t: Toggles, x, p):
    """The l_2 rule and what makes the toggles fit a housing and a shaft."""
    return [
        at_least("lever_length", t.lever_length * (cos(t.limit_angle) - cos(t.engagement_angle)),
                 p.lining_thickness, equation="l_2 rule", unit="mm",
                 description="l_2 (cos gamma_pr - cos gamma_0) >= delta"),
        *_case_limits(t, x, p),
        _lining_clears_flange(t),
        _flange_over_shaft(t, p),
    ]


DESIGN = MODEL.formulation("design", "Lever CFC, geometry free: l_2, angles, z, d_phi, b, m, d_l",
                           DESIGN_VARIABLES, _design_toggles, _housing_constraints)
