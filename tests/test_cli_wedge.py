"""The CLI as users run it: JSON contracts, and one-line errors with exit code 2 for each class of bad input."""

import json
import re
import subprocess
import sys

import pytest

from tests.conftest import CASES, ROOT

PAPER = (CASES / "wedge_paper.toml").read_text()


def test_solve_json_contract(cli):
    result = cli("solve", "cases/wedge_paper.toml", "--json")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    assert data["status"] == "optimal"
    assert data["objective"]["unit"] == "kg" and data["objective"]["value"] == pytest.approx(0.66795, rel=1e-4)
    assert set(data["design"]) == {"weight_mass", "finger_diameter"}
    assert data["design"]["finger_diameter"] == pytest.approx(5.4616e-3, rel=1e-4)  # SI: metres
    names = {c["name"] for c in data["constraints"]}
    assert names == {"torque", "flank_pressure", "finger_bending", "weight_covers_flank", "sectors_fit",
                     "not_self_locking", "outer_diameter", "top_land_width", "hub_clearance", "finger_fits_width",
                     "finger_guide_length",
                     "finger_fits_chord"}  # after the paper's three: the rules that make a buildable part, as in
    # geometry mode (wedge/modes.py constructive_constraints)
    for c in data["constraints"]:
        assert {"value", "limit", "margin", "active"} <= set(c)
    assert {"name", "status", "iterations", "time_s"} <= set(data["solver"])


def test_compare_json_sets_printed_formula_and_nlp_side_by_side(cli):
    result = cli("compare", "cases/wedge_paper.toml", "--json")
    assert result.returncode == 0, result.stderr
    rows = {row["quantity"]: row for row in json.loads(result.stdout)["rows"]}
    mass = rows["weight_mass"]
    assert mass["paper_printed"] == 0.235
    assert mass["paper_eq27_first_form"] == pytest.approx(0.15687, rel=1e-4)
    assert mass["paper_eq27_second_form"] == pytest.approx(1.5687, rel=1e-4)
    assert mass["nlp_paper"] == pytest.approx(mass["closed_form"], rel=1e-6)
    assert mass["nlp_geometry"] > 0
    assert rows["finger_diameter"]["paper_printed"] == pytest.approx(3.1e-3)


def test_text_tables(cli):
    result = cli("solve", "cases/wedge_fan.toml", "--mode", "geometry", "--objective", "cost")
    assert result.returncode == 0, result.stderr
    assert "status: optimal" in result.stdout and "Constraints" in result.stdout
    assert re.search(r"finger_bending .* yes", result.stdout)


BAD = {
    "missing field": (lambda t: t.replace('inertia = "0.5 kg*m^2"\n', ""), "duty.inertia"),
    "wrong dimension": (lambda t: t.replace('"4 MPa"', '"4 kg"'), "material.allowable_pressure"),
    "negative inertia": (lambda t: t.replace('"0.5 kg*m^2"', '"-0.5 kg*m^2"'), "duty.inertia"),
    "alpha at 90 deg": (lambda t: t.replace('"15 deg"', '"90 deg"'), "geometry.flank_angle"),
    "alpha above 90 deg": (lambda t: t.replace('"15 deg"', '"120 deg"'), "geometry.flank_angle"),
    "lambda = 1": (lambda t: t.replace("radius_ratio = 1.2", "radius_ratio = 1.0"), "geometry.radius_ratio"),
    "lambda < 1": (lambda t: t.replace("radius_ratio = 1.2", "radius_ratio = 0.8"), "geometry.radius_ratio"),
    "NaN text": (lambda t: t.replace('"160 MPa"', '"nan MPa"'), "material.allowable_bending_stress"),
    "NaN literal": (lambda t: t.replace("friction_coefficient = 0.15", "friction_coefficient = nan"),
                    "material.friction_coefficient"),
    "unknown key": (lambda t: t.replace("[duty]\n", "[duty]\ninertial = 3\n"), "duty.inertial"),
    "TOML syntax": (lambda t: t.replace('speed = "1000 rpm"', 'speed = "1000 rpm'), "bad.toml"),
}


@pytest.mark.parametrize("kind", BAD)
def test_bad_input_is_one_line_naming_the_field(cli, tmp_path, kind):
    mutate, field = BAD[kind]
    path = tmp_path / "bad.toml"
    text = mutate(PAPER)
    assert text != PAPER
    path.write_text(text)
    for command in ("solve", "compare"):
        result = cli(command, str(path), "--json")
        assert result.returncode == 2
        assert result.stdout == ""
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error:") and field in lines[0], result.stderr
        assert "Traceback" not in result.stderr


def test_unknown_mode_and_missing_file(cli):
    for args, field in ((("solve", "cases/wedge_paper.toml", "--mode", "dream"), "mode"),
                        (("solve", "cases/none.toml"), "cases/none.toml")):
        result = cli(*args)
        assert result.returncode == 2 and result.stderr.count("\n") == 1 and field in result.stderr


@pytest.mark.parametrize("args, heavy", [
    (["--help"], ("casadi", "numpy", "pandas", "pint", "scipy", "cvxpy", "matplotlib")),
    *[(["solve", f"cases/{case}.toml", "--json", "--no-store"],
       ("pandas", "pint", "scipy.optimize", "scipy.special", "scipy.stats", "cvxpy", "matplotlib", "clutchopt.store"))
      for case in ("wedge_paper", "lever_centrifuge", "ball_crusher", "cable_pump")],
    (["solve", "cases/wedge_paper.toml", "--no-store"],  # (its text tables: no pandas, output._frame)
     ("pandas", "pint", "scipy.optimize", "scipy.special", "cvxpy", "matplotlib", "clutchopt.store")),
    (["simulate", "cases/scenes/paper_transient.toml", "--no-store"],  # (no --plot: no figure, no matplotlib)
     ("matplotlib", "pandas", "pint", "scipy.stats", "cvxpy", "clutchopt.store")),
])
def test_a_command_imports_only_what_it_uses(args, heavy):
    # what `clutchopt solve --json` waits for is measured in `clutchopt bench` (section cli_launch); here: what it
    # loads (the ball's and the cable's static solves had imported scipy.optimize and scipy.special, 0.4-0.5 s, for
    # closed forms only their paper procedures and threads mode call)
    code = ("import sys\nfrom clutchopt.cli import main\ntry:\n    main(%r)\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in sys.modules if m in %r))" % (args, heavy))
    result = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip().splitlines()[-1] == "[]"
