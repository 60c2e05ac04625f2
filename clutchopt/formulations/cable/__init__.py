"""Inertial-centrifugal cable coupling (Strilets, Fedoruk, Strilets & Kovalchuk, 2013; seed
cable_coupling_strilets_2013.txt).

The driving cup-shaped half-coupling 1 sits on the driving shaft on a non-self-locking thread 5 (lead angle
beta) against a return spring 6. z radial cables 10 are clamped in the driven half-coupling 8 and in z moving
weights 14; each cable passes through a radial hole of a finger 2 of the cup (finger circle D). At start-up the
cup's inertia force screws it along thread 5: the fingers deflect the cables transversely and compress the
spring. At speed the weights, each on its own non-self-locking thread 16 (lead angle beta_w, radial axis),
move outwards and turn: they stretch the cables (x_2) and twist them (phi_1).

Equation numbers are the paper's. Where the printed equation is inconsistent the consistent form is used here
and the printed one is kept as ``paper_eq*`` for comparison; see docs/errata.md (C1-C9) and docs/cable.md.

Two posed problems:
- ``paper``: the case's threads (beta, beta_w) are given, as in the paper's sizing; free: half-coupling mass m,
  weight mass m_w, cable count z (integer), finger and clamp-screw diameters. ``options.free`` may free either
  lead angle. The optimum is the consistent closed form (``closed_form``).
- ``threads``: both lead angles free as well. The hub thread goes to its non-self-locking limit; the weight
  thread to the best screw efficiency 45 deg + phi'/2 unless its wear or its smallest diameter stops it first.

The package, one concern a module: ``quantities`` (what a case gives), ``equations`` (the consistent model, by
the paper's equation numbers), ``paper`` (the printed forms and the paper's formulas at a case), ``forces`` (the
forces, thread loads and stresses of a design: the constraints, objectives and outputs both modes share),
``speed_law`` (the cables as a tension-stiffened link in a start-up), ``modes`` (the two posed problems),
``closed_forms`` (the optima by hand), ``comparison`` (what ``clutchopt compare`` shows).
"""

from __future__ import annotations

from clutchopt.formulations.cable.comparison import COMPARISON
from clutchopt.formulations.cable.modes import PAPER, THREADS
from clutchopt.formulations.cable.quantities import MATERIALS, QUANTITIES, check_drives, check_hub_load, check_threads
from clutchopt.model import Coupling


COUPLING = Coupling(
    name="cable",
    title="Inertial-centrifugal cable coupling",
    source="Strilets, Fedoruk, Strilets & Kovalchuk (2013), cable_coupling_strilets_2013.txt",
    quantities=QUANTITIES,
    formulations={"paper": PAPER, "threads": THREADS},
    default_mode="paper",
    comparison=COMPARISON,
    case_checks=(check_drives, check_threads, check_hub_load),
    materials=MATERIALS,
)
