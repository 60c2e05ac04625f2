"""What ``clutchopt compare`` shows for the wedge coupling: the paper as printed, the paper's formulas, the
consistent closed form and the NLP optima, each design evaluated with the consistent model."""

from __future__ import annotations

import math
from types import SimpleNamespace

from clutchopt.formulations.wedge.closed_forms import closed_form_finger_diameter, closed_form_weight_mass
from clutchopt.formulations.wedge.modes import PAPER
from clutchopt.formulations.wedge.paper import paper_eq27_first_form, paper_eq27_second_form, paper_eq28
from clutchopt.model import Comparison, ComparisonRow

ROWS = (
    ComparisonRow("weight_mass", "kg", "m_r, mass of one weight"),
    ComparisonRow("finger_diameter", "mm", "d_n"),
    ComparisonRow("flank_pressure", "MPa", "q of that design, consistent (13)"),
    ComparisonRow("torque", "N*m", "friction torque of that design, consistent (15)"),
    ComparisonRow("weight_count", "", "z"),
    ComparisonRow("total_mass", "kg", "z (m_r + finger)"),
)


def _paper_design_rows(p, weight_mass, finger_diameter):
    """Rows for a design at the paper's geometry, evaluated with the consistent model."""
    outputs = PAPER.outputs(SimpleNamespace(weight_mass=weight_mass, finger_diameter=finger_diameter), p)
    return {"weight_mass": weight_mass, "finger_diameter": finger_diameter,
            "flank_pressure": outputs["flank_pressure"].value, "torque": outputs["torque"].value,
            "weight_count": p.weight_count, "total_mass": outputs["total_mass"].value}


def _references(p):
    columns = {}
    if not math.isnan(p.printed_weight_mass):
        printed_dn = p.printed_finger_diameter
        columns["paper_printed"] = _paper_design_rows(p, p.printed_weight_mass, printed_dn)
    for column, form in (("paper_eq27_first_form", paper_eq27_first_form),
                         ("paper_eq27_second_form", paper_eq27_second_form)):
        mass = form(p)
        columns[column] = _paper_design_rows(p, mass, paper_eq28(p, mass))
    mass = closed_form_weight_mass(p)
    columns["closed_form"] = _paper_design_rows(p, mass, closed_form_finger_diameter(p, mass))
    return columns


def _rows_from_design(mode, design, outputs, p):
    return {"weight_mass": outputs["weight_mass"],
            "finger_diameter": design["finger_diameter"],
            "flank_pressure": outputs["flank_pressure"], "torque": outputs["torque"],
            "weight_count": design.get("weight_count", p.weight_count), "total_mass": outputs["total_mass"]}


COMPARISON = Comparison(
    rows=ROWS,
    references=_references,
    solves=(("nlp_paper", "paper", "mass"), ("nlp_geometry", "geometry", "mass")),
    rows_from_design=_rows_from_design,
    baseline="closed_form",
    column_notes={
        "paper_printed": "the paper's example as printed (m_r = 0.235 kg, d_n = 3.1 mm)",
        "paper_eq27_first_form": "eq. (27) first form, d_n by eq. (28) read as mm",
        "paper_eq27_second_form": "eq. (27) second form (T_c t_p for I_n w/t_p), d_n by eq. (28)",
        "closed_form": "consistent closed form of the paper-mode model",
        "nlp_paper": "IPOPT, paper mode, minimum mass",
        "nlp_geometry": "IPOPT, geometry mode, minimum mass (weights as real bodies)",
    },
)
