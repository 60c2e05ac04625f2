"""Start-up simulation: the right-hand side assembled from the listed effects, stick and slip as events.

Integrator: SciPy's ``solve_ivp``, chosen by the scene's stiffness. Without a motor the phases are smooth between
events and at most mildly stiff (the paper's law with a w0 = +1000 starts at its cap of 1e130 k, but the fast
part lasts no longer than the solver needs to resolve it), so DOP853 (explicit Runge-Kutta 8(5,3)) reaches
1e-10 relative at low cost (see docs/simulate.md for what accuracy needed). A motor adds a fast mode, its time
constant J_m / (dT/dw); where that is below 1 % of the start-up's time scale an explicit method's steps are set
by stability, not accuracy, and LSODA (which switches to BDF when it detects stiffness; Radau and BDF alone fail on
the friction torque's sign change) takes over at a tenth of the relative tolerance, which makes it at least as
accurate as DOP853 at the full one. Events locate zero slip (lock-up), the static capacity being exceeded (break
loose) and a steady slip (no lock-up) on the dense output. CasADi's integrators (CVODES/IDAS) would need the
stick/slip switching written around them and bring no accuracy we lack; they remain the choice if a scene ever
enters an optimisation.

State y = [w_driver, slip w_r = w_driver - w_driven, friction work, work into the clutch from the driving half,
temperature rise]. The slip is integrated itself, not as a difference of speeds, so that the solver controls its
relative error as it goes to zero: a start-up whose torque barely exceeds the load spends most of its time at
small slip, and t_c is as accurate as the slip there.
Slip phase:  J dw/dt = T_fr sign(w_r) - T_load (the driven half rests while T_fr <= T_load at w = 0);
             J_m dw_a/dt = T_motor - T_fr (motor_curve), else w_a = const.
Stick phase (lockup): (J + J_m) dw/dt = T_motor - T_load; the clutch carries T = T_load + J dw/dt and breaks
loose when T exceeds its static capacity.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
from scipy.integrate import solve_ivp

from clutchopt.errors import InputError
from clutchopt.simulate import effects as fx
from clutchopt.simulate.laws import InductionMotor, Load
from clutchopt.simulate.ranges import BREAKDOWN_SLIP, CONDUCTANCE, HEAT_CAPACITY, INERTIA, LOAD, SPEED, TIME, TORQUE

STEADY = 1e-9  # relative net acceleration below which a slipping start-up is steady (no lock-up)
MAX_SWITCHES = 200  # stick/slip switches before a run is declared chattering
SAMPLES = 400  # dense-output samples per phase for the history
STIFF_RATIO = 0.01  # a mode faster than this fraction of the start-up's time scale makes the scene stiff


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
    integrator: str = "auto"  # by the scene's stiffness; "DOP853" or "LSODA" to force one (benchmarks)

    def has(self, effect: str) -> bool:
        return effect in self.effects


@dataclass
class SimulationResult:
    history: pd.DataFrame
    headline: dict
    events: list[dict] = field(default_factory=list)

    def as_dict(self) -> dict:
        return {"headline": self.headline, "events": self.events}


class _Run:
    """The assembled right-hand sides of one model; only listed effects are called."""

    def __init__(self, model: Model):
        self.m = model
        self.motor = model.motor if model.has("motor_curve") else None
        self.heat = model.has("friction_heat")
        self.w_ref = self.motor.synchronous_speed if self.motor else model.driver_speed
        self.torque_scale = max(model.law.capacity(self.w_ref), model.load.largest(), 1e-300)
        self.driver_inertia = self.motor.inertia if self.motor else 0.0
        self.time_scale = (model.inertia + self.driver_inertia) * self.w_ref / self.torque_scale
        energy = self.torque_scale * self.w_ref * self.time_scale
        heat = energy / model.heat_capacity if self.heat else 1.0
        speed = min(self.w_ref, model.law.slip_scale)  # the paper's law changes over 1/|a| of slip
        stiff = self.motor is not None and self.motor.time_constant < STIFF_RATIO * self.time_scale
        self.method = model.integrator if model.integrator != "auto" else "LSODA" if stiff else "DOP853"
        self.state_scale = np.array([speed, 1e-6 * speed, energy, energy, heat])  # absolute tolerance per rtol

    def integrate(self, rhs, t: float, bound: float, y, events, method: str | None = None):
        """One phase by ``solve_ivp``; LSODA at a tenth of the tolerance, and should it fail (its stiff Newton
        iterations can stall at a kink of the friction law), DOP853 takes the phase again."""
        method = method or self.method
        rtol = self.m.rtol / 10 if method == "LSODA" else self.m.rtol
        with warnings.catch_warnings(record=True) as warned:  # LSODA warns of convergence failures, then fails
            warnings.simplefilter("always")
            sol = solve_ivp(rhs, (t, bound), y, method=method, rtol=rtol, atol=rtol * self.state_scale, events=events,
                            dense_output=True)
        if method == "LSODA" and (sol.status < 0 or warned):
            return self.integrate(rhs, t, bound, y, events, "DOP853")
        for warning in warned:
            warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)
        return sol

    def torques(self, t, y):
        """Friction torque on the driven half, driving torque, load."""
        wa, slip = y[0], y[1]
        friction = fx.slip_friction(self.m.law, wa, slip)
        drive = fx.motor_curve(self.motor, wa) if self.motor else 0.0
        return friction, drive, self.m.load(t, wa - slip)

    def _heat(self, power, y):
        return fx.friction_heat(power, y[4], self.m.heat_capacity, self.m.conductance) if self.heat else 0.0

    def slip(self, t, y):
        friction, drive, load = self.torques(t, y)
        net = self.m.law.excess(y[0], y[1], load)
        if y[0] - y[1] <= 0.0 and net < 0.0:
            net = 0.0  # at rest the load is a reaction up to its value
        dwa = (drive - friction) / self.driver_inertia if self.motor else 0.0
        power = friction * y[1]
        return [dwa, dwa - net / self.m.inertia, power, friction * y[0], self._heat(power, y)]

    def carried(self, t, y):
        """Stick: common acceleration and the torque the clutch must carry."""
        _, drive, load = self.torques(t, y) if self.motor else (0.0, 0.0, self.m.load(t, y[0]))
        accel = (drive - load) / (self.m.inertia + self.driver_inertia) if self.motor else 0.0
        return accel, load + self.m.inertia * accel

    def stick(self, t, y):
        accel, torque = self.carried(t, y)
        return [accel, 0.0, 0.0, torque * y[0], self._heat(0.0, y)]

    def net_rate(self, t, y):
        d = self.slip(t, y)
        return (abs(d[0]) + abs(d[0] - d[1])) * self.time_scale / self.w_ref


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
        raise InputError("start-up", f"not simulated: {'; '.join(problems)} (the ranges the simulator is tested "
                                     "over)")
    run = _Run(model)
    verdict = None
    if not run.motor and model.load.constant:  # closed-form verdict: does the start-up lock up at all?
        verdict = model.law.lockup_failure(model.driver_speed, model.load.torque, model.inertia)
    closed_form_locks = not run.motor and model.load.constant and verdict is None

    def lock(t, y):
        return y[1]

    lock.terminal, lock.direction = True, -1

    def steady(t, y):
        return run.net_rate(t, y) - STEADY

    steady.terminal, steady.direction = True, -1

    def loose(t, y):
        return model.law.capacity(y[0]) - run.carried(t, y)[1]

    loose.terminal, loose.direction = True, -1

    bound = model.end_time if model.end_time is not None else (1e300 if closed_form_locks else 1e8 * run.time_scale)
    start = 0.0 if run.motor else model.driver_speed
    t, y = 0.0, np.array([start, start, 0.0, 0.0, 0.0])
    frames, events, phase = [], [], "slip"
    start_time, reason, start_state = math.nan, "", None
    if not closed_form_locks and run.net_rate(0.0, y) <= STEADY:
        reason = verdict or "no lock-up: the driven half does not start (friction torque <= load at rest)"
    for _ in range(MAX_SWITCHES):
        if reason or t >= bound:
            break
        if phase == "slip":
            event_list = [lock] if closed_form_locks else [lock, steady]
            sol = run.integrate(run.slip, t, bound, y, event_list)
        else:
            sol = run.integrate(run.stick, t, bound, y, [loose])
        frames.append(_samples(run, sol, phase))
        t, y = sol.t[-1], sol.y[:, -1].copy()
        if sol.status != 1:  # reached the end time (or failed)
            if sol.status < 0:
                reason = f"integration failed: {sol.message}"
            elif math.isnan(start_time):
                reason = verdict or f"no lock-up by the end time {bound:.6g} s"
            break
        if phase == "stick":
            events.append({"time": t, "event": "break loose", "torque": run.carried(t, y)[1]})
            phase = "slip"
            continue
        if event_list[-1] is steady and sol.t_events[-1].size:
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
            phase = "stick"
            if model.end_time is None:
                bound = t + 0.25 * t
        else:
            events[-1]["event"] = "zero slip, capacity too small to stick"
    else:
        reason = f"stopped after {MAX_SWITCHES} stick-slip switches (chatter)"
    history = pd.concat(frames, ignore_index=True) if frames else _samples(run, None, "slip", y)
    return SimulationResult(history, _headline(model, history, start_time, start_state, reason, y), events)


def _steady_reason(run: _Run, t: float, y) -> str:
    friction, _, load = run.torques(t, y)
    if y[0] - y[1] <= 0.0:
        return (f"no lock-up: the driven half stays at rest, clutch torque {friction:.6g} N*m <= load {load:.6g} N*m "
                f"at driving speed {y[0]:.6g} rad/s")
    return (f"no lock-up: steady slip {y[1]:.6g} rad/s at driving speed {y[0]:.6g} rad/s, clutch torque "
            f"{friction:.6g} N*m = load")


def _samples(run: _Run, sol, phase: str, y0=None) -> pd.DataFrame:
    """History rows: the solver's steps and evenly spaced dense-output samples of one phase."""
    if sol is None:
        t, y = np.array([0.0]), np.asarray(y0).reshape(-1, 1)
    elif sol.sol is None or len(sol.t) < 2:  # the first step failed: there is no dense output to sample
        t, y = sol.t, sol.y
    else:
        t = np.union1d(sol.t, np.linspace(sol.t[0], sol.t[-1], SAMPLES))
        y = sol.sol(t)
        y[:, np.searchsorted(t, sol.t)] = sol.y  # exact step values where we have them
    rows = []
    for i, ti in enumerate(t):
        yi = y[:, i]
        if phase == "stick":
            torque = run.carried(ti, yi)[1]
        else:
            torque = run.torques(ti, yi)[0]
        slip = yi[1]
        rows.append((ti, yi[0], yi[0] - slip, slip, torque, torque * slip, yi[2], yi[3], yi[4], phase))
    return pd.DataFrame(rows, columns=["t", "w_driver", "w_driven", "slip", "friction_torque", "power_lost",
                                       "friction_work", "source_work", "temperature_rise", "phase"])


def _headline(model, history, start_time, start_state, reason, y_end) -> dict:
    """Headline figures in SI; L and L_s are taken at the first lock-up (the start-up), totals at the end."""
    locked = start_state is not None
    at_start = start_state if locked else y_end
    headline = {
        "locks_up": locked and not reason,
        "reason": reason,
        "start_time": start_time if locked else math.inf,
        "friction_work": at_start[2] if locked else math.inf,
        "source_work": at_start[3] if locked else math.inf,
        "lock_up_speed": at_start[0] if locked else math.nan,
        "peak_slip_power": float(history["power_lost"].max()),
        "end_time": float(history["t"].iloc[-1]),
        "total_friction_work": float(y_end[2]),
        "final_driver_speed": float(y_end[0]),
        "final_driven_speed": float(y_end[0] - y_end[1]),
        "effects": list(model.effects),
    }
    if model.has("friction_heat"):
        headline["temperature_rise"] = float(history["temperature_rise"].max())
    return headline
