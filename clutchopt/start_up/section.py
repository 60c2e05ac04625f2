"""The ``[start_up]`` section of a case file: the drive a coupling is designed for, read into SI and checked.

Layout (quantities with units; bare numbers are SI; the vocabulary of start-up scenes)::

    [start_up]
    effects = ["slip_friction", "motor_curve", "spring_preload", "gravity", "lockup", "friction_heat"]
    spring_preload = "12 N"          # per weight; free it with options.free = ["spring_preload"]
    intervals = 16                   # collocation intervals per phase (optional; doubled as the tolerance needs)
    tolerance = 1e-6                 # simulated start against the limits, relative (optional)
    [start_up.driver]                # effect motor_curve: an induction motor (else the duty's constant speed)
    synchronous_speed = "1000 rpm"
    breakdown_torque = "37 N*m"
    breakdown_slip = 0.2
    inertia = "0.012 kg*m^2"
    [start_up.driven]                # defaults: the duty's inertia and resisting torque
    inertia = "0.5 kg*m^2"
    resisting_torque = "5 N*m"       # or [start_up.driven.load_profile] over = "speed"|"time", points, torque
    max_transmitted_torque = "80 N*m"  # optional: the coupling as a torque limiter (overload_torque)
    [start_up.overload]              # optional: the friction the overload is checked with (docs/start_up.md)
    friction_max = 0.45              # default: the pair's friction_max or the [scatter] range's high end
    [start_up.heat]                  # effect friction_heat
    capacity = "1400 J/K"
    conductance = "4 W/K"
    ambient = "40 degC"              # the default
    [start_up.wear]                  # defaults: the friction pair's wear_rate, the coupling's lining thickness
    wear_rate = "1e-4 mm^3/J"
    allowance = "3 mm"
    [start_up.limits]                # max_start_time defaults to duty.acceleration_time
    max_start_time = "10 s"
    max_friction_work = "8 kJ"
    max_temperature_rise = "15 K"
    min_engagement_speed = "300 rpm"
    max_engagement_speed = "600 rpm"
    starts_per_hour = "6 1/hour"
    heat_dissipation = "40 W"
    max_lining_temperature = "250 degC"      # default: the friction pair's max_temperature
    max_continuous_temperature = "200 degC"  # default: the friction pair's continuous_temperature
    min_life = "20000 h"
"""

from __future__ import annotations

from clutchopt.errors import InputError, Problems
from clutchopt.model import REQUIRED, ElasticLaw, followed
from clutchopt.start_up.equations import (
    EFFECTS,
    LIMITS,
    LOCK_UP_SHARE,
    QUANTITIES,
    RADIAL_EFFECTS,
    SLIP_EFFECTS,
    SLIP_ONLY,
    LoadProfile,
    StartUpSpec,
)
from clutchopt.start_up.nameplate import FIELDS as NAMEPLATE_FIELDS
from clutchopt.start_up.nameplate import KLOSS, derived_from, kloss_from_nameplate, nameplate_fields
from clutchopt.units import to_si

SECTION = "start_up"
_TABLES = ("driver", "driven", "heat", "wear", "limits", "overload")
_SETTINGS = ("effects", "intervals", "tolerance")
MAX_INTERVALS = 128
MAX_PROFILE_POINTS = 1000  # a load profile is a curve of a few dozen points; each point costs every evaluation
PROFILE_SPEED_MAX, PROFILE_TIME_MAX, PROFILE_TORQUE_MAX = 1e5, 1e9, 1e9  # rad/s, s, N*m (the simulator's ranges)
BY_NAME = {q.name: q for q in QUANTITIES}
DEFAULTS_FROM_DUTY = {"driven_inertia": "inertia", "load_torque": "resisting_torque",
                      "max_start_time": "acceleration_time"}


def parse_start_up(table, coupling, duty: dict[str, float], duty_sound: bool = True,
                   library: dict[str, float] | None = None) -> tuple[dict[str, float], StartUpSpec, dict, set]:
    """SI values of the start-up quantities, the spec of a ``[start_up]`` table of a case of ``coupling``, the
    defaults that follow another quantity (``{name: (source, factor)}``: the value is factor times the source's,
    through every change a command makes; see :attr:`clutchopt.cases.Case.follows`) and the names taken from
    ``library``: the values the case's friction pair fills (its temperature limits and wear rate, SI, by name;
    :func:`clutchopt.materials.fill`), where the section does not give them itself.

    Every field's own problem is raised together (one InputError); the checks across fields (:func:`_check`) run
    once the fields are sound, and only if ``duty_sound`` (the defaults follow the duty's values)."""
    if not isinstance(table, dict):
        raise InputError(SECTION, "must be a table")
    laws = [f.speed_law for f in coupling.formulations.values()]
    if not all(laws):
        raise InputError(SECTION, f"the {coupling.name} coupling has no start-up law in clutchopt yet")
    problems = Problems()
    values, profile, spec = read_tables(table, problems)
    effects = spec.pop("effects")
    motor_note = ""
    plate = nameplate_fields(_table(table, f"{SECTION}.driver"))
    if plate:
        with problems.field():
            kloss = [k for k in KLOSS if BY_NAME[k].key.rsplit(".", 1)[1] in _table(table, f"{SECTION}.driver")]
            derived, motor_note = kloss_from_nameplate(plate, f"{SECTION}.driver", kloss)
            values.update(derived)
    given = {q.name for q in QUANTITIES if q.key.rsplit(".", 1)[1] in _table(table, q.section)}  # good or bad
    taken = {name for name in library or {} if name not in values}
    values.update({name: (library or {})[name] for name in taken})
    follows = {name: (source, 1.0) for name, source in DEFAULTS_FROM_DUTY.items()
               if name not in given and source in duty}
    if "motor_curve" in effects and "min_lock_up_speed" not in given and "synchronous_speed" in values:
        follows["min_lock_up_speed"] = ("synchronous_speed", LOCK_UP_SHARE)
    if "wear_allowance" not in given and "lining_thickness" in duty:  # the paper's delta: the wear the levers follow
        follows["wear_allowance"] = ("lining_thickness", 1.0)
    elastic = [law for law in laws if isinstance(law, ElasticLaw)]
    if elastic and "max_link_stress" not in given and elastic[0].stress_limit in duty:
        follows["max_link_stress"] = (elastic[0].stress_limit, 1.0)
    values = followed({**duty, **values}, follows)
    values = with_defaults(values, given)
    values = {name: value for name, value in values.items() if name not in duty}
    if profile is not None and "resisting_torque" in table.get("driven", {}):
        problems.errors.append(InputError(f"{SECTION}.driven", "give either resisting_torque or load_profile, "
                                                               "not both"))
    if profile is not None:
        values["load_torque"] = max(profile.values)
        follows.pop("load_torque", None)
    _check_ranges(values, duty, problems, set(KLOSS) if plate else set())
    problems.raise_any()
    if duty_sound:
        _check(values, effects, coupling, laws, profile, given)
    if spec.get("overload") and elastic:  # asked for, never made
        raise InputError(f"{SECTION}.overload.check", f"does not apply to the {coupling.name} coupling: an elastic "
                                                      "link does not slip, so it has no overload torque to check")
    return values, StartUpSpec(effects, tuple(name for name in LIMITS if name in values), profile, **spec,
                               motor_note=motor_note, friction_max_given="friction_max" in given), follows, taken


def with_defaults(values: dict[str, float], given=frozenset()) -> dict[str, float]:
    """``values`` with the default of each start-up quantity that has one and is neither in them nor ``given``."""
    return {**values, **{q.name: q.check(to_si(q.key, q.default, q.unit)) for q in QUANTITIES
                         if q.name not in values and q.name not in given and q.default not in (None, REQUIRED)}}


def _table(table: dict, section: str) -> dict:
    """The sub-table of ``[start_up]`` that holds the quantities of ``section`` (``start_up.driver``), or ``{}``."""
    sub = table.get(section.partition(".")[2], {}) if "." in section else table
    return sub if isinstance(sub, dict) else {}


def read_tables(table: dict, problems: Problems) -> tuple[dict[str, float], LoadProfile | None, dict]:
    """The fields of a ``[start_up]`` section, each checked on its own: its own keys (known ones; effects,
    spring_preload, intervals, tolerance) and those of its sub-tables (driver, driven, heat, ...; the nameplate's
    fields aside: :func:`clutchopt.start_up.nameplate.kloss_from_nameplate`): the quantities' SI values, the load
    profile and the spec's settings (``effects`` among them); each bad field a problem of ``problems``."""
    declared = {q.key: q for q in QUANTITIES}
    allowed = set(_SETTINGS) | set(_TABLES) | {q.key.split(".")[1] for q in QUANTITIES if q.section == SECTION}
    for key in table:
        if key not in allowed:
            problems.errors.append(InputError(f"{SECTION}.{key}",
                                              f"unknown key; [{SECTION}] takes {', '.join(sorted(allowed))}"))
    values: dict[str, float] = {}
    profile, spec = None, {"effects": ()}
    with problems.field():
        spec["effects"] = parse_effects(table.get("effects"), f"{SECTION}.effects")
    if "spring_preload" in table:
        with problems.field():
            quantity = declared[f"{SECTION}.spring_preload"]
            values["spring_preload"] = quantity.check(to_si(quantity.key, table["spring_preload"], quantity.unit))
    with problems.field():
        spec["intervals"] = _intervals(table.get("intervals", StartUpSpec.intervals))
    with problems.field():
        spec["tolerance"] = _tolerance(table.get("tolerance", StartUpSpec.tolerance))
    for name in _TABLES:
        sub = table.get(name, {})
        if not isinstance(sub, dict):
            problems.errors.append(InputError(f"{SECTION}.{name}", "must be a table"))
            continue
        for key, raw in sub.items():
            if name == "driver" and key in NAMEPLATE_FIELDS:
                continue
            with problems.field():
                if name == "driven" and key == "load_profile":
                    profile = parse_load_profile(raw, f"{SECTION}.{name}.{key}")
                elif name == "overload" and key == "check":
                    spec["overload"] = _switch(raw, f"{SECTION}.{name}.{key}")
                else:
                    values.update(_field_value(declared, name, key, raw))
    return values, profile, spec


def _field_value(declared, table: str, key: str, raw) -> dict[str, float]:
    """``{name: SI value}`` of one field of ``[start_up.<table>]``, checked."""
    field = f"{SECTION}.{table}.{key}"
    quantity = declared.get(field)
    if quantity is None:
        known = [q.key.rsplit(".", 1)[1] for q in QUANTITIES if q.section == f"{SECTION}.{table}"]
        raise InputError(field, f"unknown key; [{SECTION}.{table}] takes {', '.join(known)}"
                                + (", load_profile" if table == "driven" else "")
                                + (", check" if table == "overload" else "")
                                + (f" (or the nameplate: {', '.join(NAMEPLATE_FIELDS)})" if table == "driver" else ""))
    return {quantity.name: quantity.check(to_si(field, raw, quantity.unit))}


def parse_effects(raw, field: str) -> tuple[str, ...]:
    """A list of effect names (shared by cases and scenes)."""
    if raw is None:
        raise InputError(field, f"missing: list the effects to model, from {', '.join(EFFECTS)}")
    if not isinstance(raw, list) or not all(isinstance(e, str) for e in raw):
        raise InputError(field, f"must be a list of effect names from {', '.join(EFFECTS)}")
    unknown = [e for e in raw if e not in EFFECTS]
    if unknown:
        raise InputError(field, f"unknown effect {unknown[0]!r}; effects are {', '.join(EFFECTS)}")
    if len(set(raw)) != len(raw):
        raise InputError(field, "lists an effect twice")
    if "slip_friction" not in raw:
        raise InputError(field, "must include slip_friction (the coupling itself)")
    return tuple(raw)


def _check(values, effects, coupling, laws, profile, explicit=frozenset()) -> None:
    """What one field cannot show: what an effect needs, and what is given (``explicit``: by the case, not the
    library) for an effect not listed."""
    def given(*names):
        return [n for n in names if n in values]

    def key(name):
        return next(q.key for q in QUANTITIES if q.name == name)

    for name in ("driven_inertia", "load_torque"):
        if name not in values:
            raise InputError(key(name), f"missing (the {coupling.name} case has no duty value to take it from)")
    if "max_start_time" not in values:
        raise InputError(key("max_start_time"), "missing (the case has no duty.acceleration_time to take it from)")
    motor = ("synchronous_speed", "breakdown_torque", "breakdown_slip", "motor_inertia")
    if "motor_curve" in effects:
        for name in motor:
            if name not in values:
                raise InputError(key(name), "missing (effect motor_curve lists an induction motor)")
    elif given(*motor, "min_lock_up_speed"):
        raise InputError(key(given(*motor, "min_lock_up_speed")[0]), "given, but effects do not list motor_curve "
                                                                     "(the driver then turns at the duty's constant "
                                                                     "speed)")
    if any(isinstance(law, ElasticLaw) for law in laws):
        _check_elastic(values, effects, coupling, key, explicit)
    elif "max_link_stress" in values:
        raise InputError(key("max_link_stress"), f"applies to couplings with an elastic link (the cable coupling), "
                                                 f"not to the {coupling.name} coupling")
    if "friction_heat" in effects and "heat_capacity" not in values:
        raise InputError(key("heat_capacity"), "missing (effect friction_heat)")
    heat_only = [n for n in ("heat_capacity", "heat_conductance", "max_temperature_rise", "max_lining_temperature",
                             "max_continuous_temperature", "ambient_temperature") if n in explicit]
    if "friction_heat" not in effects and heat_only:
        raise InputError(key(heat_only[0]), "given, but effects do not list friction_heat")
    if values.get("spring_preload", 0.0) > 0 and "spring_preload" not in effects:
        raise InputError(key("spring_preload"), "given, but effects do not list spring_preload")
    radial = [e for e in effects if e in RADIAL_EFFECTS]
    if radial and not all(getattr(law, "mass_radius", None) for law in laws):
        raise InputError(f"{SECTION}.effects", f"{radial[0]} does not apply to the {coupling.name} coupling "
                                               "(it has no weights held in by springs or their own weight)")
    window = given("min_engagement_speed", "max_engagement_speed")
    if window and not radial:
        raise InputError(key(window[0]), "needs spring_preload or gravity in effects (else the coupling engages "
                                         "at standstill)")
    if "heat_dissipation" in values and "starts_per_hour" not in values:
        raise InputError(key("starts_per_hour"), "missing (given heat_dissipation: the heat balance over an hour "
                                                 "needs the starts in it)")
    if "min_life" in values:
        _check_life(values, coupling, laws, key)


def _check_life(values, coupling, laws, key) -> None:
    """min_life needs the hours (starts_per_hour), the wear rate, the wear allowance and the coupling's friction
    area."""
    if "starts_per_hour" not in values:
        raise InputError(key("starts_per_hour"), "missing (given min_life: the hours until worn need the starts "
                                                 "per hour)")
    if not all(getattr(law, "friction_area", None) for law in laws):
        raise InputError(key("min_life"), f"the {coupling.name} coupling declares no friction area that wears, so "
                                          "its lining's life is not computed")
    if "wear_rate" not in values:
        raise InputError(key("wear_rate"), "missing (given min_life; or name a friction_pair in [library])")
    if "wear_allowance" not in values:
        raise InputError(key("wear_allowance"), f"missing (given min_life: the thickness of lining that may wear; "
                                                f"the {coupling.name} coupling has no lining thickness to take it "
                                                "from)")


def check_values(values: dict[str, float]) -> None:
    """What a case's drive must satisfy together (its duty's and start-up's values by name), at the values read and
    at every point a sweep or a scatter moves them to: within the simulator's ranges, an engagement window that is
    not empty, a wear allowance within the lining's thickness, and an induction motor that reaches the duty speed, the lock-up and the engagement asked for (it runs
    below its synchronous speed)."""
    problems = Problems()
    _check_ranges(values, values, problems)
    if "min_engagement_speed" in values and "max_engagement_speed" in values \
            and not values["min_engagement_speed"] < values["max_engagement_speed"]:
        problems.errors.append(InputError(BY_NAME["min_engagement_speed"].key, "must be below max_engagement_speed"))
    for name in ("max_lining_temperature", "max_continuous_temperature"):
        if name in values and "ambient_temperature" in values \
                and not values[name] > values["ambient_temperature"]:
            shown = BY_NAME[name].show
            problems.errors.append(InputError(BY_NAME[name].key, (
                f"{shown(values[name])} is not above the ambient temperature {shown(values['ambient_temperature'])}"
                " (start_up.heat.ambient): the lining cannot be cooler than the air around it")))
    if "wear_allowance" in values and "lining_thickness" in values \
            and not values["wear_allowance"] <= values["lining_thickness"]:
        shown = BY_NAME["wear_allowance"].show
        problems.errors.append(InputError(BY_NAME["wear_allowance"].key, (
            f"{shown(values['wear_allowance'])} is more than geometry.lining_thickness "
            f"{shown(values['lining_thickness'])}: a lining cannot wear away more than it is thick (the hours until "
            "worn would count wear the lining does not have)")))
    if "heat_capacity" in values and "starts_per_hour" in values and not values.get("heat_conductance", 0.0) > 0:
        problems.errors.append(InputError(BY_NAME["heat_conductance"].key, (
            f"{BY_NAME['heat_conductance'].show(values.get('heat_conductance', 0.0))} with starts_per_hour: give the "
            "housing's conductance above 0 W/K (friction_heat: the steady temperature of repeated starts is the heat "
            "they bring over what the housing sheds per kelvin)")))
    synchronous = values.get("synchronous_speed")
    if synchronous is not None:
        shown = BY_NAME["synchronous_speed"].show
        if "speed" in values and synchronous < values["speed"]:
            problems.errors.append(InputError(BY_NAME["synchronous_speed"].key, (
                f"{shown(synchronous)} is below duty.speed {shown(values['speed'])}: an induction motor runs below "
                "its synchronous speed, so this one cannot drive the machine to its duty speed")))
        for name in ("min_lock_up_speed", "min_engagement_speed"):
            if name in values and not values[name] < synchronous:
                problems.errors.append(InputError(BY_NAME[name].key, (
                    f"{shown(values[name])} is not below start_up.driver.synchronous_speed {shown(synchronous)}: an "
                    "induction motor runs below its synchronous speed, so the drive never reaches it")))
    problems.raise_any()


def _check_elastic(values, effects, coupling, key, explicit) -> None:
    """A coupling with an elastic link (the cable coupling) starts on a motor; springs, the weights' weight (its
    equations hold g already, eq. 1) and what a slipping coupling has (:data:`SLIP_ONLY`, ``explicit``: given by the
    case; every one given is named) are not its own."""
    if "motor_curve" not in effects:
        raise InputError(f"{SECTION}.effects", f"the {coupling.name} coupling is an elastic link: its start needs the "
                                               "motor that drives it (list motor_curve)")
    for effect in RADIAL_EFFECTS + SLIP_EFFECTS:
        if effect in effects:
            raise InputError(f"{SECTION}.effects", f"{effect} does not apply to the {coupling.name} coupling (an "
                                                   "elastic link: no friction surfaces, no springs on its weights; "
                                                   "its own gravity is in its equations, eq. 1)")
    if "max_link_stress" not in values:
        raise InputError(key("max_link_stress"), "missing (the largest cable stress during the start)")
    given = [name for name in SLIP_ONLY if name in explicit]  # each one named, not the first alone
    if given:
        raise InputError.several([InputError(key(name), (
            f"does not apply to the {coupling.name} coupling: an elastic link does not slip, so it releases no "
            "friction heat (only its damping's few joules, which the simulator reports), wears no lining and limits "
            "no torque")) for name in given])


def _check_ranges(values: dict[str, float], duty: dict[str, float], problems: Problems,
                  nameplate: set[str] = frozenset()) -> None:
    """The drive's quantities within the ranges the simulator is tested over (it starts every optimum again);
    each one out of range is a problem of ``problems``, naming the nameplate fields it came from if it is one of
    ``nameplate`` (derived, not given)."""
    from clutchopt.simulate import ranges as tested

    limits = {"driven_inertia": tested.INERTIA, "load_torque": tested.LOAD, "synchronous_speed": tested.SPEED,
              "breakdown_torque": tested.TORQUE, "breakdown_slip": tested.BREAKDOWN_SLIP,
              "motor_inertia": tested.INERTIA, "heat_capacity": tested.HEAT_CAPACITY,
              "heat_conductance": tested.CONDUCTANCE, "max_start_time": tested.TIME, "spring_preload": tested.FORCE}
    for name, (low, high, unit) in limits.items():
        if name in values and not low <= values[name] <= high:
            source = f"{derived_from(name, BY_NAME[name].section)}: " if name in nameplate else ""
            problems.errors.append(InputError(BY_NAME[name].key, f"{source}must be from {low:g} to {high:g} {unit} "
                                                                 f"(the range the simulator is tested over), got "
                                                                 f"{values[name]:.6g} {unit}".replace("  ", " ")))
    if "speed" in duty and not tested.SPEED[0] <= duty["speed"] <= tested.SPEED[1]:
        problems.errors.append(InputError("duty.speed", f"must be from {tested.SPEED[0]:g} to {tested.SPEED[1]:g} "
                                                        f"rad/s for a case with a [start_up] section (the simulator's "
                                                        f"range), got {duty['speed']:.6g}"))


def _switch(raw, field: str) -> bool:
    if not isinstance(raw, bool):
        raise InputError(field, f"must be true or false, got {raw!r}")
    return raw


def _intervals(raw) -> int:
    if isinstance(raw, bool) or not isinstance(raw, int) or not 2 <= raw <= MAX_INTERVALS:
        raise InputError(f"{SECTION}.intervals", f"must be a whole number from 2 to {MAX_INTERVALS}, got {raw!r}")
    return raw


def _tolerance(raw) -> float:
    value = to_si(f"{SECTION}.tolerance", raw, "")
    if not 1e-12 <= value <= 1e-2:
        raise InputError(f"{SECTION}.tolerance", f"must be between 1e-12 and 1e-2 (relative), got {raw!r}")
    return value


def parse_load_profile(profile, key: str) -> LoadProfile:
    """``{over = "speed"|"time", points = [...], torque = [...]}`` into SI (shared by cases and scenes)."""
    if not isinstance(profile, dict) or set(profile) != {"over", "points", "torque"}:
        raise InputError(key, "must be a table with over = \"speed\" or \"time\", points = [...], torque = [...]")
    over = profile["over"]
    if over not in ("speed", "time"):
        raise InputError(f"{key}.over", f"must be \"speed\" or \"time\", got {over!r}")
    points, torques = profile["points"], profile["torque"]
    if not isinstance(points, list) or not isinstance(torques, list) or len(points) != len(torques) \
            or not 2 <= len(points) <= MAX_PROFILE_POINTS:
        raise InputError(key, f"points and torque must be lists of the same length (2 to {MAX_PROFILE_POINTS})")
    unit, largest = ("rpm", PROFILE_SPEED_MAX) if over == "speed" else ("s", PROFILE_TIME_MAX)
    xs = tuple(to_si(f"{key}.points[{i}]", raw, unit) for i, raw in enumerate(points))
    ys = tuple(to_si(f"{key}.torque[{i}]", raw, "N*m") for i, raw in enumerate(torques))
    if any(b <= a for a, b in zip(xs, xs[1:])):
        raise InputError(f"{key}.points", "must increase strictly")
    if xs[0] < 0 or xs[-1] > largest:
        raise InputError(f"{key}.points", f"must lie from 0 to {largest:g} {'rad/s' if over == 'speed' else 's'}")
    if any(y < 0 for y in ys):
        raise InputError(f"{key}.torque", "must not be negative (the load opposes the motion)")
    if max(ys) > PROFILE_TORQUE_MAX:
        raise InputError(f"{key}.torque", f"must be at most {PROFILE_TORQUE_MAX:g} N*m")
    return LoadProfile(over, xs, ys)
