"""The cable coupling in a start-up: its cables as a tension-stiffened link whose torque and stress follow the
driving speed and the twist of the halves (docs/cable.md, "Start-up")."""

from __future__ import annotations

import math

import numpy as np

from clutchopt.backend import fmax, sqrt, tan
from clutchopt.formulations.cable.equations import (
    cable_diameter,
    cable_wire_area,
    inertia_force,
    length_ratio,
    reduced_friction_angle,
    weight_mass,
    weight_thread_diameter,
)
from clutchopt.model import ElasticLaw


def cable_pretension(transverse_stiffness, span):
    """N_0 = c_k l / 4: a cable of span l under tension N_0 has the transverse stiffness 4 N_0 / l at mid-span
    (the case's c_k, eq. 3, is read as that pretension's)."""
    return transverse_stiffness * span / 4.0


def weight_stiffness(p, weight_lead_angle, friction_angle):
    """k_w = c_kn + 4 c_kk / (d_2w^2 tan beta_w tan(beta_w - phi')): the radial force per metre of travel that a
    weight meets, its cable's stretch plus the cable's twist through thread 16 (x_2 = phi_1 (d_2w / 2) tan beta_w,
    the moment c_kk phi_1 back-driving the thread: eq. (9) made consistent, errata C3)."""
    d_2w = weight_thread_diameter(p.elongation, p.cable_twist, weight_lead_angle)
    return p.longitudinal_stiffness + 4.0 * p.torsional_stiffness / (
        d_2w**2 * tan(weight_lead_angle) * tan(weight_lead_angle - friction_angle))


def weight_travel(weight, radius, speed, gravity, stiffness):
    """x_2 = m_rv (R_rv w^2 - g)^+ / k_w: how far the weights have moved out at the driving speed w (eq. 8-9);
    none while their centrifugal force is below their own weight."""
    return fmax(inertia_force(weight, radius, speed, gravity), 0.0) / stiffness


def twist_stretch(longitudinal_stiffness, span, ratio, twist):
    """c_kn l (sqrt(1 + theta^2 / (4 psi^2)) - 1): a twist theta of the halves lengthens each cable from l to
    (D / 2) sqrt(4 psi^2 + theta^2), the geometry of eq. (18)."""
    return longitudinal_stiffness * span * (sqrt(1.0 + twist**2 / (4.0 * ratio**2)) - 1.0)


def link_tension(x, p, speed, twist):
    """N = N_0 + c_kn x_2(w) + c_kn (lengthening by the twist): the tension of one cable in a start-up."""
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    travel = weight_travel(x.weight_mass, p.weight_radius, speed, p.gravity,
                           weight_stiffness(p, x.weight_lead_angle, phi))
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    return (cable_pretension(p.transverse_stiffness, p.span) + p.longitudinal_stiffness * travel
            + twist_stretch(p.longitudinal_stiffness, p.span, ratio, twist))


def link_torque(x, p, speed, twist):
    """T = z N l theta / (4 psi^2 + theta^2): eq. (18) read the other way, the torque z cables of tension N
    carry at the twist theta."""
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    return x.cable_count * link_tension(x, p, speed, twist) * p.span * twist / (4.0 * ratio**2 + twist**2)


def wire_area(p):
    """A_s, the wire area of one cable (eq. 18)."""
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    return cable_wire_area(p.area_ratio, cable_diameter(p.finger_circle_diameter, ratio, p.cable_coefficient,
                                                        p.twist_angle))


def link_stress(x, p, speed, twist):
    """sigma = N / A_s, the cable stress of eq. (18) with the tension of the start."""
    return link_tension(x, p, speed, twist) / wire_area(p)


BISECTIONS = 60  # halvings of [0, 2 psi] for the twist of the least tension (to 2 psi 2^-60: the float's own)


def least_pull(x, p, speed):
    """A lower bound on the tension c_kn x_2 the weights add at the driving speed w (an array), for a weight thread
    of the lead angle x.weight_lead_angle; 0 where that angle is free (NaN) or the thread self-locks. The static row
    weight_turns_cable, (m_rv (R_rv w_d^2 - g) - c_kn x_2) (d_2w / 2) tan(beta_w - phi') >= c_kk phi_1 at the duty
    speed w_d, holds the weight mass at least eq. (9)'s m_rv (``weight_mass``: that row solved for m_rv), and the
    travel m_rv (R_rv w^2 - g)^+ / k_w grows with it (met to the NLP's 1e-8, the row moves the bound by as little)."""
    speed = np.asarray(speed, dtype=float)
    beta = float(x.weight_lead_angle)
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    duty = p.weight_radius * p.speed**2 - p.gravity
    if not (math.isfinite(beta) and phi < beta < math.pi / 2 and duty > 0.0):
        return np.zeros_like(speed)
    travel = weight_travel(weight_mass(p, beta, phi), p.weight_radius, speed, p.gravity,
                           weight_stiffness(p, beta, phi))
    return p.longitudinal_stiffness * travel


def least_link_stress(x, p, speed, torque):
    """A lower bound on the stress with which x.cable_count cables carry ``torque`` (an array, N*m) at the driving
    speed ``speed`` (an array), whatever the other design variables: the weights' pull is at least
    :func:`least_pull` (0 where their thread's lead angle is free: their travel is >= 0 in every design the NLP
    admits, its row weight_thread_not_self_locking keeping beta_w above phi', where the weight thread's stiffness
    k_w is positive: eq. 8-9's travel x_2 >= 0), and more pull shortens the twist that carries the torque and so
    needs more tension, N = T (4 psi^2 + theta^2) / (z l theta) (eq. 18 solved for N), falling as theta grows; the
    cables' own tension N_0 + that least pull + stretch(theta) grows with it. So the least N is where the two meet,
    or, where that tension at the largest twist 2 psi cannot carry T, 4 psi T / (z l) there (more pull making up the
    rest); the twist is bisected, the bound taken at its upper end."""
    torque = np.maximum(np.asarray(torque, dtype=float), 0.0)
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    pulled = cable_pretension(p.transverse_stiffness, p.span) + least_pull(x, p, speed)

    def needed(twist):
        return torque * (4.0 * ratio**2 + twist**2) / (x.cable_count * p.span * twist)

    def own(twist):
        return pulled + twist_stretch(p.longitudinal_stiffness, p.span, ratio, twist)

    low, high = np.zeros_like(torque), np.full_like(torque, 2.0 * ratio)
    for _ in range(BISECTIONS):
        middle = 0.5 * (low + high)
        short = own(middle) < needed(middle)
        low, high = np.where(short, middle, low), np.where(short, high, middle)
    return needed(high) / wire_area(p)


def link_stiffness(x, p, speed):
    """dT/dtheta at theta = 0: z N l / (4 psi^2), N without stretch."""
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    return x.cable_count * link_tension(x, p, speed, 0.0) * p.span / (4.0 * ratio**2)


def largest_twist(x, p):
    """2 psi: up to this twist the leaning cables' torque z N l theta / (4 psi^2 + theta^2) grows (N held);
    beyond it they are past square to the halves, a start that no longer holds together."""
    return 2.0 * length_ratio(p.span, p.finger_circle_diameter)


ELASTIC_LAW = ElasticLaw(link_torque, link_stress, link_stiffness, lambda x, p: p.damping_ratio, largest_twist,
                         "allowable_cable_stress", least_link_stress)
