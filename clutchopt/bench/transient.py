"""The simulator's accuracy against time, and what each listed effect costs.

- Tolerance: the paper scene (constant driving speed, the paper's friction law) simulated at several relative
  tolerances of ``solve_ivp`` (DOP853); the start time t_c and friction work L against the closed forms.
- Effects: the solved wedge design on an induction motor with return springs, simulated with the effects
  switched on one by one (the right-hand side evaluates only the listed effects).
- Stiffness: that motor scene (stiff: the motor's time constant is 0.2 % of the start-up's time scale) by DOP853
  and by the integrator the engine picks (LSODA at a tenth of the tolerance), against DOP853 at rtol 1e-13.
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

from clutchopt.bench.timing import repeated
from clutchopt.cases import read_toml
from clutchopt.simulate.analytic import PaperTransient
from clutchopt.simulate.engine import simulate
from clutchopt.simulate.scene import load_scene, parse_scene

SCENES = Path(__file__).resolve().parents[2] / "cases" / "scenes"
TOLERANCES = (1e-4, 1e-6, 1e-8, 1e-10, 1e-12)
EFFECT_STEPS = ("slip_friction", "lockup", "spring_preload", "gravity", "motor_curve", "friction_heat")


def _relative(value: float, reference: float) -> float:
    return abs(value - reference) / abs(reference)


def tolerance_rows(config) -> list[dict]:
    """t_c and L of the paper scene against the closed forms, per integrator tolerance."""
    scene = load_scene(SCENES / "paper_transient.toml")
    m = scene.model
    exact = PaperTransient(m.inertia, m.law.k, m.law.a, m.load.torque, m.driver_speed).summary()
    rows = []
    for rtol in TOLERANCES:
        model = replace(m, rtol=rtol)
        head = simulate(model).headline
        timing = repeated(lambda: simulate(model), config.repeats)
        rows.append({"scene": "paper_transient", "rtol": rtol,
                     "t_c_rel_error": _relative(head["start_time"], exact["start_time"]),
                     "L_rel_error": _relative(head["friction_work"], exact["friction_work"]),
                     "median_s": timing["median_s"], "iqr_s": timing["iqr_s"]})
    return rows


def stiffness_rows(config) -> list[dict]:
    """The motor scene by each integrator at the default tolerance, errors against a tight reference."""
    model = load_scene(SCENES / "wedge_motor_springs.toml").model
    reference = simulate(replace(model, integrator="DOP853", rtol=1e-13)).headline
    rows, times = [], {}
    for label, integrator in (("DOP853 (before)", "DOP853"), ("by stiffness (now)", "auto")):
        run = replace(model, integrator=integrator)
        head = simulate(run).headline
        times[label] = repeated(lambda: simulate(run), max(3, config.repeats // 4))["median_s"]
        rows.append({"scene": "wedge_motor_springs", "integrator": label, "rtol": model.rtol,
                     "t_c_rel_error": _relative(head["start_time"], reference["start_time"]),
                     "L_rel_error": _relative(head["friction_work"], reference["friction_work"]),
                     "median_s": times[label]})
    for row in rows:
        row["speedup"] = times["DOP853 (before)"] / row["median_s"]
    return rows


def effects_rows(config) -> list[dict]:
    """Time per scene as effects are added, and the start time each set of effects gives."""
    path = SCENES / "wedge_motor_springs.toml"
    data = read_toml(path)
    rows = []
    for count in range(2, len(EFFECT_STEPS) + 1):
        effects = list(EFFECT_STEPS[:count])
        scene = parse_scene({**data, "effects": effects}, str(path))
        head = simulate(scene.model).headline
        timing = repeated(lambda: simulate(scene.model), config.repeats)
        rows.append({"scene": path.stem, "effects": " + ".join(effects),
                     "start_time_s": head["start_time"] if math.isfinite(head["start_time"]) else None,
                     "median_s": timing["median_s"], "iqr_s": timing["iqr_s"]})
    return rows
