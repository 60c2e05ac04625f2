"""The lining of a start-up (docs/start_up.md, "The lining: temperature and life"): its peak and steady temperature
against the friction pair's limits, its wear and life, each recomputed by hand from the reported friction work."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from clutchopt.errors import InputError
from clutchopt.materials import library
from clutchopt.units import from_si, to_si

LEVER = "cases/lever_motor_start.toml"


def lever_case(tmp_path, name: str, library_pair: bool = True, **replace: str) -> str:
    """cases/lever_motor_start.toml (``[library] friction_pair = "organic_dry"``, its explicit friction coefficient
    and allowable pressure still winning), without the friction pair unless ``library_pair``, text replaced."""
    with open(LEVER, encoding="utf-8") as file:
        text = file.read()
    pair = '[library]\nfriction_pair = "organic_dry"\n\n'
    assert pair in text
    if not library_pair:
        text = text.replace(pair, "")
    for old, new in replace.items():
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / f"{name}.toml"
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_degc_is_an_absolute_temperature_both_ways():
    """40 degC = 313.15 K in, 313.15 K = 40 degC out (not a difference of 313.15 K)."""
    assert to_si("x", "40 degC", "degC") == pytest.approx(313.15, abs=1e-12)
    assert from_si(523.15, "degC") == pytest.approx(250.0, abs=1e-12)
    assert from_si(np.array([273.15, 373.15]), "degC") == pytest.approx([0.0, 100.0], abs=1e-12)
    assert from_si(2.0, "kJ") == 0.002
    assert to_si("x", "300 K", "degC") == 300.0  # kelvin is absolute too
    with pytest.raises(InputError, match="a temperature difference; write a temperature in degC or K"):
        to_si("start_up.heat.ambient", "40 delta_degC", "degC")


def test_every_friction_pair_has_its_temperature_limits_and_wear_rate():
    """Tribology Handbook table 7.4: continuous below peak; the wear rate named in the source."""
    pairs = library()["friction_pairs"]
    for entry in pairs.values():
        assert entry.values["continuous_temperature"] <= entry.values["max_temperature"], entry.name
        assert 1e-16 < entry.values["wear_rate"] < 1e-12, entry.name  # m^3/J: 1e-4 mm^3/J is 1e-13
        assert "wear_rate" in entry.source and "continuous" in entry.source, entry.name
    assert pairs["organic_dry"].values["continuous_temperature"] == pytest.approx(473.15)  # 200 degC, moulded


def test_a_solved_lever_start_recomputed_by_hand(tmp_path, cli):
    """At the optimum, from the simulated friction work L and the start's rise dT:
    steady T_s = T_0 + L n_h / G; peak = T_s + dT; wear h = k_w L / A with A = i pi d_cp b (two lined faces);
    N = s_w / h with s_w = delta (the lever's lining thickness, 4 mm); life = N / n_h."""
    path = lever_case(tmp_path, "life", **{'min_engagement_speed = "450 rpm"':
                                           'min_engagement_speed = "450 rpm"\nmin_life = "1000 h"'})
    result = cli("solve", path, "--json", "--no-store")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["status"] == "optimal"
    start, out = data["start_up"], data["outputs"]
    work, rise = start["friction_work_simulated"], start["temperature_rise_simulated"]
    ambient, per_second, conductance = 313.15, 4.0 / 3600.0, 10.0
    steady = ambient + work * per_second / conductance
    peak = steady + rise
    area = 2 * math.pi * out["mean_diameter"] * out["lining_width"]
    wear = 1e-13 * work / area
    starts = 4e-3 / wear
    hours = starts / 4.0
    assert start["steady_temperature_simulated"] == pytest.approx(steady, rel=1e-12)
    assert start["lining_temperature_simulated"] == pytest.approx(peak, rel=1e-12)
    assert start["wear_per_start_simulated"] == pytest.approx(wear, rel=1e-12)
    assert start["starts_until_worn_simulated"] == pytest.approx(starts, rel=1e-12)
    assert start["life_simulated"] == pytest.approx(hours * 3600.0, rel=1e-12)
    assert start["units"]["lining_temperature"] == "K" and start["units"]["life"] == "s"
    checks = {c["name"]: c for c in data["constraints"]}
    assert checks["lining_temperature"]["value"] == pytest.approx(peak, rel=1e-12)
    assert checks["lining_temperature"]["limit"] == pytest.approx(523.15)  # organic_dry: 250 degC
    assert checks["lining_temperature"]["unit"] == "K" and checks["lining_temperature"]["display_unit"] == "degC"
    assert checks["continuous_temperature"]["value"] == pytest.approx(steady, rel=1e-12)
    assert checks["continuous_temperature"]["limit"] == pytest.approx(473.15)  # 200 degC
    assert checks["lining_life"]["value"] == pytest.approx(hours * 3600.0, rel=1e-12)
    assert checks["lining_life"]["limit"] == pytest.approx(3.6e6)
    assert start["lining_notes"] == []
    table = cli("solve", path, "--no-store").stdout
    assert f"{peak - 273.15:.6g}" in table and "degC" in table  # the table in degC


def test_a_heat_capacity_too_small_for_the_lining_finds_no_design(tmp_path, cli):
    """C = 100 J/K: a start that brings 12 kg m^2 to about 1450 rpm releases some 100 kJ, about 1000 K over
    ambient; organic_dry stands 250 degC. Not optimal at that rise: no design, the lining temperature named."""
    path = lever_case(tmp_path, "hot", **{'capacity = "7000 J/K"': 'capacity = "100 J/K"',
                                          'max_temperature_rise = "30 K"\n': ""})
    result = cli("solve", path, "--json", "--no-store")
    data = json.loads(result.stdout)
    assert data["status"] in ("infeasible", "not_found")
    assert data["status"] != "optimal"
    assert "lining_temperature" in data["diagnosis"]
    checks = {c["name"]: c for c in data["constraints"]}
    assert checks["lining_temperature"]["limit"] == pytest.approx(523.15)
    assert checks["lining_temperature"]["value"] > 523.15


def test_a_start_up_without_heat_says_the_lining_was_not_checked(tmp_path, cli):
    path = lever_case(tmp_path, "cold", library_pair=False, **{
        '"lockup", "friction_heat"]': '"lockup"]', '[start_up.heat]\ncapacity = "7000 J/K"\nconductance = "10 W/K"\n':
        "", 'max_temperature_rise = "30 K"\n': "", 'heat_dissipation = "250 W"\n': ""})
    data = json.loads(cli("solve", path, "--json", "--no-store").stdout)
    notes = data["start_up"]["lining_notes"]
    assert notes[0].startswith("lining temperature not checked: the start-up has no heat data")
    assert "lining_temperature" not in {c["name"] for c in data["constraints"]}
    # the lever's own lining thickness is the wear allowance; without a friction pair there is no wear rate
    assert any(note.startswith("lining life not computed: no wear rate") for note in notes)


@pytest.mark.parametrize(("replace", "field", "words"), [
    ({'max_temperature_rise = "30 K"': 'max_lining_temperature = "30 degC"'}, "start_up.limits.max_lining_temperature",
     "not above the ambient temperature 40 degC"),
    ({'starts_per_hour = "4 1/hour"\n': "", 'heat_dissipation = "250 W"': 'min_life = "100 h"'},
     "start_up.limits.starts_per_hour", "given min_life"),
    ({'conductance = "10 W/K"': 'ambient = "20 K/s"'}, "start_up.heat.ambient", "expected"),
])
def test_bad_lining_input_names_the_field(tmp_path, cli, replace, field, words):
    result = cli("solve", lever_case(tmp_path, "bad", **replace), "--no-store")
    assert result.returncode == 2
    assert f"error: {field}" in result.stderr and words in result.stderr
    assert "Traceback" not in result.stderr


def test_heat_dissipation_needs_the_starts():
    from clutchopt.formulations import get_coupling
    from clutchopt.start_up.section import parse_start_up

    table = {"effects": ["slip_friction"], "limits": {"heat_dissipation": "10 W"}}
    with pytest.raises(InputError, match="starts_per_hour.*heat_dissipation"):
        parse_start_up(table, get_coupling("wedge"), {"inertia": 1.0, "resisting_torque": 1.0,
                                                      "acceleration_time": 5.0, "speed": 100.0})


def test_the_mean_steady_temperature_is_above_the_periodic_one():
    """docs/start_up.md: a start of L = 100 kJ every tau = 900 s (4 an hour) into C = 7000 J/K shedding G = 10 W/K
    starts, in the periodic state of the lumped model, at (L / C) / (exp(G tau / C) - 1) over ambient: x = G tau / C
    = 1.2857, e^x - 1 = 2.6172, 14.286 K / 2.6172 = 5.458 K; the mean steady rise L n_h / G = 100000 / 900 / 10 =
    11.11 K is above it (e^x - 1 >= x): the safe side."""
    from clutchopt.start_up.equations import steady_temperature_rise

    work, tau, capacity, conductance = 1e5, 900.0, 7000.0, 10.0
    mean = steady_temperature_rise(work, 1.0 / tau, conductance)
    periodic = (work / capacity) / math.expm1(conductance * tau / capacity)
    assert mean == pytest.approx(100000.0 / 900.0 / 10.0, rel=1e-15)
    assert periodic == pytest.approx(5.4583, rel=1e-4)
    assert periodic < mean


def test_the_friction_areas_that_wear():
    """Wedge: both flanks of z = 4 weights, gamma = 0.785 rad, r1 = 50 mm, r2 = 60 mm, alpha = 15 deg:
    2 z gamma (r2^2 - r1^2) / (2 cos alpha) = 8 x 0.785 x 0.0011 / 1.93185 = 3.5759e-3 m^2. Lever: i = 2 lined
    faces of d_cp = 200 mm, b = 50 mm: 2 pi 0.2 0.05 = 0.062832 m^2."""
    from clutchopt.formulations.lever.equations import lining_area
    from clutchopt.formulations.wedge.equations import flank_area_total

    wedge = 2 * 4 * 0.785 * (0.06**2 - 0.05**2) / (2 * math.cos(math.radians(15)))
    assert flank_area_total(4, 0.785, 0.05, 0.06, math.radians(15)) == pytest.approx(wedge, rel=1e-12)
    assert wedge == pytest.approx(3.5759e-3, rel=1e-4)
    assert lining_area(2, 0.2, 0.05) == pytest.approx(0.062832, rel=1e-5)


LEAST_WORK_MOTOR = 0.5 * 12.0 * (450 * math.pi / 30) ** 2  # J w_e,min^2 / 2 = 13,324.0 J (min_engagement_speed)
LEAST_WORK_CONSTANT = 0.5 * 12.0 * (1450 * math.pi / 30) ** 2  # J w^2 / 2 = 138,336 J (the constant driving speed)


def test_a_lining_no_design_can_keep_cool_is_proven_infeasible_with_a_motor(tmp_path, cli):
    """Nearly adiabatic housing (G = 0.1 W/K, C = 100 J/K), 4 starts an hour, min_engagement_speed 450 rpm: every
    start releases at least W = J w_e^2 / 2 = 13.324 kJ (optimise/proofs.py), so the steady rise W n_h / G = 148.04 K
    and a start's rise e^(-G t_max / C) W / C = e^(-0.03) 133.24 = 129.30 K put the lining at 40 + 148.04 + 129.30 =
    317.3 degC at least, above organic_dry's 250 degC: proven, whatever the coupling's geometry."""
    steady = LEAST_WORK_MOTOR * 4 / 3600 / 0.1
    rise = math.exp(-0.1 * 30 / 100) * LEAST_WORK_MOTOR / 100
    assert (steady, rise) == pytest.approx((148.044, 129.302), rel=1e-5)
    path = lever_case(tmp_path, "adiabatic", **{'capacity = "7000 J/K"': 'capacity = "100 J/K"',
                                                'conductance = "10 W/K"': 'conductance = "0.1 W/K"',
                                                'max_temperature_rise = "30 K"\n': "",
                                                'heat_dissipation = "250 W"\n': ""})
    data = json.loads(cli("solve", path, "--json", "--no-store").stdout)
    assert data["status"] == "infeasible" and "proven" in data["diagnosis"]
    assert f"the lining reaches at least {40 + steady + rise:.6g} degC, above its limit 250 degC" in data["diagnosis"]
    assert f"at least J w^2 / 2 = {LEAST_WORK_MOTOR / 1e3:.6g} kJ" in data["diagnosis"]


def test_a_lining_no_design_can_keep_cool_on_a_constant_speed_drive_is_proven(tmp_path, cli):
    """Driven at a constant 1450 rpm (no motor_curve), C = 100 J/K and G = 1 W/K: W >= J w^2 / 2 = 138.3 kJ, a
    start's rise >= e^(-0.3) 1383.4 K: proven; the rise limit (max_temperature_rise 30 K) too."""
    path = lever_case(tmp_path, "constant", **{
        '"motor_curve", ': "", 'capacity = "7000 J/K"': 'capacity = "100 J/K"',
        'conductance = "10 W/K"': 'conductance = "1 W/K"', 'heat_dissipation = "250 W"\n': "",
        '[start_up.driver]\nsynchronous_speed = "1500 rpm"\nbreakdown_torque = "265 N*m"\nbreakdown_slip = 0.15\n'
        'inertia = "0.09 kg*m^2"\n': "", '[start_up.overload]\n': "", "check = false": "",
        'min_engagement_speed = "450 rpm"\n': "", 'max_engagement_speed = "750 rpm"\n': ""})
    data = json.loads(cli("solve", path, "--json", "--no-store").stdout)
    rise = math.exp(-0.3) * LEAST_WORK_CONSTANT / 100
    assert data["status"] == "infeasible" and "proven" in data["diagnosis"]
    assert f"temperature_rise: every start releases at least J w^2 / 2 = {LEAST_WORK_CONSTANT / 1e3:.6g} kJ" \
        in data["diagnosis"]
    assert f"the friction parts rise by at least {rise:.6g} K, above its limit 30 K" in data["diagnosis"]
    assert "lining_temperature" in data["diagnosis"]


def test_a_sweep_of_the_ambient_reads_degc_as_an_absolute_temperature():
    """--vary values are numbers in the display unit; for degC that is an offset: 20 degC = 293.15 K, 60 degC =
    333.15 K (not 20 x 274.15 K, a factor's reading); a speed stays a factor, 1000 rpm = 104.72 rad/s."""
    from clutchopt.cases import load_case
    from clutchopt.optimise.sweep_grid import parse_vary

    case = load_case(LEVER)
    ambient = parse_vary("ambient_temperature=20,60", "lever", case.quantities)
    assert ambient.values == pytest.approx((293.15, 333.15), rel=1e-15) and ambient.shown == (20.0, 60.0)
    assert parse_vary("speed=1000:1200:3", "lever", case.quantities).values == pytest.approx(
        tuple(n * math.pi / 30 for n in (1000, 1100, 1200)), rel=1e-15)


def test_the_library_note_keeps_the_librarys_order_whatever_the_hash_seed():
    """What the friction pair fills in [start_up] is listed in the library's order (it followed a set's order, which
    changed with PYTHONHASHSEED from one run to the next)."""
    import ast
    import os
    import subprocess
    import sys

    from tests.conftest import ROOT

    code = f"from clutchopt.cases import load_case\nprint(list(load_case({LEVER!r}).filled))"
    runs = {subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True,
                           env={**os.environ, "PYTHONHASHSEED": str(seed)}).stdout for seed in (1, 2, 3, 4)}
    assert len(runs) == 1
    filled = ast.literal_eval(runs.pop())
    assert filled.index("max_lining_temperature") < filled.index("max_continuous_temperature") < \
        filled.index("wear_rate")  # the order organic_dry's fields fill them in
