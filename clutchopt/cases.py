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

import math
import tomllib
from dataclasses import dataclass, field, replace
from pathlib import Path
from types import SimpleNamespace
from typing import Any

from clutchopt import materials
from clutchopt.errors import InputError
from clutchopt.formulations.start_up import QUANTITIES as START_UP_QUANTITIES
from clutchopt.formulations.start_up import SPRING_PRELOAD, StartUpSpec
from clutchopt.model import REQUIRED, Quantity
from clutchopt.units import to_si

_TOP_LEVEL = {"coupling", "title", "description"}
_OPTION_KEYS = {"free", "objective", "mode", "choose"}
_EXTRA_SECTIONS = ("bounds", "options", "library", "start_up")


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
        """A copy with some SI values replaced and re-checked (sweeps, tests)."""
        declared = {q.name: q for q in self.quantities}
        for name, value in values.items():
            if name not in declared:
                raise InputError(name, f"unknown quantity for coupling {self.coupling!r}")
            declared[name].check(float(value))
        return replace(self, values={**self.values, **{k: float(v) for k, v in values.items()}})


def read_toml(path: str | Path) -> dict:
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(str(path), "no such file") from None
    except OSError as exc:
        raise InputError(str(path), f"cannot read ({exc.strerror})") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(str(path), f"not valid TOML: {exc}") from None


def load_case(path: str | Path) -> Case:
    """Read and check a case file."""
    return parse_case(read_toml(path), str(path))


def parse_case(data: dict, path: str = "") -> Case:
    from clutchopt.formulations import get_coupling

    if "coupling" not in data:
        raise InputError("coupling", "missing: say which coupling this case is for, e.g. coupling = \"wedge\"")
    coupling = get_coupling(data["coupling"])
    declared = {q.key: q for q in coupling.quantities}
    sections = {q.section for q in coupling.quantities}

    values: dict[str, float] = {}
    for key, table in data.items():
        if key in _TOP_LEVEL or key in _EXTRA_SECTIONS:
            continue
        if key not in sections or not isinstance(table, dict):
            raise InputError(key, f"unknown section or key; this {coupling.name} case may have "
                                  f"{', '.join(sorted(sections | set(_EXTRA_SECTIONS)))}")
        for name, raw in table.items():
            quantity = declared.get(f"{key}.{name}")
            if quantity is None:
                raise InputError(f"{key}.{name}", f"unknown key; [{key}] takes "
                                                  f"{', '.join(q.name for q in coupling.quantities if q.section == key)}")
            values[quantity.name] = quantity.check(to_si(quantity.key, raw, quantity.unit))

    options = data.get("options", {})
    choose = (materials.check_choose(options["choose"], coupling.materials)
              if isinstance(options, dict) and "choose" in options else {})
    filled = materials.fill(data.get("library", {}), coupling.materials, coupling.quantities, values,
                            choose)
    for quantity in coupling.quantities:
        if quantity.name in values:
            continue
        if quantity.default is REQUIRED:
            raise InputError(quantity.key, f"missing ({quantity.description}, in {quantity.unit or 'SI'})"
                                           + materials.hint(coupling.materials, quantity.name))
        if quantity.default is not None:
            values[quantity.name] = quantity.check(to_si(quantity.key, quantity.default, quantity.unit))

    start_up = None
    if "start_up" in data:
        from clutchopt.start_up_case import parse_start_up

        start_values, start_up = parse_start_up(data["start_up"], coupling, values)
        values.update(start_values)
    bounds = _parse_bounds(data.get("bounds", {}), coupling, start_up is not None)
    if not isinstance(options, dict):
        raise InputError("options", "must be a table")
    for name in options:
        if name not in _OPTION_KEYS:
            raise InputError(f"options.{name}", f"unknown option; options are {', '.join(sorted(_OPTION_KEYS))}")
    free = options.get("free", [])
    freeable = {v.name for v in coupling.variables if v.fixed_unless_freed} | ({"spring_preload"} if start_up else set())
    if not isinstance(free, list) or any(name not in freeable for name in free):
        raise InputError("options.free", f"must be a list drawn from {sorted(freeable)}, got {free!r}")
    for name in ("mode", "objective"):
        if name in options and not isinstance(options[name], str):
            raise InputError(f"options.{name}", f"must be text, got {options[name]!r}")

    case = Case(coupling.name, str(data.get("title", "")), values, bounds, tuple(free),
                {**options, **({"choose": choose} if choose else {})}, path, start_up, filled)
    coupling.check_case(case)
    materials.variants(case, coupling)  # every choice of options.choose is checked here, before any solve
    return case


def _parse_bounds(table: Any, coupling, start_up: bool = False) -> dict[str, tuple[float, float]]:
    if not isinstance(table, dict):
        raise InputError("bounds", "must be a table of [lower, upper] pairs")
    variables = {v.name: v for v in coupling.variables + ((SPRING_PRELOAD,) if start_up else ())}
    bounds = {}
    for name, pair in table.items():
        variable = variables.get(name)
        key = f"bounds.{name}"
        if variable is None:
            raise InputError(key, f"unknown design variable; bounds may be set for {', '.join(variables)}")
        if not isinstance(pair, list) or len(pair) != 2:
            raise InputError(key, f"must be a pair [lower, upper], got {pair!r}")
        lower, upper = (variable.check(to_si(key, raw, variable.unit), key) for raw in pair)
        if not lower < upper:
            raise InputError(key, f"lower bound {variable.show(lower)} must be below upper bound {variable.show(upper)}")
        bounds[name] = (lower, upper)
    return bounds


def quantity_table(quantities: tuple[Quantity, ...], values: dict[str, float]) -> list[dict]:
    """Rows (key, symbol, value in unit, SI value, description) for printing the inputs of a case."""
    return [
        {"key": q.key, "symbol": q.symbol, "value": q.show(values[q.name]), "si": values[q.name],
         "description": q.description}
        for q in quantities if q.name in values
    ]
