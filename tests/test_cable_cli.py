"""Cable cases as users run them: JSON contracts of solve and compare; bad input is an InputError naming the field."""

import json
import math
import tomllib

import pytest

from clutchopt.cases import parse_case
from clutchopt.errors import InputError

from tests.conftest import CASES

PUMP = (CASES / "cable_pump.toml").read_text()


@pytest.mark.parametrize("name, mode", [("cable_pump", "threads"), ("cable_conveyor", "paper")])
def test_solve_json_contract(cli, name, mode):
    result = cli("solve", f"cases/{name}.toml", "--mode", mode, "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["status"] == "optimal" and data["mode"] == mode
    assert data["objective"]["name"] == "mass" and data["objective"]["unit"] == "kg"
    assert set(data["design"]) == {"half_coupling_mass", "weight_mass", "cable_count", "finger_diameter",
                                   "screw_diameter", "lead_angle", "weight_lead_angle"}
    assert float(data["design"]["cable_count"]).is_integer()
    for c in data["constraints"]:
        assert {"name", "value", "limit", "margin", "active"} <= set(c) and c["margin"] >= -1e-8
    assert {"name", "status", "iterations", "time_s"} <= set(data["solver"])


def test_solve_pump_numbers(cli):
    data = json.loads(cli("solve", "cases/cable_pump.toml", "--json").stdout)
    assert data["design"]["cable_count"] == 6
    assert data["design"]["half_coupling_mass"] == pytest.approx(0.069943, rel=1e-4)  # see test_cable_closed_forms
    assert data["objective"]["value"] == pytest.approx(3.02155, rel=1e-5)


def test_compare_json_sets_paper_closed_forms_and_nlp_side_by_side(cli):
    result = cli("compare", "cases/cable_pump.toml", "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["baseline"] == "closed_form"
    assert set(data["columns"]) == {"paper_formulas", "closed_form", "closed_form_threads", "nlp_paper", "nlp_threads"}
    rows = {row["quantity"]: row for row in data["rows"]}
    mass = rows["half_coupling_mass"]
    assert mass["paper_formulas"] == pytest.approx(0.73988, rel=1e-4)  # printed (7): 10.6 times the consistent mass
    assert mass["relative"]["nlp_paper"] == pytest.approx(0, abs=1e-6)
    assert rows["total_mass"]["nlp_threads"] == pytest.approx(rows["total_mass"]["closed_form_threads"], rel=1e-6)
    # the printed mass, run through the consistent (5), pushes F_a = 370 N / tan^2(beta + phi')
    beta_phi = math.radians(11.18) + math.atan(0.1 / math.cos(math.radians(15)))
    assert rows["hub_axial_force"]["paper_formulas"] == pytest.approx(370 / math.tan(beta_phi) ** 2, rel=1e-12)
    assert all(solve["status"] == "optimal" for solve in data["solves"].values())


BAD = {
    "missing field": (lambda t: t.replace('cable_twist = "2 deg"\n', ""), "cables.cable_twist"),
    "wrong dimension": (lambda t: t.replace('torque = "108 N*m"', 'torque = "108 N"'), "duty.torque"),
    "negative torque": (lambda t: t.replace('"108 N*m"', '"-108 N*m"'), "duty.torque"),
    "area ratio above 1": (lambda t: t.replace("area_ratio = 0.5", "area_ratio = 1.2"), "cables.area_ratio"),
    "twist of 90 deg": (lambda t: t.replace('twist_angle = "3 deg"', 'twist_angle = "90 deg"'), "cables.twist_angle"),
    "fractional starts": (lambda t: t.replace("starts = 3\nweight", "starts = 2.5\nweight"), "thread.starts"),
    "self-locking hub thread": (lambda t: t.replace('lead_angle = "11.18 deg"', 'lead_angle = "5 deg"'),
                                "thread.lead_angle"),
    "too slow to drive": (lambda t: t.replace('speed = "1460 rpm"', 'speed = "100 rpm"'), "geometry.mass_radius"),
    "unknown option": (lambda t: t + '\n[options]\nfree = ["span"]\n', "options.free"),
}


@pytest.mark.parametrize("kind", BAD)
def test_bad_input_is_an_input_error_naming_the_field(kind):
    mutate, field = BAD[kind]
    text = mutate(PUMP)
    assert text != PUMP
    with pytest.raises(InputError) as error:
        parse_case(tomllib.loads(text), "bad.toml")
    assert error.value.field == field and "\n" not in str(error.value)


def test_self_locking_thread_is_one_line_on_the_cli(cli, tmp_path):
    path = tmp_path / "locked.toml"
    path.write_text(PUMP.replace('lead_angle = "11.18 deg"', 'lead_angle = "5 deg"'))
    result = cli("compare", str(path), "--json")
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: thread.lead_angle:")
    assert "beta = 5 deg must exceed phi' = 5.911 deg" in lines[0]


def test_unknown_mode(cli):
    result = cli("solve", "cases/cable_pump.toml", "--mode", "geometry")
    assert result.returncode == 2 and "mode" in result.stderr and "paper, threads" in result.stderr
