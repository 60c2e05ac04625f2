"""Scenes: TOML files naming a coupling (law, case or solved design), the driven machine, the driver, the effects.

Layout (quantities with units as in case files; bare numbers are SI; paths relative to the scene file)::

    title = "..."
    effects = ["slip_friction", "lockup"]     # exactly these are evaluated
    end_time = "2 s"                          # optional: default until lock-up (+25 % locked)
    [coupling]
    law = "paper"                             # paper: k, a | constant: torque | centrifugal: case [, design]
    k = "25 N*m"
    a = "0.02 s"                              # 1 / slip speed (s/rad)
    case = "../wedge_paper.toml"              # centrifugal: a case of a coupling with a speed law (wedge)
    design = "../designs/wedge_paper.json"    # optional: clutchopt solve --json output; else the case is solved
    spring_preload = "10 N"                   # per weight (effect spring_preload)
    [driven]
    inertia = "0.5 kg*m^2"                    # defaults: the case's duty
    resisting_torque = "5 N*m"                # or [driven.load_profile] over = "speed"|"time", points, torque
    [driver]
    speed = "1000 rpm"                        # constant driving speed (default: the case's duty.speed)
    synchronous_speed = "1500 rpm"            # motor_curve: Kloss curve and rotor inertia
    breakdown_torque = "60 N*m"
    breakdown_slip = 0.25
    inertia = "0.02 kg*m^2"
    [heat]
    capacity = "2000 J/K"                     # friction_heat: lumped heat capacity, optional conductance
    conductance = "5 W/K"
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from clutchopt.cases import read_toml
from clutchopt.errors import InputError
from clutchopt.formulations.start_up import RADIAL_EFFECTS
from clutchopt.simulate.engine import Model, simulate
from clutchopt.simulate.laws import ConstantFriction, InductionMotor, Load, PaperFriction
from clutchopt.start_up_case import parse_effects, parse_load_profile
from clutchopt.units import to_si

LAWS = ("paper", "constant", "centrifugal")
_TOP = {"title", "description", "effects", "end_time", "tolerance", "coupling", "driven", "driver", "heat"}
_KEYS = {
    "coupling": {"law", "k", "a", "torque", "case", "design", "mode", "objective", "spring_preload"},
    "driven": {"inertia", "resisting_torque", "load_profile"},
    "driver": {"speed", "synchronous_speed", "breakdown_torque", "breakdown_slip", "inertia"},
    "heat": {"capacity", "conductance"},
}


@dataclass
class Scene:
    title: str
    path: str
    model: Model
    source: dict  # where the coupling came from: law and case/design, engagement speed if any


class _Fields:
    """Reads one scene's fields with units; every problem names the field."""

    def __init__(self, data: dict, path: str):
        self.data, self.path = data, path

    def table(self, name: str) -> dict:
        table = self.data.get(name, {})
        if not isinstance(table, dict):
            raise InputError(name, "must be a table")
        for key in table:
            if key not in _KEYS[name]:
                raise InputError(f"{name}.{key}", f"unknown key; [{name}] takes {', '.join(sorted(_KEYS[name]))}")
        return table

    def quantity(self, section: str, key: str, unit: str, default=None, *, positive=True, at_least_zero=False):
        raw = self.table(section).get(key) if section else self.data.get(key)
        field = f"{section}.{key}" if section else key
        if raw is None:
            if default is None:
                raise InputError(field, f"missing (in {unit or 'SI'})")
            return default
        value = to_si(field, raw, unit)
        if positive and not at_least_zero and not value > 0:
            raise InputError(field, f"must be positive, got {raw!r}")
        if at_least_zero and value < 0:
            raise InputError(field, f"must not be negative, got {raw!r}")
        return value

    def file(self, key: str) -> Path:
        raw = self.table("coupling").get(key)
        if not isinstance(raw, str):
            raise InputError(f"coupling.{key}", f"must be a path (text), got {raw!r}")
        return (Path(self.path).parent / raw).resolve()


def load_scene(path: str | Path) -> Scene:
    """Read and check a scene file (InputError naming the field for bad input)."""
    return parse_scene(read_toml(path), str(path))


def parse_scene(data: dict, path: str = "") -> Scene:
    for key in data:
        if key not in _TOP:
            raise InputError(key, f"unknown key; a scene has {', '.join(sorted(_TOP))}")
    f = _Fields(data, path)
    effects = parse_effects(data.get("effects"), "effects")
    law_name = f.table("coupling").get("law")
    if law_name not in LAWS:
        raise InputError("coupling.law", f"must be one of {', '.join(LAWS)}, got {law_name!r}")
    for effect in RADIAL_EFFECTS:
        if effect in effects and law_name != "centrifugal":
            raise InputError("effects", f"{effect} applies to centrifugal couplings (law = \"centrifugal\") only")
    case, law, source = _coupling(f, law_name, effects)
    duty = case.params() if case else None
    inertia = f.quantity("driven", "inertia", "kg*m^2", getattr(duty, "inertia", None))
    load = _load(f, duty)
    motor = _motor(f) if "motor_curve" in effects else None
    speed = math.nan if motor else f.quantity("driver", "speed", "rpm", duty.speed if duty else None)
    heat = ((f.quantity("heat", "capacity", "J/K"), f.quantity("heat", "conductance", "W/K", 0.0, at_least_zero=True))
            if "friction_heat" in effects else (math.nan, 0.0))
    end_time = f.quantity("", "end_time", "s", math.inf)
    tolerance = f.quantity("", "tolerance", "", 1e-11)
    if not tolerance < 1e-3:
        raise InputError("tolerance", f"must be below 1e-3 (relative), got {tolerance:g}")
    model = Model(law, inertia, load, effects, speed, motor, heat[0], heat[1],
                  None if math.isinf(end_time) else end_time, tolerance)
    title = data.get("title", "")
    if not isinstance(title, str):
        raise InputError("title", "must be text")
    return Scene(title, path, model, source)


def _coupling(f: _Fields, law_name: str, effects):
    if law_name == "paper":
        return None, PaperFriction(f.quantity("coupling", "k", "N*m"),
                                   f.quantity("coupling", "a", "s", positive=False)), {"law": "paper"}
    if law_name == "constant":
        return None, ConstantFriction(f.quantity("coupling", "torque", "N*m")), {"law": "constant"}
    from clutchopt.cases import load_case
    from clutchopt.simulate.design import centrifugal_law, design_from_json, speed_law_missing

    table = f.table("coupling")
    if "case" not in table:
        raise InputError("coupling.case", "missing: a centrifugal law needs the coupling's case file")
    case_path = f.file("case")
    case = load_case(case_path)
    missing = speed_law_missing(case.coupling)
    if missing:
        raise InputError("coupling.case", missing)
    source = {"law": "centrifugal", "coupling": case.coupling, "case": table["case"]}
    if "design" in table:
        mode, design = design_from_json(f.file("design"), case.coupling, case_path)
        source["design"] = table["design"]
    else:
        from clutchopt.optimise import solve_case

        solution = solve_case(case, table.get("mode"), table.get("objective"))
        if solution.status != "optimal":
            raise InputError("coupling.case", f"the case does not solve to an optimal design ({solution.status})")
        mode, design = solution.mode, solution.design
        source["design"] = "solved from the case"
    preload = f.quantity("coupling", "spring_preload", "N", None if "spring_preload" in effects else 0.0,
                         at_least_zero=True)
    law = centrifugal_law(case, mode, design, effects, preload)
    source["engagement_speed"] = law.engagement_speed()
    source["design_torque"] = law.capacity(case.params().speed)
    return case, law, source


def _load(f: _Fields, duty) -> Load:
    table = f.table("driven")
    profile = table.get("load_profile")
    if profile is None:
        return Load(f.quantity("driven", "resisting_torque", "N*m", getattr(duty, "resisting_torque", None),
                               at_least_zero=True))
    profile = parse_load_profile(profile, "driven.load_profile")
    return Load(over=profile.over, points=profile.points, values=profile.values)


def _motor(f: _Fields) -> InductionMotor:
    slip = f.quantity("driver", "breakdown_slip", "")
    if not slip < 1:
        raise InputError("driver.breakdown_slip", f"must be between 0 and 1, got {slip:g}")
    return InductionMotor(f.quantity("driver", "synchronous_speed", "rpm"), f.quantity("driver", "breakdown_torque", "N*m"),
                          slip, f.quantity("driver", "inertia", "kg*m^2"))


def run_scene(scene: Scene):
    """Simulate a scene's start-up; the headline carries where the coupling came from."""
    result = simulate(scene.model)
    result.headline["source"] = scene.source
    return result
