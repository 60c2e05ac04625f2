"""The start-up inside the NLP: a centrifugal coupling's start on its drive, transcribed by Radau collocation.

A start from rest has up to three phases, each with its own free duration (docs/start_up.md):
- ``run_up``: the motor runs up unloaded until its speed reaches the engagement speed w_e (motor_curve with spring
  preload or gravity): J_m dw_a/dt = T_m(w_a);
- ``breakaway``: the weights press, but the coupling's torque is still below the load at rest, so the driven
  machine stands while the coupling slips (motor_curve with a load at rest): J_m dw_a/dt = T_m - T;
- ``slip``: both halves turn until the slip s = w_a - w falls to zero (lock-up): J dw/dt = T - T_c(w, t),
  J_m dw_a/dt = T_m - T (constant w_a without motor_curve).
Friction work L (dL/dt = T s) and, with friction_heat, the temperature rise (C dT/dt = T s - G T) are states too.
Each phase has ``intervals`` intervals of Radau IIA collocation of degree 3 (order 5 at the interval ends,
L-stable, so the motor's fast electrical-mechanical mode costs nothing); the phase ends are equalities (w_a = w_e,
T(w_a) = T_c at rest, s = 0) and the lock-up is the first zero of a falling slip (T >= the torque the locked
drive needs). Start time, friction work, temperature rise and engagement speed are then NLP expressions with exact
derivatives and become named constraints. Every optimum is started again by the independent simulator
(``clutchopt.simulate``, solve_ivp with events): the simulated figures are the constraint values reported.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import SimpleNamespace

import casadi as ca
import numpy as np

from clutchopt.backend import sqrt
from clutchopt.model import Constraint, ElasticLaw, SpeedLaw, at_least, at_most, namespace
from clutchopt.start_up import equations as su

DEGREE = 3
MAX_INTERVALS = 128  # per phase, refining by doubling
BACK_OFF_STEPS = 4  # defect corrections of limits the simulated start misses
MESH_STEPS = 3  # adaptations of the mesh to the simulated start before the intervals are doubled
MONITOR_FLOOR = 0.2  # of the mean error monitor, added everywhere: no interval grows without bound
LIMIT_OF = {"start_time": "max_start_time", "friction_work": "max_friction_work",
            "temperature_rise": "max_temperature_rise", "heat_per_hour": "heat_dissipation",
            "link_stress": "max_link_stress"}
LOCKED_SAMPLES = 8  # speeds from lock-up to synchronous at which a locked drive must stay locked (lockup)


GRADED_PARTS = (0.05, 0.1, 0.2, 0.4)  # share of the slip phase graded: the motor's knee times 20, rounded up


def graded_mesh(intervals: int, graded_part: float = 0.05, first: float = 1e-4) -> np.ndarray:
    """Interval lengths (fractions of a phase, summing to 1): half the intervals grow geometrically from ``first``
    over the first ``graded_part`` of the phase, the rest are uniform. The motor's run-up to the speed where its
    torque meets the coupling's (a knee over a small part of the start) lies in the graded part."""
    graded = intervals // 2
    if graded < 2:
        return np.full(intervals, 1.0 / intervals)
    from scipy.optimize import brentq  # scipy.optimize costs 0.3 s to import: only problems with a start-up pay it

    largest = (graded_part / first) ** (1.0 / (graded - 1))  # the last term alone reaches the graded part
    ratio = brentq(lambda r: first * (r**graded - 1.0) / (r - 1.0) - graded_part, 1.0 + 1e-12, largest)
    lengths = first * ratio ** np.arange(graded)
    uniform = np.full(intervals - graded, (1.0 - graded_part) / (intervals - graded))
    return np.concatenate([lengths / lengths.sum() * graded_part, uniform])


def _collocation(degree: int):
    """Radau points tau_0 = 0 < tau_1 .. tau_d = 1 and C[r, j] = l_r'(tau_j) of the Lagrange basis."""
    tau = np.append(0.0, ca.collocation_points(degree, "radau"))
    c = np.zeros((degree + 1, degree + 1))
    for r in range(degree + 1):
        basis = np.poly1d([1.0])
        for q in range(degree + 1):
            if q != r:
                basis *= np.poly1d([1.0, -tau[q]]) / (tau[r] - tau[q])
        derivative = np.polyder(basis)
        c[r] = [derivative(t) for t in tau]
    return tau, c


@dataclass(frozen=True)
class Structure:
    """What fixes the shape of a start-up NLP (part of the problem cache key)."""

    spec: su.StartUpSpec
    load_at_rest: bool  # the driven machine needs torque to break away: a breakaway phase (motor_curve)
    intervals: int
    graded_part: float = GRADED_PARTS[0]  # of the slip phase, where the motor runs up to meet the coupling
    elastic: bool = False  # an elastic link (the cable coupling): one locked phase, the link quasi-static

    @classmethod
    def of(cls, case, intervals: int | None = None) -> "Structure":
        """The structure of a case: the motor's knee time J_m w_s / T_k (its run-up at breakdown torque), 20 times
        over, rounded up to one of GRADED_PARTS of the start time, sets the graded part of the slip phase."""
        spec, v = case.start_up, case.values
        rest = spec.load_profile.at(0.0, 0.0) if spec.load_profile else v["load_torque"]
        graded = GRADED_PARTS[0]
        if spec.has("motor_curve"):
            knee = 20.0 * v["motor_inertia"] * v["synchronous_speed"] / v["breakdown_torque"] / v["max_start_time"]
            graded = next((part for part in GRADED_PARTS if part >= knee), GRADED_PARTS[-1])
        from clutchopt.formulations import get_coupling

        elastic = isinstance(get_coupling(case.coupling).formulation().speed_law, ElasticLaw)
        return cls(spec, spec.has("motor_curve") and rest > 0 and not elastic, intervals or spec.intervals, graded,
                   elastic)

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
        self.energy_ref = p.driven_inertia * self.speed_ref**2
        self.torque_ref = p.driven_inertia * self.speed_ref / p.max_start_time + p.load_torque
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
        profile = self.s.spec.load_profile
        return profile.at(driven_speed, time) if profile else self.p.load_torque

    def carried(self, speed, time):
        """Torque the coupling must carry at lock-up and after: the locked drive's share of the load."""
        if not self.s.motor:
            return self.load(speed, time)
        return su.carried_torque(self.motor(speed), self.load(speed, time), self.p.driven_inertia,
                                 self.p.motor_inertia)

    def heat_rate(self, power, temperature):
        return su.heat_rate(power, temperature, self.p.heat_capacity, self.p.heat_conductance)


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
    if "starts_per_hour" in limits:
        out.append(at_most("heat_per_hour", p.starts_per_hour * q.friction_work, p.heat_dissipation,
                           equation="heat balance", unit="W", description="mean friction heat within what the "
                                                                          "housing sheds"))
    if "min_lock_up_speed" in limits:
        out.append(at_least("lock_up_speed", q.lock_up_speed, p.min_lock_up_speed, equation="start-up", unit="rpm",
                            description="the machine is nearly up to speed when the coupling locks"))
    if s.motor:
        out.append(at_least("motor_breakdown_torque", p.breakdown_torque, p.load_torque, equation="Kloss",
                            unit="N*m", description="the motor's breakdown torque exceeds the largest load"))
    lock_speed = q.lock_up_speed
    out.append(at_least("lock_up", drive.torque(lock_speed), drive.carried(lock_speed, q.start_time),
                        equation="slip falls to 0", unit="N*m",
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
    if "starts_per_hour" in limits:
        out.append(at_most("heat_per_hour", p.starts_per_hour * q.friction_work, p.heat_dissipation,
                           equation="heat balance", unit="W", description="mean heat within what the housing sheds"))
    out.append(at_least("motor_breakdown_torque", p.breakdown_torque, p.load_torque, equation="Kloss", unit="N*m",
                        description="the motor's breakdown torque exceeds the largest load"))
    out.append(at_least("motor_starting_torque", drive.motor(0.0), drive.load(0.0, 0.0), equation="Kloss",
                        unit="N*m", scale=p.breakdown_torque,
                        description="the motor's torque at rest exceeds the load at rest"))
    return out


class StartUpBlock:
    """One start-up transcribed for one problem: internal variables (scaled), equalities, named constraints."""

    def __init__(self, structure: Structure, law: SpeedLaw, x, p):
        self.s = structure
        self.drive = d = Drive(structure, law, x, p)
        self.tau, self.c = _collocation(DEGREE)
        self._hat: list[ca.SX] = []
        self._scale: list = []
        self._bounds: list[tuple[float, float]] = []
        self.kinds: list[tuple[str, str]] = []  # (phase, state or "duration") of each internal variable
        self._mesh: list = []
        self.equalities: list = []
        self.points: list[tuple] = []  # (time, {state: value}) of every phase start and collocation point
        self.nodes: list[dict] = []  # the states at the collocation points (the phase starts excluded)
        state = {"driver_speed": 0.0 if structure.motor else p.speed, "friction_work": 0.0, "temperature": 0.0}
        time = 0.0
        self.durations = {}
        for phase in structure.phases:
            duration, state = self._phase(phase, state, time)
            self.durations[phase] = duration
            time = time + duration
        self.start_time = time
        self.end_state = state
        temperatures = [node["temperature"] for node in self.nodes if isinstance(node["temperature"], ca.SX)]
        stresses = [d.link_stress(node["driver_speed"], node["twist"]) for node in self.nodes if "twist" in node]
        self.figures = SimpleNamespace(
            start_time=time, friction_work=state["friction_work"], lock_up_speed=state["driver_speed"],
            temperatures=ca.vertcat(*temperatures) if temperatures else 0.0,
            stresses=ca.vertcat(*stresses) if stresses else 0.0)
        self.constraints = named_constraints(structure, d, self.figures)

    # --- variables and phases ----------------------------------------------------------------------------------
    def _variable(self, phase: str, kind: str, scale, lower: float, upper: float):
        hat = ca.SX.sym(f"{phase}_{kind}")
        self._hat.append(hat)
        self._scale.append(scale)
        self._bounds.append((lower, upper))
        self.kinds.append((phase, kind))
        return hat * scale

    def _states(self, phase: str) -> dict[str, tuple]:
        """State -> (scale, lower, upper) in scaled units, of one phase."""
        d, s = self.drive, self.s
        states = {}
        if s.motor:
            states["driver_speed"] = (d.speed_ref, 0.0, 1.0)
        if phase == "locked":  # motor and machine as one: the speed of both
            return states
        if phase == "slip":
            states["slip"] = (d.speed_ref, 0.0, 2.0)
        if phase != "run_up":
            states["friction_work"] = (d.energy_ref, 0.0, math.inf)
            if s.heat:
                states["temperature"] = (d.temperature_ref, -math.inf, math.inf)
        return states

    def _rates(self, phase: str, time, state: dict) -> dict:
        d = self.drive
        speed = state["driver_speed"]
        if phase == "run_up":
            return {"driver_speed": d.motor(speed) / d.p.motor_inertia}
        if phase == "locked":
            return {"driver_speed": (d.motor(speed) - d.load(speed, time)) / (d.p.motor_inertia + d.p.driven_inertia)}
        torque = d.torque(speed)
        slip = state["slip"] if phase == "slip" else speed
        rates = {"friction_work": torque * slip}
        if self.s.motor:
            rates["driver_speed"] = (d.motor(speed) - torque) / d.p.motor_inertia
        if phase == "slip":
            driven = speed - slip
            rates["slip"] = rates.get("driver_speed", 0.0) - (torque - d.load(driven, time)) / d.p.driven_inertia
        if self.s.heat:
            rates["temperature"] = d.heat_rate(torque * slip, state["temperature"])
        return rates

    def _phase(self, phase: str, state: dict, start_time):
        d, n = self.drive, self.s.intervals
        duration = self._variable(phase, "duration", d.time_ref, 0.0, 100.0)
        mesh = ca.SX.sym(f"{phase}_mesh", n)  # interval lengths over the duration: NLP parameters
        self._mesh.append(mesh)
        starts = [sum(mesh[i] for i in range(k)) for k in range(n)]
        states = self._states(phase)
        previous = dict(state)
        if phase == "slip":  # the driven machine starts from rest: all of the driving speed is slip
            previous["slip"] = previous["driver_speed"]
        if phase == "locked":  # both halves at rest, nothing twisted yet
            previous.update(slip=0.0, twist=0.0)
        self.points.append((start_time, dict(previous)))
        for k in range(n):
            step = mesh[k] * duration
            nodes = [previous]
            for j in range(1, DEGREE + 1):
                node = dict(previous)
                for name, (scale, lower, upper) in states.items():
                    node[name] = self._variable(phase, name, scale, lower, upper)
                nodes.append(node)
            for j in range(1, DEGREE + 1):
                time = start_time + (starts[k] + self.tau[j] * mesh[k]) * duration
                if phase == "locked":  # the link's twist where its torque meets the locked drive's
                    twist = nodes[j]["twist"] = self._variable(phase, "twist", d.twist_ref, 0.0, 2.0)
                    self.equalities.append((d.link(nodes[j]["driver_speed"], twist)
                                            - d.carried(nodes[j]["driver_speed"], time)) / d.torque_ref)
                rates = self._rates(phase, time, nodes[j])
                for name, (scale, _, _) in states.items():
                    slope = sum(self.c[r, j] * nodes[r][name] for r in range(DEGREE + 1))
                    self.equalities.append((slope - step * rates[name]) / scale)
                self.points.append((time, nodes[j]))
                self.nodes.append(nodes[j])
            previous = nodes[DEGREE]
        self.equalities.append(self._phase_end(phase, previous, start_time + duration))
        return duration, previous

    def first_mesh(self, phase: str) -> np.ndarray:
        """Interval lengths of a phase as fractions of its duration before any adaptation: graded where the motor
        runs up through the slip phase's start, uniform elsewhere."""
        if phase == "slip" and self.s.motor:
            return graded_mesh(self.s.intervals, self.s.graded_part)
        return np.full(self.s.intervals, 1.0 / self.s.intervals)

    @property
    def mesh_parameters(self):
        return ca.vertcat(*self._mesh)

    def initial_mesh(self) -> np.ndarray:
        return np.concatenate([self.first_mesh(phase) for phase in self.s.phases])

    def adapted_mesh(self, history, phase_times: list[float]) -> np.ndarray:
        """A mesh for the next solve from the simulated start, over the NLP's phase timing: each phase's intervals
        equidistribute sqrt|x''| of the states (each scaled by its range and the phase duration), the error
        monitor of a corner (the motor's knee), with a fifth of its mean added everywhere."""
        t_all = history["t"].to_numpy()
        columns = [history[name].to_numpy() for name in ("w_driver", "w_driven", "friction_work", "temperature_rise")]
        meshes, begin = [], 0.0
        for phase, end in zip(self.s.phases, np.cumsum(phase_times)):
            inside = (t_all >= begin) & (t_all <= end)
            t, first = np.unique(t_all[inside], return_index=True)
            if not end > begin or len(t) < 5:
                meshes.append(self.first_mesh(phase))
                begin = end
                continue
            span = end - begin
            monitor = np.zeros(len(t))
            for column in columns:
                values = column[inside][first]
                spread = values.max() - values.min()
                if spread > 0:
                    monitor += np.abs(np.gradient(np.gradient(values, t), t)) * span * span / spread
            monitor = np.sqrt(monitor)
            monitor = MONITOR_FLOOR * monitor.mean() + monitor if monitor.mean() > 0 else np.ones_like(monitor)
            weight = np.concatenate([[0.0], np.cumsum(0.5 * (monitor[1:] + monitor[:-1]) * np.diff(t))])
            edges = np.interp(np.linspace(0.0, weight[-1], self.s.intervals + 1), weight, (t - begin) / span)
            edges[0], edges[-1] = 0.0, 1.0
            meshes.append(np.diff(edges))
            begin = end
        return np.concatenate(meshes)

    def _phase_end(self, phase: str, state: dict, time):
        d = self.drive
        if phase == "run_up":
            return (state["driver_speed"] ** 2 - d.engagement_squared) / d.speed_ref**2
        if phase == "breakaway":
            return (d.torque(state["driver_speed"]) - d.load(0.0, time)) / d.torque_ref
        if phase == "locked":
            return (state["driver_speed"] - d.p.min_lock_up_speed) / d.speed_ref
        return state["slip"] / d.speed_ref

    # --- what the problem needs -----------------------------------------------------------------------------------
    @property
    def hat(self):
        return ca.vertcat(*self._hat)

    @property
    def size(self) -> int:
        return len(self._hat)

    @property
    def scales(self) -> list:
        """Scale of each internal variable (expressions of the case quantities): value = scale * hat."""
        return self._scale

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        lower, upper = zip(*self._bounds)
        return np.array(lower), np.array(upper)

    def outputs(self) -> dict:
        """Figures of the NLP's start (expressions): for the start_up report and the trajectory."""
        d = self.drive
        figures = {"start_time": self.start_time, "friction_work": self.figures.friction_work,
                   "engagement_speed": ca.sqrt(d.engagement_squared) if self.s.radial else 0.0,
                   "lock_up_speed": self.figures.lock_up_speed}
        for phase, duration in self.durations.items():
            figures[f"{phase}_time"] = duration
        return figures

    def trajectory(self) -> dict:
        """Time, driving speed, driven speed, friction work, temperature at every collocation point."""
        times, driver, driven, work, heat, twist = [], [], [], [], [], []
        for time, state in self.points:
            times.append(time)
            driver.append(state["driver_speed"])
            driven.append(state["driver_speed"] - state["slip"] if "slip" in state else 0.0)
            work.append(state["friction_work"])
            heat.append(state["temperature"])
            twist.append(state.get("twist", 0.0))
        return {"t": times, "w_driver": driver, "w_driven": driven, "friction_work": work, "temperature_rise": heat,
                "twist": twist}

    def guess(self, history, headline, engagement_squared: float, time_ref: float, scales: np.ndarray,
              mesh: np.ndarray) -> np.ndarray:
        """Internal variables (scaled by ``scales``) from a simulation of the start design, which ends at its
        lock-up, or at ``time_ref`` if it does not lock up."""
        d = self.s
        locked = headline.get("locks_up") and math.isfinite(headline.get("start_time", math.inf))
        t_end = headline["start_time"] if locked else time_ref
        t = history["t"].to_numpy()
        driver = history["w_driver"].to_numpy()
        driven = history["w_driven"].to_numpy()
        engage = t[np.argmax(driver >= math.sqrt(engagement_squared))] if d.motor and d.radial else 0.0
        moving = driven > 1e-9 * max(driver.max(), 1e-300)
        breakaway = t[np.argmax(moving)] if d.load_at_rest and moving.any() else engage
        bounds = {"run_up": (0.0, engage), "breakaway": (engage, breakaway), "slip": (breakaway, t_end),
                  "locked": (0.0, t_end)}
        columns = {"driver_speed": driven if d.elastic else driver, "slip": driver - driven,
                   "friction_work": history["friction_work"].to_numpy(),
                   "temperature": history["temperature_rise"].to_numpy(),
                   "twist": history["twist"].to_numpy() if "twist" in history else np.zeros_like(t)}
        values = []
        for index, phase in enumerate(d.phases):
            begin, end = bounds[phase]
            end = max(end, begin)
            values.append(end - begin)
            lengths = mesh[index * d.intervals:(index + 1) * d.intervals]
            starts = np.concatenate([[0.0], np.cumsum(lengths)[:-1]])
            for k in range(d.intervals):
                for j in range(1, DEGREE + 1):
                    time = begin + (starts[k] + self.tau[j] * lengths[k]) * (end - begin)
                    for name in self._states(phase):
                        values.append(float(np.interp(time, t, columns[name])))
                    if phase == "locked":
                        values.append(float(np.interp(time, t, columns["twist"])))
        return np.array(values) / scales


def initial_states(block: StartUpBlock, case, formulation, design: dict[str, float], scales: np.ndarray,
                   mesh: np.ndarray) -> np.ndarray:
    """The internal variables (scaled) of the start design's simulated start: a start point on the dynamics."""
    from clutchopt.start_up.simulation import run_start_up

    model = _dense(case, formulation, design, rtol=1e-6, end_time=3.0 * case.values["max_start_time"])
    result = run_start_up(model)
    squared = 0.0 if block.s.elastic else model.law.engagement_squared
    return block.guess(result.history, result.headline, squared, case.values["max_start_time"], scales, mesh)


def _dense(case, formulation, design, rtol: float = 1e-11, end_time: float | None = None):
    """The start-up model of a design, simulated with DOP853 whatever the stiffness for a slipping coupling: its
    stability-bound steps sample the motor's knee densely, and the adapted mesh is taken from the second
    derivatives of these samples (LSODA's few long steps give a poorer mesh, and at 64 intervals a start guess
    from which IPOPT finds no feasible point). ``end_time``: cut a start that does not finish there."""
    from clutchopt.start_up.simulation import start_up_model
    from clutchopt.simulate.engine import Model

    model = start_up_model(case, formulation.mode, design, rtol=rtol)
    if isinstance(model, Model):
        model = replace(model, integrator="DOP853")
    return replace(model, end_time=end_time) if end_time is not None else model


UNITS = {"start_time": "s", "friction_work": "J", "temperature_rise": "K", "engagement_speed": "rad/s",
         "lock_up_speed": "rad/s", "engagement_time": "s", "lock_up_time": "s", "peak_link_stress": "Pa",
         "peak_twist": "rad"}


def start_up_report(block: StartUpBlock, case, formulation, design: dict[str, float], params, figures):
    """The NLP's start beside the independent simulator's (solve_ivp with events, float64) at the design, and the
    start-up constraints re-checked with the simulated figures: (summary in SI, constraint checks, the mesh the
    simulated start suggests for the next solve)."""
    from clutchopt.optimise.verify import check_constraints
    from clutchopt.start_up.simulation import run_start_up

    values, *columns = figures
    nlp = dict(zip(block.outputs(), np.array(values).ravel()))
    trajectory = {name: np.array(column).ravel() for name, column in zip(block.trajectory(), columns)}
    result = run_start_up(_dense(case, formulation, design))
    head = result.headline
    s = block.s
    stresses = result.history["stress"].to_numpy() if s.elastic else 0.0
    simulated = SimpleNamespace(start_time=head["start_time"], friction_work=head["friction_work"],
                                temperatures=head.get("temperature_rise", 0.0), lock_up_speed=head["lock_up_speed"],
                                stresses=stresses if head["locks_up"] else math.inf)
    drive = Drive(s, formulation.speed_law, namespace(design), params)
    checks = check_constraints(named_constraints(s, drive, simulated), s.spec.tolerance)
    engaged = float(nlp.get("run_up_time", 0.0))
    summary = {
        "start_time": float(nlp["start_time"]),
        "start_time_simulated": head["start_time"],
        "friction_work": float(nlp["friction_work"]),
        "friction_work_simulated": head["friction_work"],
        "temperature_rise": float(trajectory["temperature_rise"].max()) if s.heat else None,
        "temperature_rise_simulated": head.get("temperature_rise"),
        "engagement_speed": float(nlp["engagement_speed"]),
        "engagement_time": engaged,
        "lock_up_time": float(nlp["start_time"]) - engaged,
        "lock_up_speed": float(nlp["lock_up_speed"]),
        "lock_up_speed_simulated": head["lock_up_speed"],
        "intervals": s.intervals,
        "phases": list(s.phases),
        "effects": list(s.spec.effects),
        "tolerance": s.spec.tolerance,
        "locks_up": head["locks_up"],
        "reason": head["reason"],
        "discretisation_error": {name: _relative(float(nlp[name]), head[name])
                                 for name in ("start_time", "friction_work", "lock_up_speed")},
        "units": UNITS,
        "trajectory": {name: column.tolist() for name, column in trajectory.items()},
    }
    if s.elastic:  # the link's stress and twist: the NLP's quasi-static link beside the simulated dynamic one
        nodes = zip(trajectory["w_driver"], trajectory["twist"])
        summary.update(peak_link_stress=max(float(drive.link_stress(w, theta)) for w, theta in nodes),
                       peak_link_stress_simulated=head["peak_stress"], peak_twist=float(trajectory["twist"].max()),
                       peak_twist_simulated=head["peak_twist"])
    times = [float(nlp[f"{phase}_time"]) for phase in s.phases]
    return summary, checks, block.adapted_mesh(result.history, times)


def _relative(nlp: float, simulated: float) -> float:
    """(NLP - simulated) / |simulated|: the collocation's error against the simulator (its own error ~1e-10)."""
    if not math.isfinite(simulated) or simulated == 0:
        return math.nan
    return (nlp - simulated) / abs(simulated)


def tightened_limits(solution, nlp_case) -> dict[str, float]:
    """Limits for the next solve where the simulated start misses the case's limit: each moved in from the one the
    NLP last saw by what the simulation exceeds the case's limit, and half the tolerance more."""
    summary, tolerance = solution.start_up, solution.start_up["tolerance"]
    limits = {}
    for check in solution.constraints:
        name = LIMIT_OF.get(check.name)
        if name is None or check.feasible or check.sense != "<=" or not math.isfinite(check.value):
            continue
        excess = check.value - check.limit
        limits[name] = nlp_case.values[name] - excess - 0.5 * tolerance * abs(check.limit)
        if not limits[name] > 0 or summary["locks_up"] is False:
            return {}
    return limits
