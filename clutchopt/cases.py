"""Case files: TOML with quantities in units, read into SI and checked field by field.

Layout of a case::

    coupling = "wedge"              # which formulation family
    title = "..."                   # optional
    [duty]                          # sections as the coupling declares them
    inertia = "0.5 kg*m^2"          # bare numbers are SI
    [bounds]                        # optional: search box of design variables
    flank_inner_radius = ["30 mm", "120 mm"]
    [options]                       # optional
    free = ["flank_angle"]          # variables fixed at the case value unless listed here
    objective = "mass"
    [library]                       # optional: entries of the material library (clutchopt materials)
    material = "C45_QT"             # fills the fields it maps to, unless the case gives them
    friction_pair = "organic_dry"

Every problem raises :class:`~clutchopt.errors.InputError` naming the field (``duty.inertia``).
"""

from __future__ import annotations

import difflib
import itertools
import math
import tomllib
from dataclasses import dataclass, field, replace
from numbers import Real
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from clutchopt import materials
from clutchopt.errors import InputError, Problems, shown_value
from clutchopt.files import CASE_BYTES, read_text, shown
from clutchopt.scatter import Scatter, parse_correlation, parse_scatter
from clutchopt.model import REQUIRED, Quantity, followed
from clutchopt.start_up.equations import QUANTITIES as START_UP_QUANTITIES
from clutchopt.start_up.equations import LIMITS as START_UP_LIMITS, SPRING_PRELOAD, StartUpSpec
from clutchopt.start_up.overload import FRICTION
from clutchopt.units import BelowFloat64, float_text, to_si

_TOP_LEVEL = {"coupling", "title", "description"}
_OPTION_KEYS = {"free", "objective", "mode", "choose"}
_EXTRA_SECTIONS = ("bounds", "options", "library", "start_up", "scatter")


@dataclass(frozen=True)
class Case:
    """A checked case: SI values by quantity name, variable bounds, options."""

    coupling: str
    title: str
    values: dict[str, float]
    bounds: dict[str, tuple[float, float]] = field(default_factory=dict)
    free: tuple[str, ...] = ()
    options: dict[str, Any] = field(default_factory=dict)
    path: str = ""
    start_up: StartUpSpec | None = None  # the drive of a [start_up] section
    filled: dict[str, tuple[str, str]] = field(default_factory=dict)  # from the library: name -> (role, entry)
    scatter: tuple[Scatter, ...] = ()  # the [scatter] section: ranges and distributions of case quantities
    # defaults that refer to another quantity, {name: (source, factor)}: the start-up's driven inertia and load follow
    # the duty's, its start time limit t_p, its lock-up speed 90 % of synchronous. Each is set from its source when
    # the values change (with_values) and when a problem is posed (the NLP's parameters, a robust design's corners)
    follows: dict[str, tuple[str, float]] = field(default_factory=dict)
    # [scatter.correlation]: the correlation matrix of the scattered quantities' normal scores (n x n, in the order of
    # scatter; a Gaussian copula, clutchopt.scatter.draw), None: independent
    correlation: tuple[tuple[float, ...], ...] | None = None

    @property
    def quantities(self) -> tuple[Quantity, ...]:
        """The coupling's quantities, and those of the start-up section if the case has one."""
        from clutchopt.formulations import get_coupling

        extra = START_UP_QUANTITIES if self.start_up else ()
        return get_coupling(self.coupling).quantities + extra

    def params(self) -> SimpleNamespace:
        """Values by attribute; quantities the case leaves out (optional ones) read as NaN."""
        names = {q.name: math.nan for q in self.quantities}
        names.update(self.values)
        return SimpleNamespace(**names)

    def with_values(self, **values: float) -> "Case":
        """A copy with some SI values replaced and re-checked (sweeps, tests); a default that follows a replaced
        quantity follows it, one that is replaced itself is given from then on (nor filled by the library)."""
        declared = {q.name: q for q in self.quantities}
        limits = self.start_up.limits if self.start_up is not None else ()
        for name, value in values.items():
            if name not in declared:
                raise InputError(name, f"unknown quantity for coupling {self.coupling!r}")
            if name in START_UP_LIMITS and name not in limits:  # (its row posed only where the case file gives it)
                raise InputError(name, f"the case leaves out {declared[name].key}, which no constraint then reads: "
                                       "give it in the case file to set it")
        values = {name: _si_number(name, value) for name, value in values.items()}
        for name, value in values.items():
            declared[name].check(value)
        follows = {name: rule for name, rule in self.follows.items() if name not in values}
        return replace(self, values=self.followed({**self.values, **values}, follows), follows=follows,
                       filled={name: entry for name, entry in self.filled.items() if name not in values})

    def followed(self, values: dict, follows: dict | None = None) -> dict:
        """``values`` (floats, arrays or CasADi symbols by name) with each default that follows another quantity set
        from its source."""
        return followed(values, self.follows if follows is None else follows)

    def missing_for(self, objective: str, quantities: tuple[Quantity, ...] | None = None) -> list[Quantity]:
        """The quantities ``objective`` alone needs (``needed_by``) that the case leaves out (a ball case's prices),
        among ``quantities`` (default: the case's)."""
        return [q for q in quantities or self.quantities if q.needed_by == objective and q.name not in self.values]

    def require(self, *objectives: str, quantities: tuple[Quantity, ...] | None = None) -> None:
        """Refuse, naming each, what ``objectives`` need and the case leaves out (among ``quantities``, default: the
        case's): called before any solve that poses one of them."""
        from clutchopt.formulations import get_coupling

        problems = Problems()
        for objective in objectives:
            for quantity in self.missing_for(objective, quantities):
                problems.errors.append(InputError(quantity.key, _missing(
                    quantity, get_coupling(self.coupling), f"the {objective} objective needs it: ")))
        problems.raise_any()

    def mode_of(self, mode: str | None) -> str | None:
        """The mode asked for, else (None) the case's option (None: the coupling's default); an empty name is asked
        for, and refused as unknown, not read as none."""
        return self.options.get("mode") if mode is None else mode

    def objective_of(self, objective: str | None) -> str:
        """The objective asked for, else (None) the case's option, else mass (an empty name: as :meth:`mode_of`)."""
        return self.options.get("objective", "mass") if objective is None else objective

    def given(self, *names: str) -> "Case":
        """A copy in which ``names`` are given at their present values: none of them follows another quantity
        (a quantity a sweep varies or a scatter spreads is the one it names)."""
        return replace(self, follows={name: rule for name, rule in self.follows.items() if name not in names})


def _si_number(name: str, value) -> float:
    """A value given to :meth:`Case.with_values`: a real number (SI), as a float; an InputError naming ``name`` for
    anything else (review 27: ``True`` had read as 1, the text '100' in another script's digits as 100, and a unit
    text, None or a list had raised from ``float``)."""
    if not isinstance(value, Real) or isinstance(value, bool):  # (NumPy's numbers are Real, its bool_ not)
        raise InputError(name, f"must be a number in SI units, got {shown_value(value, 80)} (a case file's "
                               "quantities take their units: '1000 rpm')")
    try:
        return float(value)
    except OverflowError:
        raise InputError(name, "is beyond the float64 range") from None


def _where(text: str, literal: str) -> str:
    """``line N (key): `` of the first line of ``text`` that holds ``literal`` (a number the parser refused), or
    nothing."""
    for number, line in enumerate(text.splitlines(), 1):
        if literal in line:
            key = line.split("=")[0].strip() if "=" in line else ""
            return f"line {number}{f' ({key})' if key else ''}: "
    return ""


def read_toml(path: str | Path) -> dict:
    """A TOML file (case or scene): a regular UTF-8 file of at most 1 MiB, parsed; problems name the path."""
    text = read_text(path, CASE_BYTES)
    try:
        return tomllib.loads(text, parse_float=float_text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(shown(path), f"not valid TOML: {exc}") from None
    except BelowFloat64 as exc:
        raise InputError(shown(path), f"{_where(text, str(exc).split()[0])}{exc}") from None
    except ValueError as exc:  # an integer of more than 4300 digits
        raise InputError(shown(path), f"not valid TOML: {str(exc).split(';')[0]}") from None
    except RecursionError:
        raise InputError(shown(path), "not valid TOML for clutchopt: arrays or tables nested too deeply") from None


def load_case(path: str | Path) -> Case:
    """Read and check a case file."""
    return parse_case(read_toml(path), str(path))


NEUTRAL = "any"  # the coupling of a neutral case: one duty posed for every coupling (clutchopt.optimise.choose)


def parse_case(data: dict, path: str = "") -> Case:
    """Check every field of a case; all problems found are raised together (one InputError carrying them)."""
    from clutchopt.formulations import get_coupling

    if "coupling" not in data:
        raise InputError("coupling", "missing: say which coupling this case is for, e.g. coupling = \"wedge\"")
    if data["coupling"] == NEUTRAL:
        raise InputError("coupling", f"\"{NEUTRAL}\" poses one duty for every coupling: `clutchopt choose-coupling` "
                                     "takes it; this command takes a case of one coupling (its `[couplings.NAME]` "
                                     "tables, or `clutchopt init NAME`)")
    coupling = get_coupling(data["coupling"])
    declared = {q.key: q for q in coupling.quantities}
    sections = {q.section for q in coupling.quantities}
    problems = Problems()

    values: dict[str, float] = {}
    for key, table in data.items():
        if key in _TOP_LEVEL or key in _EXTRA_SECTIONS:
            continue
        if key in sections and not isinstance(table, dict):
            problems.errors.append(InputError(key, f"must be a table [{key}] of "
                                   f"{', '.join(q.name for q in coupling.quantities if q.section == key)}"))
            continue
        if key not in sections:
            known = sections | set(_EXTRA_SECTIONS)
            problems.errors.append(InputError(key, f"unknown section or key{_did_you_mean(key, known)}; this "
                                                   f"{coupling.name} case may have {', '.join(sorted(known))}"))
            continue
        for name, raw in table.items():
            quantity = declared.get(f"{key}.{name}")
            with problems.field():
                if quantity is None:
                    known = [q.name for q in coupling.quantities if q.section == key]
                    raise InputError(f"{key}.{name}", f"unknown key{_did_you_mean(name, known)}; [{key}] takes "
                                                      f"{', '.join(known)}")
                values[quantity.name] = quantity.check(to_si(quantity.key, raw, quantity.unit))

    options = data.get("options", {})
    choose, filled = {}, {}
    with problems.field():
        choose = (materials.check_choose(options["choose"], coupling.materials)
                  if isinstance(options, dict) and "choose" in options else {})
    with problems.field():
        filled = materials.fill(data.get("library", {}), coupling.materials, coupling.quantities, values, choose)
    given = {q.name for q in coupling.quantities if q.name in _table(data.get(q.section))}
    refused_choice = {name for role in coupling.materials if not choose and role.key in _table(
        _table(options).get("choose")) for name in role.fills.values()}  # (what a refused options.choose would
    # have filled is not missing besides its own error: review 25)
    for quantity in coupling.quantities:
        if quantity.name in given or quantity.name in values or quantity.name in refused_choice:
            continue
        with problems.field():
            if quantity.default is REQUIRED and not quantity.needed_by:
                raise InputError(quantity.key, _missing(quantity, coupling))
            if quantity.default not in (None, REQUIRED):
                values[quantity.name] = quantity.check(to_si(quantity.key, quantity.default, quantity.unit))

    start_up, follows = None, {}
    if "start_up" in data:  # its defaults follow the duty's values: checked across fields only if those are sound
        from clutchopt.start_up.section import parse_start_up

        with problems.field():
            lining: dict[str, float] = {}  # what the friction pair fills in the section (a bad [library]: above)
            lining_filled = _quietly(materials.fill, data.get("library", {}), coupling.materials,
                                     START_UP_QUANTITIES, lining, choose) or {}
            start_values, start_up, follows, taken = parse_start_up(data["start_up"], coupling, values,
                                                                    not problems, lining)
            values.update(start_values)
            filled.update({name: lining_filled[name] for name in lining_filled if name in taken})  # the library's
            # order: ``taken`` is a set, whose order changed from run to run (PYTHONHASHSEED) in the library note
            _highest_friction_given(values, start_up)
    scatter, correlation = (), None
    if "scatter" in data:  # scattered around the case's values: not checked against a value that is itself bad
        with problems.field():
            quantities = coupling.quantities + (START_UP_QUANTITIES if "start_up" in data else ())
            keys = {q.key: q.name for q in quantities}
            broken = {keys[p.field] for error in problems.errors for p in error.problems if p.field in keys}
            broken |= {q.name for q in START_UP_QUANTITIES} if "start_up" in data and start_up is None else set()
            scatter = parse_scatter(data["scatter"], quantities, values, broken,
                                    materials.scatter_ranges(data.get("library"), coupling.materials))
            correlation = parse_correlation(data["scatter"], scatter)
    bounds = _parse_bounds(data.get("bounds", {}), coupling, problems, "start_up" in data)
    options = _parse_options(options, coupling, problems, "start_up" in data)
    for name in ("title", "description"):
        with problems.field():
            check_text(name, data.get(name, ""), multiline=name == "description")
    problems.raise_any()

    case = Case(coupling.name, data.get("title", ""), values, bounds, tuple(options.get("free", ())),
                {**options, **({"choose": choose} if choose else {})}, path, start_up, filled, scatter,
                {name: rule for name, rule in follows.items() if name not in {s.name for s in scatter}}, correlation)
    case = replace(case, values=materials.with_highest_friction(case, case.values, case.filled))
    check_across(case)
    check_scatter_corners(case)
    materials.variants(case, coupling)  # every choice of options.choose is checked here, before any solve
    sets, _ = materials.chosen(case, coupling)
    for s in scatter:
        with problems.field():
            if s.name in sets:
                raise InputError(f"scatter.{s.name}", f"options.choose.{sets[s.name]} sets it for each choice, so "
                                                      "one range cannot hold for all of them; scatter it in a case "
                                                      "that names one entry")
    problems.raise_any()
    return case


def _highest_friction_given(values: dict[str, float], start_up) -> None:
    """A [start_up.overload] friction_max the case gives is at least the case's own friction coefficient: the overload
    takes max(f, f_max) (clutchopt/start_up/overload.py, for a sweep or a scatter's corner above it), which would
    set a value below the case's own aside without a word."""
    highest, nominal = values.get("friction_max"), values.get(FRICTION)
    if start_up.friction_max_given and highest is not None and nominal is not None and highest < nominal:
        raise InputError("start_up.overload.friction_max", f"{highest:g} is below the case's friction_coefficient "
                                                           f"{nominal:g}: the highest friction coefficient the pair "
                                                           "reaches cannot be below its nominal one")


def _quietly(function, *args):
    """``function(*args)``, or None where it raises an InputError that another field's check reports already."""
    try:
        return function(*args)
    except InputError:
        return None


def check_across(case: Case) -> None:
    """The checks across fields, the coupling's and a [start_up]'s drive's: on the case as read, and on every point
    a sweep or a scatter moves it to, before any solve."""
    from clutchopt.formulations import get_coupling

    get_coupling(case.coupling).check_case(case)
    if case.start_up is not None:
        from clutchopt.start_up.section import check_values

        check_values(case.values)


def check_scatter_corners(case: Case) -> None:
    """:func:`check_across` at every corner of the scattered quantities' ranges (the ends a worst-case design
    meets): a scatter that moves the case where it means nothing is refused, naming the corner."""
    if not case.scatter:
        return
    names = [s.name for s in case.scatter]
    for ends in itertools.product(*((s.low, s.high) for s in case.scatter)):
        try:
            check_across(case.with_values(**dict(zip(names, ends))))
        except InputError as exc:
            declared = {q.name: q for q in case.quantities}
            corner = ", ".join(f"{name} = {declared[name].show(end)}" for name, end in zip(names, ends))
            raise exc.at(f"scatter (at {corner})") from None


def _parse_options(options: Any, coupling, problems: Problems, start_up: bool) -> dict[str, Any]:
    if not isinstance(options, dict):
        problems.errors.append(InputError("options", "must be a table"))
        return {}
    for name in options:
        if name not in _OPTION_KEYS:
            problems.errors.append(InputError(f"options.{name}", f"unknown option; options are "
                                                                 f"{', '.join(sorted(_OPTION_KEYS))}"))
    free = options.get("free", [])
    freeable = ({v.name for v in coupling.variables if v.fixed_unless_freed}
                | ({"spring_preload"} if start_up else set()))
    if not isinstance(free, list) or not all(isinstance(name, str) and name in freeable for name in free):
        problems.errors.append(InputError("options.free", f"must be a list drawn from {sorted(freeable)}, "
                                                          f"got {shown_value(free)}"))
    elif len(set(free)) != len(free):
        problems.errors.append(InputError("options.free", f"lists a variable twice: {free!r}"))
    for name in ("mode", "objective"):
        if name in options and not (isinstance(options[name], str) and options[name].strip()):
            problems.errors.append(InputError(f"options.{name}",
                                              f"must be a name (text), got {shown_value(options[name])}"))
    return {name: value for name, value in options.items() if name in _OPTION_KEYS}


TITLE_CHARACTERS = 200
DESCRIPTION_CHARACTERS = 10_000


def check_text(field: str, value: Any, multiline: bool = False) -> str:
    """A title (one printable line, at most TITLE_CHARACTERS) or a description (lines of printable text): text
    that is printed to a terminal must not carry control characters (escape sequences)."""
    limit = DESCRIPTION_CHARACTERS if multiline else TITLE_CHARACTERS
    if not isinstance(value, str):
        raise InputError(field, f"must be text, got {type(value).__name__}")
    if len(value) > limit:
        raise InputError(field, f"text of {len(value)} characters is too long (at most {limit})")
    bad = next((c for c in value if not c.isprintable() and not (multiline and c in "\n\t")), None)
    if bad is not None:
        raise InputError(field, f"contains the control character {bad!r}")
    return value


def _missing(quantity: Quantity, coupling, why: str = "") -> str:
    """``missing (price of the balls, in EUR/kg); or name a ...``: what a missing quantity is and where to get it."""
    return (f"missing ({why}{quantity.description}, in {quantity.unit or 'SI'})"
            + materials.hint(coupling.materials, quantity.name))


def _did_you_mean(name: str, known) -> str:
    """`` (did you mean 'duty'?)`` for a near miss, else nothing."""
    close = difflib.get_close_matches(str(name), list(known), n=1)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _table(value: Any) -> dict:
    return value if isinstance(value, dict) else {}


def _parse_bounds(table: Any, coupling, problems: Problems, start_up: bool = False) -> dict[str, tuple[float, float]]:
    if not isinstance(table, dict):
        problems.errors.append(InputError("bounds", "must be a table of [lower, upper] pairs"))
        return {}
    variables = {v.name: v for v in coupling.variables + ((SPRING_PRELOAD,) if start_up else ())}
    bounds = {}
    for name, pair in table.items():
        variable = variables.get(name)
        key = f"bounds.{name}"
        with problems.field():
            if variable is None:
                raise InputError(key, f"unknown design variable; bounds may be set for {', '.join(variables)}")
            if not isinstance(pair, list) or len(pair) != 2:
                raise InputError(key, f"must be a pair [lower, upper], got {shown_value(pair)}")
            lower, upper = (variable.check(to_si(key, raw, variable.unit), key) for raw in pair)
            if not lower < upper:
                raise InputError(key, f"lower bound {variable.show(lower)} must be below upper bound "
                                      f"{variable.show(upper)}")
            bounds[name] = (lower, upper)
    return bounds


def quantity_table(quantities: tuple[Quantity, ...], values: dict[str, float]) -> list[dict]:
    """Rows (key, symbol, value in unit, SI value, description) for printing the inputs of a case."""
    return [
        {"key": q.key, "symbol": q.symbol, "value": q.show(values[q.name]), "si": values[q.name],
         "description": q.description}
        for q in quantities if q.name in values
    ]
