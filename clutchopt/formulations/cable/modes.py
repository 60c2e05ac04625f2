"""The cable coupling's two posed problems: the case's threads given, or both lead angles designed too."""

from __future__ import annotations

import math

from clutchopt.formulations.cable.forces import MODEL, CableCoupling
from clutchopt.model import Variable, si


V = Variable
MASS_AND_SIZE_VARIABLES = (
    V("half_coupling_mass", "kg", "mass of the driving half-coupling", "m", lower=1e-6, upper=1e4, above=0),
    V("weight_mass", "kg", "mass of one moving weight", "m_rv", lower=1e-6, upper=1e3, above=0),
    V("cable_count", "", "number of cables (and of fingers and weights)", "z", lower=2, upper=48, at_least=1,
      integer=True),
    V("finger_diameter", "mm", "finger diameter", "d_n", lower=si(0.2, "mm"), upper=si(200, "mm"), above=0),
    V("screw_diameter", "mm", "core diameter of the clamp screws", "d_1", lower=si(0.2, "mm"), upper=si(100, "mm"),
      above=0),
)
LEAD_ANGLE_BOUNDS = {"lead_angle": (si(1, "deg"), si(45, "deg")), "weight_lead_angle": (si(1, "deg"), si(60, "deg"))}


def _lead_angles(fixed_unless_freed: bool):
    return tuple(
        V(name, "deg", description, symbol, lower=LEAD_ANGLE_BOUNDS[name][0], upper=LEAD_ANGLE_BOUNDS[name][1],
          above=0, below=math.pi / 2, fixed_unless_freed=fixed_unless_freed)
        for name, description, symbol in (("lead_angle", "lead angle of the hub thread 5", "beta"),
                                          ("weight_lead_angle", "lead angle of the weight thread 16", "beta_w"))
    )


def _formulation(mode, title, fixed_unless_freed):
    return MODEL.formulation(mode, title, MASS_AND_SIZE_VARIABLES + _lead_angles(fixed_unless_freed), CableCoupling)


PAPER = _formulation("paper", "Cable coupling, the paper's sizing: threads given, masses, z, d_n, d_1 free", True)
THREADS = _formulation("threads", "Cable coupling, threads designed: both lead angles free as well", False)
