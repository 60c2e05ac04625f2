"""The material library (clutchopt/data/materials.toml) and how a case names its entries.

The library has three tables: ``materials`` (steels and cast irons), ``friction_pairs`` (a friction material
against steel, dry or in oil) and ``thread_pairs`` (screw and nut, greased); each entry names its source. A
coupling declares the roles a case may fill from it (:class:`clutchopt.model.MaterialRole`), e.g. for the lever::

    [library]
    material = "41Cr4_QT"            # weights, links, pins and spring flange
    friction_pair = "organic_dry"    # linings

Each role fills the case quantities it maps to, unless the case gives them itself (explicit values win); what
the library filled is recorded in ``Case.library`` and reported by ``clutchopt solve``. ``options.choose`` lists
alternatives, e.g. ``choose = {friction_pair = ["organic_dry", "sintered_bronze_oiled"]}``: every combination is
a variant of the case (:func:`variants`), designed and ranked by every design command (``clutchopt.optimise.design``).
A role is named in ``[library]`` or listed in ``options.choose``, not in both (the choices would replace the entry).
"""

from __future__ import annotations

import itertools
import math
import tomllib
from dataclasses import dataclass, replace
from functools import lru_cache
from importlib.resources import files

from clutchopt.errors import InputError
from clutchopt.model import MaterialRole, Quantity
from clutchopt.units import from_si, to_si

Q = Quantity
MAX_CHOICES = 30  # combinations of options.choose designed in one run (each a design: with a [start_up], 2-3 s)
FIELDS: dict[str, tuple[Quantity, ...]] = {
    "materials": (
        Q("density", "kg/m^3", "density", "rho", above=0),
        Q("elastic_modulus", "GPa", "Young's modulus", "E", above=0),
        Q("poisson", "", "Poisson's ratio", "nu", at_least=0, below=0.5),
        Q("yield_strength", "MPa", "minimum yield strength R_e (R_p0.2), 16 < d <= 40 mm", "R_e", above=0),
        Q("tensile_strength", "MPa", "minimum tensile strength R_m", "R_m", above=0),
        Q("allowable_bending", "MPa", "allowable bending stress, R_e / 2.5 (grey iron R_m / 4)", "[sigma_b]",
          above=0),
        Q("allowable_normal", "MPa", "allowable tension or compression, R_e / 2.5 (grey iron R_m / 4)", "[sigma]",
          above=0),
        Q("allowable_shear", "MPa", "allowable shear stress, [sigma] / sqrt(3)", "[tau]", above=0),
        Q("allowable_contact", "MPa", "allowable Hertz contact stress, S_c / 1.3", "[p_H]", above=0),
        Q("price", "EUR/kg", "price of the raw material per kg (our estimate)", "", at_least=0),
    ),
    "friction_pairs": (
        Q("friction_coefficient", "", "nominal friction coefficient, to size with", "f", above=0, at_most=1),
        Q("friction_min", "", "lowest friction coefficient of the scatter range", "f_min", above=0, at_most=1),
        Q("friction_max", "", "highest friction coefficient of the scatter range", "f_max", above=0, at_most=1),
        Q("allowable_pressure", "MPa", "allowable pressure for a coupling slipping at every start (wear)", "[p]",
          above=0),
        Q("max_temperature", "degC", "peak bulk temperature of the friction material (a start's peak)", "T_max",
          above=0),
        Q("continuous_temperature", "degC", "bulk temperature the friction material may keep (repeated starts)",
          "T_cont", above=0),
        Q("wear_rate", "mm^3/J", "specific wear rate: lining volume worn per joule of friction work", "k_w", above=0),
        Q("density", "kg/m^3", "density of the friction material", "rho", above=0),
        Q("price", "EUR/cm^2", "price per area of friction surface (lining or grinding; our estimate)", "",
          at_least=0),
    ),
    "thread_pairs": (
        Q("friction_coefficient", "", "nominal friction coefficient of the thread", "f", above=0, at_most=1),
        Q("friction_min", "", "lowest friction coefficient of the scatter range", "f_min", above=0, at_most=1),
        Q("friction_max", "", "highest friction coefficient of the scatter range", "f_max", above=0, at_most=1),
        Q("allowable_pressure", "MPa", "allowable flank pressure [q] of the thread", "[q]", above=0),
    ),
}
KIND_TITLES = {"materials": "Steels and cast irons", "friction_pairs": "Friction pairs",
               "thread_pairs": "Thread pairs"}
_TEXT_FIELDS = ("description", "source", "notes")
LINING_FILLS = {"max_temperature": "max_lining_temperature", "continuous_temperature": "max_continuous_temperature",
                "wear_rate": "wear_rate"}  # what a friction pair fills in a case's [start_up] (clutchopt.start_up)


def fills_of(role: MaterialRole, declared) -> dict[str, str]:
    """Library field -> quantity the role fills among ``declared`` (quantity names): the coupling's own
    (``role.fills``) and, for a friction pair, a start-up's lining limits and wear rate (LINING_FILLS)."""
    extra = LINING_FILLS if role.kind == "friction_pairs" else {}
    return {field: quantity for field, quantity in {**role.fills, **extra}.items() if quantity in declared}


@dataclass(frozen=True)
class LibraryEntry:
    """One material or pair: its values in SI by field name (fields it does not give are absent)."""

    kind: str
    name: str
    description: str
    source: str
    values: dict[str, float]
    notes: str = ""

    def fields(self) -> tuple[Quantity, ...]:
        return tuple(q for q in FIELDS[self.kind] if q.name in self.values)


@lru_cache(maxsize=1)
def library() -> dict[str, dict[str, LibraryEntry]]:
    """Every entry of the shipped library, by table and name (read once per process)."""
    text = files("clutchopt.data").joinpath("materials.toml").read_text(encoding="utf-8")
    tables = tomllib.loads(text)
    return {kind: {name: _entry(kind, name, raw) for name, raw in tables.get(kind, {}).items()} for kind in FIELDS}


def _entry(kind: str, name: str, raw: dict) -> LibraryEntry:
    declared = {q.name: q for q in FIELDS[kind]}
    values = {}
    for key, value in raw.items():
        if key in _TEXT_FIELDS:
            continue
        field = f"{kind}.{name}.{key}"
        if key not in declared:
            raise InputError(field, f"unknown field; {kind} have {', '.join(declared)}")
        values[key] = declared[key].check(to_si(field, value, declared[key].unit), field)
    if not raw.get("source"):
        raise InputError(f"{kind}.{name}", "every entry names its source")
    return LibraryEntry(kind, name, raw.get("description", ""), raw["source"], values, raw.get("notes", ""))


def lookup(role: MaterialRole, name: object, field: str | None = None) -> LibraryEntry:
    """The entry ``name`` of the role's table; bad input names the field and lists the known names."""
    entries = library()[role.kind]
    if not isinstance(name, str) or name not in entries:
        raise InputError(field or role.key, f"unknown {role.kind.replace('_', ' ')[:-1]} {name!r}; known: "
                                            f"{', '.join(entries)} (clutchopt materials lists them)")
    return entries[name]


def check_choose(choose: object, roles: tuple[MaterialRole, ...]) -> dict[str, tuple[str, ...]]:
    """``options.choose``: a table from role to a list of at least one known entry name, at most MAX_CHOICES
    combinations in all."""
    by_key = {role.key: role for role in roles}
    if not isinstance(choose, dict) or not choose:
        raise InputError("options.choose", f"must be a table of lists, e.g. {{{_example(roles)}}}")
    checked = {}
    for key, names in choose.items():
        field = f"options.choose.{key}"
        if key not in by_key:
            raise InputError(field, f"unknown role; this coupling may choose {', '.join(by_key) or 'nothing'}")
        if not isinstance(names, list) or not names or len(set(map(str, names))) != len(names):
            raise InputError(field, f"must be a list of different names, e.g. [{_example(roles, list_only=True)}]")
        checked[key] = tuple(lookup(by_key[key], name, field).name for name in names)
    combinations = math.prod(len(names) for names in checked.values())
    if combinations > MAX_CHOICES:
        raise InputError("options.choose", f"{combinations} combinations ("
                                           f"{' x '.join(f'{len(names)} {key}' for key, names in checked.items())}); "
                                           f"at most {MAX_CHOICES} are designed in one run: list fewer names, or name "
                                           "one role's entry in [library] and choose among the others")
    return checked


def chosen(case, coupling) -> tuple[dict[str, str], dict[str, str]]:
    """What ``options.choose`` sets for each choice, and what the case keeps whatever the choice: quantity ->
    the role (``friction_pair``) of each quantity a chosen role fills from the library, and of each it would fill
    but the case gives itself."""
    by_key = {role.key: role for role in coupling.materials}
    sets, kept = {}, {}
    for key in case.options.get("choose") or {}:
        for quantity in fills_of(by_key[key], {q.name for q in case.quantities}).values():
            if case.filled.get(quantity, (None,))[0] == key:
                sets[quantity] = key
            elif quantity in case.values:
                kept[quantity] = key
    return sets, kept


def _example(roles: tuple[MaterialRole, ...], list_only: bool = False) -> str:
    """``friction_pair = ["organic_dry", "organic_oiled"]`` (or the list alone) for the coupling's last role."""
    role = roles[-1] if roles else MaterialRole("material", "materials", "", {})
    listed = ", ".join(f'"{n}"' for n in list(library()[role.kind])[:2])
    return listed if list_only else f"{role.key} = [{listed}]"


def _named(roles: tuple[MaterialRole, ...]) -> str:
    """``friction_pair = "organic_dry"``: how a case names an entry for the coupling's last role."""
    role = roles[-1] if roles else MaterialRole("material", "materials", "", {})
    return f'{role.key} = "{next(iter(library()[role.kind]))}"'


def fill(table: object, roles: tuple[MaterialRole, ...], quantities: tuple[Quantity, ...],
         values: dict[str, float], choose: dict[str, tuple[str, ...]]) -> dict[str, tuple[str, str]]:
    """Fill ``values`` (SI, by quantity name) from the entries the case's ``[library]`` names; explicit values
    are kept. A role listed in ``options.choose`` and not in ``[library]`` takes its first choice. Returns what
    was filled: quantity name -> (role key, entry name).
    """
    if not isinstance(table, dict):
        raise InputError("library", f"must be a table of names, e.g. [library] {_named(roles)}")
    keys = [role.key for role in roles]
    for key in table:
        if key not in keys:
            raise InputError(f"library.{key}", f"unknown key; [library] takes {', '.join(keys) or 'nothing'} "
                                               "for this coupling")
    both = [key for key in keys if key in table and key in choose]
    if both:
        raise InputError(f"library.{both[0]}", f"names {table[both[0]]!r}, and options.choose.{both[0]} lists the "
                                               "entries to choose from: name one entry in [library] or several in "
                                               "options.choose, not both")
    declared = {q.name: q for q in quantities}
    filled = {}
    for role in roles:
        name = table.get(role.key, choose.get(role.key, (None,))[0])
        if name is None:
            continue
        entry = lookup(role, name, f"library.{role.key}")
        for library_field, quantity in fills_of(role, declared).items():
            if quantity not in values and library_field in entry.values:
                values[quantity] = declared[quantity].check(entry.values[library_field],
                                                            f"{role.key} = {entry.name}: {library_field}")
                filled[quantity] = (role.key, entry.name)
    return filled


SCATTER_RANGES = {"friction_coefficient": ("friction_min", "friction_max")}  # library field -> its scatter range


def scatter_ranges(table: object, roles: tuple[MaterialRole, ...]) -> dict[str, tuple[float, float, str]]:
    """The scatter ranges the entries a case's ``[library]`` names give (``[scatter] friction_coefficient =
    "library"``): quantity name -> (low, high, "friction_pair = organic_dry"), SI. Only entries named in
    ``[library]`` (a choice of ``options.choose`` sets the value per choice); a bad table gives none (:func:`fill`
    refuses it)."""
    if not isinstance(table, dict):
        return {}
    ranges = {}
    for role in roles:
        entry = library()[role.kind].get(table.get(role.key)) if isinstance(table.get(role.key), str) else None
        for library_field, quantity in role.fills.items() if entry else ():
            ends = SCATTER_RANGES.get(library_field)
            if ends and all(end in entry.values for end in ends):
                ranges[quantity] = (entry.values[ends[0]], entry.values[ends[1]], f"{role.key} = {entry.name}")
    return ranges


def hint(roles: tuple[MaterialRole, ...], quantity: str) -> str:
    """``; or name a friction_pair (clutchopt materials)`` for a missing quantity a role would fill, else ``""``."""
    keys = [role.key for role in roles if quantity in role.fills.values()]
    return f"; or name a {' or '.join(keys)} (clutchopt materials)" if keys else ""


def variants(case, coupling) -> list[tuple[dict[str, str], object]]:
    """Every combination of ``options.choose`` as (choice, case): the chosen entries fill what the library
    filled in the case (explicit values stay), checked as the case was. Without ``options.choose``: the case
    itself, no choice."""
    choose = case.options.get("choose") or {}
    if not choose:
        return [({}, case)]
    by_key = {role.key: role for role in coupling.materials}
    declared = {q.name: q for q in case.quantities}
    result = []
    for names in itertools.product(*choose.values()):
        choice = dict(zip(choose, names))
        values, filled = dict(case.values), dict(case.filled)
        for key, name in choice.items():
            role, entry = by_key[key], lookup(by_key[key], name)
            for library_field, quantity in fills_of(role, declared).items():
                if filled.get(quantity, (None,))[0] != key:
                    continue  # given by the case itself
                if library_field not in entry.values:
                    raise InputError(f"options.choose.{key}", f"{name} has no {library_field}, which "
                                                              f"{declared[quantity].key} takes from the library; "
                                                              "give that field in the case")
                values[quantity] = declared[quantity].check(entry.values[library_field],
                                                            f"{key} = {name}: {library_field}")
                filled[quantity] = (key, name)
        variant = replace(case, values=with_highest_friction(case, case.followed(values), filled), filled=filled)
        coupling.check_case(variant)
        result.append((choice, variant))
    return result


def with_highest_friction(case, values: dict, filled: dict) -> dict:
    """``values`` with a [start_up]'s ``friction_max`` (the overload's friction, docs/start_up.md) set, unless the
    case gives it: the largest of the nominal friction coefficient, the friction_max of the library pair that filled
    it, and the high end of its [scatter] range."""
    friction = "friction_coefficient"
    if case.start_up is None or case.start_up.friction_max_given or friction not in values:
        return values
    highest = [values[friction]] + [s.high for s in case.scatter if s.name == friction]
    if friction in filled:
        entry = next(lookup(role, filled[friction][1]) for role in _roles(case) if role.key == filled[friction][0])
        highest.append(entry.values.get("friction_max", values[friction]))
    return {**values, "friction_max": max(highest)}


def _roles(case) -> tuple[MaterialRole, ...]:
    from clutchopt.formulations import get_coupling

    return get_coupling(case.coupling).materials


def rows(kind: str) -> list[dict]:
    """One row per entry, values in their display units (``clutchopt materials``)."""
    table = []
    for entry in library()[kind].values():
        row = {"name": entry.name}
        row.update({q.name: display(q, entry.values.get(q.name, math.nan)) for q in FIELDS[kind]})
        table.append(row)
    return table


def display(quantity: Quantity, value: float) -> float:
    """An SI value in the field's display unit (degC is an offset, not a factor, from kelvin)."""
    return from_si(value, quantity.unit)


def filled_by(case) -> dict[str, dict]:
    """What the library filled in a case, by role: entry, source and the filled values (SI), as ``solve`` reports."""
    from clutchopt.formulations import get_coupling

    coupling = get_coupling(case.coupling)
    declared = {q.name: q for q in case.quantities}
    report: dict[str, dict] = {}
    for quantity, (key, name) in case.filled.items():
        role = next(r for r in coupling.materials if r.key == key)
        entry = lookup(role, name)
        item = report.setdefault(key, {"entry": name, "source": entry.source, "values": {}})
        item["values"][quantity] = (declared[quantity], case.values[quantity])
        if "friction_min" in entry.values and role.fills.get("friction_coefficient") == quantity:
            item["friction_range"] = (entry.values["friction_min"], entry.values["friction_max"])
    return report
