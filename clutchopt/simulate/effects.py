"""The effects a scene may switch on, each one small function the right-hand side calls only if it is listed.

``slip_friction``  the clutch's friction torque (law of the scene's coupling); always needed
``motor_curve``    the driver is an induction motor with its own inertia (else: constant driving speed)
``spring_preload`` return springs hold each weight of a centrifugal coupling in: F_s less radial force
``gravity``        the weight's own weight m g less radial force (worst position, as F_i = m (R w^2 - g))
``lockup``         at zero slip the halves stick while the static capacity covers the torque; they break loose
                   when it does not (else: the run ends at zero slip, the paper's t_c)
``friction_heat``  lumped temperature of the friction parts: C dT/dt = P_fr - G T
"""

from __future__ import annotations

from clutchopt.formulations.duty import GRAVITY
from clutchopt.start_up.equations import heat_rate


def slip_friction(law, driver_speed: float, slip: float) -> float:
    """Friction torque on the driven half while the driver leads (w_r >= 0). The law is continued smoothly past
    w_r = 0 inside the solver step that meets the lock-up event, so the event is located on a smooth solution."""
    return law.kinetic(driver_speed, slip)


def motor_curve(motor, speed: float) -> float:
    """Driving torque of the motor at its speed."""
    return motor(speed)


def spring_preload(preload: float) -> float:
    """Radial force the springs take from each weight, N."""
    return preload


def gravity(weight_mass: float) -> float:
    """Radial force the weight's own weight takes at its worst position, m g, N."""
    return weight_mass * GRAVITY


def friction_heat(power: float, temperature_rise: float, heat_capacity: float, conductance: float) -> float:
    """dT/dt = (P_fr - G T) / C, T the temperature rise over ambient."""
    return heat_rate(power, temperature_rise, heat_capacity, conductance)
