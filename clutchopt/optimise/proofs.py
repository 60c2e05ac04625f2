"""Infeasibility that can be shown, not only met: bounds no design can beat, from the case's values alone.

A solver that ends without a feasible design has shown nothing about the case (its restoration may have stalled
from a poor start). A verdict ``infeasible`` is given only with a proof (``clutchopt.optimise.problem`` otherwise
reports ``not_found``: no feasible design found from the starts it names). The proofs here hold for every design
of every coupling, because they bound what the drive can do:

- the motor cannot hold the machine at the lock-up speed asked for: above the breakdown speed w_s (1 - s_k) the
  Kloss torque falls with speed, so the largest torque at or above w_L,min is T(w_L,min) there (T_k below it); a
  locked drive turning at w >= w_L,min needs T_m(w) >= T_c;
- the motor cannot bring the masses to the lock-up speed in time: at lock-up motor and machine turn at
  w_L >= w_L,min, so the motor has put in at least (J + J_m) w_L,min^2 / 2 (slip heat and the load's work come on
  top); it delivers at most P_peak = max_w T(w) w, so t_start >= (J + J_m) w_L,min^2 / (2 P_peak).
"""

from __future__ import annotations

import math

import numpy as np

from clutchopt.start_up.equations import kloss_torque


def start_up_proofs(case) -> list[str]:
    """What the case's drive makes impossible whatever the coupling, each in words with its numbers (none: no
    proof). Applies to a [start_up] with an induction motor (effect motor_curve) and a lock-up speed limit."""
    if case.start_up is None or not case.start_up.has("motor_curve"):
        return []
    v = case.values
    if "min_lock_up_speed" not in v:
        return []
    w_s, t_k, s_k, w_l = v["synchronous_speed"], v["breakdown_torque"], v["breakdown_slip"], v["min_lock_up_speed"]
    profile = case.start_up.load_profile
    load = max(profile.values) if profile is not None else v["load_torque"]
    proofs = []
    if w_l >= w_s:
        proofs.append(f"min_lock_up_speed {w_l * 30 / math.pi:.6g} rpm is not below the motor's synchronous speed "
                      f"{w_s * 30 / math.pi:.6g} rpm, where an induction motor gives no torque")
        return proofs
    largest = t_k if w_l < w_s * (1.0 - s_k) else float(kloss_torque(w_l, w_s, t_k, s_k))
    if largest < load:
        proofs.append(f"the motor gives at most {largest:.6g} N*m at or above the lock-up speed "
                      f"{w_l * 30 / math.pi:.6g} rpm, less than the machine's load {load:.6g} N*m")
    speeds = np.linspace(0.0, w_s, 100_001)  # Kloss power T(w) w is smooth with one peak: the grid finds it
    peak = float(np.max(kloss_torque(speeds, w_s, t_k, s_k) * speeds))  # to 1e-9 relative
    inertia = v["driven_inertia"] + v["motor_inertia"]
    shortest = 0.5 * inertia * w_l**2 / peak
    if shortest > v["max_start_time"] * (1.0 + 1e-6):
        proofs.append(f"bringing {inertia:.6g} kg*m^2 to {w_l * 30 / math.pi:.6g} rpm takes at least "
                      f"{shortest:.4g} s at the motor's peak power {peak / 1e3:.6g} kW, more than max_start_time "
                      f"{v['max_start_time']:.6g} s")
    return proofs
