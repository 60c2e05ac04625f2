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
(``clutchopt.simulate``, stiff where the motor is, events): the simulated figures are the constraint values reported.
"""

from __future__ import annotations

import itertools
import math
from functools import cached_property
from types import SimpleNamespace

import casadi as ca
import numpy as np

from clutchopt.model import SpeedLaw
from clutchopt.start_up.drive import Drive, Structure, graded_part, named_constraints, seen_constraints
from clutchopt.start_up.mesh import adapted_mesh, first_mesh, knee_part

DEGREE = 3
GUESS_RTOL = 1e-6  # the start guess's simulation: a guess, not a check
TRAJECTORY = ("t", "w_driver", "w_driven", "friction_work", "temperature_rise", "twist")  # trajectory()'s columns


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


class StartUpBlock:
    """One start-up transcribed for one problem: internal variables (scaled), equalities, named constraints."""

    def __init__(self, structure: Structure, law: SpeedLaw, x, p, seen=None):
        """``seen``: name -> the design and case values ``(x, p)`` of each constraint, ``seen(None)`` of the start
        (:func:`~clutchopt.start_up.drive.seen_constraints`; a robust design's corners); None: ``x`` and ``p``."""
        if seen is not None:
            x, p = seen(None)
        self.s = structure
        self.drive = d = Drive(structure, law, x, p)
        tau, self.c = _collocation(DEGREE)
        self.tau = tau.tolist()  # as Python floats: NumPy scalars times SX go through NumPy's ufunc dispatch
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
        twisted = [node for node in self.nodes if "twist" in node]  # an elastic link's stress at all its nodes at once
        stresses = (d.link_stress(*(ca.vertcat(*(node[name] for node in twisted)) for name in ("driver_speed",
                                                                                                  "twist")))
                    if twisted else 0.0)
        self.figures = SimpleNamespace(
            start_time=time, friction_work=state["friction_work"], lock_up_speed=state["driver_speed"],
            temperatures=ca.vertcat(*temperatures) if temperatures else 0.0,
            stresses=stresses)
        self.constraints = (seen_constraints(structure, law, self.figures, seen, d) if seen is not None
                            else named_constraints(structure, d, self.figures))

    # --- variables and phases ----------------------------------------------------------------------------------
    def _variable(self, phase: str, kind: str, scale, lower: float, upper: float):
        hat = ca.SX.sym(f"{phase}_{kind}")
        self._hat.append(hat)
        self._scale.append(scale)
        self._bounds.append((lower, upper))
        self.kinds.append((phase, kind))
        return hat * scale

    def _variables(self, phase: str, specs: list[tuple]) -> list:
        """Internal variables ``(kind, scale, lower, upper)`` in this order, their values (scale times hat) taken in
        one product of a symbol vector with its scales (one CasADi call, not one a variable)."""
        hats = ca.SX.sym(phase, len(specs))
        self._hat += ca.vertsplit(hats)
        for kind, scale, lower, upper in specs:
            self._scale.append(scale)
            self._bounds.append((lower, upper))
            self.kinds.append((phase, kind))
        return ca.vertsplit(hats * ca.vertcat(*(scale for _, scale, _, _ in specs)))

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
            rates["driven"] = (torque - d.load(speed - slip, time)) / d.p.driven_inertia  # dw/dt of the machine
            rates["slip"] = rates.get("driver_speed", 0.0) - rates["driven"]
        if self.s.heat:
            rates["temperature"] = d.heat_rate(torque * slip, state["temperature"])
        return rates

    def _phase(self, phase: str, state: dict, start_time):
        """One phase's collocation: its variables in the NLP's order (per interval its nodes' states, then in the
        locked phase their twists), then the dynamics at all its collocation points at once (each state a vector
        over the phase's nodes: one CasADi operation per term of an equation, not one per node and term), then the
        residuals in the NLP's order (per node: the link's balance, then each state's)."""
        d, n = self.drive, self.s.intervals
        typical = d.motor_time_ref if phase in ("run_up", "breakaway") else d.time_ref  # the machine rests: the
        duration = self._variable(phase, "duration", typical, 0.0, math.inf)  # motor's own time; start_time bounds
        symbols = ca.SX.sym(f"{phase}_mesh", n)  # interval lengths over the duration: NLP parameters
        self._mesh.append(symbols)
        mesh = ca.vertsplit(symbols)  # each element taken once (indexing an SX is a call)
        starts = list(itertools.accumulate(mesh[:-1], initial=0))  # sum(mesh[:k]), each sum from the one before
        states = self._states(phase)
        previous = dict(state)
        if phase == "slip":  # the driven machine starts from rest: all of the driving speed is slip
            previous["slip"] = previous["driver_speed"]
        if phase == "locked":  # both halves at rest, nothing twisted yet
            previous.update(slip=0.0, twist=0.0)
        self.points.append((start_time, dict(previous)))
        interval = [(name, *states[name]) for _ in range(DEGREE) for name in states]
        interval += [("twist", d.twist_ref, 0.0, 2.0)] * DEGREE if phase == "locked" else []  # the link's twist
        values = iter(self._variables(phase, interval * n))  # where its torque meets the locked drive's
        chain = [previous]  # the phase start, then each interval's nodes 1..DEGREE (node 0: the one before)
        for k in range(n):
            nodes = [dict(chain[-1], **{name: next(values) for name in states}) for _ in range(DEGREE)]
            if phase == "locked":
                for node in nodes:
                    node["twist"] = next(values)
            chain += nodes
        nodes, count = chain[1:], n * DEGREE
        steps = [mesh[k] * duration for k in range(n)]
        step = ca.vertcat(*[steps[k] for k in range(n) for _ in range(DEGREE)])
        lengths = ca.vertcat(*[mesh[k] for k in range(n) for _ in range(DEGREE)])
        offsets = ca.vertcat(*[starts[k] for k in range(n) for _ in range(DEGREE)])
        taus = ca.DM(self.tau[1:] * n)
        times = start_time + (offsets + taus * lengths) * duration
        at = {name: ca.vertcat(*(node[name] for node in nodes)) for name in nodes[0]}
        equalities = []  # per kind, a vector over the phase's nodes
        if phase == "locked":
            equalities.append((d.link(at["driver_speed"], at["twist"])
                               - d.carried(at["driver_speed"], times)) / d.torque_ref)
        rates = self._rates(phase, times, at)
        c = self._phase_slopes(n)
        slopes = {name: c @ ca.vertcat(*(node[name] for node in chain)) for name in states}
        for name, (scale, _, _) in states.items():
            residual = slopes[name] - step * rates[name]
            if name == "driver_speed" and phase != "locked":  # J_m dw_a/dt = T_m - T: its terms' size
                scale = scale + lengths * typical * d.torque_ref / d.p.motor_inertia
            if name == "slip" and "driver_speed" in states:  # less the driver's equation: the machine's,
                residual = slopes["slip"] - slopes["driver_speed"] + step * rates["driven"]  # no 1/J_m in it
            equalities.append(residual / scale)
        rows = [ca.vertsplit(vector) for vector in equalities]
        self.equalities += [row[i] for i in range(count) for row in rows]
        self.points += zip(ca.vertsplit(times), nodes)
        self.nodes += nodes
        previous = chain[-1]
        self.equalities.append(self._phase_end(phase, previous, start_time + duration))
        return duration, previous

    def _phase_slopes(self, n: int) -> ca.DM:
        """The slopes at a phase's collocation points from its chain of node values (the phase start, then each
        interval's nodes 1..DEGREE): row k DEGREE + j - 1 holds l_r'(tau_j) at column k DEGREE + r."""
        c = np.zeros((n * DEGREE, n * DEGREE + 1))
        for k in range(n):
            c[k * DEGREE:(k + 1) * DEGREE, k * DEGREE:(k + 1) * DEGREE + 1] = self.c[:, 1:].T
        return ca.sparsify(ca.DM(c))

    @cached_property
    def mesh_parameters(self):
        """The interval lengths of every phase (NLP parameters), built once: each solve reads their count."""
        return ca.vertcat(*self._mesh)

    def initial_mesh(self, graded_part: float) -> np.ndarray:
        """The first mesh of every phase (:func:`~clutchopt.start_up.mesh.first_mesh`; ``graded_part``: the case's,
        :func:`~clutchopt.start_up.drive.graded_part`)."""
        return np.concatenate([first_mesh(self.s, phase, graded_part) for phase in self.s.phases])


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
        """The internal variables' bounds (scaled), built once (read only: each solve reads them)."""
        return self._bound_arrays

    @cached_property
    def _bound_arrays(self) -> tuple[np.ndarray, np.ndarray]:
        arrays = tuple(np.array(side) for side in zip(*self._bounds))
        for array in arrays:
            array.setflags(write=False)
        return arrays

    def outputs(self) -> dict:
        """Figures of the NLP's start (expressions): for the start_up report and the trajectory. Built once (each
        solve's report reads their names); not to be changed by the caller."""
        return self._figure_outputs

    @cached_property
    def _figure_outputs(self) -> dict:
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
        return dict(zip(TRAJECTORY, (times, driver, driven, work, heat, twist)))

    def phase_bounds(self, history, headline, engagement_squared: float, time_ref: float) -> dict:
        """Phase -> (begin, end) of a simulated start, which ends at its lock-up, or where the simulation ended (at
        most ``time_ref``) if it does not lock up: the motor's run-up to the engagement speed, the breakaway (until
        the driven machine moves), the slip until lock-up; an elastic link's locked phase all of it."""
        d = self.s
        locked = headline.get("locks_up") and math.isfinite(headline.get("start_time", math.inf))
        t = np.asarray(history["t"])
        t_end = headline["start_time"] if locked else min(time_ref, t[-1])
        driver = np.asarray(history["w_driver"])
        driven = np.asarray(history["w_driven"])
        engage = t[np.argmax(driver >= math.sqrt(engagement_squared))] if d.motor and d.radial else 0.0
        moving = driven > 1e-9 * max(driver.max(), 1e-300)
        breakaway = t[np.argmax(moving)] if d.load_at_rest and moving.any() else engage
        bounds = {"run_up": (0.0, engage), "breakaway": (engage, breakaway), "slip": (breakaway, t_end),
                  "locked": (0.0, t_end)}
        return {phase: (begin, max(end, begin)) for phase, (begin, end) in bounds.items()}

    def guess(self, history, headline, engagement_squared: float, time_ref: float, scales: np.ndarray,
              mesh: np.ndarray) -> np.ndarray:
        """Internal variables (scaled by ``scales``) from a simulation of the start design, which ends at its
        lock-up, or where the simulation ended (at most ``time_ref``) if it does not lock up."""
        d = self.s
        t = np.asarray(history["t"])  # a run's columns (arrays) or its history (a DataFrame)
        driver = np.asarray(history["w_driver"])
        driven = np.asarray(history["w_driven"])
        bounds = self.phase_bounds(history, headline, engagement_squared, time_ref)
        columns = {"driver_speed": driven if d.elastic else driver, "slip": driver - driven,
                   "friction_work": np.asarray(history["friction_work"]),
                   "temperature": np.asarray(history["temperature_rise"]),
                   "twist": np.asarray(history["twist"]) if "twist" in history else np.zeros_like(t)}
        n, tau = d.intervals, np.array(self.tau[1:])
        values, place = np.zeros(self.size), 0
        for index, phase in enumerate(d.phases):
            begin, end = bounds[phase]
            values[place] = end - begin
            lengths = mesh[index * n:(index + 1) * n]
            starts = np.concatenate([[0.0], np.cumsum(lengths)[:-1]])
            times = begin + (starts[:, None] + tau * lengths[:, None]) * (end - begin)  # (interval, node)
            names = list(self._states(phase))
            twists = DEGREE if phase == "locked" else 0
            width = DEGREE * len(names) + twists  # an interval's: its nodes' states, then (locked) their twists
            first = place + 1 + width * np.arange(n)[:, None]  # each interval's first place in the NLP's order
            for i, name in enumerate(names):  # each state interpolated at all its nodes of the phase at once
                values[first + np.arange(DEGREE) * len(names) + i] = np.interp(times, t, columns[name])
            if twists:
                values[first + DEGREE * len(names) + np.arange(DEGREE)] = np.interp(times, t, columns["twist"])
            place += 1 + width * n
        return values / scales


def initial_states(block: StartUpBlock, case, formulation, design: dict[str, float], scales: np.ndarray,
                   mesh: np.ndarray) -> np.ndarray:
    """The internal variables (scaled) of the start design's simulated start: a start point on the dynamics."""
    result, squared = _simulated_start(block, case, formulation, design)
    return block.guess(result.columns, result.headline, squared, case.values["max_start_time"], scales, mesh)


def mesh_of_the_start(block: StartUpBlock, case, formulation, design: dict[str, float]) -> np.ndarray:
    """A mesh adapted to the design's own simulated start (:func:`~clutchopt.start_up.mesh.adapted_mesh` over its
    simulated phases), where no solve of this design has given one: a design another mesh cannot collocate (the
    lighter side of a fold, ``optimise.problem.held_by_the_mesh``) is collocated on the mesh its start draws."""
    result, squared = _simulated_start(block, case, formulation, design)
    bounds = block.phase_bounds(result.columns, result.headline, squared, case.values["max_start_time"])
    return adapted_mesh(block.s, result.columns, [bounds[phase][1] - bounds[phase][0] for phase in block.s.phases],
                        graded_part(block.s.spec, case.values))


def first_mesh_of_the_start(block: StartUpBlock, case, formulation, design: dict[str, float]) -> np.ndarray:
    """The first mesh of a solve from ``design``, its slip phase graded over the motor's knee as the design's own
    simulated start shows it (:func:`~clutchopt.start_up.mesh.knee_part`; the simulation the start guess takes)."""
    graded = graded_part(block.s.spec, case.values)
    if "slip" not in block.s.phases:  # (an elastic link's locked phase: uniform)
        return block.initial_mesh(graded)
    result, squared = _simulated_start(block, case, formulation, design)
    bounds = block.phase_bounds(result.columns, result.headline, squared, case.values["max_start_time"])
    return block.initial_mesh(knee_part(block.s, result.columns, bounds["slip"], graded))


def _simulated_start(block: StartUpBlock, case, formulation, design: dict[str, float]):
    """The design's start simulated to GUESS_RTOL (up to 3 times max_start_time) and its engagement speed squared."""
    from clutchopt.simulate.ranges import TIME
    from clutchopt.start_up.simulation import start_guess

    model, result = start_guess(case, formulation.mode, design, GUESS_RTOL,
                                min(3.0 * case.values["max_start_time"], TIME[1]))
    return result, 0.0 if block.s.elastic else model.law.engagement_squared

