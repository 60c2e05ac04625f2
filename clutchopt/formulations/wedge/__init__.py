"""Wedge centrifugal friction coupling (Ambartsumyants & Deli, 2015; seed wedge_cfc_ambartsumyants_deli_2015.txt).

z weights, annular sectors of central angle gamma, slide radially on fingers of the driving shaft. Centrifugal
force pushes each weight's trapezoidal top (flanks inclined alpha to the radial direction, between radii r1 and
r2 = lambda r1) into a V-groove of the driven half-coupling; friction on the two flanks carries the torque.

Equation numbers are the paper's. Where the printed equation is inconsistent the consistent form is used here
and the printed one is kept as ``paper_eq*`` for comparison; see docs/errata.md (W1-W6).

Two posed problems (``modes``):
- ``paper``: the paper's geometry (r1, lambda, h_r, z, alpha, gamma) is given, r_c = r2 - 2/3 h_r (11);
  free: weight mass m_r and finger diameter d_n.
- ``geometry``: the weight is a real body (annular sector r_in..r2, axial width b, trapezoidal top) whose mass
  and exact centroid follow from its geometry; free: r1, lambda, h_r, gamma, b, d_n (alpha and z if freed).

The package, one concern a module: ``quantities`` (what a case gives), ``equations`` (the consistent model, by
the paper's equation numbers), ``paper`` (the printed forms), ``weight_set`` (the weights at a design: the
constraints, objectives and outputs both modes share), ``modes`` (the two posed problems), ``closed_forms`` (the
optimum of paper mode by hand), ``comparison`` (what ``clutchopt compare`` shows).
"""

from __future__ import annotations

from clutchopt.formulations.common import check_shell_room
from clutchopt.formulations.wedge.comparison import COMPARISON
from clutchopt.formulations.wedge.modes import GEOMETRY, PAPER
from clutchopt.formulations.wedge.quantities import MATERIALS, QUANTITIES, check_case
from clutchopt.model import Coupling

COUPLING = Coupling(
    name="wedge",
    title="Wedge centrifugal friction coupling",
    source="Ambartsumyants & Deli (2015), wedge_cfc_ambartsumyants_deli_2015.txt",
    quantities=QUANTITIES,
    formulations={"paper": PAPER, "geometry": GEOMETRY},
    default_mode="paper",
    comparison=COMPARISON,
    case_checks=(check_case, check_shell_room),
    materials=MATERIALS,
)
