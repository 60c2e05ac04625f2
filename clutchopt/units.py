"""Quantities with units: one pint registry, parsing of case values to SI floats.

A case value is either a string with units (``"1000 rpm"``, ``"4 MPa"``) or a bare number, which is taken
as SI. Costs use the unit ``EUR`` (a dimension of its own, ``[currency]``).

pint is the unit library, but importing it and building its registry costs about 0.35 s, more than a whole
solve. So the registry ``ureg`` is built on first use, and what :func:`unit_info`, :func:`si_factor` and
:func:`si_unit` say of the units clutchopt declares and case files usually write is in a table taken from that
same registry (:mod:`clutchopt.unit_table`: SI factor, SI unit, dimensionality, power of radian; ``python -m
clutchopt.units`` writes it, tests/test_units.py checks every entry against pint). A value such as ``"4 MPa"`` is
read without pint (the factor is pint's, so is the value, to the last bit); any other unit goes through pint.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache
from numbers import Real
from typing import NamedTuple

from clutchopt.errors import InputError, shown_value
from clutchopt.unit_table import UNITS


@lru_cache(maxsize=None)
def registry():
    """pint's registry with ``EUR`` and ``rev`` defined, built once on first use."""
    import pint

    units = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    units.define("EUR = [currency]")
    units.define("@alias revolution = rev")
    return units


def __getattr__(name: str):
    if name == "ureg":  # ``from clutchopt.units import ureg``: the registry, built when first asked for
        return registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def table_entry(unit: str) -> tuple[float, str, tuple, float]:
    """What :mod:`clutchopt.unit_table` holds for ``unit``, computed with pint: SI factor, SI unit, dimensionality,
    power of radian (as :func:`unit_info` reads them)."""
    info = _pint_unit_info(unit)
    if info.offset:
        raise ValueError(f"{unit!r} has an offset; the table holds multiplicative units only")
    dimensions = tuple(sorted((name, int(power) if power == int(power) else power) for name, power in info.dimensions))
    return info.factor, _pint_si(unit)[1], dimensions, info.angle


# Offset units (a temperature, not a difference): SI = value * scale + offset, as pint's OffsetConverter computes it
# (pint: degree_Celsius = kelvin; offset: 273.15), so a case's "40 degC" is read without building pint's registry
# (0.35 s: a start-up case's ambient temperature defaults to 40 degC); tests/test_units.py checks it against pint.
OFFSET_UNITS = {"degC": (1.0, 273.15, "K", (("[temperature]", 1),))}


def _offset_si(unit: str) -> tuple[float, str] | None:
    """(pint's SI factor, SI unit) of an offset unit of the table (the factor: its 1 in SI, 1 degC = 274.15 K)."""
    if unit not in OFFSET_UNITS:
        return None
    scale, offset, si, _ = OFFSET_UNITS[unit]
    return scale + offset, si


def _pint_si(unit: str) -> tuple[float, str]:
    quantity = registry().Quantity(1.0, unit)
    base = quantity.to_base_units()
    text = _PRETTY_SI.get(str(base.units), f"{base.units:~}") if str(base.units) != "dimensionless" else "1"
    if text == "N*m" and any(name in str(quantity.units) for name in ENERGY_UNITS):
        text = "J"  # an energy, not a torque, though pint gives them one dimension (review 28: a friction work in kJ
    return float(base.magnitude), text  # had been labelled N*m)


ENERGY_UNITS = ("joule", "watt_hour", "calorie", "electron_volt", "erg")  # pint's names of units of energy


@lru_cache(maxsize=None)
def si_factor(unit: str) -> float:
    """Multiply a value in ``unit`` by this to get SI (``mm`` -> 1e-3, ``deg`` -> pi/180)."""
    return (UNITS.get(unit) or _offset_si(unit) or _pint_si(unit))[0]


@lru_cache(maxsize=None)
def si_unit(unit: str) -> str:
    """The SI base unit of ``unit`` as text (``MPa`` -> ``kg / m / s ** 2`` is avoided: named forms kept)."""
    return (UNITS.get(unit) or _offset_si(unit) or _pint_si(unit))[1]


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


_KIND_EXAMPLES = {  # a unit of each kind of quantity a case uses, and its plain name: a kind is a dimension and a
    # power of radian, so that an angle is no ratio and an angular speed no count per time (to pint all are alike)
    "": "a ratio (a bare number or %)",
    "rad": "an angle",
    "rad/s": "an angular speed",
    "1/s": "a count per time",
    "Pa": "a pressure or stress",
    "N*m": "a torque or energy",
    "N*m/rad": "a torque per angle",
    "N": "a force",
    "m": "a length",
    "m^2": "an area",
    "m^3": "a volume",
    "kg": "a mass",
    "s": "a time",
    "s/rad": "a time per angle",
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


def _kind(unit: str) -> tuple[frozenset, float]:
    """What a unit measures, order-independent: its dimensionality (pint's text form orders the base dimensions
    freely) and its power of radian."""
    info = unit_info(unit)
    return info.dimensions, info.angle


@lru_cache(maxsize=1)
def _kind_names() -> dict:
    return {_kind(unit): name for unit, name in _KIND_EXAMPLES.items()}


_ANGULAR_SPEED = (frozenset({("[time]", -1)}), 1)


def describe_dimension(unit: str) -> str:
    """Plain name of what ``unit`` measures: ``MPa`` -> ``a pressure or stress``, ``deg`` -> ``an angle``, ``1/h``
    -> ``a count per time``."""
    dimensions, angle = _kind(unit)
    name = _kind_names().get((dimensions, angle))
    if name is not None:
        return name
    base = _kind_names().get((dimensions, 0)) or str(registry().Quantity(1.0, unit).dimensionality)
    return f"{base} times an angle to the power {angle:g}" if angle else base


MAX_TEXT = 100  # characters of one quantity, e.g. "0.05 EUR/cm^2"; longer text is refused before pint sees it
MAX_EXPONENT = 12  # |n| of a unit power m^n; with at most two levels of parentheses pint's work stays tiny
_MINUS = "\u2212"  # the typographic minus sign, read as "-" (it can mean nothing else)
_NUMBER = re.compile(r"\s*([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|[+-]?(?:nan|inf|infinity))(?![\w.])\s*\*?\s*",
                     re.IGNORECASE | re.ASCII)  # ASCII digits only: no number in another script is read silently
_UNIT_TOKEN = re.compile(r"\s+|\*\*|[*/^()\u00b7]"  # space, powers, products, quotients, parentheses
                         r"|[A-Za-z_\u00b5\u03bc\u03a9\u00b0%][A-Za-z0-9_\u00b5\u03bc\u03a9\u00b0]*"  # unit names
                         r"|[\u00b2\u00b3\u00b9\u2070\u2074-\u2079\u207b]+|[+-]?[0-9]+(?:\.[0-9]+)?")  # powers
_QUANTITY_EXAMPLE = "a number and a unit, e.g. '1000 rpm', '4 MPa' or '0.5 kg*m^2'"
_SPEED_HINT = ("an angular speed needs an angle per time: write e.g. '1000 rpm', '16.67 rps' (revolutions per second) "
               "or '104.7 rad/s'; Hz and 1/s are refused because they do not say whether they count revolutions or "
               "radians (a factor 2 pi)")


def _split(field: str, text: str) -> tuple[float, str]:
    """Split quantity text into its number and its unit expression, refusing what pint should never evaluate.

    The grammar is bounded: a decimal number, then unit names joined by ``*``, ``/``, spaces and ``^``/``**`` with
    a small integer or decimal exponent (|n| <= MAX_EXPONENT), parentheses at most two deep; digits elsewhere in the
    unit only as the ``1`` of ``1/s``. So no text can ask pint for a large power or a long computation.
    """
    if len(text) > MAX_TEXT:
        raise InputError(field, f"text of {len(text)} characters is too long for a quantity (at most {MAX_TEXT}); "
                                f"expected {_QUANTITY_EXAMPLE}")
    bad = next((c for c in text if not c.isprintable()), None)
    if bad is not None:
        raise InputError(field, f"contains the control character {bad!r}; expected {_QUANTITY_EXAMPLE}")
    text = text.replace(_MINUS, "-")
    number = _NUMBER.match(text)
    if number is None:
        raise InputError(field, f"cannot read {text.strip()!r} as a quantity: expected {_QUANTITY_EXAMPLE}")
    unit = text[number.end():].strip()
    depth, previous, position = 0, "", 0
    while position < len(unit):
        token = _UNIT_TOKEN.match(unit, position)
        if token is None:
            raise InputError(field, f"cannot read {text.strip()!r}: unexpected character {unit[position]!r} in its "
                                    f"unit; expected {_QUANTITY_EXAMPLE}")
        position, piece = token.end(), token.group()
        if piece.isspace():
            continue
        if piece == "(":
            depth += 1
            if depth > 2:
                raise InputError(field, f"cannot read {text.strip()!r}: parentheses nested too deeply in its unit")
        elif piece == ")":
            depth -= 1
        elif piece[0] in "+-0123456789":
            if previous in ("^", "**"):
                if abs(float(piece)) > MAX_EXPONENT:
                    raise InputError(field, f"cannot read {text.strip()!r}: unit power {piece} is out of range "
                                            f"(at most {MAX_EXPONENT})")
            elif piece != "1":
                raise InputError(field, f"cannot read {text.strip()!r}: a number inside the unit ({piece}); "
                                        f"expected {_QUANTITY_EXAMPLE}")
        previous = piece
    try:
        return float_text(number.group(1)), unit
    except BelowFloat64 as exc:
        raise InputError(field, str(exc)) from None


class BelowFloat64(ValueError):
    """A nonzero number in a file too small for float64 (under about 4.9e-324 in magnitude): read, it would be 0
    (review 25: ``"1e-400 N*m"`` had solved with no load)."""


def float_text(text: str) -> float:
    """``float(text)``, refusing a nonzero number that float64 would read as 0 (:class:`BelowFloat64`) and digits
    other than ASCII's (ValueError; ``float`` reads every script's: review 27, ``--vary`` read an Arabic-Indic
    ``5e-400`` as 0, past the test below, as :data:`_NUMBER` refuses them in quantity text); the parser of every
    number read from a case, scene or design file."""
    if not text.isascii():
        raise ValueError(f"{text!r}: ASCII digits only")
    value = float(text)
    if value == 0.0 and any(digit in "123456789" for digit in text.lower().split("e")[0]):
        raise BelowFloat64(f"{text.strip()} is below the float64 range: it would be read as 0")
    return value


def _nonzero_kept(field: str, raw: str, number: float, value: float) -> float:
    """``value`` (``number`` in SI), refusing a nonzero number its unit brings to 0 in float64."""
    if number != 0.0 and value == 0.0:
        raise InputError(field, f"{raw.strip()!r} is below the float64 range in SI: it would be read as 0")
    return value


class UnitInfo(NamedTuple):
    """What a unit expression means, multiplicatively: SI factor, dimensionality, power of radian, and whether it
    is an offset unit (degC, degF: a temperature, not a temperature difference)."""

    factor: float
    dimensions: frozenset
    angle: float
    offset: bool


@lru_cache(maxsize=512)
def unit_info(unit: str) -> UnitInfo:
    """:class:`UnitInfo` of a unit expression (bounded by :func:`_split` for text from a file), from the table where
    it is there (multiplicative units only), else from pint, whose errors and OverflowError (e.g. ``Ym^12``) pass
    to the caller."""
    entry = UNITS.get(unit)
    if entry is not None:
        return UnitInfo(entry[0], frozenset(entry[2]), entry[3], False)
    if unit in OFFSET_UNITS:
        return UnitInfo(_offset_si(unit)[0], frozenset(OFFSET_UNITS[unit][3]), 0, True)
    return _pint_unit_info(unit)


def _pint_unit_info(unit: str) -> UnitInfo:
    ureg = registry()
    units = ureg.parse_units(unit) if unit else ureg.dimensionless
    one = ureg.Quantity(1.0, units)
    root = dict(one.to_root_units().unit_items())
    offset = ureg.Quantity(0.0, units).to_base_units().magnitude != 0
    return UnitInfo(float(one.to_base_units().magnitude), frozenset(one.dimensionality.items()),
                    root.get("radian", 0), offset)


def to_si(field: str, raw: object, unit: str) -> float:
    """Parse a case value for ``field`` expected in ``unit`` (any compatible unit) and return SI float.

    Raises InputError naming the field for text that is no quantity, a quantity of another kind (a wrong dimension,
    or the right one with another power of radian: an angle where a ratio is expected, an angular speed where a
    count per time is, a pure frequency (Hz, 1/s) where an angular speed is, see ``_SPEED_HINT``), NaN or infinity,
    a value beyond float64, and an offset temperature (degC), which clutchopt's temperature rises cannot mean; a
    bare number where an absolute temperature is expected (SI would make 40 ambient 40 K, not 40 degC)
    """
    expected = unit_info(unit)
    wanted = f"a quantity in {unit}" if unit else "a number"
    if isinstance(raw, bool):
        raise InputError(field, f"expected {wanted}, got a boolean")
    if isinstance(raw, Real):  # a bare number is SI (NumPy's too: a case given as a dict from Python)
        if expected.offset:  # 40 would be 40 K, -233 degC, where an absolute temperature is asked for
            raise InputError(field, f"a bare number is ambiguous for a temperature: write '{raw} degC' or '{raw} K'")
        try:
            value, given = float(raw), expected._replace(factor=1.0)
        except OverflowError:
            raise InputError(field, f"{len(str(abs(raw)))}-digit number is beyond the float64 range") from None
    elif isinstance(raw, str):
        number, unit_text = _split(field, raw)
        try:
            given = unit_info(unit_text)
        except OverflowError:
            raise InputError(field, f"cannot read {raw.strip()!r}: its unit is beyond the float64 range") from None
        except Exception as exc:  # pint raises several types for unparsable text
            names = getattr(exc, "unit_names", None)
            why = f"unknown unit {', '.join(map(repr, names))}" if names else type(exc).__name__
            raise InputError(field, f"cannot read {raw.strip()!r} as a quantity ({why}); expected "
                                    f"{_QUANTITY_EXAMPLE}") from None
        if given.offset and not expected.offset:
            raise InputError(field, f"{raw.strip()!r} is a temperature on a scale with an offset; write a "
                                    "temperature difference in K (or delta_degC)")
        if expected.offset and "delta_" in unit_text:
            raise InputError(field, f"{raw.strip()!r} is a temperature difference; write a temperature in degC or K")
        if _kind(unit) == _ANGULAR_SPEED and (given.dimensions, given.angle) == (expected.dimensions, 0):
            raise InputError(field, f"{raw.strip()!r} is ambiguous: {_SPEED_HINT}")
        if not unit_text:  # a number in text is read as a bare one: SI (radians, where an angle is expected)
            given = given._replace(angle=expected.angle)
        if given.offset:  # an absolute temperature (the field is one too): pint adds the offset
            value = float(into_si(number, unit_text))
        else:
            value = _nonzero_kept(field, raw, number, number * given.factor if number else 0.0)  # (0 * inf would be
            # nan; inf is refused below)
    else:
        raise InputError(field, f"expected {wanted}, got {type(raw).__name__} {shown_value(raw)}")
    if given.dimensions != expected.dimensions or given.angle != expected.angle:
        raise InputError(field, f"expected {describe_dimension(unit)}{f' (e.g. in {unit})' if unit else ''}, got "
                                f"{shown_value(raw)}, which is {describe_dimension(unit_text)}")
    if not math.isfinite(value):
        raise InputError(field, f"must be a finite number within the float64 range, got {shown_value(raw)}")
    return value


def difference_unit(unit: str) -> str:
    """The unit of a difference of two values in ``unit``: K for an offset unit (degC: two temperatures differ by
    kelvins), else the unit itself."""
    return "K" if unit not in UNITS and unit_info(unit).offset else unit


def into_si(value, unit: str):
    """A number in ``unit`` (a number or a NumPy array) in SI, the inverse of :func:`from_si`: an offset unit (degC)
    gives the absolute temperature in K, so 20 degC is 293.15 K, not 20 x 274.15."""
    if unit in OFFSET_UNITS:
        scale, offset, *_ = OFFSET_UNITS[unit]
        return value * scale + offset
    if unit not in UNITS and unit_info(unit).offset:
        return registry().Quantity(value, unit).to(registry().kelvin).magnitude
    return value * si_factor(unit)


def from_si(value, unit: str):
    """Convert an SI value to ``unit`` for display; an offset unit (degC) takes an absolute temperature in K, so
    293.15 K is 20 degC, not 293.15 (a number or a NumPy array)."""
    if unit in OFFSET_UNITS:
        scale, offset, *_ = OFFSET_UNITS[unit]
        return (value - offset) / scale
    if unit not in UNITS and unit_info(unit).offset:
        return registry().Quantity(value, registry().kelvin).to(unit).magnitude
    return value / si_factor(unit)


TABLE_UNITS = (  # the units case files and scenes usually write, besides those the package declares
    "", "mm", "cm", "m", "um", "m^2", "m^3", "kg", "g", "t", "s", "ms", "min", "h", "rpm", "rps", "rad/s", "1/s",
    "Hz", "deg", "rad", "N", "kN", "N*m", "kN*m", "Pa", "kPa", "MPa", "GPa", "N/mm^2", "bar", "W", "kW", "MW", "J",
    "kJ", "J/K", "W/K", "kg*m^2", "kg/m^3", "g/cm^3", "N/m", "N/mm", "N*m/rad", "m/s^2", "m^3/s^2", "s/rad", "EUR",
    "EUR/kg", "EUR/cm^2", "EUR/m^2", "K", "kJ/K", "1/hour", "1/h", "1/min", "kJ/hour", "kJ/h", "mm^3/J",
)


def _write_table(units: list[str]) -> str:
    """The source of :mod:`clutchopt.unit_table` for ``units``, every entry computed by pint."""
    lines = ['"""SI factor, SI unit, dimensionality and power of radian of the units clutchopt declares and case files',
             'usually write, as pint defines them. Generated by ``python -m clutchopt.units``; tests/test_units.py',
             'checks every entry against pint and that every unit the package declares is here."""', "",
             "UNITS = {"]
    lines += [f"    {unit!r}: {table_entry(unit)!r}," for unit in units]
    return "\n".join(lines + ["}", ""])


if __name__ == "__main__":
    from pathlib import Path

    from clutchopt.unit_table import UNITS as CURRENT

    target = Path(__file__).with_name("unit_table.py")
    target.write_text(_write_table(sorted(set(CURRENT) | set(TABLE_UNITS))), encoding="utf-8")
