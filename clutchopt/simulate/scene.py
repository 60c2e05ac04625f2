"""Scenes: TOML files naming a coupling (law, case or solved design), the driven machine, the driver, the effects.

Layout (quantities with units as in case files; bare numbers are SI; paths relative to the scene file)::

    title = "..."
    effects = ["slip_friction", "lockup"]     # exactly these are evaluated
    end_time = "2 s"                          # optional: default until lock-up (+25 % locked)
    [coupling]
    law = "paper"                             # paper: k, a | constant: torque | centrifugal: case [, design]
    k = "25 N*m"
    a = "0.02 s/rad"                          # 1 / slip speed
    case = "../wedge_paper.toml"              # centrifugal: a case of a coupling with a speed law (wedge)
    design = "../designs/wedge_paper.json"    # optional: clutchopt solve --json output; else the case is solved
    spring_preload = "10 N"                   # per weight (effect spring_preload); not where the design sets it
    [driven]                                  # defaults: the case's (a start-up case's [start_up.driven], else
    inertia = "0.5 kg*m^2"                    # its duty; its load profile too)
    resisting_torque = "5 N*m"                # or [driven.load_profile] over = "speed"|"time", points, torque
    [driver]
    speed = "1000 rpm"                        # constant driving speed (default: the case's duty.speed)
    synchronous_speed = "1500 rpm"            # motor_curve: Kloss curve and rotor inertia (default: a start-up
                                              # case's [start_up.driver])
    breakdown_torque = "60 N*m"
    breakdown_slip = 0.25
    inertia = "0.02 kg*m^2"
    [heat]
    capacity = "2000 J/K"                     # friction_heat: lumped heat capacity, optional conductance
                                              # (default: a start-up case's [start_up.heat])
    conductance = "5 W/K"
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

from clutchopt.cases import check_text, read_toml
from clutchopt.errors import InputError, Problems, shown_value
from clutchopt.simulate.engine import Model, simulate
from clutchopt.simulate.ranges import (
    BREAKDOWN_SLIP,
    CONDUCTANCE,
    FORCE,
    HEAT_CAPACITY,
    INERTIA,
    LOAD,
    SLIP_SCALE,
    SPEED,
    TIME,
    TOLERANCE,
    TORQUE,
)
from clutchopt.simulate.laws import ConstantFriction, InductionMotor, Load, PaperFriction
from clutchopt.start_up.equations import RADIAL_EFFECTS
from clutchopt.start_up.section import parse_effects, parse_load_profile
from clutchopt.units import si_unit, to_si

LAWS = ("paper", "constant", "centrifugal")
_LAW_KEYS = {"paper": ("k", "a"), "constant": ("torque",),
             "centrifugal": ("case", "design", "mode", "objective", "spring_preload")}  # what each law reads
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
    data: dict = field(default_factory=dict)  # the scene file as read (recorded in the run store)
    units: dict = field(default_factory=dict)  # the SI unit of each quantity field, as ``data`` nests them


class _Fields:
    """Reads one scene's fields with units; every problem names the field and is collected in ``problems``."""

    def __init__(self, data: dict, path: str):
        self.data, self.path = data, path
        self.problems = Problems()
        self.units: dict = {}  # the SI unit of each quantity read: of a bare number in ``data``
        self.defaults: dict[str, float] = {}  # the case's values of fields the scene may leave out (_from_the_case)
        self.taken: list[dict] = []  # the fields left out and taken from the case (field, SI value and unit)
        self.case_failed = False  # a centrifugal law's case refused: the fields it would give are not missing
        self.over: list[str] = []  # the fields given where the case has a value too (the scene's kept)

    def table(self, name: str) -> dict:
        table = self.data.get(name, {})
        if not isinstance(table, dict):
            return {}
        return table

    def check_tables(self) -> None:
        for name, keys in _KEYS.items():
            table = self.data.get(name, {})
            if not isinstance(table, dict):
                self.problems.errors.append(InputError(name, f"must be a table [{name}] of {', '.join(sorted(keys))}"))
                continue
            for key in table:
                if key not in keys:
                    self.problems.errors.append(InputError(f"{name}.{key}", f"unknown key; [{name}] takes "
                                                                            f"{', '.join(sorted(keys))}"))

    def quantity(self, section: str, key: str, unit: str, valid: tuple, default=None) -> float:
        """The field in SI, checked against ``valid`` (low, high, unit shown); NaN after a recorded problem. Not
        given: the case's value (``defaults``, said in ``taken``), else ``default``; given where the case has one:
        said in ``over``."""
        raw = self.table(section).get(key) if section else self.data.get(key)
        field_name = f"{section}.{key}" if section else key
        with self.problems.field():
            low, high, shown = valid
            if raw is None:
                if field_name not in self.defaults:
                    if default is None and not (self.case_failed and field_name in _FROM_A_CASE):
                        raise InputError(field_name, f"missing (in {unit or 'SI'})")
                    return math.nan if default is None else default
                value = self.defaults[field_name]
                self.taken.append({"field": field_name, "value": value, "unit": si_unit(unit) if unit else ""})
                said = f"the case's {value:g} (SI): give one in range in the scene"
            else:
                if field_name in self.defaults:
                    self.over.append(field_name)
                (self.units.setdefault(section, {}) if section else self.units)[key] = si_unit(unit)
                value, said = to_si(field_name, raw, unit), repr(raw)
            if not low <= value <= high:
                raise InputError(field_name, f"must be from {low:g} to {high:g} {shown} (the range the simulator "
                                             f"is tested over), got {said}".replace("  ", " "))
            return value
        return math.nan

    def file(self, key: str) -> Path | None:
        raw = self.table("coupling").get(key)
        if not isinstance(raw, str) or not raw.strip() or "\x00" in raw or len(raw) > 4096:
            self.problems.errors.append(InputError(f"coupling.{key}", f"must be a file path (text), got {raw!r}"))
            return None
        return (Path(self.path).parent / raw).resolve()


def load_scene(path: str | Path) -> Scene:
    """Read and check a scene file (InputError naming each bad field)."""
    return parse_scene(read_toml(path), str(path))


def parse_scene(data: dict, path: str = "") -> Scene:
    """Check every field of a scene (all problems raised together), then build its model; a centrifugal
    coupling's case is solved (or its design read) only once the rest of the scene is sound."""
    f = _Fields(data, path)
    for key in data:
        if key not in _TOP:
            f.problems.errors.append(InputError(key, f"unknown key; a scene has {', '.join(sorted(_TOP))}"))
    f.check_tables()
    effects = ()
    with f.problems.field():
        effects = parse_effects(data.get("effects"), "effects")
    law_name = f.table("coupling").get("law")
    if law_name not in LAWS:
        f.problems.errors.append(InputError("coupling.law", f"must be one of {', '.join(LAWS)}, got {law_name!r}"))
    else:  # (another law's field beside it had been ignored without a word: review 21c)
        for key in f.table("coupling"):
            if key != "law" and key not in _LAW_KEYS[law_name]:
                f.problems.errors.append(InputError(f"coupling.{key}", f"not read by law = {law_name!r} (it reads "
                                                                       f"{', '.join(_LAW_KEYS[law_name])})"))
    for effect in RADIAL_EFFECTS:
        if effect in effects and law_name in LAWS and law_name != "centrifugal":  # (a law refused: its error alone)
            f.problems.errors.append(InputError("effects", f"{effect} applies to centrifugal couplings "
                                                           "(law = \"centrifugal\") only"))
    case = _case(f, effects) if law_name == "centrifugal" else None
    f.defaults = _from_the_case(case)
    f.case_failed = case is None and (law_name == "centrifugal" or law_name not in LAWS and "case" in f.table(
        "coupling"))  # (a law refused beside a case: the fields that case would give are not said to be missing)
    unread = _unread(f, effects)
    inertia = f.quantity("driven", "inertia", "kg*m^2", INERTIA)
    load = _load(f, case.start_up.load_profile if case is not None and case.start_up is not None else None)
    motor = _motor(f) if "motor_curve" in effects else None
    speed = math.nan if motor else f.quantity("driver", "speed", "rpm", SPEED)
    heat = ((f.quantity("heat", "capacity", "J/K", HEAT_CAPACITY),
             f.quantity("heat", "conductance", "W/K", CONDUCTANCE, 0.0))
            if "friction_heat" in effects else (math.nan, 0.0))
    end_time = f.quantity("", "end_time", "s", TIME, math.inf)
    tolerance = f.quantity("", "tolerance", "", TOLERANCE, 1e-11)
    title = data.get("title", "")
    for name in ("title", "description"):
        with f.problems.field():
            check_text(name, data.get(name, ""), multiline=name == "description")
    for name in ("mode", "objective"):
        value = f.table("coupling").get(name)
        if value is not None and not (isinstance(value, str) and value.strip()):
            f.problems.errors.append(InputError(f"coupling.{name}", f"must be a name (text), got {value!r}"))
    law, source = None, {}
    if law_name in ("paper", "constant"):
        law, source = _friction_law(f, law_name)
    elif case is not None:
        law, source = _centrifugal(f, case, effects)
        source |= {"from_the_case": f.taken, "over_the_case": f.over}
    source["unread"] = unread
    f.problems.raise_any()
    model = Model(law, inertia, load, effects, speed, motor, heat[0], heat[1],
                  None if math.isinf(end_time) else end_time, tolerance)
    return Scene(title, path, model, source, data, f.units)


def _friction_law(f: _Fields, law_name: str):
    if law_name == "paper":
        return PaperFriction(f.quantity("coupling", "k", "N*m", TORQUE),
                             f.quantity("coupling", "a", "s/rad", SLIP_SCALE)), {"law": "paper"}
    return ConstantFriction(f.quantity("coupling", "torque", "N*m", TORQUE)), {"law": "constant"}


def _case(f: _Fields, effects: tuple[str, ...]):
    """The centrifugal coupling's case (checked; its problems named inside ``coupling.case``), or None."""
    from clutchopt.cases import load_case
    from clutchopt.formulations import get_coupling
    from clutchopt.start_up.simulation import speed_law_missing

    if "case" not in f.table("coupling"):
        f.problems.errors.append(InputError("coupling.case", "missing: a centrifugal law needs the coupling's "
                                                             "case file"))
        return None
    case_path = f.file("case")
    if case_path is None:
        return None
    try:
        case = load_case(case_path)
    except InputError as exc:
        f.problems.errors += [InputError(f"coupling.case ({case_path.name})", str(problem))
                              for problem in exc.problems]
        return None
    missing = speed_law_missing(case.coupling, slipping=True)
    if missing:
        f.problems.errors.append(InputError("coupling.case", missing))
        return None
    radial = [effect for effect in effects if effect in RADIAL_EFFECTS]
    laws = [formulation.speed_law for formulation in get_coupling(case.coupling).formulations.values()]
    if radial and not all(law is not None and law.mass_radius is not None for law in laws):
        f.problems.errors.append(InputError("effects", f"{radial[0]} does not apply to the {case.coupling} coupling "
                                                       "(no weights held in by springs or their own weight)"))
    return case


def _centrifugal(f: _Fields, case, effects):
    from clutchopt.start_up.simulation import centrifugal_law, design_from_json

    table = f.table("coupling")
    source = {"law": "centrifugal", "coupling": case.coupling, "case": table["case"]}
    design, formulation, given = None, None, None
    if "design" in table:
        design_path = f.file("design")
        try:  # (read beside the scene's other problems: every one named in one run)
            if design_path is not None:
                given = design_from_json(design_path, case.coupling, case.path, case.start_up is not None)
                mode, design, case = given.mode, given.design, _chosen(case, given.choice)
        except InputError as error:
            f.problems.errors.append(error)
        if design is not None:  # (a plain design of a [scatter] case: said as a solved one is, review 34)
            source["design"] = table["design"] + (" (a robust design, simulated at the case's nominal values)"
                                                  if given.robust else
                                                  "; nominal: the case's [scatter] is not designed for"
                                                  if case.scatter else "")
        for name in ("mode", "objective"):  # (the file's design is simulated: neither solves the case; a value
            # that is no name is refused as such above; a mode beside a file not read is not known to differ)
            value = table.get(name)
            if isinstance(value, str) and value.strip() and not (name == "mode" and (design is None or value == mode)):
                f.problems.errors.append(InputError(f"coupling.{name}", f"{shown_value(value)} is for a case solved "
                                                    f"for its design; the design file gives it"
                                                    + (f" (mode {mode})" if design is not None else "")))
    else:
        formulation = _solved_formulation(f, case, table)
    designed = ("spring_preload" in design if design is not None  # one of the design's variables (a start-up's)
                else any(v.name == "spring_preload" for v in formulation.variables) if formulation is not None
                else case.start_up is not None)  # (a design file or a mode refused: a start-up's sets it)
    if designed and "spring_preload" in table:  # the start simulated with the design's, as its start-up was solved
        f.problems.errors.append(InputError("coupling.spring_preload", "the design sets the spring preload (one of "
                                                                       "its variables): leave it out of the scene"))
    preload = None if designed else f.quantity("coupling", "spring_preload", "N", FORCE,
                                               None if "spring_preload" in effects else 0.0)
    f.problems.raise_any()
    if design is None:  # designed as `solve` designs the case: every choice of options.choose, the best kept
        from clutchopt.optimise.design import design_case

        best = design_case(case, table.get("mode"), table.get("objective"))[0]
        if best.solution.status != "optimal":
            raise InputError("coupling.case", f"the case does not solve to an optimal design ({best.solution.status})")
        case, mode, design = best.case, best.solution.mode, best.solution.design
        source["design"] = "solved from the case" + (f", {best.choice_text} the best of options.choose"
                                                     if best.choice else "")
        if case.scatter:  # (as every command designing a case with [scatter] without --robust says)
            source["design"] += "; nominal: the case's [scatter] is not designed for"
    law = centrifugal_law(case, mode, design, effects, design["spring_preload"] if designed else preload)
    if given is not None:  # (after the law's own checks: a design edited by hand is refused by those first)
        _solved_for(case, given, table["design"])
    source["engagement_speed"] = law.engagement_speed()
    source["design_torque"] = law.capacity(case.params().speed)
    return law, source


def _solved_formulation(f: _Fields, case, table: dict):
    """The formulation the scene's case is solved with (its ``coupling.mode``, checked with its
    ``coupling.objective`` as the scene's fields); None where the mode is refused (a value that is no name refused as
    such, before)."""
    from clutchopt.optimise.problem import case_formulation

    given = [table.get(name) for name in ("mode", "objective")]
    if any(value is not None and not (isinstance(value, str) and value.strip()) for value in given):
        return None
    try:
        formulation = case_formulation(case, given[0])
    except InputError as error:
        f.problems.errors.append(InputError("coupling.mode", error.problem))
        return None
    if given[1] is not None:
        with f.problems.field():
            try:
                formulation.objective(given[1])
            except InputError as error:
                raise InputError("coupling.objective", error.problem) from None
    return formulation


def _chosen(case, choice: dict[str, str]):
    """``case`` as a design file's choice of its ``options.choose`` (``choice``) makes it, which the design was
    solved with (its friction pair's coefficient, ...); a choice the case does not offer refused by name."""
    if not case.options.get("choose"):
        if choice:
            raise InputError("coupling.design", f"names the choice {shown_value(choice)}, but the case chooses "
                                                "nothing")
        return case
    from clutchopt.optimise.design import choices

    offered = list(choices(case))
    variant = next((variant for named, variant in offered if named == choice), None)
    if variant is None:
        raise InputError("coupling.design", f"was solved with {shown_value(choice) if choice else 'no choice'}, "
                                            f"not one of the case's options.choose "
                                            f"({shown_value(', '.join(str(named) for named, _ in offered), 200)})")
    return variant


_FROM_THE_START_UP = (
    ("driven.inertia", "driven_inertia"), ("driven.resisting_torque", "load_torque"),
    ("driver.synchronous_speed", "synchronous_speed"), ("driver.breakdown_torque", "breakdown_torque"),
    ("driver.breakdown_slip", "breakdown_slip"), ("driver.inertia", "motor_inertia"),
    ("heat.capacity", "heat_capacity"), ("heat.conductance", "heat_conductance"))  # a scene's field and the
# [start_up] quantity of a case that gives it
_FROM_A_CASE = ("driver.speed", *(name for name, _ in _FROM_THE_START_UP))  # the fields a centrifugal coupling's case
# may give (_from_the_case: its duty's inertia, resisting torque and speed, its start-up's)
_NEEDS = {"driver.synchronous_speed": "motor_curve", "driver.breakdown_torque": "motor_curve",
          "driver.breakdown_slip": "motor_curve", "driver.inertia": "motor_curve", "heat.capacity": "friction_heat",
          "heat.conductance": "friction_heat", "coupling.spring_preload": "spring_preload"}  # the fields only an
# effect reads


def _unread(f: _Fields, effects: tuple[str, ...]) -> list[str]:
    """The fields the scene gives that the effects it lists leave unread (the motor's without motor_curve, the heat's
    without friction_heat: a scene's effects switched off, its data kept), said in its output; two values for one
    thing refused by name (a constant driving speed beside motor_curve, a constant load beside a load profile: the
    first had been ignored without a word)."""
    def given(name: str) -> bool:
        section, key = name.split(".")
        return key in f.table(section)

    if given("driver.speed") and "motor_curve" in effects:
        f.problems.errors.append(InputError("driver.speed", "given, but effects list motor_curve: the motor's curve "
                                                            "drives, not a constant speed"))
    if given("driven.resisting_torque") and given("driven.load_profile"):
        f.problems.errors.append(InputError("driven.resisting_torque", "given beside driven.load_profile: one or "
                                                                       "the other"))
    return [name for name, effect in _NEEDS.items() if given(name) and effect not in effects]


def _from_the_case(case) -> dict[str, float]:
    """The scene's fields a centrifugal coupling's case gives where the scene does not: its duty's, and the drive of
    its [start_up] where it has one (the start-up's own driven inertia and load, motor and heat: the start it was
    designed for)."""
    if case is None:
        return {}
    duty, values = case.params(), case.values
    given = {"driven.inertia": getattr(duty, "inertia", None),  # (the ball's duty has none: its power and speed)
             "driven.resisting_torque": getattr(duty, "resisting_torque", None), "driver.speed": duty.speed}
    if case.start_up is not None:
        given |= {field: values[name] for field, name in _FROM_THE_START_UP if name in values}
    return {field: value for field, value in given.items() if value is not None}


def _load(f: _Fields, profile_of_the_case) -> Load:
    """The driven machine's load: the scene's constant torque or profile, else the case's (its start-up's profile,
    else its constant load)."""
    profile = f.table("driven").get("load_profile")
    if profile is None and "resisting_torque" not in f.table("driven") and profile_of_the_case is not None:
        f.taken.append({"field": "driven.load_profile"})
        return Load(over=profile_of_the_case.over, points=profile_of_the_case.points,
                    values=profile_of_the_case.values)
    if profile is None:
        return Load(f.quantity("driven", "resisting_torque", "N*m", LOAD))
    if profile_of_the_case is not None or "driven.resisting_torque" in f.defaults:
        f.over.append("driven.load_profile")
    with f.problems.field():
        profile = parse_load_profile(profile, "driven.load_profile")
        return Load(over=profile.over, points=profile.points, values=profile.values)
    return Load()


def _motor(f: _Fields) -> InductionMotor:
    return InductionMotor(f.quantity("driver", "synchronous_speed", "rpm", SPEED),
                          f.quantity("driver", "breakdown_torque", "N*m", TORQUE),
                          f.quantity("driver", "breakdown_slip", "", BREAKDOWN_SLIP),
                          f.quantity("driver", "inertia", "kg*m^2", INERTIA))


SAME_OUTPUT = 1e-9  # relative: a design file's derived quantities against the same design's at the scene's case


def _solved_for(case, given, name: str) -> None:
    """Refuse a design file solved for another case than ``case`` though of its file name (review 34: a case edited
    after its solve, or another folder's of that name, had been taken without a word): the derived quantities the
    solve wrote against the same design's at this case, naming those that differ."""
    from clutchopt.optimise.problem import case_formulation
    from clutchopt.optimise.verify import evaluate_outputs

    here = evaluate_outputs(case_formulation(case, given.mode), given.design, case.params())
    differ = [(key, value, here[key].value) for key, value in given.outputs.items() if key in here
              and abs(here[key].value - value) > SAME_OUTPUT * max(abs(value), abs(here[key].value), 1e-300)]
    if differ:
        shown = ", ".join(f"{key} {value:.6g} there, {now:.6g} here" for key, value, now in differ[:3])
        raise InputError("coupling.design", f"{name} was solved for another case than {case.path} (its derived "
                                            f"quantities differ: {shown}; SI): solve this case again")


def run_scene(scene: Scene):
    """Simulate a scene's start-up; the headline carries where the coupling came from."""
    result = simulate(scene.model)
    result.headline["source"] = scene.source
    return result
