"""What ``clutchopt compare`` shows for the lever coupling: the paper's printed formula, the consistent closed
form and the NLP optima, each design evaluated with the consistent model."""

from __future__ import annotations

import math
from types import SimpleNamespace

from clutchopt.formulations.common import duty_torque
from clutchopt.formulations.lever.closed_forms import closed_form_characteristic_number, closed_form_link_diameter
from clutchopt.formulations.lever.modes import PAPER
from clutchopt.formulations.lever.paper import paper_characteristic_number, paper_geometry, paper_k
from clutchopt.model import Comparison, ComparisonRow

ROWS = (
    ComparisonRow("characteristic_number", "kg", "m z"),
    ComparisonRow("weight_mass", "kg", "m, one weight"),
    ComparisonRow("weight_count", "", "z"),
    ComparisonRow("lever_length", "mm", "l_2"),
    ComparisonRow("engagement_angle", "deg", "gamma_0"),
    ComparisonRow("limit_angle", "deg", "gamma_pr"),
    ComparisonRow("mean_diameter", "mm", "d_cp"),
    ComparisonRow("lining_width", "mm", "b"),
    ComparisonRow("link_diameter", "mm", "d_l"),
    ComparisonRow("torque", "N*m", "torque of that design with new linings, consistent statics"),
    ComparisonRow("worn_torque", "N*m", "torque of that design with worn linings"),
    ComparisonRow("lining_pressure", "MPa", "p of that design, worn linings"),
    ComparisonRow("spring_stiffness", "N/m", "return spring c, consistent"),
    ComparisonRow("total_mass", "kg", "weights, links, spring flange, linings"),
)


def _rows(design, outputs, p):
    return {
        **{name: outputs[name] for name in ("characteristic_number", "weight_mass", "lever_length", "mean_diameter",
                                            "lining_width", "torque", "worn_torque", "lining_pressure",
                                            "spring_stiffness", "total_mass")},
        "weight_count": design.get("weight_count", p.weight_count),
        "engagement_angle": design.get("engagement_angle", p.engagement_angle),
        "limit_angle": design.get("limit_angle", p.limit_angle),
        "link_diameter": design["link_diameter"],
    }


def _paper_design_rows(p, weight_mass, link_diameter):
    """Rows of a design at the paper's geometry, evaluated with the consistent model."""
    design = {"weight_mass": weight_mass, "link_diameter": link_diameter}
    outputs = {name: out.value for name, out in PAPER.outputs(SimpleNamespace(**design), p).items()}
    return _rows(design, outputs, p)


def _references(p):
    lever, _ = paper_geometry(p)
    printed = paper_characteristic_number(duty_torque(p), p.friction_coefficient, p.speed, p.engagement_angle, lever,
                                          paper_k(p.shaft_diameter, p.flange_diameter, p.spring_free_length))
    mass = closed_form_characteristic_number(p) / p.weight_count
    return {
        "paper_formula": _paper_design_rows(p, printed / p.weight_count, math.nan),
        "closed_form": _paper_design_rows(p, mass, closed_form_link_diameter(p, mass)),
    }


COMPARISON = Comparison(
    rows=ROWS,
    references=_references,
    solves=(("nlp_paper", "paper", "mass"), ("nlp_design", "design", "mass")),
    rows_from_design=lambda mode, design, outputs, p: _rows(design, outputs, p),
    baseline="closed_form",
    column_notes={
        "paper_formula": "m z by the printed formula (32 ...) at the paper's geometry; the paper sizes no link",
        "closed_form": "consistent closed form of the paper-mode model (two friction surfaces)",
        "nlp_paper": "IPOPT, paper mode, minimum mass",
        "nlp_design": "IPOPT, design mode (geometry free), minimum mass",
    },
)
