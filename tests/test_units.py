"""Quantities in case files: units to SI, and one clear error per bad value."""

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from clutchopt.errors import InputError
from clutchopt.units import describe_dimension, from_si, si_unit, to_si


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
    CasADi expressions, whose units are plain text), the [start_up] quantities and the units scenes read."""
    import casadi as ca

    from clutchopt.formulations import MODULES, get_coupling
    from clutchopt.model import namespace
    from clutchopt.start_up.equations import QUANTITIES

    units = {"kg*m^2", "rpm", "J/K", "W/K", "s", "s/rad", "", "N*m", "N"}  # clutchopt/simulate/scene.py
    units |= {q.unit for q in QUANTITIES}  # a case's [start_up] section
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

    offset = {"degC"}  # absolute temperatures: an offset, not a factor, read by pint (the table is multiplicative)
    assert _declared_units() - offset <= set(UNITS), "add the unit to TABLE_UNITS and run python -m clutchopt.units"


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
    from clutchopt.units import ureg

    text = f"{form.format(value)} {unit}"
    assert to_si("field", text, unit) == float(ureg.Quantity(text).to_base_units().magnitude)


def test_a_case_in_table_units_is_read_without_pint():
    import subprocess
    import sys

    from tests.conftest import CASES, ROOT

    code = (f"import sys\nfrom clutchopt.cases import load_case\nload_case({str(CASES / 'wedge_paper.toml')!r})\n"
            "print('pint' in sys.modules)")
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "False"
@pytest.mark.parametrize("text, si", [
    ("1000 rpm", 1000 * 2 * math.pi / 60),
    ("1000 rev/min", 1000 * 2 * math.pi / 60),
    ("16.5 rps", 16.5 * 2 * math.pi),  # revolutions per second
    ("6000 deg/s", 6000 * math.pi / 180),
    ("104.7 rad/s", 104.7),
])
def test_an_angular_speed_says_it_counts_an_angle(text, si):
    assert to_si("duty.speed", text, "rpm") == pytest.approx(si, rel=1e-14)


@pytest.mark.parametrize("text", ["16.67 Hz", "104.7 1/s", "104.7 s^-1", "1000 1/min", "0.0167 kHz"])
def test_a_pure_frequency_is_refused_for_an_angular_speed(text):
    """Hz and 1/s count revolutions or radians: read as rad/s (pint's reading) 16.67 Hz would be 2 pi too slow."""
    with pytest.raises(InputError, match=r"is ambiguous: an angular speed needs an angle per time"):
        to_si("duty.speed", text, "rpm")


def test_the_typographic_minus_is_a_minus():
    assert to_si("coupling.a", "\u22120.01 s/rad", "s/rad") == -0.01


@pytest.mark.parametrize("text, words", [
    ("1 m**99999999", "unit power 99999999 is out of range"),
    ("2**99999999 m", "a number inside the unit"),
    ("1 (((m)))", "parentheses nested too deeply"),
    ("1" + "0" * 400 + " m", "too long for a quantity"),
    ("1e400 m", "finite number within the float64 range"),
    ("10\x00 m", "control character"),
    ("\uff11 m", "cannot read"),  # a full-width digit: only ASCII digits are numbers
])
def test_text_pint_should_never_evaluate_is_refused(text, words):
    with pytest.raises(InputError, match=words):
        to_si("geometry.flank_inner_radius", text, "mm")


def test_a_huge_integer_is_beyond_float64():
    with pytest.raises(InputError, match="401-digit number is beyond the float64 range"):
        to_si("duty.inertia", 10**400, "kg*m^2")


def test_a_temperature_rise_is_no_temperature():
    """A rise of "15 degC" read by pint is 288.15 K; a temperature difference is written in K (or delta_degC)."""
    assert to_si("start_up.limits.max_temperature_rise", "15 delta_degC", "K") == 15.0
    with pytest.raises(InputError, match="a temperature on a scale with an offset"):
        to_si("start_up.limits.max_temperature_rise", "15 degC", "K")


def test_an_absolute_temperature_takes_celsius():
    assert to_si("friction_pairs.x.max_temperature", "250 degC", "degC") == pytest.approx(523.15, rel=1e-15)
    assert to_si("friction_pairs.x.max_temperature", "523.15 K", "degC") == 523.15


# --- kinds: a quantity is read by what it means, not by pint's dimensionality alone (issue 25) ---------------------
@pytest.mark.parametrize("text, unit, si", [
    ("600 1/h", "1/hour", 600 / 3600), ("10 1/min", "1/hour", 10 / 60), ("0.5 1/s", "1/hour", 0.5),
    ("20 %", "", 0.2), ("0.2", "", 0.2), ("11.46 deg", "deg", math.radians(11.46)), ("0.2", "deg", 0.2),
    ("28 N*m/deg", "N*m/rad", 28 * 180 / math.pi), ("-0.01 s/rad", "s/rad", -0.01),
])
def test_each_kind_takes_its_own_units(text, unit, si):
    assert to_si("field", text, unit) == pytest.approx(si, rel=1e-14)


@pytest.mark.parametrize("text, unit, words", [
    ("10 rpm", "1/hour", "expected a count per time (e.g. in 1/hour), got '10 rpm', which is an angular speed"),
    ("10 rev/hour", "1/hour", "which is an angular speed"),
    ("0.1 rad/s", "1/hour", "which is an angular speed"),
    ("11.46 deg", "", "expected a ratio (a bare number or %), got '11.46 deg', which is an angle"),
    ("0.2 rad", "", "which is an angle"),
    ("0.1 rev", "", "which is an angle"),
    ("20 %", "deg", "expected an angle (e.g. in deg), got '20 %', which is a ratio"),
    ("16 Hz", "rpm", "is ambiguous: an angular speed needs an angle per time"),
    ("28 N*m", "N*m/rad", "expected a torque per angle (e.g. in N*m/rad), got '28 N*m', which is a torque"),
    ("0.01 s", "s/rad", "expected a time per angle"),
    ("5 N*m/rad", "N*m", "expected a torque or energy (e.g. in N*m), got '5 N*m/rad', which is a torque per angle"),
])
def test_a_quantity_of_another_kind_is_refused(text, unit, words):
    with pytest.raises(InputError) as info:
        to_si("field", text, unit)
    assert words in str(info.value)


def _declared_quantities():
    """Every quantity a case, a [start_up] section or a library entry declares."""
    from clutchopt.formulations import MODULES, get_coupling
    from clutchopt.materials import FIELDS
    from clutchopt.start_up.equations import QUANTITIES

    quantities = [q for name in MODULES for q in get_coupling(name).quantities] + list(QUANTITIES)
    return quantities + [q for fields in FIELDS.values() for q in fields]


@pytest.mark.parametrize("quantity", [q for q in _declared_quantities() if q.unit != "degC"],
                         ids=lambda q: f"{q.key}[{q.unit}]")
def test_every_declared_quantity_refuses_one_angle_more(quantity):
    """An angle, a revolution or a speed slips through pint where a ratio or a count per time is meant: each
    declared quantity takes its own unit and refuses the same unit times an angle."""
    unit = quantity.unit
    assert to_si(quantity.key, f"1 {unit}", unit) == pytest.approx(1 / from_si(1.0, unit) if unit else 1.0)
    with pytest.raises(InputError, match="expected"):
        to_si(quantity.key, f"1 ({unit})*deg" if unit else "1 deg", unit)


# --- offset units without pint (issue 26: a start-up case's ambient temperature is 40 degC by default) ---------------
def test_the_offset_table_is_what_pint_says():
    from clutchopt.units import OFFSET_UNITS, _pint_si, _pint_unit_info, si_factor, si_unit, unit_info

    for unit in OFFSET_UNITS:
        assert unit_info(unit) == _pint_unit_info(unit)  # factor 274.15 (1 degC in K), [temperature], offset
        assert (si_factor(unit), si_unit(unit)) == _pint_si(unit)


@given(st.floats(min_value=-273.15, max_value=1e6, allow_subnormal=False), st.sampled_from(["{!r}", "{:.6g}"]))
def test_celsius_reads_and_shows_as_pint_to_the_last_bit(value, form):
    from clutchopt.units import from_si, into_si, ureg

    text = form.format(value)
    kelvin = float(ureg.Quantity(float(text), "degC").to("K").magnitude)
    assert to_si("start_up.heat.ambient", f"{text} degC", "degC") == kelvin == into_si(float(text), "degC")
    assert from_si(kelvin, "degC") == float(ureg.Quantity(kelvin, "K").to("degC").magnitude)


def test_a_start_up_case_is_read_without_pint():
    """Its [start_up] section's ambient temperature defaults to "40 degC": 313.15 K (40 + 273.15), not pint's work."""
    import subprocess
    import sys

    from tests.conftest import CASES, ROOT

    code = (f"import sys\nfrom clutchopt.cases import load_case\n"
            f"case = load_case({str(CASES / 'wedge_motor_start.toml')!r})\n"
            "print('pint' in sys.modules, case.values['ambient_temperature'])")
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.split() == ["False", "313.15"]


@pytest.mark.parametrize("unit, si", [("J", "J"), ("kJ", "J"), ("MJ", "J"), ("Wh", "J"), ("N*m", "N*m"),
                                      ("kN*m", "N*m"), ("kJ/K", "J/K"), ("kJ/hour", "W")])
def test_an_energy_is_in_joules_a_torque_in_newton_metres(unit, si):
    """review 28: pint gives both one dimension, so every energy declared in J or kJ (a start's friction work, its
    limit) was labelled N*m in the JSON, where `solve` labels the same figure J beside it."""
    from clutchopt.units import _pint_si

    assert si_unit(unit) == si and _pint_si(unit)[1] == si
