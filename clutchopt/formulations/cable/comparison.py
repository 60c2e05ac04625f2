"""What ``clutchopt compare`` shows for the cable coupling: the paper's formulas, the consistent closed forms and
the NLP optima, each design evaluated with the consistent model."""

from __future__ import annotations

from types import SimpleNamespace

from clutchopt.formulations.cable.closed_forms import closed_form, closed_form_threads
from clutchopt.formulations.cable.modes import PAPER
from clutchopt.formulations.cable.paper import paper_design
from clutchopt.model import Comparison, ComparisonRow


ROWS = (
    ComparisonRow("lead_angle", "deg", "beta, hub thread 5"),
    ComparisonRow("weight_lead_angle", "deg", "beta_w, weight thread 16"),
    ComparisonRow("cable_count", "", "z, eq. (18) rounded up"),
    ComparisonRow("cable_diameter", "mm", "d_k, eq. (17)"),
    ComparisonRow("half_coupling_mass", "kg", "m, eq. (7)"),
    ComparisonRow("hub_axial_force", "N", "F_a that half-coupling produces, consistent (5)"),
    ComparisonRow("hub_thread_load", "N", "F_a needed, eq. (2)"),
    ComparisonRow("weight_mass", "kg", "m_rv, eq. (9)"),
    ComparisonRow("weight_thread_diameter", "mm", "d_2w = 2 x_2 / (phi_1 tan beta_w)"),
    ComparisonRow("finger_diameter", "mm", "d_n, eqs. (21)-(22)"),
    ComparisonRow("screw_diameter", "mm", "d_1, eqs. (19)-(20)"),
    ComparisonRow("total_mass", "kg", "m + z m_rv + fingers + clamp screws"),
)


_OUTPUT_ROWS = ("cable_diameter", "hub_axial_force", "hub_thread_load", "weight_thread_diameter", "total_mass")


def _rows_from_design(mode, design, outputs, p):
    return {**design, **{name: outputs[name] for name in _OUTPUT_ROWS}}


def _design_rows(p, design):
    """Rows for a design, evaluated with the consistent model."""
    outputs = PAPER.outputs(SimpleNamespace(**design), p)
    return _rows_from_design("paper", design, {name: out.value for name, out in outputs.items()}, p)


def _references(p):
    columns = {"paper_formulas": _design_rows(p, paper_design(p)), "closed_form": _design_rows(p, closed_form(p))}
    threads = closed_form_threads(p)
    if threads is not None:
        columns["closed_form_threads"] = _design_rows(p, threads)
    return columns


COMPARISON = Comparison(
    rows=ROWS,
    references=_references,
    solves=(("nlp_paper", "paper", "mass"), ("nlp_threads", "threads", "mass")),
    rows_from_design=_rows_from_design,
    baseline="closed_form",
    column_notes={
        "paper_formulas": "the paper's printed (7), (9), (18), (19), (21) at the case's threads (no worked example)",
        "closed_form": "consistent closed form at the case's threads (paper mode)",
        "closed_form_threads": "consistent closed form with both lead angles optimal (default bounds)",
        "nlp_paper": "IPOPT, paper mode, minimum mass",
        "nlp_threads": "IPOPT, threads mode, minimum mass",
    },
)
