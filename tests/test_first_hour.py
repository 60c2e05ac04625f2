"""Issue 13, "Done when": a new user runs ``clutchopt init lever -o mine.toml``, changes three numbers, picks a
friction pair by name and gets a verified optimum with correct units in text and JSON. Done here as they would,
through the command line in a fresh folder.

Hand check of the changed duty (lever paper, T_max = I_M e + T_p with e = w / t_p):
    I = 20 kg m^2, n = 980 rpm -> w = 980 * 2 pi / 60 = 102.6254 rad/s, t_p = 20 s, T_p = 20 N m
    T_max = 20 * 102.6254 / 20 + 20 = 122.6254 N m
The friction pair sintered_bronze_dry gives f = 0.3 and [p] = 0.3 MPa (clutchopt/data/materials.toml).
"""

import json
import math
import re

import pytest

from tests.test_json_units import assert_units, printed_constraints

T_MAX = 20 * 980 * 2 * math.pi / 60 / 20 + 20


def edit(text: str, old: str, new: str) -> str:
    assert text.count(old) == 1, old
    return text.replace(old, new)


@pytest.fixture(scope="module")
def mine(tmp_path_factory):
    from tests.conftest import run_cli

    folder = tmp_path_factory.mktemp("first_hour")
    made = run_cli("init", "lever", "-o", "mine.toml", cwd=folder)
    assert made.returncode == 0 and made.stdout == "wrote mine.toml: a new lever case; solve it with: clutchopt " \
                                                   "solve mine.toml\n"
    path = folder / "mine.toml"
    text = path.read_text()
    text = edit(text, 'inertia = "12 kg*m^2"', 'inertia = "20 kg*m^2"')
    text = edit(text, 'speed = "1450 rpm"', 'speed = "980 rpm"')
    text = edit(text, 'acceleration_time = "30 s"', 'acceleration_time = "20 s"')
    text = edit(text, 'friction_pair = "organic_dry"', 'friction_pair = "sintered_bronze_dry"')
    path.write_text(text)
    return folder


def test_the_edited_case_solves_to_a_verified_optimum_in_text(mine):
    from tests.conftest import run_cli

    result = run_cli("solve", "mine.toml", "--no-store", cwd=mine)
    assert result.returncode == 0, result.stderr
    text = result.stdout
    assert "status: optimal" in text  # IPOPT converged and the float64 re-check passed
    assert re.search(rf"required_torque\s+{T_MAX:.6g}\s+N\*m", text)
    pressure = printed_constraints(text)["lining_pressure"]
    assert pressure[1] == "MPa"
    assert re.search(r"lining_pressure .* <=\s+0\.3\s+MPa", text)  # the pair's [p], in MPa
    assert "friction_pair = sintered_bronze_dry: friction_coefficient 0.3 (scatter 0.15 to 0.45), " \
           "allowable_pressure 0.3 MPa" in text


def test_the_edited_case_gives_si_values_with_their_units_in_json(mine):
    from tests.conftest import run_cli

    data = json.loads(run_cli("solve", "mine.toml", "--json", "--no-store", cwd=mine).stdout)
    assert data["status"] == "optimal"
    assert len(assert_units(data)) > 40  # numbers, each with its SI unit
    assert data["outputs"]["required_torque"] == pytest.approx(T_MAX, rel=1e-12)
    assert data["units"]["outputs"]["required_torque"] == "N*m"
    lining = next(c for c in data["constraints"] if c["name"] == "lining_pressure")
    assert (lining["limit"], lining["unit"], lining["display_unit"]) == (0.3e6, "Pa", "MPa")
    assert data["units"]["design"]["link_diameter"] == "m" and data["design"]["link_diameter"] < 0.1
    assert data["library"]["friction_pair"]["entry"] == "sintered_bronze_dry"
