"""The optima by hand: every sizing constraint active at given lead angles, and the best lead angles."""

from __future__ import annotations

import math

from clutchopt.formulations.cable.equations import (
    cable_tension,
    clamp_screw_force,
    finger_force,
    half_coupling_mass,
    hub_thread_load,
    length_ratio,
    reduced_friction_angle,
    required_cable_count,
    weight_mass,
)
from clutchopt.formulations.cable.modes import LEAD_ANGLE_BOUNDS


def hub_lead_angle_optimum(p, bounds=LEAD_ANGLE_BOUNDS["lead_angle"]):
    """m grows with tan(beta + phi'): the lightest hub thread is the flattest one that does not self-lock."""
    return max(bounds[0], reduced_friction_angle(p.friction_coefficient, p.flank_angle) + p.self_locking_margin)


def _weight_wear_interval(p, friction_angle):
    """(lowest, highest) beta_w at which the weight thread's pressure at the optimum is within [q]; None if none.

    With the weight's drive active the thread carries 2 c_kk phi_1 / (d_2w tan(beta_w - phi')) on
    d_2w = 2 x_2 / (phi_1 tan beta_w), so with s = tan(beta_w - phi'), u = tan phi' and
    K = c_kk phi_1^3 / (2 pi x_2^2 (h/p) H_w), eq. (16) reads q = K (u + s)^2 / (s (1 - u s)^2) on 0 < s < 1/u.
    q <= [q] where P(s) = [q] s (1 - u s)^2 - K (u + s)^2 >= 0: a cubic, negative at both ends for u > 0, whose
    local maximum is the smaller root of a quadratic; a root on each side of it bounds the interval.
    """
    k = p.torsional_stiffness * p.cable_twist**3 / (2 * math.pi * p.elongation**2 * p.height_ratio * p.weight_nut_height)
    u, q = math.tan(friction_angle), p.allowable_thread_pressure

    def excess(s):
        return q * s * (1 - u * s) ** 2 - k * (u + s) ** 2

    from scipy.optimize import brentq  # (imported where the threads' closed form is asked for: 0.3-0.4 s a process,
    #                                    which a paper-mode solve no longer pays)
    a, b, c = 3 * q * u**2, -2 * (2 * q * u + k), q - 2 * k * u  # P'(s) = a s^2 + b s + c
    if c <= 0:
        return None
    s_max = 2 * c / (-b + math.sqrt(b * b - 4 * a * c))  # the smaller root, stable as a -> 0
    if excess(s_max) < 0:
        return None
    s_low = brentq(excess, 0.0, s_max, xtol=1e-300, rtol=1e-15) if u > 0 else 0.0
    s_high = brentq(excess, s_max, 1 / u, xtol=1e-300, rtol=1e-15) if u > 0 else q / k
    return friction_angle + math.atan(s_low), friction_angle + math.atan(s_high)


def weight_lead_angle_optimum(p, bounds=LEAD_ANGLE_BOUNDS["weight_lead_angle"]):
    """beta_w minimising tan(beta_w) / tan(beta_w - phi') (the weight's mass), i.e. 45 deg + phi'/2, kept within the
    non-self-locking limit, the wear interval, the smallest thread diameter and the bounds; None if they exclude
    each other."""
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    wear = _weight_wear_interval(p, phi)
    if wear is None:
        return None
    lead = 2 * math.pi * p.elongation / p.cable_twist
    lower = max(bounds[0], phi + p.self_locking_margin, wear[0])
    upper = min(bounds[1], math.atan(lead / (math.pi * p.min_weight_thread_diameter)), wear[1])
    if lower > upper:
        return None
    return min(max(math.pi / 4 + phi / 2, lower), upper)


def closed_form(p, lead_angle=None, weight_lead_angle=None, count_bounds=(2, 48)):
    """The consistent optimum with the given lead angles (default: the case's): every sizing constraint active.

    z = (18) rounded up; m = (7) and m_rv = (9) consistent; d_1 from (20), d_n from (22) with that z."""
    beta = p.lead_angle if lead_angle is None else lead_angle
    beta_w = p.weight_lead_angle if weight_lead_angle is None else weight_lead_angle
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    z = float(min(max(math.ceil(required_cable_count(p) - 1e-9), count_bounds[0]), count_bounds[1]))
    m = half_coupling_mass(hub_thread_load(p, z), beta, phi, p.mass_radius, p.speed, p.gravity)
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    tension = cable_tension(p.torque, ratio, p.twist_angle, p.span, z)
    d_1 = math.sqrt(1.3 * clamp_screw_force(tension, p.clamp_friction) / (math.pi / 4 * p.allowable_screw_stress))
    d_n = (32 * finger_force(p.torque, z, p.finger_circle_diameter) * p.finger_length / 2
           / (math.pi * p.allowable_finger_stress)) ** (1 / 3)
    return {"half_coupling_mass": m, "weight_mass": weight_mass(p, beta_w, phi), "cable_count": z,
            "finger_diameter": d_n, "screw_diameter": d_1, "lead_angle": beta, "weight_lead_angle": beta_w}


def closed_form_threads(p):
    """The consistent optimum of ``threads`` mode (default bounds): both lead angles at their optimum."""
    beta_w = weight_lead_angle_optimum(p)
    if beta_w is None:
        return None
    return closed_form(p, hub_lead_angle_optimum(p), beta_w)
