"""Quantities in case files: units to SI, and one clear error per bad value."""

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from clutchopt.errors import InputError
from clutchopt.units import describe_dimension, from_si, to_si


@pytest.mark.parametrize("text, unit, si", [
    ("1000 rpm", "rpm", 1000 * 2 * math.pi / 60),
    ("104.72 rad/s", "rpm", 104.72),
    ("15 deg", "deg", 15 * math.pi / 180),
    ("0.785 rad", "deg", 0.785),
    ("4 MPa", "MPa", 4e6),
    ("4 N/mm^2", "MPa", 4e6),
    ("0.5 kg*m^2", "kg*m^2", 0.5),
    ("20 mm", "mm", 0.02),
    ("5 N*m", "N*m", 5.0),
    ("3 EUR/kg", "EUR/kg", 3.0),
    ("0.05 EUR/cm^2", "EUR/cm^2", 500.0),
    ("1.2", "", 1.2),
])
def test_text_to_si(text, unit, si):
    assert to_si("field", text, unit) == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize("raw, unit, si", [(0.5, "kg*m^2", 0.5), (10, "s", 10.0), (0.26, "deg", 0.26), (4e6, "MPa", 4e6)])
def test_bare_numbers_are_si(raw, unit, si):
    assert to_si("field", raw, unit) == si


@pytest.mark.parametrize("raw, words", [
    ("4 kg", "expected a pressure or stress"),
    ("4 m", "which is a length"),
    ("four MPa", "cannot read"),
    ("nan MPa", "finite"),
    ("inf MPa", "finite"),
    (float("nan"), "finite"),
    (True, "boolean"),
    ([4], "expected"),
])
def test_bad_values_name_the_field(raw, words):
    with pytest.raises(InputError) as info:
        to_si("material.allowable_pressure", raw, "MPa")
    message = str(info.value)
    assert message.startswith("material.allowable_pressure: ") and words in message and "\n" not in message


@given(st.floats(min_value=1e-6, max_value=1e6))
def test_millimetres_round_trip(value):
    si = to_si("x", f"{value!r} mm", "mm")
    assert si == pytest.approx(value / 1000, rel=1e-12)
    assert from_si(si, "mm") == pytest.approx(value, rel=1e-12)


@pytest.mark.parametrize("unit, name", [
    ("MPa", "a pressure or stress"), ("kN*m", "a torque or energy"), ("kg*m^2", "a moment of inertia"),
    ("rpm", "an angular speed"), ("kW", "a power"), ("N/mm", "a stiffness"), ("EUR/kg", "a price per mass"),
])
def test_dimensions_are_named_whatever_order_pint_prints_them(unit, name):
    assert describe_dimension(unit) == name


def test_a_wrong_torque_unit_names_a_torque():
    with pytest.raises(InputError, match="expected a torque or energy .* which is a mass"):
        to_si("duty.resisting_torque", "5 kg", "N*m")


def _declared_units() -> set[str]:
    """Every unit the couplings declare: quantities, variables, objectives, constraints and outputs (read off the
    CasADi expressions, whose units are plain text), and the units scenes read."""
    import casadi as ca

    from clutchopt.formulations import MODULES, get_coupling
    from clutchopt.model import namespace

    units = {"kg*m^2", "rpm", "J/K", "W/K", "s", "", "N*m", "N"}  # clutchopt/simulate/scene.py
    for name in MODULES:
        coupling = get_coupling(name)
        units |= {q.unit for q in coupling.quantities}
        for formulation in coupling.formulations.values():
            x = namespace({v.name: ca.SX.sym(v.name) for v in formulation.variables})
            p = namespace({q.name: ca.SX.sym(q.name) for q in formulation.quantities})
            units |= {v.unit for v in formulation.variables} | {o.unit for o in formulation.objectives}
            units |= {c.unit for c in formulation.constraints(x, p)} | {o.unit for o in formulation.outputs(x, p).values()}
    return units


def test_every_declared_unit_is_in_the_table():
    from clutchopt.unit_table import UNITS

    assert _declared_units() <= set(UNITS), "add the unit to TABLE_UNITS and run python -m clutchopt.units"


def test_the_table_is_what_pint_says():
    from clutchopt.unit_table import UNITS
    from clutchopt.units import TABLE_UNITS, table_entry

    assert set(TABLE_UNITS) <= set(UNITS)
    for unit, entry in UNITS.items():
        assert table_entry(unit) == entry, unit


@given(st.floats(min_value=-1e12, max_value=1e12, allow_subnormal=False),
       st.sampled_from(["mm", "MPa", "deg", "rpm", "N*m", "kg*m^2", "EUR/cm^2", "kW", "N*m/rad", "kg/m^3", "GPa"]),
       st.sampled_from(["{!r}", "{:.6g}", "{:.3e}", "{:.0f}"]))
def test_the_table_gives_pints_value_to_the_last_bit(value, unit, form):
    from clutchopt.units import _from_table, ureg

    text = f"{form.format(value)} {unit}"
    assert _from_table(text, unit) == float(ureg.Quantity(text).to_base_units().magnitude)
    assert to_si("field", text, unit) == _from_table(text, unit)


@pytest.mark.parametrize("text, unit", [("20mm", "mm"), ("20 N * m", "N*m"), ("1_000 mm", "mm"), ("4 kg", "MPa"),
                                        ("20 mm", "furlong"), ("1e400 mm", "mm"), (True, "")])
def test_text_outside_the_table_goes_to_pint(text, unit):
    from clutchopt.units import _from_table

    assert _from_table(text, unit) is None
