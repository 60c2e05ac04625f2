"""The drive of a start at a design: the shape of its NLP (:class:`Structure`), its equations at the design's values
(:class:`Drive`, CasADi symbols or floats) and its requirements as named constraints, for the NLP's figures or the
simulator's (docs/start_up.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from clutchopt.backend import fmax, fmin, sqrt
from clutchopt.model import Constraint, ElasticLaw, SpeedLaw, at_least, at_most
from clutchopt.start_up import equations as su
from clutchopt.start_up.mesh import GRADED_PARTS
from clutchopt.start_up.overload import overload_limit, overload_torque

LOCKED_SAMPLES = 8  # speeds from lock-up to synchronous at which a locked drive must stay locked (lockup)
RUN_UPS = 100  # the time scale of a motor's start: at most this many run-ups at breakdown torque, (J + J_m) w_s / T_k
LEAST_SHARE = 1e-6  # of the drive's torque scale: the least torque a lock-up's margin is relative to


def elastic_link(case) -> bool:
    """Whether the case's coupling drives through an elastic link (the cable's: it twists, it does not slip)."""
    from clutchopt.formulations import get_coupling  # (the formulations import the start-up's drive)

    return isinstance(get_coupling(case.coupling).formulation().speed_law, ElasticLaw)


@dataclass(frozen=True)
class Structure:
    """What fixes the shape of a start-up NLP (part of the problem cache key)."""

    spec: su.StartUpSpec
    load_at_rest: bool  # the driven machine needs torque to break away: a breakaway phase (motor_curve)
    intervals: int
    elastic: bool = False  # an elastic link (the cable coupling): one locked phase, the link quasi-static

    @classmethod
    def of(cls, case, intervals: int | None = None) -> "Structure":
        """The structure of a case (its first mesh is the case's own: :func:`graded_part`)."""
        spec, v = case.start_up, case.values
        rest = spec.load_profile.at(0.0, 0.0) if spec.load_profile else v["load_torque"]
        elastic = elastic_link(case)
        return cls(spec, spec.has("motor_curve") and rest > 0 and not elastic, intervals or spec.intervals, elastic)

    @property
    def motor(self) -> bool:
        return self.spec.has("motor_curve")

    @property
    def radial(self) -> bool:
        return any(self.spec.has(e) for e in su.RADIAL_EFFECTS)

    @property
    def heat(self) -> bool:
        return self.spec.has("friction_heat")

    @property
    def phases(self) -> tuple[str, ...]:
        if self.elastic:
            return ("locked",)
        names = ("run_up",) if self.motor and self.radial else ()
        return names + (("breakaway",) if self.load_at_rest else ()) + ("slip",)


def graded_part(spec: su.StartUpSpec, values) -> float:
    """The part of a start's slip phase that its first mesh grades where no start is simulated, and the most a
    simulated start's knee sets (:func:`~.mesh.knee_part`): the motor's knee time J_m w_s / T_k (its run-up at
    breakdown torque), 20 times over, rounded up to one of GRADED_PARTS of the start time (``values``: the case's, SI;
    the first of them without a motor). The case's, not its NLP's shape (the mesh is a parameter of the NLP): a
    sweep's point is graded as ``solve`` of it alone grades it, whatever case the sweep's problem was built from
    (review 24: ball_motor_start at a start time of 16 s, in a sweep of the case at 8 s, had been graded by 8 s's
    part and kept 950.755 kg where ``solve`` alone keeps 957.546 kg, the two local optima of docs/start_up.md)."""
    if not spec.has("motor_curve"):
        return GRADED_PARTS[0]
    knee = (20.0 * values["motor_inertia"] * values["synchronous_speed"] / values["breakdown_torque"]
            / values["max_start_time"])
    return next((part for part in GRADED_PARTS if part >= knee), GRADED_PARTS[-1])


class Drive:
    """The drive's equations at given design and case values (CasADi symbols or floats)."""

    def __init__(self, structure: Structure, law: SpeedLaw | ElasticLaw, x, p):
        self.s, self.p, self.law, self.x = structure, p, law, x
        spec = structure.spec
        self.coefficient = None if structure.elastic else law.torque_coefficient(x, p)
        if structure.radial:
            force = su.radial_reduction(spec.effects, x.spring_preload, law.weight_mass(x, p))
            self.engagement_squared = su.engagement_speed_squared(force, law.mass_radius(x, p))
        else:
            self.engagement_squared = 0.0
        self.speed_ref = p.synchronous_speed if structure.motor else p.speed
        self.time_ref = p.max_start_time
        if structure.motor:  # a limit far beyond any start the motor makes (1e8 s) scales nothing
            run_up = (p.driven_inertia + p.motor_inertia) * p.synchronous_speed / p.breakdown_torque
            self.time_ref = fmin(p.max_start_time, RUN_UPS * run_up)
            self.motor_time_ref = p.motor_inertia * p.synchronous_speed / p.breakdown_torque  # its own run-up
        self.energy_ref = p.driven_inertia * self.speed_ref**2
        self.torque_ref = p.driven_inertia * self.speed_ref / self.time_ref + p.load_torque
        self.temperature_ref = self.energy_ref / p.heat_capacity if structure.heat else 1.0
        self.twist_ref = law.largest_twist(x, p) / 2.0 if structure.elastic else 1.0

    def link(self, speed, twist):
        """An elastic link's torque at the driving speed and twist."""
        return self.law.torque(self.x, self.p, speed, twist)

    def link_stress(self, speed, twist):
        return self.law.stress(self.x, self.p, speed, twist)

    def torque(self, driving_speed):
        return su.coupling_torque(self.coefficient, driving_speed, self.engagement_squared)

    def motor(self, speed):
        p = self.p
        return su.kloss_torque(speed, p.synchronous_speed, p.breakdown_torque, p.breakdown_slip)

    def load(self, driven_speed, time):
        """The driven machine's torque: the case's load_torque, or its load profile at the speed or the time (a
        number, or a vector of them: a phase's collocation points)."""
        profile = self.s.spec.load_profile
        if not profile:
            return self.p.load_torque
        return profile.at(driven_speed, time)

    def carried(self, speed, time):
        """Torque the coupling must carry at lock-up and after: the locked drive's share of the load."""
        if not self.s.motor:
            return self.load(speed, time)
        return su.carried_torque(self.motor(speed), self.load(speed, time), self.p.driven_inertia,
                                 self.p.motor_inertia)

    def heat_rate(self, power, temperature):
        return su.heat_rate(power, temperature, self.p.heat_capacity, self.p.heat_conductance)

    # --- the lining: its temperature against the friction pair's limits, its wear (docs/start_up.md) -------------
    @property
    def repeated(self) -> bool:
        """Repeated starts given (starts_per_hour): the lining starts from their steady temperature."""
        return "starts_per_hour" in self.s.spec.limits

    def steady_rise(self, friction_work):
        """dT_s = L n_h / G over the ambient, 0 for a single start."""
        if not self.repeated:
            return 0.0
        return su.steady_temperature_rise(friction_work, self.p.starts_per_hour, self.p.heat_conductance)

    def lining_temperature(self, friction_work, temperature_rise):
        """T_0 + dT_s + dT of the start (``temperature_rise``: its rise, all along the start or its largest)."""
        return su.lining_temperature(self.p.ambient_temperature, self.steady_rise(friction_work), temperature_rise)

    def wear_per_start(self, friction_work):
        return su.wear_per_start(friction_work, self.p.wear_rate, self.law.friction_area(self.x, self.p))

    def starts_until_worn(self, friction_work):
        return su.starts_until_worn(self.p.wear_allowance, self.wear_per_start(friction_work))

    def life(self, friction_work):
        """Time until worn at starts_per_hour: N / n_h (s)."""
        return self.starts_until_worn(friction_work) / self.p.starts_per_hour


CLOSED_FORM = ("min_engagement_speed", "max_engagement_speed", "motor_breakdown_torque", "motor_starting_torque",
               "overload_torque", "worn_engages_first")
# the start-up's constraints that read no figure of the start: closed forms in the design and the case's values


def named_constraints(s: Structure, drive: Drive, q) -> list[Constraint]:
    """The start-up's requirements as named constraints, of the figures ``q`` (start_time, friction_work,
    temperatures, lock_up_speed, lock_up_time): NLP expressions, or the simulator's figures for the float64 check."""
    p, limits = drive.p, s.spec.limits
    if s.elastic:
        return _elastic_constraints(s, drive, q)
    engagement = sqrt(drive.engagement_squared)
    out = [at_most("start_time", q.start_time, p.max_start_time, equation="start-up", unit="s",
                   description="switch-on to lock-up within max_start_time")]
    if "max_friction_work" in limits:
        out.append(at_most("friction_work", q.friction_work, p.max_friction_work, equation="start-up", unit="kJ",
                           description="heat released by slip in one start"))
    if "max_temperature_rise" in limits:
        out.append(at_most("temperature_rise", q.temperatures, p.max_temperature_rise, equation="C dT/dt = P - G T",
                           unit="K", description="temperature rise of the friction parts, all along the start"))
    if "min_engagement_speed" in limits:
        out.append(at_least("min_engagement_speed", engagement, p.min_engagement_speed, equation="w_e",
                            unit="rpm", description="the motor runs up unloaded to at least this speed"))
    if "max_engagement_speed" in limits:
        out.append(at_most("max_engagement_speed", engagement, p.max_engagement_speed, equation="w_e", unit="rpm",
                           description="the weights engage by this driving speed"))
    if "heat_dissipation" in limits:
        out.append(at_most("heat_per_hour", p.starts_per_hour * q.friction_work, p.heat_dissipation,
                           equation="heat balance", unit="W", description="mean friction heat within what the "
                                                                          "housing sheds"))
    out += _lining_constraints(s, drive, q)
    if "min_lock_up_speed" in limits:
        out.append(at_least("lock_up_speed", q.lock_up_speed, p.min_lock_up_speed, equation="start-up", unit="rpm",
                            description="the machine is nearly up to speed when the coupling locks"))
    if s.motor:
        out.append(at_least("motor_breakdown_torque", p.breakdown_torque, p.load_torque, equation="Kloss",
                            unit="N*m", scale=p.breakdown_torque,
                            description="the motor's breakdown torque exceeds the largest load"))
    machine = "max_transmitted_torque" in limits
    if s.spec.overload and (s.motor or machine):
        out.append(_overload(s, drive, machine))
    if drive.law.worn_torque is not None and s.spec.has("spring_preload"):
        force = su.radial_reduction(s.spec.effects, drive.x.spring_preload, drive.law.weight_mass(drive.x, p))
        out.append(at_least("worn_engages_first", drive.law.worn_torque(drive.x, p, engagement, force), 0.0,
                            equation="worn", unit="N*m", scale=drive.torque_ref,
                            description="worn linings pass torque by the new engagement speed: the start with new "
                                        "linings is the slower"))
    lock_speed = q.lock_up_speed
    carried = drive.carried(lock_speed, q.start_time)  # 0 with neither a motor nor a load
    out.append(at_least("lock_up", drive.torque(lock_speed), carried, equation="slip falls to 0", unit="N*m",
                        scale=fmax(carried, LEAST_SHARE * drive.torque_ref),
                        description="at lock-up the coupling covers the torque of the locked drive"))
    if s.motor and s.spec.has("lockup"):
        fractions = np.arange(1, LOCKED_SAMPLES + 1) / LOCKED_SAMPLES
        speeds = lock_speed + (p.synchronous_speed - lock_speed) * fractions
        if isinstance(lock_speed, ca.SX):
            speeds = ca.vertcat(*[lock_speed + (p.synchronous_speed - lock_speed) * f for f in fractions])
        out.append(at_least("stays_locked", drive.torque(speeds) - drive.carried(speeds, q.start_time), 0.0,
                            equation="lockup", unit="N*m", scale=drive.torque_ref,
                            description="torque margin over the locked run-up to synchronous speed"))
    return out


def _lining_constraints(s: Structure, drive: Drive, q) -> list[Constraint]:
    """The lining's temperature against the friction pair's peak and continuous limits (effect friction_heat; on
    whenever the limits are known, from the library or the case) and its life (min_life)."""
    p, limits, out = drive.p, s.spec.limits, []
    if s.heat and "max_lining_temperature" in limits:
        out.append(at_most("lining_temperature", drive.lining_temperature(q.friction_work, q.temperatures),
                           p.max_lining_temperature, equation="T_0 + L n_h/G + dT", unit="degC",
                           scale=p.max_lining_temperature - p.ambient_temperature,
                           description="peak temperature of the friction material in a start (on the steady "
                                       "temperature of repeated starts)"))
    if s.heat and drive.repeated and "max_continuous_temperature" in limits:
        out.append(at_most("continuous_temperature", drive.lining_temperature(q.friction_work, 0.0),
                           p.max_continuous_temperature, equation="T_0 + L n_h/G", unit="degC",
                           scale=p.max_continuous_temperature - p.ambient_temperature,
                           description="steady temperature of repeated starts (starts_per_hour)"))
    if "min_life" in limits:
        out.append(at_least("lining_life", drive.life(q.friction_work), p.min_life, equation="s_w A / (k_w L n_h)",
                            unit="h", description="hours of starts until the lining's wear allowance is gone"))
    return out


def _overload(s: Structure, drive: Drive, machine: bool) -> Constraint:
    """The largest torque the coupling passes (top speed, worn linings where they matter, highest friction) below the
    motor's breakdown torque and the machine's limit: it slips before the motor stalls (docs/start_up.md)."""
    p = drive.p
    limit = overload_limit(p, s.motor, machine)
    what = " and ".join(["the motor's breakdown torque"] * s.motor + ["max_transmitted_torque"] * machine)
    worn = ", worn" if drive.law.worn_torque is not None else ""
    return at_most("overload_torque", overload_torque(drive.law, drive.x, p, s.spec.effects, s.motor), limit,
                   equation="overload", unit="N*m", scale=limit,
                   description=f"largest torque passed (top speed{worn}, f_max) within {what}: it slips first")


def seen_constraints(s: Structure, law: SpeedLaw | ElasticLaw, q, seen, drive: Drive) -> list[Constraint]:
    """:func:`named_constraints` of the figures ``q`` of one start, each evaluated with the design and case values
    ``seen(name)`` gives it, ``(x, p)``: under scatter each at its own corner (its limit at its strict end, the
    engagement window at the preload that narrows it), while the figures are those of the start simulated at
    ``seen(None)``, whose ``drive`` the caller has built."""
    start = seen(None)
    constraints = named_constraints(s, drive, q)
    return [constraint if _same_values(at := seen(constraint.name), start)  # (without scatter: every one, once)
            else named_constraints(s, Drive(s, law, *at), q)[i] for i, constraint in enumerate(constraints)]


def _same_values(seen: tuple, start: tuple) -> bool:
    """Whether the design and case values ``seen`` are those of ``start`` (each the same object, or an equal number):
    its constraint is then the one built at ``start`` (the simulator's check built a drive per constraint, 12 a
    check, 2 ms of a 20 ms sweep point); the same pair at once (a solve's check without scatter: 1 ms a check
    comparing 150 values 12 times)."""
    return seen is start or all(vars(a).keys() == vars(b).keys()
                                and all(u is (v := vars(b)[name]) or (type(u) is float and type(v) is float and u == v)
                                        for name, u in vars(a).items())
                                for a, b in zip(seen, start))


def _elastic_constraints(s: Structure, drive: Drive, q) -> list[Constraint]:
    """An elastic link's start: its time to the start speed, the stress of the link all along it (``q.stresses``),
    the damping's heat if limited, and a motor that can start the machine at all."""
    p, limits = drive.p, s.spec.limits
    out = [at_most("start_time", q.start_time, p.max_start_time, equation="start-up", unit="s",
                   description="switch-on until the machine runs at the start speed (min_lock_up_speed)"),
           at_most("link_stress", q.stresses, p.max_link_stress, equation="(18), start-up", unit="MPa",
                   description="stress of the link all along the start")]
    if "max_friction_work" in limits:
        out.append(at_most("friction_work", q.friction_work, p.max_friction_work, equation="start-up", unit="kJ",
                           description="energy the link's damping takes in one start"))
    if "heat_dissipation" in limits:
        out.append(at_most("heat_per_hour", p.starts_per_hour * q.friction_work, p.heat_dissipation,
                           equation="heat balance", unit="W", description="mean heat within what the housing sheds"))
    out.append(at_least("motor_breakdown_torque", p.breakdown_torque, p.load_torque, equation="Kloss", unit="N*m",
                        scale=p.breakdown_torque, description="the motor's breakdown torque exceeds the largest load"))
    out.append(at_least("motor_starting_torque", drive.motor(0.0), drive.load(0.0, 0.0), equation="Kloss",
                        unit="N*m", scale=p.breakdown_torque,
                        description="the motor's torque at rest exceeds the load at rest"))
    return out
