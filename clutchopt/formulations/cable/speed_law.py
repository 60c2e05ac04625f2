"""The cable coupling in a start-up: its cables as a tension-stiffened link whose torque and stress follow the
driving speed and the twist of the halves (docs/cable.md, "Start-up")."""

from __future__ import annotations

import numpy as np

from clutchopt.backend import fmax, sqrt, tan
from clutchopt.formulations.cable.equations import (
    cable_diameter,
    cable_wire_area,
    inertia_force,
    length_ratio,
    reduced_friction_angle,
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


def least_pull(p, speed):
    """A lower bound on the tension c_kn x_2 the weights add at the driving speed w (an array) in any design meeting
    the static rows: c_kn e (R_rv w^2 - g)^+ / (R_rv w_d^2 - g), e the cable's elongation, w_d the duty speed. The row
    weight_turns_cable, (m_rv (R_rv w_d^2 - g) - c_kn e) (d_2w / 2) tan(beta_w - phi') >= c_kk phi_1, holds
    m_rv (R_rv w_d^2 - g) >= c_kn e + 2 c_kk phi_1 / (d_2w tan(beta_w - phi')) = e k_w (d_2w = 2 e / (phi_1 tan
    beta_w), eq. 9's k_w), so the travel m_rv (R_rv w^2 - g)^+ / k_w is at least e (R_rv w^2 - g)^+ / (R_rv w_d^2 - g)
    whatever the weight thread's lead angle beta_w in (phi', 90 deg) (weight_thread_not_self_locking) and mass: the
    weights reach the design travel e at the duty speed. Met to the NLP's 1e-8, the row moves it by as little."""
    duty = p.weight_radius * p.speed**2 - p.gravity
    if not duty > 0.0:
        return np.zeros_like(np.asarray(speed, dtype=float))
    return p.longitudinal_stiffness * weight_travel(p.elongation, p.weight_radius, speed, p.gravity, duty)


def least_link_stress(x, p, speed, torque):
    """A lower bound on the stress with which x.cable_count cables carry ``torque`` (an array, N*m) at the driving
    speed ``speed`` (an array), whatever the other design variables: the weights' pull is at least
    :func:`least_pull`, and more pull shortens the twist that carries the torque and so needs more tension,
    N = T (4 psi^2 + theta^2) / (z l theta) (eq. 18 solved for N), falling as theta grows; the cables' own tension
    N_0 + that least pull + stretch(theta) grows with it. So the least N is where the two meet, or, where that tension
    at the largest twist 2 psi cannot carry T, 4 psi T / (z l) there (more pull making up the rest); the twist is
    bisected, the bound taken at its upper end."""
    torque = np.maximum(np.asarray(torque, dtype=float), 0.0)
    ratio = length_ratio(p.span, p.finger_circle_diameter)
    pulled = cable_pretension(p.transverse_stiffness, p.span) + least_pull(p, speed)

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
