"""The start-up of a centrifugal coupling on its real drive: the ``[start_up]`` section of a case, its equations.

Every sizing method of the papers assumes a constant driving speed and a constant angular acceleration
(T_max = I_n w_a / t_p + T_c, wedge eqs. 5, 17). A case with a ``[start_up]`` section describes the drive instead:
the effects to model (the vocabulary of start-up scenes, ``clutchopt.simulate``), an induction motor or a constant
driving speed, return-spring preload, the weights' own weight, the driven machine's load, the heat capacity of the
friction parts, and the limits the start-up must meet. The same equations serve the NLP (``clutchopt.start_up.
transcription``, collocation) and the simulator (``clutchopt.simulate``), through ``clutchopt.backend``.

The torque of a centrifugal coupling follows its *driving* speed w_a, since the weights ride on the driving half:
T = K (w_a^2 - w_e^2) once engaged, K = dT/d(w_a^2) of the coupling's own torque equation (a
:class:`~clutchopt.model.SpeedLaw`), w_e the engagement speed at which the centrifugal force m r w_e^2 of a weight
equals what holds it in, spring preload F_s and (effect ``gravity``) its own weight m g at its worst position.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from dataclasses import dataclass, field, replace
from functools import lru_cache

import casadi as ca
import numpy as np

from clutchopt.backend import fmax, fmin, is_symbolic, sqrt
from clutchopt.formulations.duty import GRAVITY
from clutchopt.model import Formulation, Quantity, Variable

EFFECTS = ("slip_friction", "motor_curve", "spring_preload", "gravity", "lockup", "friction_heat")
RADIAL_EFFECTS = ("spring_preload", "gravity")  # effects that take radial force from the weights

Q = Quantity
SECTION = "start_up"
QUANTITIES = (
    Q("spring_preload", "N", "return-spring preload on each weight (effect spring_preload; may be freed)", "F_s",
      SECTION, "0 N", at_least=0),
    Q("driven_inertia", "kg*m^2", "moment of inertia of the driven machine (default: duty.inertia)", "J",
      f"{SECTION}.driven", None, above=0, toml_key="inertia"),
    Q("load_torque", "N*m", "resisting torque of the driven machine, constant (default: duty.resisting_torque)",
      "T_c", f"{SECTION}.driven", None, at_least=0, toml_key="resisting_torque"),
    Q("synchronous_speed", "rpm", "synchronous speed of the induction motor (effect motor_curve)", "w_s",
      f"{SECTION}.driver", None, above=0),
    Q("breakdown_torque", "N*m", "breakdown (pull-out) torque of the motor, Kloss curve", "T_k",
      f"{SECTION}.driver", None, above=0),
    Q("breakdown_slip", "", "slip at the breakdown torque, Kloss curve", "s_k", f"{SECTION}.driver", None,
      above=0, below=1),
    Q("motor_inertia", "kg*m^2", "rotor inertia of the motor with the driving half-coupling", "J_m",
      f"{SECTION}.driver", None, above=0, toml_key="inertia"),
    Q("heat_capacity", "J/K", "heat capacity of the parts the friction heat goes into (effect friction_heat)", "C",
      f"{SECTION}.heat", None, above=0, toml_key="capacity"),
    Q("heat_conductance", "W/K", "heat the housing sheds per kelvin of temperature rise", "G",
      f"{SECTION}.heat", "0 W/K", at_least=0, toml_key="conductance"),
    Q("max_start_time", "s", "switch-on to lock-up at most (default: duty.acceleration_time)", "t_max",
      f"{SECTION}.limits", None, above=0),
    Q("max_friction_work", "kJ", "heat released by slip in one start at most", "L_max", f"{SECTION}.limits",
      None, above=0),
    Q("max_temperature_rise", "K", "temperature rise of the friction parts at most (effect friction_heat)",
      "dT_max", f"{SECTION}.limits", None, above=0),
    Q("min_lock_up_speed", "rpm", "lock-up at least at this speed, the machine nearly up to speed (motor_curve; "
      "default: 90 % of synchronous speed)", "w_L,min", f"{SECTION}.limits", None, above=0),
    Q("max_link_stress", "MPa", "largest stress of an elastic link during the start (cable coupling; default: its "
      "allowable, allowable_cable_stress)", "sigma_max", f"{SECTION}.limits", None, above=0),
    Q("min_engagement_speed", "rpm", "engagement speed at least (the motor runs up unloaded first; leave it out for "
      "none)", "w_e,min", f"{SECTION}.limits", None, above=0),
    Q("max_engagement_speed", "rpm", "engagement speed at most", "w_e,max", f"{SECTION}.limits", None, above=0),
    Q("starts_per_hour", "1/hour", "starts per hour (the steady temperature of repeated starts, the lining's life "
      "in hours; with heat_dissipation: the heat balance over an hour)", "n_h",
      f"{SECTION}.limits", None, above=0),
    Q("heat_dissipation", "W", "mean heat the housing can shed (e.g. '180 kJ/hour')", "P_d",
      f"{SECTION}.limits", None, above=0),
    Q("ambient_temperature", "degC", "temperature of the air around the coupling (effect friction_heat)", "T_0",
      f"{SECTION}.heat", "40 degC", above=0, toml_key="ambient"),
    Q("max_lining_temperature", "degC", "peak temperature of the friction material in a start, at most (default: "
      "the friction pair's max_temperature)", "T_peak,max", f"{SECTION}.limits", None, above=0),
    Q("max_continuous_temperature", "degC", "steady temperature of repeated starts, at most (default: the friction "
      "pair's continuous_temperature)", "T_cont,max", f"{SECTION}.limits", None, above=0),
    Q("wear_rate", "mm^3/J", "specific wear rate of the lining: volume worn per friction work (default: the friction "
      "pair's)", "k_w", f"{SECTION}.wear", None, above=0),
    Q("wear_allowance", "mm", "thickness of lining that may wear away (default: the lining thickness, where the "
      "coupling has one)", "s_w", f"{SECTION}.wear", None, above=0, toml_key="allowance"),
    Q("min_life", "h", "hours of starts (at starts_per_hour) until the lining is worn, at least", "L_h,min",
      f"{SECTION}.limits", None, above=0),
    Q("max_transmitted_torque", "N*m", "largest torque the driven machine may be given (the coupling as a torque "
      "limiter: overload_torque)", "T_lim", f"{SECTION}.driven", None, above=0),
    Q("friction_max", "", "highest friction coefficient of the friction pair, for the overload (default: the "
      "largest of the nominal, the library pair's friction_max and the [scatter] range's high end)", "f_max",
      f"{SECTION}.overload", None, above=0, at_most=1),
)


# --- Equations ---------------------------------------------------------------------------------------------------
def engagement_speed_squared(radial_reduction, mass_radius):
    """w_e^2 = (F_s + m g) / (m r): the centrifugal force m r w^2 of a weight first exceeds what holds it in."""
    return radial_reduction / mass_radius


def radial_reduction(effects, spring_preload, weight_mass):
    """Radial force per weight that works against the centrifugal force: F_s (spring_preload) + m g (gravity)."""
    force = 0.0
    if "spring_preload" in effects:
        force = force + spring_preload
    if "gravity" in effects:
        force = force + weight_mass * GRAVITY
    return force


def coupling_torque(torque_coefficient, driving_speed, engagement_squared):
    """T = K (w_a^2 - w_e^2), engaged (w_a >= w_e): the coupling's torque equation at the driving speed."""
    return torque_coefficient * (driving_speed**2 - engagement_squared)


def kloss_torque(speed, synchronous_speed, breakdown_torque, breakdown_slip):
    """Induction motor, Kloss: T = 2 T_k / (s / s_k + s_k / s) = 2 T_k s s_k / (s^2 + s_k^2), s = 1 - w / w_s.

    The second form has no division by s, so it is smooth (and zero) at synchronous speed.
    """
    s = 1.0 - speed / synchronous_speed
    return 2.0 * breakdown_torque * s * breakdown_slip / (s * s + breakdown_slip * breakdown_slip)


def piecewise_linear(x, points, values):
    """y(x) through (points, values), held constant beyond both ends (as numpy.interp). A CasADi symbol gets one
    call of a linear interpolant (exact derivatives, the segment's slope), so a table of a thousand points is one
    node of the NLP at each use, not a thousand; a symbol vector (a phase's collocation points) one such node per
    element, in that one call (CasADi maps a function of a number over the vector it is given); an array goes to
    numpy.interp, a number is looked up by bisection (:func:`table_segment`)."""
    if is_symbolic(x):
        return _interpolant(tuple(points), tuple(values))(fmin(fmax(x, points[0]), points[-1]))
    if np.ndim(x):
        return np.interp(x, points, values)
    return table_segment(x, points, values)[0]


def table_segment(x: float, points, values) -> tuple[float, float]:
    """(y, dy/dx) of the piecewise-linear table at a number x, held constant (slope 0) beyond both ends; NaN at NaN
    (a start that does not lock up has no lock-up speed), as numpy.interp."""
    if math.isnan(x):
        return math.nan, math.nan
    if x <= points[0]:
        return values[0], 0.0
    if x >= points[-1]:
        return values[-1], 0.0
    i = bisect_right(points, x) - 1
    slope = (values[i + 1] - values[i]) / (points[i + 1] - points[i])
    return values[i] + slope * (x - points[i]), slope


@lru_cache(maxsize=64)
def _interpolant(points: tuple[float, ...], values: tuple[float, ...]):
    return ca.interpolant("load_profile", "linear", [points], values, {"lookup_mode": ["binary"]})


def heat_rate(power, temperature_rise, heat_capacity, conductance):
    """dT/dt = (P_fr - G T) / C: the lumped temperature rise T of the friction parts over ambient."""
    return (power - conductance * temperature_rise) / heat_capacity


def steady_temperature_rise(friction_work, starts_per_hour, conductance):
    """dT_s = L n_h / G: the mean heat input of repeated starts (friction work L per start, n_h starts per unit time)
    shed by the housing's conductance G, the lumped model's steady state (G dT_s = mean of P_fr). Above the exact
    periodic temperature before a start, (L / C) / (exp(G / (n_h C)) - 1), since e^x - 1 >= x (docs/start_up.md)."""
    return friction_work * starts_per_hour / conductance


def lining_temperature(ambient, steady_rise, start_rise):
    """T = T_0 + dT_s + dT: the lining's absolute temperature, a start's rise over the steady temperature of repeated
    starts (dT_s = 0 for a single start) over the ambient."""
    return ambient + steady_rise + start_rise


def wear_per_start(friction_work, wear_rate, friction_area):
    """Lining worn per start, uniform over the area: h = k_w L / A (Archard's law written per friction energy, the
    specific wear rate k_w in m^3/J; A the lining area that wears, L the friction work of the start)."""
    return wear_rate * friction_work / friction_area


def starts_until_worn(wear_allowance, wear_depth):
    """N = s_w / h: the starts until the wear allowance s_w is gone at h per start (infinite where a start wears
    nothing: one that never slips, a number only)."""
    if not is_symbolic(wear_depth) and np.ndim(wear_depth) == 0 and wear_depth == 0:
        return math.inf
    return wear_allowance / wear_depth


def carried_torque(motor_torque, load, driven_inertia, motor_inertia):
    """Torque a locked coupling carries while motor and machine run up together:
    (J + J_m) dw/dt = T_m - T_c, so the coupling gives the machine T_c + J dw/dt = (J_m T_c + J T_m) / (J + J_m)."""
    return (motor_inertia * load + driven_inertia * motor_torque) / (driven_inertia + motor_inertia)


def engagement_speed(radial_force, mass_radius):
    """w_e = sqrt((F_s + m g) / (m r))."""
    return sqrt(engagement_speed_squared(radial_force, mass_radius))


# --- What a case's [start_up] section fixes beyond its quantities -------------------------------------------------
@dataclass(frozen=True)
class LoadProfile:
    """Resisting torque of the driven machine, piecewise linear over its speed (``over = "speed"``) or over time
    (``"time"``), held constant beyond the table (SI)."""

    over: str
    points: tuple[float, ...]
    values: tuple[float, ...]

    def at(self, speed, time):
        return piecewise_linear(speed if self.over == "speed" else time, self.points, self.values)


@dataclass(frozen=True)
class StartUpSpec:
    """The start-up a case asks for: effects (only these are modelled, in the NLP and the simulator), the load
    profile if not constant, the limits given (names of QUANTITIES), the collocation intervals per phase and the
    relative tolerance within which the simulated start must meet the limits."""

    effects: tuple[str, ...]
    limits: tuple[str, ...]
    load_profile: LoadProfile | None = None
    intervals: int = 16
    tolerance: float = 1e-6
    overload: bool = True  # the overload_torque check (with a motor or max_transmitted_torque); check = false: off
    motor_note: str = field(default="", compare=False)  # how a nameplate was read (no part of the structure)
    friction_max_given: bool = field(default=False, compare=False)  # else the pair's or the scatter's (overload)

    def has(self, effect: str) -> bool:
        return effect in self.effects


LIMITS = ("max_start_time", "max_friction_work", "max_temperature_rise", "min_lock_up_speed", "max_link_stress",
          "min_engagement_speed", "max_engagement_speed", "starts_per_hour", "heat_dissipation",
          "max_lining_temperature", "max_continuous_temperature", "min_life", "max_transmitted_torque")
SLIP_ONLY = ("max_friction_work", "max_temperature_rise", "starts_per_hour", "heat_dissipation", "heat_capacity",
             "heat_conductance", "ambient_temperature", "max_lining_temperature", "max_continuous_temperature",
             "wear_rate", "wear_allowance", "min_life", "max_transmitted_torque", "friction_max")
"""The quantities of a coupling that slips (friction heat, lining wear, the torque it passes slipping): what an
elastic link (the cable coupling) cannot have; :func:`clutchopt.start_up.section.parse_start_up` refuses them on
one, ``choose-coupling`` leaves them out of the neutral case it poses for one."""
SLIP_EFFECTS = ("friction_heat",)
WEAR_ONLY = ("wear_rate", "wear_allowance", "min_life")
"""The quantities of lining wear: what a coupling that declares no friction area that wears cannot have."""
LOCK_UP_SHARE = 0.9  # default min_lock_up_speed over the synchronous speed

SPRING_PRELOAD = Variable("spring_preload", "N", "return-spring preload on each weight", "F_s", lower=0.0,
                          upper=1e6, at_least=0, fixed_unless_freed=True)


def with_start_up(formulation: Formulation) -> Formulation:
    """The formulation of a case with a [start_up] section: its quantities and the spring preload (a design
    variable when freed) added, the papers' constant-acceleration torque requirement left to the start-up model."""
    return replace(
        formulation,
        quantities=formulation.quantities + QUANTITIES,
        variables=formulation.variables + (SPRING_PRELOAD,),
        constraints=lambda x, p: [c for c in formulation.constraints(x, p) if not c.constant_acceleration],
    )
