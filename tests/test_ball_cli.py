"""Ball cases as users run them: JSON contracts of solve and compare; bad input is an InputError naming the field."""

import json
import tomllib

import pytest

from clutchopt.cases import parse_case
from clutchopt.errors import InputError
from tests.conftest import CASES

CRUSHER = (CASES / "ball_crusher.toml").read_text()
DESIGN = {"active_radius", "filling", "ball_radius", "groove_conformity", "ball_rows"}


def test_solve_json_contract(cli):
    result = cli("solve", "cases/ball_compressor.toml", "--objective", "cost", "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["status"] == "optimal" and data["mode"] == "design"
    assert data["objective"]["name"] == "cost" and data["objective"]["unit"] == "EUR"
    assert set(data["design"]) == DESIGN and float(data["design"]["ball_rows"]).is_integer()
    assert {"torque", "contact_stress", "ball_mass", "body_mass", "total_mass", "cost"} <= set(data["outputs"])
    for c in data["constraints"]:
        assert {"name", "value", "limit", "margin", "active"} <= set(c) and c["margin"] >= -1e-8


def test_compare_json_sets_the_paper_procedure_beside_the_nlp(cli):
    result = cli("compare", "cases/ball_crusher.toml", "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["baseline"] == "paper_procedure"
    assert data["columns"] == ["paper_procedure", "nlp_mass", "nlp_cost"]
    rows = {row["quantity"]: row for row in data["rows"]}
    assert {"active_radius", "active_width", "ball_rows", "filling", "torque", "contact_stress", "ball_mass",
            "body_mass", "total_mass", "cost"} <= set(rows)
    assert rows["active_radius"]["paper_procedure"] == pytest.approx(0.320344, rel=1e-5)  # fifth root (4)
    assert rows["ball_rows"]["paper_procedure"] == 11
    mass = rows["total_mass"]
    assert mass["relative"]["nlp_mass"] == pytest.approx((mass["nlp_mass"] - mass["paper_procedure"]) / mass["paper_procedure"])
    assert all(solve["status"] == "optimal" for solve in data["solves"].values())


BAD = {
    "missing field": (lambda t: t.replace("construction_density = 0.8\n", ""), "body.construction_density"),
    "wrong dimension": (lambda t: t.replace('power = "500 kW"', 'power = "500 N*m"'), "duty.power"),
    "negative power": (lambda t: t.replace('"500 kW"', '"-500 kW"'), "duty.power"),
    "NaN friction": (lambda t: t.replace("friction_coefficient = 0.04", "friction_coefficient = nan"),
                     "balls.friction_coefficient"),
    "packing above close packing": (lambda t: t.replace("[balls]\n", "[balls]\npacking_density = 0.8\n"),
                                    "balls.packing_density"),
    "groove tighter than the ball": (lambda t: t.replace("groove_conformity = 1.02", "groove_conformity = 1.0"),
                                     "balls.groove_conformity"),
    "fractional shovels": (lambda t: t.replace("[body]\n", "[body]\nshovel_count = 5.5\n"), "body.shovel_count"),
    "K5 range upside down": (lambda t: t.replace("width_ratio_max = 3.0", "width_ratio_max = 0.3"),
                             "limits.width_ratio_max"),
    "filling bound out of range": (lambda t: t.replace('ball_radius = ["6 mm", "16 mm"]',
                                                       'ball_radius = ["6 mm", "16 mm"]\nfilling = [0.4, 1.2]'),
                                   "bounds.filling"),
}


@pytest.mark.parametrize("kind", BAD)
def test_bad_input_is_an_input_error_naming_the_field(kind):
    mutate, field = BAD[kind]
    text = mutate(CRUSHER)
    assert text != CRUSHER
    with pytest.raises(InputError) as error:
        parse_case(tomllib.loads(text), "bad.toml")
    assert error.value.field == field and "\n" not in str(error.value)


def test_bad_input_is_one_line_and_exit_2_on_the_cli(cli, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(CRUSHER.replace('power = "500 kW"', 'power = "500 kg"'))
    result = cli("compare", str(path), "--json")
    assert result.returncode == 2 and result.stdout == ""
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: duty.power:")
