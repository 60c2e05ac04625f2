"""Couplings of clutchopt as friction laws of a start-up, and designs checked against the t_p they were sized for.

A centrifugal coupling's torque is proportional to the net radial force on each weight: for the wedge coupling
(eqs. 10-15 of Ambartsumyants & Deli) T = z f r_m (m_r r_c w_a^2 - F_s) / sin(alpha); for the lever coupling with
new linings (weight at R_0, spring slack) T = i f d_cp z m R_0 w_a^2 / (4 tan gamma_0). So a solved design gives
the torque per newton of radial force c_F = T / (m r w_d^2) from its torque T at the design speed w_d, its weight
mass m and the weight's radius r. Sizing assumes the
torque T_max = I_n w_a / t_p + T_c acts from the start at constant driving speed (constant angular acceleration,
eqs. 5, 17): then the simulated start-up time is exactly I_n w_a / (T - T_c), which is t_p when the torque
constraint is active.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from clutchopt.errors import InputError, Problems
from clutchopt.files import CASE_BYTES, read_text
from clutchopt.simulate import effects as fx
from clutchopt.simulate.engine import Model, SimulationResult, simulate
from clutchopt.simulate.laws import CentrifugalFriction, Load

# couplings whose solved designs give a speed-dependent torque law: outputs (torque, weight mass, weight radius)
SPEED_LAWS = {"wedge": ("torque", "weight_mass", "centroid_radius"),
              "lever": ("torque", "weight_mass", "start_radius")}


def speed_law_missing(coupling: str, solution=None) -> str | None:
    """Why a coupling (or its solution) cannot be started here, or None."""
    if coupling not in SPEED_LAWS:
        return (f"the {coupling} coupling has no speed-dependent torque law in clutchopt.simulate yet "
                f"(available: {', '.join(SPEED_LAWS)})")
    if solution is not None and solution.status != "optimal":
        return f"the solution's status is {solution.status}, there is no design to start"
    return None


# Valid range (SI) of each output a speed law is built from: a design JSON is a file like any other input.
DESIGN_RANGES = {"torque": (1e-9, 1e9, "N*m"), "weight_mass": (1e-9, 1e6, "kg"),
                 "centroid_radius": (1e-6, 1e2, "m"), "start_radius": (1e-6, 1e2, "m")}


def design_outputs(path: str | Path, coupling: str, case_path: str | Path | None = None) -> dict[str, float]:
    """Outputs (SI) of a solved design: the JSON of ``clutchopt solve --json`` (of the case file ``case_path``),
    those the speed law needs checked to be numbers in ``DESIGN_RANGES``."""
    field = "coupling.design"
    text = read_text(path, CASE_BYTES, f"{field} ({Path(path).name})")
    try:
        data = json.loads(text, parse_constant=_no_constant)
    except json.JSONDecodeError as exc:
        raise InputError(field, f"cannot read {path} as the JSON of clutchopt solve ({exc})") from None
    except ValueError as exc:
        raise InputError(field, f"{path}: {exc}") from None
    except RecursionError:
        raise InputError(field, f"{path}: JSON nested too deeply to be the output of clutchopt solve") from None
    if not isinstance(data, dict) or data.get("coupling") != coupling or not isinstance(data.get("outputs"), dict):
        raise InputError(field, f"{path} is not a solved {coupling} design (clutchopt solve --json)")
    if case_path is not None and Path(str(data.get("case", ""))).name != Path(case_path).name:
        raise InputError(field, f"{path} was solved for {_short(data.get('case'))}, not for {Path(case_path).name}")
    if data.get("status") != "optimal":
        raise InputError(field, f"{path}: the design's status is {_short(data.get('status'))}, not optimal")
    outputs = dict(data["outputs"])
    problems = Problems()
    for name in SPEED_LAWS[coupling]:
        low, high, unit = DESIGN_RANGES[name]
        value = outputs.get(name)
        number = isinstance(value, (int, float)) and not isinstance(value, bool)
        try:
            inside = number and low <= float(value) <= high
        except OverflowError:  # an integer beyond float64
            inside = False
        if not inside:
            problems.errors.append(InputError(f"{field} outputs.{name}", f"must be a number from {low:g} to "
                                                                         f"{high:g} {unit}, got {_short(value)}"))
        else:
            outputs[name] = float(value)
    problems.raise_any()
    return outputs


def _no_constant(name: str):
    raise ValueError(f"{name} is not a number a solved design can hold")


def _short(value) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:50] + "..."


def solved_outputs(solution) -> dict[str, float]:
    return {name: out.value for name, out in solution.outputs.items()}


def centrifugal_law(coupling: str, outputs: dict[str, float], design_speed: float, effects: tuple[str, ...],
                    spring_preload: float = 0.0) -> CentrifugalFriction:
    """The law of a solved design sized at ``design_speed``; spring preload and gravity enter only if listed."""
    torque, mass, radius = (outputs[name] for name in SPEED_LAWS[coupling])
    reductions = []
    if "spring_preload" in effects:
        reductions.append(lambda: fx.spring_preload(spring_preload))
    if "gravity" in effects:
        reductions.append(lambda: fx.gravity(mass))
    return CentrifugalFriction(torque / (mass * radius * design_speed**2), mass * radius, tuple(reductions))


def ideal_start(case, outputs: dict[str, float]) -> SimulationResult:
    """The start-up the sizing assumes: constant driving speed, constant resisting torque, no springs."""
    p = case.params()
    law = centrifugal_law(case.coupling, outputs, p.speed, ("slip_friction", "lockup"))
    return simulate(Model(law, p.inertia, Load(p.resisting_torque), ("slip_friction", "lockup"), driver_speed=p.speed))


def verify(case, solution) -> dict:
    """Simulate the optimised design from rest; achieved acceleration time against the sized t_p (SI)."""
    missing = speed_law_missing(case.coupling, solution)
    if missing:
        return {"verified": False, "reason": missing}
    p = case.params()
    result = ideal_start(case, solved_outputs(solution))
    achieved = result.headline["start_time"]
    return {
        "verified": result.headline["locks_up"],
        "reason": result.headline["reason"],
        "sized_acceleration_time": p.acceleration_time,
        "simulated_acceleration_time": achieved,
        "relative_difference": achieved / p.acceleration_time - 1.0 if math.isfinite(achieved) else math.inf,
        "friction_work": result.headline["friction_work"],
        "assumption": "constant driving speed and resisting torque, no springs (the sizing's constant acceleration)",
    }


def verify_text(check: dict) -> str:
    if "sized_acceleration_time" not in check:
        return f"verify: not simulated - {check['reason']}"
    if not check["verified"]:
        return f"verify: the design does not start up - {check['reason']}"
    return (f"verify: start-up simulated at constant driving speed: acceleration time "
            f"{check['simulated_acceleration_time']:.6g} s against t_p = {check['sized_acceleration_time']:.6g} s "
            f"({check['relative_difference']:+.2e}); friction work {check['friction_work']:.6g} J")


def report_figure(case, solution):
    """(Figure, caption) of a solved design's start-up at constant driving speed, or (None, reason)."""
    missing = speed_law_missing(case.coupling, solution)
    if missing:
        return None, missing
    from clutchopt.simulate.plot import history_figure

    p = case.params()
    result = ideal_start(case, solved_outputs(solution))
    h = result.headline
    if not h["locks_up"]:
        return history_figure(result, case.title), f"Start-up of the optimised design: {h['reason']}."
    caption = (f"Start-up of the optimised {case.coupling} design from rest at constant driving speed "
               f"{p.speed:.6g} rad/s against {p.resisting_torque:.6g} N*m: the driven machine reaches speed in "
               f"{h['start_time']:.4g} s (sized for t_p = {p.acceleration_time:.4g} s); friction work "
               f"{h['friction_work']:.4g} J, peak slip power {h['peak_slip_power']:.4g} W.")
    return history_figure(result, case.title), caption
