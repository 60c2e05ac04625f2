"""Start-up simulation: the right-hand side assembled from the listed effects; rest, slip and stick as phases.

Integrator: SciPy's solvers, DOP853 and Radau stepped by :mod:`clutchopt.simulate.stepping` (events on each step's
interpolant), LSODA in spans of ``odeint`` by :mod:`clutchopt.simulate.spans` (events on the spans' samples), a budget
of MAX_STEPS solver steps per run, chosen by the scene's stiffness; the phases only an induction motor moves (its
run-up to the weights' engagement, the locked drive at a constant load) in closed form where they are
(:mod:`clutchopt.simulate.motor_phases`). Without a motor the phases are smooth
and at most mildly stiff (the paper's law with a w0 = +1000 starts at its cap of 1e130 k, but the fast part lasts
no longer than the solver needs to resolve it), so DOP853 (explicit Runge-Kutta 8(5,3)) reaches 1e-10 relative at
low cost (docs/simulate.md). A motor adds a fast mode, its time constant J_m / (dT/dw) = J_m s_k w_s / (2 T_k), and
friction heat with a conductance another, C / G; where the faster is below 1 % of the start's time scale
(J + J_m) w / T an explicit method's steps are set by stability, not accuracy, and their number grows as the mode
gets faster (1e11 steps at J_m = 1e-9 kg m^2). There LSODA takes over with the Jacobian of the equations (it
switches to BDF when it detects stiffness), at a tenth of the relative tolerance, which makes it more accurate than
DOP853 at the full one; should its Newton iterations fail in a phase, Radau IIA (L-stable, the same Jacobian) takes
that phase again.

Every kink of the right-hand side is a phase boundary, so that each phase is smooth: the driven half breaking away
from rest (its friction torque reaching the load), the weights engaging (the driving speed reaching w_e), zero
slip (lock-up) and the static capacity exceeded (break loose). A steady slip (no lock-up) ends a run, and so does
the step budget, with a reason that names the start's time scales.

State y = [w_driver, slip w_r = w_driver - w_driven, friction work, work into the clutch from the driving half,
temperature rise]. The slip is integrated itself, not as a difference of speeds, so that the solver controls its
relative error as it goes to zero: a start-up whose torque barely exceeds the load spends most of its time at
small slip, and t_c is as accurate as the slip there.
Rest:        the driven half stands (w_r = w_a) while its friction torque is at most the load, a reaction up to its
             value; J_m dw_a/dt = T_motor - T_fr (motor_curve).
Slip phase:  J dw/dt = T_fr - T_load; J_m dw_a/dt = T_motor - T_fr (motor_curve), else w_a = const.
Stick phase (lockup): (J + J_m) dw/dt = T_motor - T_load; the clutch carries T = T_load + J dw/dt and breaks
loose when T exceeds its static capacity.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from clutchopt.errors import NOT_SIMULATED, InputError
from clutchopt.simulate import effects as fx
from clutchopt.simulate.laws import InductionMotor, Load
from clutchopt.simulate.on_floats import bound, parametrised
from clutchopt.simulate.motor_phases import in_closed_form, locked, run_up
from clutchopt.simulate.ranges import BREAKDOWN_SLIP, CONDUCTANCE, HEAT_CAPACITY, INERTIA, LOAD, SPEED, TIME, TORQUE
from clutchopt.simulate.spans import integrate_spans
from clutchopt.simulate.stepping import Budget, Phase, integrate

if TYPE_CHECKING:
    import pandas as pd

STEADY = 1e-9  # relative net acceleration below which a slipping start-up is steady (no lock-up)
MAX_SWITCHES = 200  # phase switches (rest, slip, stick, engagement) before a run is declared chattering
MAX_STEPS = 20_000  # solver steps per run: the runs of the tests take at most a few thousand
LSODA_STEPS = 5_000  # LSODA's steps in a phase before Radau takes it (its phases take a few hundred)
STIFF_RATIO = 0.01  # a mode faster than this fraction of the start-up's time scale makes the scene stiff
FIRST_SPAN = 1e-3  # of the start-up's time scale: LSODA's first span of a phase (clutchopt.simulate.spans)


@dataclass
class Model:
    """One start-up, SI: the friction law, the driven machine, the driver and the listed effects."""

    law: object
    inertia: float
    load: Load
    effects: tuple[str, ...]
    driver_speed: float = math.nan  # constant driving speed (no motor_curve)
    motor: InductionMotor | None = None
    heat_capacity: float = math.nan  # J/K (friction_heat)
    conductance: float = 0.0  # W/K (friction_heat)
    end_time: float | None = None  # None: until lock-up (+25 % locked), or until a verdict of no lock-up
    rtol: float = 1e-11
    integrator: str = "auto"  # by the scene's stiffness; "DOP853", "LSODA" or "Radau" to force one (benchmarks)

    def has(self, effect: str) -> bool:
        return effect in self.effects


@dataclass
class SimulationResult:
    """A run: its samples as columns (name -> NumPy array, one entry a sample), headline figures, events. The
    solve's check reads the columns; :attr:`history` is them as a pandas DataFrame, built when first asked for
    (pandas' import is 0.3 s, a start-up solve's check needs none of it)."""

    columns: dict[str, np.ndarray]
    headline: dict
    events: list[dict] = field(default_factory=list)

    @cached_property
    def history(self) -> pd.DataFrame:
        import pandas as pd

        return pd.DataFrame(self.columns)

    def as_dict(self) -> dict:
        return {"headline": self.headline, "events": self.events}


def _event(function, terminal: bool, direction: int):
    function.terminal, function.direction = terminal, direction
    return function


class _Rates:
    """The right-hand sides of a start-up's phases and the torques they are made of, at a state of numbers, at one of
    arrays (a column a sample: the events on a span's samples at once, clutchopt.simulate.spans) or at CasADi
    symbols: the law's, the load's and the motor's numbers may be symbols too, so that each right-hand side is
    traced once per structure and written out on floats (:func:`_flat`). A solver's state is read as numbers
    (y.tolist(): arithmetic on NumPy scalars costs twice)."""

    def __init__(self, law, load: Load, motor: InductionMotor | None, inertia, heat_capacity, conductance,
                 heat: bool):
        self.law, self.load, self.motor, self.inertia, self.heat = law, load, motor, inertia, heat
        self.heat_capacity, self.conductance = heat_capacity, conductance
        self.driver_inertia = motor.inertia if motor else 0.0
        self._own_excess = law.own_excess

    def friction(self, wa, slip):
        """The friction torque on the driven half (effect slip_friction) at numbers or at samples."""
        return self.law.kinetic_samples(wa, slip) if isinstance(wa, np.ndarray) else fx.slip_friction(self.law,
                                                                                                          wa, slip)

    def capacity(self, wa):
        """The static capacity at numbers or at samples."""
        law = self.law
        return law.capacity_samples(wa) if isinstance(wa, np.ndarray) else law.capacity(wa)

    def excess(self, wa, slip, friction, load):
        """Friction torque less load; a law with its own form of the difference (no cancellation) gives it."""
        return self.law.excess(wa, slip, load) if self._own_excess else friction - load

    def torques(self, t, y):
        """Friction torque on the driven half, driving torque (effect motor_curve), load."""
        wa, slip = y[0], y[1]
        drive = fx.motor_curve(self.motor, wa) if self.motor else 0.0
        return self.friction(wa, slip), drive, self.load(t, wa - slip)

    def _turning(self, kind: str, t, y) -> list:
        """Rates of a rest or a slip phase: of the driving half, the slip, the works and the heat."""
        y = y.tolist() if type(y) is np.ndarray and y.ndim == 1 else y
        wa, slip, rise = y[0], y[1], y[4]
        friction, drive, load = self.torques(t, y)
        dwa = (drive - friction) / self.driver_inertia if self.motor else 0.0
        power = friction * slip
        heat = fx.friction_heat(power, rise, self.heat_capacity, self.conductance) if self.heat else 0.0
        driven = self.excess(wa, slip, friction, load) / self.inertia if kind == "slip" else 0.0
        return [dwa, dwa - driven, power, friction * wa, heat]

    def slip(self, t, y):
        return self._turning("slip", t, y)

    def rest(self, t, y):
        """The driven half stands: all of the driving speed is slip."""
        return self._turning("rest", t, y)

    def carried(self, t, y):
        """Stick: common acceleration and the torque the clutch must carry."""
        _, drive, load = self.torques(t, y) if self.motor else (0.0, 0.0, self.load(t, y[0]))
        accel = (drive - load) / (self.inertia + self.driver_inertia) if self.motor else 0.0
        return accel, load + self.inertia * accel

    def stick(self, t, y):
        y = y.tolist() if type(y) is np.ndarray and y.ndim == 1 else y
        accel, torque = self.carried(t, y)
        heat = fx.friction_heat(0.0, y[4], self.heat_capacity, self.conductance) if self.heat else 0.0
        return [accel, 0.0, 0.0, torque * y[0], heat]


def _flat(run: _Run) -> dict:
    """The run's right-hand side of each phase (``rest``, ``slip``, ``stick``) for the solver: the equations of
    :class:`_Rates` traced once per structure (law, load and effects; their numbers parameters) and written out as
    one Python function on floats (:func:`clutchopt.simulate.on_floats.bound`), bound to this run's numbers and
    compared with the equations at probes; the equations themselves where they cannot be traced (a load table, the
    paper's law) or the probes differ."""
    m = run.m
    objects = parametrised(m.law, m.load, run.motor, m.inertia, m.heat_capacity, m.conductance)
    w = run.w_ref
    probes = [(t, np.array([wa, slip, 0.0, 0.0, rise])) for t in (0.0, run.time_scale)
              for wa, slip, rise in ((0.3 * w, 0.3 * w, 0.0), (0.9 * w, 0.2 * w, 2.0), (1.02 * w, 1e-3 * w, 5.0))]
    flat = {}
    for kind in ("rest", "slip", "stick"):
        flat[kind] = bound(lambda *rebuilt, kind=kind: getattr(_Rates(*rebuilt, run.heat), kind), (0, 5), objects,
                           ("engine", kind, run.heat), getattr(run, kind), probes)
    return flat


class _Run(_Rates):
    """The assembled right-hand sides of one model and their Jacobians; only listed effects are called."""

    def __init__(self, model: Model):
        self.m = model
        super().__init__(model.law, model.load, model.motor if model.has("motor_curve") else None, model.inertia,
                         model.heat_capacity, model.conductance, model.has("friction_heat"))
        self.w_ref = self.motor.synchronous_speed if self.motor else model.driver_speed
        self.torque_scale = max(model.law.capacity(self.w_ref), model.load.largest(), 1e-300)
        self.time_scale = (model.inertia + self.driver_inertia) * self.w_ref / self.torque_scale
        energy = self.torque_scale * self.w_ref * self.time_scale
        heat = energy / model.heat_capacity if self.heat else 1.0
        speed = min(self.w_ref, model.law.slip_scale)  # the paper's law changes over 1/|a| of slip
        modes = {}  # the fast modes a start may have, by what makes them
        if self.motor:
            modes["the motor's time constant J_m s_k w_s / (2 T_k)"] = self.motor.time_constant
        if self.heat and model.conductance > 0:
            modes["the heat's time constant C / G"] = model.heat_capacity / model.conductance
        self.fastest = min(modes.items(), key=lambda mode: mode[1], default=None)
        stiff = self.fastest is not None and self.fastest[1] < STIFF_RATIO * self.time_scale
        self.method = model.integrator if model.integrator != "auto" else "LSODA" if stiff else "DOP853"
        self.state_scale = np.array([speed, 1e-6 * speed, energy, energy, heat])  # absolute tolerance per rtol
        self.budget = Budget(MAX_STEPS)
        self._last = None, None  # (kind, t, y) and the rates there
        self._last_samples = None, None, None, None  # (kind, times, states, rates) of the last samples (arrays)
        self.flat = _flat(self)  # the solver's right-hand sides

    def integrate(self, kind: str, t: float, bound: float, y, events: list) -> Phase:
        """One phase (``rest``, ``slip`` or ``stick``); LSODA at a tenth of the tolerance, and should it fail (its
        stiff Newton iterations can stall) or take more than LSODA_STEPS (its switch to BDF can lag a mode 1e9
        times faster than the start), Radau takes the phase again, LSODA charged LSODA_STEPS at most: a span of
        its samples can overrun its steps many times (they are counted after each span), and how far is not
        LSODA's own to decide (scipy's odeint: a heat mode 2,600 times faster than the start ran 46 or 32,712 steps
        in one span from the same state, one run in two, reading memory of an earlier run), so that Radau, not the
        run's luck, gives the verdict."""
        rates = self.flat[kind]
        jacobian = {"rest": self.rest_jacobian, "slip": self.slip_jacobian, "stick": self.stick_jacobian}[kind]
        if self.method != "LSODA":
            return integrate(rates, jacobian, t, y, bound, events, self.method, self.m.rtol,
                             self.m.rtol * self.state_scale, self.budget)
        rtol, budget = self.m.rtol / 10, self.budget
        trial = Budget(min(budget.steps, budget.taken + LSODA_STEPS), budget.taken)
        phase = integrate_spans(getattr(rates, "into", rates), jacobian, t, y, bound, events, rtol,  # (odeint copies
                                rtol * self.state_scale, trial, FIRST_SPAN * self.time_scale)  # the array at once;
        # solve_ivp's methods keep a step's rates: theirs the list)
        budget.taken = min(trial.taken, trial.steps)
        if phase.status == "failed" or (phase.status == "budget" and not budget.spent):
            phase = integrate(rates, jacobian, t, y, bound, events, "Radau", self.m.rtol,
                              self.m.rtol * self.state_scale, budget)
        return phase

    # --- their Jacobians -----------------------------------------------------------------------------------------
    def _turning_jacobian(self, y, slopes, driven=None) -> np.ndarray:
        """Jacobian of the rest rates, the friction torque's ``slopes`` (dT/dw_a, dT/dw_r) at ``y`` given; ``driven``:
        the slip phase's driven-half terms (d(net torque)/dw_a, d(net torque)/dw_r over J) taken from the slip's row.
        Its entries as numbers, the array built once (an array filled row by row cost 10 us a call)."""
        wa, slip = y[0], y[1]
        friction, (by_speed, by_slip) = self.m.law.kinetic(wa, slip), slopes
        if self.motor:
            drive = ((self.motor.slope(wa) - by_speed) / self.driver_inertia, -by_slip / self.driver_inertia)
        else:
            drive = (0.0, 0.0)
        rates = [[drive[0], drive[1], 0.0, 0.0, 0.0],
                 [drive[0], drive[1], 0.0, 0.0, 0.0] if driven is None else
                 [drive[0] - driven[0], drive[1] - driven[1], 0.0, 0.0, 0.0],
                 [by_speed * slip, by_slip * slip + friction, 0.0, 0.0, 0.0],
                 [by_speed * wa + friction, by_slip * wa, 0.0, 0.0, 0.0],
                 [0.0, 0.0, 0.0, 0.0, 0.0]]
        if self.heat:
            capacity = self.m.heat_capacity
            rates[4] = [entry / capacity for entry in rates[2][:4]] + [-self.m.conductance / capacity]
        return np.array(rates)

    def slip_jacobian(self, t, y):
        slopes = self.m.law.slopes(y[0], y[1])
        load = self.m.load.slope(t, y[0] - y[1])
        return self._turning_jacobian(y, slopes, ((slopes[0] - load) / self.m.inertia,
                                                  (slopes[1] + load) / self.m.inertia))

    def rest_jacobian(self, t, y):
        return self._turning_jacobian(y, self.m.law.slopes(y[0], y[1]))

    def stick_jacobian(self, t, y):
        """Of (dw/dt, T y[0]) as :meth:`carried` gives them: with a motor the load at the driven speed w_a - w_r,
        without one at the driving speed (entries as numbers, the array built once)."""
        if self.motor:
            load = self.m.load.slope(t, y[0] - y[1])
            both = self.m.inertia + self.driver_inertia
            accel = ((self.motor.slope(y[0]) - load) / both, load / both)
            torque_slopes = (load + self.m.inertia * accel[0], -load + self.m.inertia * accel[1])
        else:
            accel = (0.0, 0.0)
            torque_slopes = (self.m.load.slope(t, y[0]), 0.0)
        rates = [[accel[0], accel[1], 0.0, 0.0, 0.0], [0.0] * 5, [0.0] * 5,
                 [y[0] * torque_slopes[0] + self.carried(t, y)[1], y[0] * torque_slopes[1], 0.0, 0.0, 0.0],
                 [0.0, 0.0, 0.0, 0.0, -self.m.conductance / self.m.heat_capacity if self.heat else 0.0]]
        return np.array(rates, dtype=float)

    # --- phases and their events ---------------------------------------------------------------------------------
    def turning_kind(self, t, y) -> str:
        """``rest`` while the driven half stands and its friction torque is at most the load, else ``slip``."""
        at_rest = y[0] - y[1] <= 0.0 and self.starting(t, y) <= 0.0
        return "rest" if at_rest else "slip"

    def starting(self, t, y):
        """Friction torque less load with the driven half at rest: positive once it breaks away."""
        friction = self.friction(y[0], y[1])
        return self.excess(y[0], y[1], friction, self.m.load(t, 0.0 * y[0]))

    def turning_rates(self, kind: str, t, y) -> list:
        """The rates of a rest or slip phase; the last point's kept, as the events evaluate it after each step,
        and the last samples' (arrays: a span's, which the events ``steady`` and ``peak`` both read)."""
        if isinstance(t, np.ndarray):
            kept_kind, kept_t, kept_y, rates = self._last_samples
            if not (kept_kind == kind and kept_t is t and kept_y is y):
                rates = self.rest(t, y) if kind == "rest" else self.slip(t, y)
                self._last_samples = kind, t, y, rates
            return rates
        key = (kind, t, y.tobytes())
        if self._last[0] != key:
            self._last = key, self.flat[kind](t, y)
        return self._last[1]

    def net_rate(self, kind: str, t, y) -> float:
        d = self.turning_rates(kind, t, y)
        return (abs(d[0]) + abs(d[0] - d[1])) * self.time_scale / self.w_ref

    def turning_events(self, kind: str, engaged: bool, steady_armed: bool) -> dict:
        """Events of a rest or slip phase by name: the terminal ones end it, ``peak`` samples the temperature's
        maximum. ``engaged``: the driving speed has reached the engagement speed (which a motor never falls below
        again: there the coupling's torque is zero)."""
        law = self.m.law
        events = {}
        if kind == "rest":
            events["starts"] = _event(lambda t, y: self.starting(t, y), True, 1)
        else:
            events["lock"] = _event(lambda t, y: y[1], True, -1)
            events["stops"] = _event(lambda t, y: y[0] - y[1], True, -1)
            events["stops"].strict = True  # the driven speed falls to zero, not a rounding of w_a - w_r at its start
        if not engaged:
            events["engages"] = _event(lambda t, y: y[0] ** 2 - law.engagement_squared, True, 1)
        if steady_armed:
            events["steady"] = _event(lambda t, y: self.net_rate(kind, t, y) - STEADY, True, -1)
        if self.heat:
            events["peak"] = _event(lambda t, y: self.turning_rates(kind, t, y)[4], False, -1)
        return events

    def budget_reason(self, t: float) -> str:
        """Why a run stopped at the step budget: the start's time scales."""
        fast = f", {self.fastest[0]} {self.fastest[1]:.3g} s" if self.fastest else ""
        return (f"stopped after {MAX_STEPS} solver steps at t = {t:.6g} s, not yet at a verdict: the start is too "
                f"long or too stiff to simulate (its time scale (J + J_m) w / T {self.time_scale:.3g} s{fast}, "
                f"integrated with {self.method})")


def range_problems(model: Model) -> list[str]:
    """What of a model lies outside the ranges the simulator is tested over (empty if nothing)."""
    motor = model.motor if model.has("motor_curve") else None
    speed = motor.synchronous_speed if motor else model.driver_speed
    checks = [("driven inertia", model.inertia, INERTIA), ("driving speed", speed, SPEED),
              ("load torque", model.load.largest(), LOAD),
              ("clutch torque at the driving speed", model.law.capacity(speed), (0.0, 2 * TORQUE[1], "N*m"))]  # 2k
    if motor:
        checks += [("motor breakdown torque", motor.breakdown_torque, TORQUE),
                   ("motor inertia", motor.inertia, INERTIA),
                   ("motor breakdown slip", motor.breakdown_slip, BREAKDOWN_SLIP)]
    if model.has("friction_heat"):
        checks += [("heat capacity", model.heat_capacity, HEAT_CAPACITY),
                   ("heat conductance", model.conductance, CONDUCTANCE)]
    if model.end_time is not None:
        checks.append(("end time", model.end_time, TIME))
    return [f"{name} {value:.6g} {unit} is outside {low:g} to {high:g} {unit}".replace("  ", " ")
            for name, value, (low, high, unit) in checks if not low <= value <= high]


def simulate(model: Model) -> SimulationResult:
    """Run the start-up from rest of the driven half (and of the motor, with motor_curve); a model outside the
    simulator's ranges is an InputError (``start-up: ...``) instead of a run that may never end."""
    problems = range_problems(model)
    if problems:
        raise InputError(NOT_SIMULATED, f"not simulated: {'; '.join(problems)} (the ranges the simulator is tested "
                                     "over)")
    run = _Run(model)
    verdict = None
    if not run.motor and model.load.constant:  # closed-form verdict: does the start-up lock up at all?
        verdict = model.law.lockup_failure(model.driver_speed, model.load.torque, model.inertia)
    closed_form_locks = not run.motor and model.load.constant and verdict is None
    loose = _event(lambda t, y: run.capacity(y[0]) - run.carried(t, y)[1], True, -1)
    bound = model.end_time if model.end_time is not None else (1e300 if closed_form_locks else 1e8 * run.time_scale)
    start = 0.0 if run.motor else model.driver_speed
    t, y = 0.0, np.array([start, start, 0.0, 0.0, 0.0])
    rows, events, kind = [], [], run.turning_kind(0.0, y)
    engaged = not run.motor or start**2 >= model.law.engagement_squared
    start_time, reason, start_state, decided = math.nan, "", None, True
    if not closed_form_locks and run.net_rate(kind, 0.0, y) <= STEADY:
        reason = verdict or "no lock-up: the driven half does not start (friction torque <= load at rest)"
    for _ in range(MAX_SWITCHES):
        if reason or t >= bound:
            break
        armed = {"loose": loose} if kind == "stick" else run.turning_events(kind, engaged, not closed_form_locks)
        span, out = FIRST_SPAN * run.time_scale, None  # (the motor's phases in closed form where they are)
        if kind == "rest" and not engaged and in_closed_form(run, y, STEADY):
            out = run_up(run, t, y, bound, span, list(armed).index("engages"))
        elif kind == "stick":
            out = locked(run, t, y, bound, span, list(armed.values()))
        out = out or run.integrate(kind, t, bound, y, list(armed.values()))
        if kind == "rest":
            out.y[1] = out.y[0]  # the driven half stands: all of the driving speed is slip, exactly
        rows.append(_samples(run, out, "stick" if kind == "stick" else "slip"))
        t, y = out.t[-1], out.y[:, -1].copy()
        if out.status != "event":
            if out.status == "failed":
                reason, decided = f"integration failed: {out.message}", False
            elif out.status == "budget":
                reason, decided = run.budget_reason(t), False
            elif math.isnan(start_time):  # (a scene's end time before lock-up decides nothing: review 34)
                decided = bool(verdict) or model.end_time is None
                reason = verdict or (f"no lock-up by the end time {bound:.6g} s" if decided else
                                     f"not locked up by the scene's end time {bound:.6g} s, where the run stops")
            break
        name = list(armed)[out.event]
        if name == "loose":
            events.append({"time": t, "event": "break loose", "torque": run.carried(t, y)[1]})
            kind = run.turning_kind(t, y)
            continue
        if name in ("starts", "stops", "engages"):  # the phase an event leads to, not the state's rounding
            kind = {"starts": "slip", "stops": "rest"}.get(name, kind)
            engaged = engaged or name == "engages"
            if name == "stops":
                y[1] = y[0]
            continue
        if name == "steady":
            reason = verdict or _steady_reason(run, t, y)
            break
        y[1] = 0.0  # slip reached zero
        if math.isnan(start_time):
            start_time, start_state = t, y.copy()
        events.append({"time": t, "event": "lock-up" if model.has("lockup") else "zero slip", "torque": math.nan})
        if not model.has("lockup"):
            break
        needed = run.carried(t, y)[1]
        if needed <= model.law.capacity(y[0]) * (1 + 1e-12):
            events[-1]["torque"] = needed
            kind = "stick"
            if model.end_time is None:
                bound = t + 0.25 * t
        else:
            events[-1]["event"] = "zero slip, capacity too small to stick"
    else:
        reason, decided = f"stopped after {MAX_SWITCHES} stick-slip switches (chatter)", False
    history = _history(rows or [_samples(run, None, "slip", y)])
    return SimulationResult(history, _headline(model, history, start_time, start_state, reason, y, decided), events)


def largest(values: np.ndarray) -> float:
    """The largest sample, NaN left out (as pandas' max)."""
    kept = values[~np.isnan(values)]
    return float(kept.max()) if kept.size else math.nan


def _steady_reason(run: _Run, t: float, y) -> str:
    friction, _, load = run.torques(t, y)
    if y[0] - y[1] <= 0.0:
        return (f"no lock-up: the driven half stays at rest, clutch torque {friction:.6g} N*m <= load {load:.6g} N*m "
                f"at driving speed {y[0]:.6g} rad/s")
    return (f"no lock-up: steady slip {y[1]:.6g} rad/s at driving speed {y[0]:.6g} rad/s, clutch torque "
            f"{friction:.6g} N*m = load")


def _samples(run: _Run, out: Phase | None, phase: str, y0=None) -> tuple:
    """(times, states, torques, phase) of one phase: the solver's steps and the middle of each (``out``), or the
    state ``y0``."""
    t, y = (np.array([0.0]), np.asarray(y0, dtype=float).reshape(-1, 1)) if out is None else (out.t, out.y)
    if phase == "stick":
        torque = np.broadcast_to(np.asarray(run.carried(t, y)[1], dtype=float), t.shape)  # every sample at once
    else:  # the friction torque (slip_friction) at every sample at once
        torque = run.m.law.kinetic_samples(y[0], y[1])
    return t, y, torque, phase


def _history(phases: list[tuple]) -> dict[str, np.ndarray]:
    """The run's history columns, one entry a sample (:func:`_samples` of each phase), built at once (a frame per
    phase, concatenated, was 15 % of a run)."""
    t = np.concatenate([p[0] for p in phases])
    y = np.concatenate([p[1] for p in phases], axis=1)
    torque = np.concatenate([np.asarray(p[2], dtype=float) for p in phases])
    phase = np.repeat(np.array([p[3] for p in phases], dtype=object), [len(p[0]) for p in phases])  # (the name
    # itself a sample: np.full of a string made a new one a sample, 85 against 13 us a run of 1,300 samples)
    return {"t": t, "w_driver": y[0], "w_driven": y[0] - y[1], "slip": y[1], "friction_torque": torque,
            "power_lost": torque * y[1], "friction_work": y[2], "source_work": y[3], "temperature_rise": y[4],
            "phase": phase}


def _headline(model, history, start_time, start_state, reason, y_end, decided: bool = True) -> dict:
    """Headline figures in SI; L and L_s are taken at the first lock-up (the start-up), totals at the end.
    ``locks_up``: None where the run stopped without a verdict (``decided`` false: the step budget spent, the
    integration failed, chatter), not False: no one knows whether it locks up
    (:func:`clutchopt.records.lock_up_verdict`)."""
    locked = start_state is not None
    at_start = start_state if locked else y_end
    headline = {
        "locks_up": (locked and not reason) if decided else None,
        "reason": reason,
        "start_time": start_time if locked else math.inf,
        "friction_work": at_start[2] if locked else math.inf,
        "source_work": at_start[3] if locked else math.inf,
        "lock_up_speed": at_start[0] if locked else math.nan,
        "peak_slip_power": largest(history["power_lost"]),
        "end_time": float(history["t"][-1]),
        "total_friction_work": float(y_end[2]),
        "final_driver_speed": float(y_end[0]),
        "final_driven_speed": float(y_end[0] - y_end[1]),
        "effects": list(model.effects),
    }
    if model.has("friction_heat"):
        headline["temperature_rise"] = largest(history["temperature_rise"])
    return headline
