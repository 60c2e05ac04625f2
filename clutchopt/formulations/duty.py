"""The duty every centrifugal coupling is sized for, shared by the formulations.

Ambartsumyants & Deli size both their wedge and their lever couplings for the same duty: a driven machine of
inertia I_n run up in t_p to the (constant) driving speed w_a against a resisting torque T_c.
"""

from __future__ import annotations

from clutchopt.model import Quantity

GRAVITY = 9.80665  # m/s^2, standard gravity

DUTY_QUANTITIES = (
    Quantity("inertia", "kg*m^2", "moment of inertia of the driven machine, reduced to the coupling", "I_n", "duty",
             above=0),
    Quantity("speed", "rpm", "driving speed (constant, wedge eq. 1)", "n_a", "duty", above=0),
    Quantity("acceleration_time", "s", "time to accelerate the driven machine to speed", "t_p", "duty", above=0),
    Quantity("resisting_torque", "N*m", "largest resisting torque of the driven machine", "T_c", "duty", at_least=0),
)


def required_torque(inertia, speed, acceleration_time, resisting_torque):
    """T_max = I_n e_max + T_c with e_max = w_a / t_p: wedge paper eqs. (5), (17); lever paper, T_max = I_M e + T_p."""
    return inertia * speed / acceleration_time + resisting_torque


def centrifugal_force(mass, speed, centroid_radius):
    """F_u = m w^2 r_c: wedge paper eq. (10)."""
    return mass * speed**2 * centroid_radius


# --- Duty given by the motor: power, speed and a service factor (the ball clutch of Tasev) ----------------------
POWER_DUTY_QUANTITIES = (
    Quantity("power", "kW", "rated power of the driving motor", "P", "duty", above=0),
    next(q for q in DUTY_QUANTITIES if q.name == "speed"),
    Quantity("service_factor", "", "torque the clutch must carry, over the rated torque P / w", "k_s", "duty", 1.0,
             at_least=1),
)


def rated_torque(power, speed, service_factor=1.0):
    """T = k_s P / w: the motor's rated torque times a service factor."""
    return service_factor * power / speed
