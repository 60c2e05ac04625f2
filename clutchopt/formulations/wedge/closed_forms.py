"""The optimum of paper mode by hand: (27) and (28) from the consistent (15)-(16) and (19)."""

from __future__ import annotations

import math
from types import SimpleNamespace

from clutchopt.backend import cbrt
from clutchopt.formulations.common import duty_torque
from clutchopt.formulations.wedge.equations import mean_flank_radius
from clutchopt.formulations.wedge.modes import paper_weight_set


def closed_form_weight_mass(p):
    """m_r = 2 T_max sin(alpha) / (f z (r1 + r2) w^2 r_c): eq. (27) from the consistent (15)-(16)."""
    per_kg = paper_weight_set(SimpleNamespace(weight_mass=1.0, finger_diameter=math.nan), p)
    return duty_torque(p) / per_kg.torque


def closed_form_finger_diameter(p, weight_mass):
    """d_n = cbrt(32 F_fr h_n / (pi [sigma])): eq. (28) from the consistent (19)."""
    w = paper_weight_set(SimpleNamespace(weight_mass=weight_mass, finger_diameter=math.nan), p)
    return cbrt(32.0 * w.friction * mean_flank_radius(w.r1, w.r2) / (math.pi * p.allowable_bending_stress))
