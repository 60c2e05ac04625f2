"""Lever centrifugal friction coupling (Ambartsumyants & Deli; seed lever_cfc_ambartsumyants_deli.txt).

Construction (the paper's figure a): each of z toggles is two links 1, 2 of length l_2, pinned to each other
through a weight 4 (the knee) and, at their other ends, to two pressure discs 3 that slide axially on the
driving shaft. A tension spring of free length l_pr ties each weight to a flange of diameter d_phi on the shaft.
At speed the centrifugal force pulls the knee outwards, the toggle straightens and pushes the two discs apart
against the two inner faces of the driven housing 5, which encloses them: two friction surfaces, linings of
thickness delta.

Geometry (figure b; the paper has no equation numbers, so relations are named by their symbol): gamma is the
angle of a link to the shaft axis. With new linings the discs touch at gamma_0, the weight sitting at
R_0 = d_b/2 + (d_phi - d_b)/4 + l_pr (spring at its free length) and the disc pins at d_cp/2 = R_0 + S_ov,
S_ov = l_2 sin gamma_0. As the linings wear by delta the discs move out by delta and the angle falls towards
gamma_pr: l_2 (cos gamma_pr - cos gamma_0) >= delta.

Statics of the knee (derived here, docs/lever.md): F = m w^2 r_w outwards, each link in compression
S = F / (2 sin gamma), each link pushes its disc axially with F / (2 tan gamma). z toggles press each disc with
N = z F / (2 tan gamma); i = 2 lined faces at mean radius d_cp/2 carry T = i f N d_cp / 2. Hence the
characteristic number m z = 4 T_max tan(gamma_0) / (i f w^2 R_0 d_cp); the printed 32/(k (4 l_2 sin gamma_0 + k))
form is this with i = 1 (errata L1).

Two states bound the life of the linings: new (gamma_0, weight at R_0, spring slack: least push, the torque
requirement) and worn (gamma_pr, weight at R_0 + l_2 (sin gamma_0 - sin gamma_pr), spring stretched: largest
push, the lining pressure and link strength checks).

Two posed problems:
- ``paper``: the paper's method: gamma_0, gamma_pr, z, d_phi given, l_2 at the paper's minimum, lining width
  B_cp = 2 (S_ov + a delta); free: weight mass m and link diameter d_l.
- ``design``: free l_2, gamma_0, gamma_pr, z (integer), d_phi, lining width b, m, d_l within the housing

The package, one concern a module: ``quantities`` (what a case gives), ``equations`` (the paper's geometric rules
and the statics derived here), ``paper`` (the paper's method and printed forms), ``toggles`` (the toggles at a
design: the constraints, objectives and outputs both modes share), ``modes`` (the two posed problems),
``closed_forms`` (the optimum of paper mode by hand), ``comparison`` (what ``clutchopt compare`` shows).
"""

from __future__ import annotations

from clutchopt.formulations.common import check_shell_room
from clutchopt.formulations.lever.comparison import COMPARISON
from clutchopt.formulations.lever.modes import DESIGN, PAPER
from clutchopt.formulations.lever.quantities import MATERIALS, QUANTITIES, check_case
from clutchopt.model import Coupling

COUPLING = Coupling(
    name="lever",
    title="Lever centrifugal friction coupling",
    source="Ambartsumyants & Deli, lever_cfc_ambartsumyants_deli.txt",
    quantities=QUANTITIES,
    formulations={"paper": PAPER, "design": DESIGN},
    default_mode="paper",
    comparison=COMPARISON,
    case_checks=(check_case, check_shell_room),
    materials=MATERIALS,
)
