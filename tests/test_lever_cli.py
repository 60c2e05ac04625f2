"""Lever coupling through the CLI (JSON contracts) and bad input (InputError naming the field)."""

import json
import math
import tomllib

import pytest

from clutchopt.cases import parse_case
from clutchopt.errors import InputError
from tests.conftest import CASES

CASE = "cases/lever_wedge_duty.toml"
TEXT = (CASES / "lever_wedge_duty.toml").read_text()


def test_solve_json_contract(cli):
    result = cli("solve", CASE, "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["status"] == "optimal" and data["mode"] == "paper"
    assert data["objective"]["name"] == "mass" and data["objective"]["unit"] == "kg"
    assert set(data["design"]) == {"weight_mass", "link_diameter"}
    assert data["design"]["weight_mass"] == pytest.approx(0.2985628 / 4, rel=1e-6)  # m z by hand / z
    assert data["design"]["link_diameter"] == pytest.approx(3.59405e-3, rel=1e-5)  # SI: metres
    names = {c["name"] for c in data["constraints"]}
    assert names == {"torque", "lining_pressure", "link_buckling", "link_compression", "weights_fit",
                     "outer_diameter", "toggle_span", "lining_clears_flange", "flange_over_shaft"}  # the case's
    # rules, in every mode (lever/modes.py: all of design mode's but the l_2 rule, met by construction)
    assert {"name", "status", "iterations", "time_s"} <= set(data["solver"])


def test_design_mode_json(cli):
    result = cli("solve", CASE, "--mode", "design", "--objective", "cost", "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["status"] == "optimal" and data["objective"]["unit"] == "EUR"
    assert {"lever_length", "engagement_angle", "limit_angle", "weight_count", "flange_diameter",
            "lining_width"} <= set(data["design"])
    assert "outer_diameter" in {c["name"] for c in data["constraints"]}


def test_compare_json_sets_printed_formula_closed_form_and_nlp_side_by_side(cli):
    result = cli("compare", CASE, "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["columns"] == ["paper_formula", "closed_form", "nlp_paper", "nlp_design"]
    rows = {row["quantity"]: row for row in data["rows"]}
    mz = rows["characteristic_number"]
    assert mz["closed_form"] == pytest.approx(0.2985628, rel=1e-6)
    assert mz["paper_formula"] == pytest.approx(2 * 0.2985628, rel=1e-6)  # errata L1
    assert mz["relative"]["paper_formula"] == pytest.approx(1.0, rel=1e-9)
    assert mz["nlp_paper"] == pytest.approx(mz["closed_form"], rel=1e-6)
    assert rows["torque"]["paper_formula"] == pytest.approx(2 * rows["torque"]["closed_form"], rel=1e-9)
    assert rows["link_diameter"]["paper_formula"] is None  # the paper sizes no link
    assert rows["total_mass"]["nlp_design"] <= rows["total_mass"]["nlp_paper"] * (1 + 1e-9)
    assert all(s["status"] == "optimal" for s in data["solves"].values())


def _case(text):
    return parse_case(tomllib.loads(text), "bad.toml")


BAD = {
    "gamma_0 above 15 deg": (lambda t: t.replace('engagement_angle = "15 deg"', 'engagement_angle = "16 deg"'),
                             "geometry.engagement_angle"),
    "gamma_pr below 1.5 deg": (lambda t: t.replace('limit_angle = "2 deg"', 'limit_angle = "1 deg"'),
                               "geometry.limit_angle"),
    "gamma_pr above 3 deg": (lambda t: t.replace('limit_angle = "2 deg"', 'limit_angle = "4 deg"'),
                             "geometry.limit_angle"),
    "gamma_0 not above gamma_pr": (lambda t: t.replace('engagement_angle = "15 deg"', 'engagement_angle = "2 deg"'),
                                   "geometry.engagement_angle"),
    "delta zero": (lambda t: t.replace('lining_thickness = "3 mm"', 'lining_thickness = "0 mm"'),
                   "geometry.lining_thickness"),
    "delta negative": (lambda t: t.replace('lining_thickness = "3 mm"', 'lining_thickness = "-3 mm"'),
                       "geometry.lining_thickness"),
    "flange inside the shaft": (lambda t: t.replace('flange_diameter = "45 mm"', 'flange_diameter = "20 mm"'),
                                "geometry.flange_diameter"),
    "width factor off the paper's range": (lambda t: t.replace("[spring]", "width_allowance = 2.5\n\n[spring]"),
                                           "geometry.width_allowance"),
    "friction coefficient above 1": (lambda t: t.replace("friction_coefficient = 0.3", "friction_coefficient = 1.3"),
                                     "material.friction_coefficient"),
    "wrong dimension": (lambda t: t.replace('"0.25 MPa"', '"0.25 kg"'), "material.allowable_pressure"),
    "missing spring": (lambda t: t.replace('spring_free_length = "25 mm"\n', ""), "spring.spring_free_length"),
    "bounds beyond 15 deg": (lambda t: t + '\n[bounds]\nengagement_angle = ["5 deg", "20 deg"]\n',
                             "bounds.engagement_angle"),
    "bounds below 1.5 deg": (lambda t: t + '\n[bounds]\nlimit_angle = ["1 deg", "3 deg"]\n', "bounds.limit_angle"),
    "housing thinner than its walls": (lambda t: t.replace('outer_diameter_max = "220 mm"',
                                                           'outer_diameter_max = "16 mm"'),
                                       "limits.outer_diameter_max"),
}


@pytest.mark.parametrize("kind", BAD)
def test_bad_input_names_the_field(kind):
    mutate, field = BAD[kind]
    text = mutate(TEXT)
    assert text != TEXT
    with pytest.raises(InputError) as error:
        _case(text)
    assert field in str(error.value)


@pytest.mark.parametrize("kind", ["gamma_0 above 15 deg", "delta zero"])
def test_bad_input_through_the_cli_is_one_line(cli, tmp_path, kind):
    mutate, field = BAD[kind]
    path = tmp_path / "bad.toml"
    path.write_text(mutate(TEXT))
    result = cli("solve", str(path), "--json")
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and field in lines[0], result.stderr


def test_the_cases_read_as_their_comments_say():
    p = _case(TEXT).params()
    assert p.speed == pytest.approx(1000 * 2 * math.pi / 60)
    assert p.engagement_angle == pytest.approx(math.radians(15)) and p.friction_surfaces == 2
    assert p.width_allowance == 1.5 and p.elastic_modulus == pytest.approx(210e9)
