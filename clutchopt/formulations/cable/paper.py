"""The cable paper's printed forms of (5), (7), (9), (19)-(22), kept for comparison (docs/errata.md), and its
formulas applied to a case."""

from __future__ import annotations

import math

from clutchopt.backend import cbrt, sin, sqrt, tan
from clutchopt.formulations.cable.equations import hub_thread_load, reduced_friction_angle, required_cable_count


def paper_eq5(inertia, lead_angle, friction_angle):
    """F_a = F_i tan(beta + phi'), eq. (5) as printed."""
    return inertia * tan(lead_angle + friction_angle)


def paper_eq7(p, cable_count):
    """m = (z c_k x + c_pr x_1) / ((R_m w^2 - g) tan(beta + phi')), eq. (7) as printed."""
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    return hub_thread_load(p, cable_count) / ((p.mass_radius * p.speed**2 - p.gravity) * tan(p.lead_angle + phi))


def paper_eq9(p):
    """m_rv = (c_kn x_2 + c_kk phi_1) / (R_rv w^2 tan(beta + phi')), eq. (9) as printed, with beta = beta_w.

    Adds a force (N) and a moment (N m): the number is the SI reading of the printed line (errata C3)."""
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    return ((p.longitudinal_stiffness * p.elongation + p.torsional_stiffness * p.cable_twist)
            / (p.weight_radius * p.speed**2 * tan(p.weight_lead_angle + phi)))


def paper_eq19(p, cable_count):
    """d_1 = sqrt(3.31 T l / (f z D^2 tan(phi) [sigma_cm])), eq. (19) as printed."""
    return sqrt(3.31 * p.torque * p.span / (p.clamp_friction * cable_count * p.finger_circle_diameter**2
                                            * tan(p.twist_angle) * p.allowable_screw_stress))


def paper_eq20(p, cable_count, core_diameter):
    """sigma_E = 3.31 T l / (d_1^2 f z D^2 sin(phi)), eq. (20) as printed."""
    return 3.31 * p.torque * p.span / (core_diameter**2 * p.clamp_friction * cable_count
                                       * p.finger_circle_diameter**2 * sin(p.twist_angle))


def paper_eq21(p, finger_count):
    """d_n = cbrt(10 T l_n / (D z_n [sigma_F])), eq. (21) as printed."""
    return cbrt(10.0 * p.torque * p.finger_length / (p.finger_circle_diameter * finger_count
                                                     * p.allowable_finger_stress))


def paper_eq22(p, finger_count, diameter):
    """sigma_F = 10 T l_n / (d_n^3 z_n D^2), eq. (22) as printed: a stress per metre (errata C7)."""
    return 10.0 * p.torque * p.finger_length / (diameter**3 * finger_count * p.finger_circle_diameter**2)


def paper_design(p):
    """The paper's formulas at the case's threads: z by (18) rounded up, m by (7), m_rv by (9), d_1 by (19),
    d_n by (21), as printed."""
    z = float(max(math.ceil(required_cable_count(p) - 1e-9), 1))  # at least one cable, however strong
    return {"half_coupling_mass": paper_eq7(p, z), "weight_mass": paper_eq9(p), "cable_count": z,
            "finger_diameter": paper_eq21(p, z), "screw_diameter": paper_eq19(p, z), "lead_angle": p.lead_angle,
            "weight_lead_angle": p.weight_lead_angle}
