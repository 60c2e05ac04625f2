"""Centrifugal ball clutch of high power (Tasev; seed ball_clutch_tasev.txt).

Balls of radius r_c fill the six chambers of a six-shovel rotor (shovel thickness a_n = K1 R_a). At speed they
form a layer, packing density Psi_n, from R_1 = K2 R_a out to the drum's active radius R_a over the active width
l_a; their centrifugal force presses them, with friction f, on the drum's cylinder (grooves of radius
r_groove = beta r_c, pitch sqrt(3) r_c) and on its two end faces.

Equation numbers are the paper's. Where the printed equation is inconsistent the consistent form is used here
and the printed one is kept as ``paper_eq*`` for comparison; see docs/errata.md (B1-B8) and docs/ball.md.

Two posed problems:
- ``paper``: the paper's simplifying assumptions: leading-order torque (no shovels, no end faces), K2 from (1),
  width continuous, l_a / R_a at least the case's K5; free: R_a, l_a. Its optimum is the fifth root (4).
- ``design``: the consistent torque (8), Hertz contact stress (9) with exact n_a, n_b, ball rows n_p integer with
  l_a from (7); free: R_a, K2, r_c, beta, n_p within the paper's ranges, the housing and the stress limit.

The package, one concern a module: ``quantities`` (what a case gives), ``equations`` (the consistent model, by
the paper's equation numbers), ``contact`` (the Hertz contact of ball on drum, eq. (9)), ``paper`` (the printed
forms), ``clutch`` (the clutch at a design: the objectives and outputs both modes share), ``modes`` (the two
posed problems), ``procedure`` (the paper's sizing procedure with its K2 loop), ``comparison`` (what
``clutchopt compare`` shows).
"""

from __future__ import annotations

from clutchopt.formulations.ball.comparison import COMPARISON
from clutchopt.formulations.ball.modes import DESIGN, PAPER
from clutchopt.formulations.ball.quantities import MATERIALS, QUANTITIES, check_shovels, check_width_ratios
from clutchopt.formulations.common import check_shell_room
from clutchopt.model import Coupling

COUPLING = Coupling(
    name="ball",
    title="Centrifugal ball clutch",
    source="Tasev, ball_clutch_tasev.txt",
    quantities=QUANTITIES,
    formulations={"design": DESIGN, "paper": PAPER},
    default_mode="design",
    comparison=COMPARISON,
    case_checks=(check_width_ratios, check_shell_room, check_shovels),
    materials=MATERIALS,
)
