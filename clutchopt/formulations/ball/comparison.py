"""What ``clutchopt compare`` shows for the ball clutch: the paper's procedure beside the NLP optima of least mass
and least cost, each design evaluated with the consistent model."""

from __future__ import annotations

from clutchopt.formulations.ball.procedure import paper_procedure
from clutchopt.model import Comparison, ComparisonRow


ROWS = (
    ComparisonRow("active_radius", "mm", "R_a"),
    ComparisonRow("active_width", "mm", "l_a, eq. (7)"),
    ComparisonRow("width_ratio", "", "K5 = l_a / R_a"),
    ComparisonRow("ball_rows", "", "n_p"),
    ComparisonRow("filling", "", "K2 = R_1 / R_a"),
    ComparisonRow("ball_radius", "mm", "r_c"),
    ComparisonRow("groove_conformity", "", "beta"),
    ComparisonRow("torque", "N*m", "torque of the design, eq. (8) consistent"),
    ComparisonRow("contact_stress", "MPa", "p_0, Hertz (9) consistent"),
    ComparisonRow("contact_stress_eq10", "MPa", "p_0, eq. (10) as printed"),
    ComparisonRow("ball_mass", "kg", "balls, eq. (2) consistent"),
    ComparisonRow("body_mass", "kg", "body, eq. (13)"),
    ComparisonRow("total_mass", "kg", "balls + body"),
    ComparisonRow("cost", "EUR", "balls and body priced per kg"),
)
_OUTPUT_ROWS = ("active_width", "width_ratio", "torque", "contact_stress", "contact_stress_eq10", "ball_mass",
                "body_mass", "total_mass", "cost")


def _references(p):
    procedure = paper_procedure(p)
    return {"paper_procedure": {row.name: procedure[row.name] for row in ROWS}}


def _rows_from_design(mode, design, outputs, p):
    return {**design, **{name: outputs[name] for name in _OUTPUT_ROWS}}


COMPARISON = Comparison(
    rows=ROWS,
    references=_references,
    solves=(("nlp_mass", "design", "mass"), ("nlp_cost", "design", "cost")),
    rows_from_design=_rows_from_design,
    baseline="paper_procedure",
    column_notes={
        "paper_procedure": "the paper's procedure: K2 (1), fifth root (4), rows (6)-(7), K2 loop on (8) to 10 %; "
                           "evaluated with the consistent model",
        "nlp_mass": "IPOPT, design mode, minimum mass (balls + body)",
        "nlp_cost": "IPOPT, design mode, minimum cost (balls and body per kg)",
    },
)
