"""Quantities with units: one pint registry, parsing of case values to SI floats.

A case value is either a string with units (``"1000 rpm"``, ``"4 MPa"``) or a bare number, which is taken
as SI. Costs use the unit ``EUR`` (a dimension of its own, ``[currency]``).
"""

from __future__ import annotations

import math
from functools import lru_cache

import pint

from clutchopt.errors import InputError

ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
ureg.define("EUR = [currency]")


@lru_cache(maxsize=None)
def si_factor(unit: str) -> float:
    """Multiply a value in ``unit`` by this to get SI (``mm`` -> 1e-3, ``deg`` -> pi/180)."""
    return float(ureg.Quantity(1.0, unit).to_base_units().magnitude)


@lru_cache(maxsize=None)
def si_unit(unit: str) -> str:
    """The SI base unit of ``unit`` as text (``MPa`` -> ``kg / m / s ** 2`` is avoided: named forms kept)."""
    base = ureg.Quantity(1.0, unit).to_base_units().units
    return _PRETTY_SI.get(str(base), f"{base:~}") if str(base) != "dimensionless" else "1"


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
    return frozenset(ureg.Quantity(1.0, unit).dimensionality.items())


_DIMENSION_NAMES = {_dimension_key(unit): name for unit, name in _DIMENSION_EXAMPLES.items()}


def describe_dimension(unit: str) -> str:
    """Plain name of the dimension of ``unit``: ``MPa`` -> ``a pressure or stress``."""
    dim = ureg.Quantity(1.0, unit).dimensionality
    if not dim:
        return "dimensionless (or an angle)"
    return _DIMENSION_NAMES.get(_dimension_key(unit), str(dim))


def to_si(field: str, raw: object, unit: str) -> float:
    """Parse a case value for ``field`` expected in ``unit`` (any compatible unit) and return SI float.

    Raises InputError naming the field for text that is no quantity, a wrong dimension, NaN or infinity.
    """
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
        if not isinstance(quantity, pint.Quantity):
            quantity = ureg.Quantity(float(quantity), "dimensionless")
    else:
        raise InputError(field, f"expected a quantity in {unit}, got {type(raw).__name__} {raw!r}")
    expected = ureg.Quantity(1.0, unit)
    if quantity.dimensionality != expected.dimensionality:
        raise InputError(
            field,
            f"expected {describe_dimension(unit)} (e.g. in {unit or 'SI'}), "
            f"got {raw!r}, which is {describe_dimension(str(quantity.units))}",
        )
    value = float(quantity.to_base_units().magnitude)
    if not math.isfinite(value):
        raise InputError(field, f"must be a finite number, got {raw!r}")
    return value


def from_si(value: float, unit: str) -> float:
    """Convert an SI value to ``unit`` for display."""
    return value / si_factor(unit)
