"""Quantities with units: one pint registry, parsing of case values to SI floats.

A case value is either a string with units (``"1000 rpm"``, ``"4 MPa"``) or a bare number, which is taken
as SI. Costs use the unit ``EUR`` (a dimension of its own, ``[currency]``).

pint is the unit library, but importing it and building its registry costs about 0.35 s, more than a whole
solve. So the registry ``ureg`` is built on first use, and the units clutchopt declares and case files usually
write are in a table taken from that same registry (:mod:`clutchopt.unit_table`: SI factor, SI unit,
dimensionality; ``python -m clutchopt.units`` writes it, tests/test_units.py checks every entry against pint).
A value written ``"<number> <unit in the table>"`` (or a bare number) is converted with the table's factor,
which is bit for bit what pint gives; any other text, and every error message, goes through pint.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache

from clutchopt.errors import InputError
from clutchopt.unit_table import UNITS


@lru_cache(maxsize=None)
def registry():
    """pint's registry with ``EUR`` defined, built once on first use."""
    import pint

    units = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    units.define("EUR = [currency]")
    return units


def __getattr__(name: str):
    if name == "ureg":  # ``from clutchopt.units import ureg``: the registry, built when first asked for
        return registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def table_entry(unit: str) -> tuple[float, str, tuple]:
    """What :mod:`clutchopt.unit_table` holds for ``unit``, computed with pint: SI factor, SI unit, dimensionality."""
    one = registry().Quantity(1.0, unit)
    base = one.to_base_units().units
    text = _PRETTY_SI.get(str(base), f"{base:~}") if str(base) != "dimensionless" else "1"
    dimensions = tuple(sorted((name, int(power) if power == int(power) else power)
                              for name, power in one.dimensionality.items()))
    return float(one.to_base_units().magnitude), text, dimensions


@lru_cache(maxsize=None)
def si_factor(unit: str) -> float:
    """Multiply a value in ``unit`` by this to get SI (``mm`` -> 1e-3, ``deg`` -> pi/180)."""
    return (UNITS.get(unit) or table_entry(unit))[0]


@lru_cache(maxsize=None)
def si_unit(unit: str) -> str:
    """The SI base unit of ``unit`` as text (``MPa`` -> ``kg / m / s ** 2`` is avoided: named forms kept)."""
    return (UNITS.get(unit) or table_entry(unit))[1]


_PRETTY_SI = {
    "kilogram / meter / second ** 2": "Pa",
    "kilogram * meter ** 2 / second ** 2": "N*m",
    "kilogram * meter / second ** 2": "N",
    "radian / second": "rad/s",
    "1 / second": "1/s",
    "radian": "rad",
    "kilogram * meter ** 2": "kg*m^2",
    "kilogram / meter ** 3": "kg/m^3",
    "kilogram / second ** 2": "N/m",
    "kilogram * meter ** 2 / second ** 3": "W",
    "kilogram * meter ** 2 / kelvin / second ** 2": "J/K",
    "kilogram * meter ** 2 / kelvin / second ** 3": "W/K",
    "meter ** 2": "m^2",
    "meter / second ** 2": "m/s^2",
    "EUR / kilogram": "EUR/kg",
    "EUR / meter ** 2": "EUR/m^2",
}


_DIMENSION_EXAMPLES = {  # a unit of each dimension a case uses, and its plain name
    "Pa": "a pressure or stress",
    "N*m": "a torque or energy",
    "N": "a force",
    "1/s": "an angular speed",
    "m": "a length",
    "kg": "a mass",
    "s": "a time",
    "kg*m^2": "a moment of inertia",
    "kg/m^3": "a density",
    "EUR/kg": "a price per mass",
    "EUR": "a cost",
    "EUR/m^2": "a cost per area",
    "N/m": "a stiffness",
    "m/s^2": "an acceleration",
    "W": "a power",
    "J/K": "a heat capacity",
}


def _dimension_key(unit: str) -> frozenset:
    """Order-independent key of a unit's dimensionality (pint's text form orders the base dimensions freely)."""
    entry = UNITS.get(unit)
    return frozenset(entry[2] if entry else registry().Quantity(1.0, unit).dimensionality.items())


@lru_cache(maxsize=1)
def _dimension_names() -> dict:
    return {_dimension_key(unit): name for unit, name in _DIMENSION_EXAMPLES.items()}


def describe_dimension(unit: str) -> str:
    """Plain name of the dimension of ``unit``: ``MPa`` -> ``a pressure or stress``."""
    key = _dimension_key(unit)
    if not key:
        return "dimensionless (or an angle)"
    return _dimension_names().get(key) or str(registry().Quantity(1.0, unit).dimensionality)


def _wrong_dimension(unit: str, raw: object, given: str) -> str:
    return (f"expected {describe_dimension(unit)} (e.g. in {unit or 'SI'}), got {raw!r}, which is "
            f"{describe_dimension(given)}")


_NUMBER_AND_UNIT = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)(?:\s+(\S+))?\s*")


def _table_quantity(raw: object) -> tuple[float, str] | None:
    """``"<number> <unit in the table>"`` (or a plain number) as (number, unit); None for any other text."""
    match = _NUMBER_AND_UNIT.fullmatch(raw) if isinstance(raw, str) else None
    return (float(match[1]), match[2] or "") if match and (match[2] or "") in UNITS else None


def _from_table(raw: object, unit: str) -> float | None:
    """SI value of ``raw`` by the table when both its unit and ``unit`` are there, the dimensions agree and the
    value is finite; None otherwise (pint decides, and words any error)."""
    expected = UNITS.get(unit)
    if expected is None or isinstance(raw, bool):
        return None
    if isinstance(raw, (int, float)):
        value = float(raw)
    elif (quantity := _table_quantity(raw)) and UNITS[quantity[1]][2] == expected[2]:
        value = quantity[0] * UNITS[quantity[1]][0]
    else:
        return None
    return value if math.isfinite(value) else None


def to_si(field: str, raw: object, unit: str) -> float:
    """Parse a case value for ``field`` expected in ``unit`` (any compatible unit) and return SI float.

    Raises InputError naming the field for text that is no quantity, a wrong dimension, NaN or infinity.
    """
    fast = _from_table(raw, unit)
    if fast is not None:
        return fast
    if unit in UNITS and (quantity := _table_quantity(raw)):  # a wrong dimension, said without pint
        raise InputError(field, _wrong_dimension(unit, raw, quantity[1]))
    ureg = registry()
    if isinstance(raw, bool):
        raise InputError(field, f"expected a quantity in {unit}, got a boolean")
    if isinstance(raw, (int, float)):
        value = float(raw)
        quantity = ureg.Quantity(value, ureg.Quantity(1.0, unit).to_base_units().units)
    elif isinstance(raw, str):
        try:
            quantity = ureg.Quantity(raw.strip())
        except Exception as exc:  # pint raises several types for unparsable text
            raise InputError(field, f"cannot read {raw!r} as a quantity ({type(exc).__name__})") from None
        if not isinstance(quantity, ureg.Quantity):
            quantity = ureg.Quantity(float(quantity), "dimensionless")
    else:
        raise InputError(field, f"expected a quantity in {unit}, got {type(raw).__name__} {raw!r}")
    expected = ureg.Quantity(1.0, unit)
    if quantity.dimensionality != expected.dimensionality:
        raise InputError(field, _wrong_dimension(unit, raw, str(quantity.units)))
    value = float(quantity.to_base_units().magnitude)
    if not math.isfinite(value):
        raise InputError(field, f"must be a finite number, got {raw!r}")
    return value


def from_si(value: float, unit: str) -> float:
    """Convert an SI value to ``unit`` for display."""
    return value / si_factor(unit)


TABLE_UNITS = (  # the units case files and scenes usually write, besides those the package declares
    "", "mm", "cm", "m", "um", "kg", "g", "t", "s", "ms", "min", "h", "rpm", "rad/s", "1/s", "Hz", "deg", "rad",
    "N", "kN", "N*m", "kN*m", "Pa", "kPa", "MPa", "GPa", "N/mm^2", "bar", "W", "kW", "MW", "J", "kJ", "J/K", "W/K",
    "kg*m^2", "kg/m^3", "g/cm^3", "N/m", "N/mm", "N*m/rad", "m/s^2", "m^3/s^2", "s/rad", "EUR", "EUR/kg", "EUR/cm^2", "EUR/m^2",
)


def _write_table(units: list[str]) -> str:
    """The source of :mod:`clutchopt.unit_table` for ``units``, every entry computed by pint."""
    lines = ['"""SI factor, SI unit and dimensionality of the units clutchopt declares and case files usually write,',
             'as pint defines them. Generated by ``python -m clutchopt.units``; tests/test_units.py checks every entry',
             'against pint and that every unit the package declares is here."""', "", "UNITS = {"]
    lines += [f"    {unit!r}: {table_entry(unit)!r}," for unit in units]
    return "\n".join(lines + ["}", ""])


if __name__ == "__main__":
    from pathlib import Path

    from clutchopt.unit_table import UNITS as CURRENT

    target = Path(__file__).with_name("unit_table.py")
    target.write_text(_write_table(sorted(set(CURRENT) | set(TABLE_UNITS))), encoding="utf-8")
