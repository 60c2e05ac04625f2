"""Which coupling suits a drive: one duty, drive and limits posed for every coupling, each designed and verified,
ranked by like-for-like mass, cost and outer diameter (``clutchopt choose-coupling``; docs/envelope.md).

A neutral case (``coupling = "any"``) gives what does not depend on the coupling type::

    [duty]        power (or torque: the motor's rated torque), speed, inertia, acceleration_time, resisting_torque
    [library]     friction_pair = "organic_dry" (and any other role a coupling has)
    [limits]      outer_diameter_max = "400 mm" (any limit a coupling declares)
    [start_up]    the drive, as in a coupling's case (the nameplate motor too)
    [couplings.NAME.SECTION]   what one coupling takes beyond its starting values (e.g. its mode; not a
                               [scatter], options.objective or options.choose, which would not apply, nor
                               a duty or drive of its own: the ranking is like for like)

Each coupling's case is its starting case (``clutchopt init``, the values of clutchopt/data/starting_values.toml)
in the mode that frees the most of its geometry (with every variable ``options.free`` may free), with the neutral duty written in the coupling's own terms: a duty
quantity the coupling declares is copied; ``power`` is the motor's rated power (the duty's, else the nameplate's,
else T_max w); ``service_factor`` makes k_s P / w = T_max (at least 1: a coupling sized by k_s never carries less
than the rated torque); ``torque`` (a coupling sized for a torque) is T_max = I w / t_p + T_c. A library role is set
where the starting case names that role (a coupling whose starting case gives its friction itself, the ball clutch's
balls on the drum, keeps it); a limit where the coupling declares it; ``[start_up]`` as written, with the driven
machine and the start time of the duty where the coupling's own case has no such duty. What did not apply is said in the notes.
"""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import dataclass, field

from clutchopt.cases import (_EXTRA_SECTIONS, NEUTRAL, Case, _did_you_mean, _table, check_text, parse_case,
                             read_toml)
from clutchopt.errors import InputError, Problems, shown_value
from clutchopt.formulations import MODULES, get_coupling
from clutchopt.formulations.duty import DUTY_QUANTITIES, required_torque
from clutchopt.model import ENVELOPE_PARTS, ElasticLaw, Quantity, namespace
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.start_up.equations import QUANTITIES as START_UP_QUANTITIES
from clutchopt.start_up.equations import SLIP_EFFECTS, SLIP_ONLY, WEAR_ONLY
from clutchopt.start_up.nameplate import FIELDS as NAMEPLATE_FIELDS
from clutchopt.start_up.section import check_values, read_tables, with_defaults
from clutchopt.units import si_unit, to_si

OBJECTIVE = "envelope_mass"  # each coupling designed for least like-for-like mass, the mass it is ranked by
SECTIONS = ("duty", "library", "limits", "start_up", "couplings")
TOP_LEVEL = ("coupling", "title", "description")
RATED = {"power": Quantity("power", "kW", "rated power of the motor", "P", "duty", None, above=0),
         "torque": Quantity("torque", "N*m", "rated torque of the motor", "T_n", "duty", None, above=0)}
DUTY = {**{q.name: q for q in DUTY_QUANTITIES}, **RATED}
START_UP_FROM_DUTY = (("driven", "inertia", "inertia"), ("driven", "resisting_torque", "resisting_torque"),
                      ("limits", "max_start_time", "acceleration_time"))
RANKINGS = (("mass", "envelope_mass"), ("cost", "cost"), ("diameter", "envelope_diameter"))
REVIEWED = ("start_time", "lining_temperature", "continuous_temperature", "lining_life", "overload_torque")
# the drive's constraints a reviewer compares across couplings (those a coupling's case has)


@dataclass
class Candidate:
    """One coupling posed for the neutral duty: its case (None: it could not be posed, ``reason`` says why), the
    verified optimum, what the posing did, and the envelope at the optimum."""

    coupling: str
    mode: str
    case: Case | None
    notes: list[str] = field(default_factory=list)
    reason: str = ""
    solution: Solution | None = None
    sized_for: float = math.nan  # N*m, the torque the coupling's own requirement asks for
    parts: dict[str, float] = field(default_factory=dict)  # kg by ENVELOPE_PARTS
    problems: tuple = ()  # the problems (InputErrors) its case was refused for, where it could not be posed

    @property
    def status(self) -> str:
        return self.solution.status if self.solution is not None else "not_posed"

    @property
    def optimal(self) -> bool:
        return self.status == "optimal"

    def output(self, name: str) -> float:
        """An output of the verified optimum (NaN without one: an unverified point is not set beside the others)."""
        if not self.optimal or name not in self.solution.outputs:
            return math.nan
        return float(self.solution.outputs[name].value)

    def sizing(self) -> list[str]:
        """The active constraints that size the design, by name."""
        return [c.name for c in self.solution.constraints if c.active] if self.solution is not None else []


@dataclass
class Choice:
    """The neutral case and its candidates, the verified ones ranked by like-for-like mass."""

    path: str
    title: str
    required_torque: float  # N*m, T_max = I w / t_p + T_c
    candidates: list[Candidate]

    @property
    def ranked(self) -> list[Candidate]:
        """Verified optima by like-for-like mass, then the others in the order of the couplings."""
        return sorted(self.candidates, key=lambda c: (not c.optimal, c.output("envelope_mass") if c.optimal else 0))

    def rank_by(self, output: str) -> list[str]:
        return [c.coupling for c in sorted((c for c in self.candidates if c.optimal), key=lambda c: c.output(output))]

    def why(self, candidate: Candidate) -> str:
        """Why a coupling is not the winner: its verdict, or what sizes it and its mass against the winner's."""
        if not candidate.optimal:
            return candidate.reason or (candidate.solution.diagnosis or candidate.status)
        winner = self.ranked[0]
        sizing = ", ".join(candidate.sizing()) or "no active constraint"
        if candidate is winner:
            return f"lightest; sized by {sizing}"
        ratio = candidate.output("envelope_mass") / winner.output("envelope_mass")
        return f"{ratio:.3g} x the {winner.coupling}'s mass; sized by {sizing}"


def neutral_duty(data: dict, path: str) -> tuple[dict[str, float], dict]:
    """SI values of the neutral ``[duty]`` (each bad field named) and the raw table, with the rated power from the
    nameplate where the duty gives neither power nor torque."""
    problems = Problems()
    for key in data:
        if key not in SECTIONS and key not in TOP_LEVEL:
            problems.errors.append(InputError(key, f"unknown section or key; a case with coupling = \"{NEUTRAL}\" "
                                                   f"may have {', '.join(TOP_LEVEL + SECTIONS)}"))
    for key in SECTIONS:
        if key in data and not isinstance(data[key], dict):
            problems.errors.append(InputError(key, f"must be a table [{key}]"))
    for key in ("title", "description"):
        with problems.field():
            check_text(key, data.get(key, ""), multiline=key == "description")
    problems.raise_any()
    raw = dict(data.get("duty", {}))
    values: dict[str, float] = {}
    for key, value in raw.items():
        if key not in DUTY:
            problems.errors.append(InputError(f"duty.{key}", f"unknown key; [duty] takes {', '.join(DUTY)}"))
            continue
        with problems.field():
            values[key] = DUTY[key].check(to_si(f"duty.{key}", value, DUTY[key].si_unit), f"duty.{key}")
    for quantity in DUTY_QUANTITIES:
        if quantity.name not in raw:
            problems.errors.append(InputError(f"duty.{quantity.name}", f"missing: {quantity.description}"))
    if "power" in raw and "torque" in raw:
        problems.errors.append(InputError("duty.torque", "given beside duty.power, which gives it: give one"))
    driver = data.get("start_up", {}).get("driver", {}) if isinstance(data.get("start_up"), dict) else {}
    if "power" not in raw and "torque" not in raw and not ("rated_power" in driver and "rated_speed" in driver):
        problems.errors.append(InputError("duty.power", "missing: the motor's rated power (or duty.torque, its rated "
                                                        "torque; or a nameplate motor in [start_up.driver])"))
    problems.raise_any()
    if "rated_power" in driver and "rated_speed" in driver and isinstance(data.get("start_up"), dict):
        plate = {}
        with problems.field():
            plate = {name: to_si(f"start_up.driver.{name}", driver[name], NAMEPLATE_FIELDS[name])
                     for name in ("rated_power", "rated_speed")}
        problems.raise_any()
        _same_motor(values, plate["rated_power"], plate["rated_power"] / plate["rated_speed"])
        if "power" not in values and "torque" not in values:
            values["torque"] = plate["rated_power"] / plate["rated_speed"]
    return values, raw


RATED_TOLERANCE = 0.01  # relative: duty.power (or torque) and the nameplate's are one motor's, written twice (a
#                        catalogue's rated torque to 3 digits, 98 N*m for 98.11, is within; another motor is not)


def _same_motor(duty: dict[str, float], power: float, torque: float) -> None:
    """duty.power (or duty.torque) beside a nameplate motor is that motor's rated power P_n (torque P_n / w_n): the
    couplings sized by k_s P / w and the start-up's motor curve are one motor."""
    name, plate, what = ("power", power, "rated_power") if "power" in duty else ("torque", torque, "rated torque")
    if name in duty and not math.isclose(duty[name], plate, rel_tol=RATED_TOLERANCE):
        shown = DUTY[name].show
        raise InputError(f"duty.{name}", (
            f"{shown(duty[name])} is not the {what} of the nameplate motor in [start_up.driver], {shown(plate)}"
            + ("" if name == "power" else " (rated_power / rated_speed)")
            + f": the motor's rating is given twice; give it once (leave duty.{name} out: the nameplate gives it)"))


def _check_shared(data: dict, problems: Problems) -> None:
    """The neutral [limits] and [library] as any coupling reads them: each limit one some coupling declares, with a
    valid value; each library key a role some coupling has, naming an entry of the library (a bad one is the case's
    error, not a reason for the couplings that take it to be left out while the others are ranked)."""
    from clutchopt.materials import lookup

    limits = {q.name: q for name in MODULES for q in get_coupling(name).quantities if q.section == "limits"}
    for key, raw in _table(data.get("limits")).items():
        with problems.field():
            if key not in limits:
                raise InputError(f"limits.{key}", f"no coupling declares this limit{_did_you_mean(key, limits)}; "
                                                  f"limits are {', '.join(sorted(limits))}")
            limits[key].check(to_si(limits[key].key, raw, limits[key].unit))
    roles = {role.key: role for name in MODULES for role in get_coupling(name).materials}
    for key, entry in _table(data.get("library")).items():
        with problems.field():
            if key not in roles:
                raise InputError(f"library.{key}", f"no coupling has this role{_did_you_mean(key, roles)}; roles are "
                                                   f"{', '.join(sorted(roles))}")
            lookup(roles[key], entry, f"library.{key}")


def posed_case(name: str, duty: dict[str, float], raw_duty: dict, data: dict, path: str) -> Candidate:
    """The case of coupling ``name`` for the neutral duty (``duty`` SI, ``raw_duty`` as written), or a candidate with
    the reason it could not be posed."""
    from clutchopt.template import case_template

    coupling = get_coupling(name)
    overrides = data.get("couplings", {}).get(name, {})
    options = overrides.get("options", {}) if isinstance(overrides.get("options"), dict) else {}
    mode = options.get("mode") or max(
        coupling.formulations.values(), key=lambda f: sum(not v.fixed_unless_freed for v in f.variables)).mode
    try:
        case_data = tomllib.loads(case_template(name, mode))
    except InputError as exc:
        return Candidate(name, str(mode), None, reason=f"cannot be posed: {exc}")
    notes: list[str] = []
    t_max = required_torque(duty["inertia"], duty["speed"], duty["acceleration_time"], duty["resisting_torque"])
    rated_torque = duty["power"] / duty["speed"] if "power" in duty else duty.get("torque", t_max)
    declared = {q.name for q in coupling.quantities if q.section == "duty"}
    written = {}
    for quantity in declared:
        if quantity == "torque":  # the torque a coupling is sized for; the neutral duty.torque is the motor's
            written["torque"] = t_max
        elif quantity in raw_duty:
            written[quantity] = raw_duty[quantity]
        elif quantity == "power":
            written["power"] = rated_torque * duty["speed"]
        elif quantity == "service_factor":
            written["service_factor"] = max(1.0, t_max / rated_torque)
            if t_max < rated_torque:
                notes.append(f"sized by k_s P / w for the rated torque {rated_torque:.6g} N*m, above T_max")
    case_data["duty"] = {**{k: v for k, v in case_data.get("duty", {}).items() if k not in declared}, **written}
    library = case_data.setdefault("library", {})
    for key, entry in data.get("library", {}).items():
        if key in library:
            library[key] = entry
        elif key in {role.key for role in coupling.materials}:
            given = ", ".join(q for role in coupling.materials if role.key == key for q in role.fills.values()
                              if q in case_data_values(case_data))
            notes.append(f"library.{key} not applied: the {name}'s starting case gives {given} itself")
        else:
            notes.append(f"library.{key} not applied: the {name} coupling has no such role")
    limits = {q.name for q in coupling.quantities if q.section == "limits"}
    for key, value in data.get("limits", {}).items():
        if key in limits:
            case_data.setdefault("limits", {})[key] = value
        else:
            notes.append(f"limits.{key} not applied: the {name} coupling has no such limit")
    if "start_up" in data:
        case_data["start_up"] = start_up = copy.deepcopy(data["start_up"])
        if isinstance(start_up, dict):  # the driven machine and start time of the duty, where the case has no duty
            for table, key, source in START_UP_FROM_DUTY:  # quantity for the start-up's default to follow
                if source not in declared and isinstance(start_up.setdefault(table, {}), dict):
                    start_up[table].setdefault(key, raw_duty[source])
            notes += _start_up_not_applied(coupling.formulation(mode).speed_law, start_up, name)
    freeable = [v.name for v in coupling.formulation(mode).variables if v.fixed_unless_freed]
    if freeable:
        case_data.setdefault("options", {})["free"] = freeable
    _merge(case_data, overrides)
    case_data["title"] = f"{data.get('title', 'choose-coupling')} ({name})"
    candidate = Candidate(name, mode, None, notes)
    try:
        candidate.case = parse_case(case_data, f"{path} ({name})")
    except InputError as exc:
        given = _override_paths(overrides)  # a field the case's own [couplings.NAME] wrote: the case's error
        own = [p for p in exc.problems if any(p.field == g or p.field.startswith(g + ".") or g.startswith(p.field + ".")
                                              for g in given)]
        if own:
            raise InputError.several([InputError(f"couplings.{name}.{p.field}", p.problem) for p in own]) from None
        candidate.reason = "cannot be posed: " + "; ".join(str(p) for p in exc.problems)
        candidate.problems = tuple(exc.problems)
    return candidate


def _override_paths(table: dict, prefix: str = "") -> list[str]:
    """The dotted keys of the values a ``[couplings.NAME]`` table writes (``geometry.flank_angle``)."""
    paths = []
    for key, value in table.items():
        path = f"{prefix}{key}"
        paths += _override_paths(value, path + ".") if isinstance(value, dict) and value else [path]
    return paths


SET_ASIDE = {  # what a coupling's case may have but choose-coupling would not apply: refused, not dropped
    "scatter": "choose-coupling designs every coupling at its nominal values; design one coupling under scatter with "
               "clutchopt solve CASE --robust",
    "options.objective": f"choose-coupling designs every coupling for least like-for-like mass ({OBJECTIVE}), the "
                         "mass it ranks them by; compare costs in its cost column",
    "options.choose": "choose-coupling designs one entry of each role: name it in [library] or "
                      "[couplings.NAME.library]; let solve choose among entries in one coupling's case",
    "start_up.heat.ambient": "the air around the coupling is one for every coupling (it ranks them like for like): "
                             "give it in the neutral [start_up.heat]",
    **dict.fromkeys(("duty", "start_up.driver", "start_up.driven", "start_up.limits.max_start_time",
                     "start_up.limits.starts_per_hour"), (
        "the duty and the drive are one for every coupling (it ranks them like for like): give them in the neutral "
        "[duty] and [start_up]"))}


def _check_override(name: str, table: dict, problems: Problems) -> None:
    """A ``[couplings.NAME]`` table holds sections of that coupling's case (each a table), and a mode it has."""
    coupling = get_coupling(name)
    sections = sorted({q.section for q in coupling.quantities} | set(_EXTRA_SECTIONS))
    for key, value in table.items():
        field = f"couplings.{name}.{key}"
        if key not in sections:
            problems.errors.append(InputError(field, f"not a section of a {name} case; [couplings.{name}] takes "
                                                     f"{', '.join(s for s in sections if s not in SET_ASIDE)}"))
        elif not isinstance(value, dict):
            problems.errors.append(InputError(field, f"must be a table [couplings.{name}.{key}]"))
    given = _override_paths(table)
    for key, why in SET_ASIDE.items():
        if any(path == key or path.startswith(key + ".") for path in given):
            problems.errors.append(InputError(f"couplings.{name}.{key}", why))
    options = table.get("options")
    if isinstance(options, dict) and "mode" in options:
        mode = options["mode"]
        if not isinstance(mode, str) or mode not in coupling.formulations:
            problems.errors.append(InputError(f"couplings.{name}.options.mode", (
                f"must be a mode of the {name} coupling ({', '.join(coupling.formulations)}), got {shown_value(mode)}")))


def _fields(names: tuple[str, ...]) -> dict[str, tuple[str, ...] | None]:
    """``{table: keys}`` of the ``[start_up]`` sub-tables that hold the quantities ``names``; ``None`` for a table
    all of whose quantities are among them (left out whole, with its switches)."""
    tables: dict[str, list[tuple[str, str]]] = {}
    for quantity in START_UP_QUANTITIES:
        section, _, key = quantity.key.rpartition(".")
        if section.count(".") == 1:
            tables.setdefault(section.split(".")[1], []).append((quantity.name, key))
    fields = {table: tuple(key for name, key in rows if name in names) for table, rows in tables.items()}
    return {table: None if len(keys) == len(tables[table]) else keys for table, keys in fields.items() if keys}


def _start_up_not_applied(law, start_up: dict, name: str) -> list[str]:
    """Take out of the neutral ``[start_up]`` what coupling ``name`` cannot have, and say so: a coupling that does
    not slip (an elastic link) has no friction heat, lining wear or overload; one that declares no friction area that
    wears has no lining life."""
    if isinstance(law, ElasticLaw):
        dropped, why = _fields(SLIP_ONLY), "an elastic link does not slip"
        effects = start_up.get("effects")
        if isinstance(effects, list) and any(e in SLIP_EFFECTS for e in effects):
            start_up["effects"] = [e for e in effects if e not in SLIP_EFFECTS]
            dropped_effects = [f"start_up.effects: {', '.join(e for e in effects if e in SLIP_EFFECTS)}"]
        else:
            dropped_effects = []
    elif law is not None and law.friction_area is None:
        dropped, why, dropped_effects = _fields(WEAR_ONLY), "it declares no friction area that wears", []
    else:
        return []
    notes = [f"{text} not applied: {why}" for text in dropped_effects]
    for table, keys in dropped.items():
        sub = start_up.get(table)
        if not isinstance(sub, dict):
            continue
        for key in list(sub) if keys is None else [k for k in keys if k in sub]:
            del sub[key]
            notes.append(f"start_up.{table}.{key} not applied: {why}")
        if not sub:
            del start_up[table]
    return notes


def case_data_values(case_data: dict) -> set[str]:
    """The quantity names a case's TOML gives a value to (its sections' keys)."""
    return {key for section in case_data.values() if isinstance(section, dict) for key in section}


def _merge(target: dict, extra: dict) -> None:
    for key, value in extra.items():
        if isinstance(value, dict) and isinstance(target.get(key), dict):
            _merge(target[key], value)
        else:
            target[key] = copy.deepcopy(value)


def pose(data: dict, path: str = "") -> tuple[Choice, dict[str, float]]:
    """Every coupling posed for the neutral case ``data`` (not solved)."""
    if data.get("coupling", NEUTRAL) != NEUTRAL:
        raise InputError("coupling", f"choose-coupling takes a case with coupling = \"{NEUTRAL}\" (or none), "
                                     f"got {data['coupling']!r}")
    problems = Problems()
    duty, raw = {}, {}
    with problems.field():
        duty, raw = neutral_duty(data, path)
    couplings = data.get("couplings", {}) if isinstance(data.get("couplings", {}), dict) else {}
    for name, table in couplings.items():
        if name not in MODULES:
            problems.errors.append(InputError(f"couplings.{name}", f"unknown coupling; known: {', '.join(MODULES)}"))
        elif not isinstance(table, dict):
            problems.errors.append(InputError(f"couplings.{name}", "must be a table of that coupling's sections"))
        else:
            _check_override(name, table, problems)
    drive = Problems()  # a bad field of the start-up's tables: the neutral case's, not a coupling's reason to lose
    if isinstance(data.get("start_up"), dict):
        start_up, _, _ = read_tables(data["start_up"], drive)
        if not (problems or drive):  # and so are the drive's checks across its fields that no coupling changes
            with problems.field():
                check_values(with_defaults({**duty, **start_up}))
    _check_shared(data, problems)
    problems.raise_any()
    candidates = []
    for name in MODULES:  # (posed where only the start-up's tables are bad: the problems each coupling's case finds
        with problems.field():  # there too are said with them, in one run: review 25)
            candidates.append(posed_case(name, duty, raw, data, path))
    problems.raise_any()
    if drive or all(c.case is None for c in candidates):  # nothing poses: the neutral case itself is wrong
        said = [{(p.field, p.problem) for p in c.problems} for c in candidates]
        shared = [p for p in candidates[0].problems if all((p.field, p.problem) in each for each in said[1:])]
        own = [problem for error in drive.errors for problem in error.problems]
        shared = own + [p for p in shared if p.field not in {q.field for q in own}]
        if shared:  # (each refused for the same fields: the neutral case's, one line each, as solve says them)
            raise InputError.several([InputError(p.field, p.problem) for p in shared])
        raise InputError(path or "case", "no coupling can be posed: " + " | ".join(
            f"{c.coupling}: {c.reason}" for c in candidates))
    t_max = required_torque(duty["inertia"], duty["speed"], duty["acceleration_time"], duty["resisting_torque"])
    return Choice(path, data.get("title", ""), t_max, candidates), duty


def choose_coupling(case, options: SolverOptions = SolverOptions()) -> Choice:
    """Every coupling designed for the neutral case (a path or its parsed TOML), verified and ranked."""
    from clutchopt.optimise.design import design_case

    path = str(case) if not isinstance(case, dict) else ""
    data = read_toml(case) if not isinstance(case, dict) else case
    choice, _ = pose(data, path)
    for candidate in choice.candidates:
        if candidate.case is None:
            continue
        try:
            candidate.solution = design_case(candidate.case, candidate.mode, OBJECTIVE, options)[0].solution
        except InputError as exc:  # the drive does not suit this coupling (e.g. an effect it does not have)
            candidate.reason = "cannot be posed: " + "; ".join(str(p) for p in exc.problems)
            continue
        candidate.sized_for = _sized_for(candidate)
        candidate.notes += (candidate.solution.start_up or {}).get("lining_notes") or []  # what was not checked
        if candidate.optimal:
            formulation = get_coupling(candidate.coupling).formulation(candidate.mode)
            envelope = formulation.envelope(namespace(candidate.solution.design), namespace(candidate.case.values))
            candidate.parts = {name: float(envelope.parts[name].mass) for name in ENVELOPE_PARTS}
        elif not candidate.reason:
            candidate.reason = f"{candidate.status}: {candidate.solution.diagnosis or 'no verified design'}"
    return choice


def _sized_for(candidate: Candidate) -> float:
    """The torque the coupling's own requirement asks for (its ``required_torque`` output, or the case's torque)."""
    if "required_torque" in candidate.solution.outputs:
        return float(candidate.solution.outputs["required_torque"].value)
    return float(candidate.case.values.get("torque", math.nan))


def choice_json(choice: Choice) -> dict:
    """The choice as plain data, SI values (units beside them via :func:`choice_units`)."""
    ranked = choice.ranked
    return {
        "case": choice.path, "title": choice.title, "required_torque": choice.required_torque,
        "drive": next((c.case.start_up.motor_note for c in choice.candidates if c.case is not None
                       and c.case.start_up is not None and c.case.start_up.motor_note), ""),
        "ranking": {what: choice.rank_by(output) for what, output in RANKINGS},
        "couplings": [{
            "coupling": c.coupling, "mode": c.mode, "status": c.status, "rank": i + 1 if c.optimal else None,
            "envelope_mass": _finite(c.output("envelope_mass")), "cost": _finite(c.output("cost")),
            "envelope_diameter": _finite(c.output("envelope_diameter")),
            "envelope_length": _finite(c.output("envelope_length")),
            "objective_mass": _finite(c.solution.objective) if c.optimal else None,
            "sized_for": _finite(c.sized_for), "parts": c.parts, "sized_by": c.sizing(), "why": choice.why(c),
            "notes": c.notes, "design": _design(c.solution), "checks": _reviewed(c),
        } for i, c in enumerate(ranked)],
    }


def choice_units() -> dict:
    per = {"rank": "", "envelope_mass": "kg", "cost": "EUR", "envelope_diameter": "m", "envelope_length": "m",
           "objective_mass": "kg", "sized_for": "N*m", "parts": {name: "kg" for name in ENVELOPE_PARTS},
           "checks": {name: {"margin": ""} for name in REVIEWED}}  # a margin relative, beside its check's ``unit``
    return {"required_torque": "N*m", "couplings": per}


def _reviewed(candidate: Candidate) -> dict:
    """The verified design's drive constraints of :data:`REVIEWED` (float64 re-check: value, limit, margin; SI with
    their units); none for a coupling without a verified design."""
    if not candidate.optimal:
        return {}
    checks = {c.name: c.as_dict() for c in candidate.solution.constraints if c.name in REVIEWED}
    return {name: {k: checks[name][k] for k in ("value", "limit", "margin", "active", "unit", "display_unit")}
            for name in REVIEWED if name in checks}


def _design(solution: Solution | None) -> dict:
    """The design variables, each as ``{"value": SI, "unit": SI unit}`` (their units differ by coupling)."""
    if solution is None:
        return {}
    return {name: {"value": value, "unit": si_unit(solution.design_units.get(name, ""))}
            for name, value in solution.design.items()}


def _finite(value: float) -> float | None:
    return value if value is not None and math.isfinite(value) else None
