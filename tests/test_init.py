"""``clutchopt init``, ``couplings`` and ``--version``: a new case solves as written in every mode, says what each
field is, and is written only where the user asked."""

import json
import tomllib

import pytest

import clutchopt
from clutchopt.cli.options import COUPLING_MODES
from clutchopt.formulations import MODULES, get_coupling
from clutchopt.model import REQUIRED
from clutchopt.template import case_template
from tests.test_json_units import run

MODES = [(coupling, mode) for coupling in MODULES for mode in get_coupling(coupling).formulations]


def test_the_cli_mode_index_is_the_formulations_own():
    """--mode help lists the modes without importing the formulations: the index must match them, default first."""
    assert list(COUPLING_MODES) == list(MODULES)
    for name, modes in COUPLING_MODES.items():
        coupling = get_coupling(name)
        assert set(modes) == set(coupling.formulations) and modes[0] == coupling.default_mode


@pytest.mark.parametrize(("coupling", "mode"), MODES)
def test_a_new_case_solves_as_written_in_every_mode(coupling, mode, tmp_path):
    path = tmp_path / "new.toml"
    assert "wrote" in run("init", coupling, "--mode", mode, "-o", path)
    data = json.loads(run("solve", path, "--json", "--no-store"))
    assert data["status"] == "optimal" and data["mode"] == mode
    assert data["library"], "the starting case names library entries"


@pytest.mark.parametrize("coupling", MODULES)
def test_every_field_is_in_the_case_with_unit_meaning_and_valid_range(coupling):
    """Each quantity appears once as a line (active or commented), its comment naming unit and valid range;
    every required one is set, by the case or by the library."""
    text = case_template(coupling)
    lines = text.splitlines()
    data = tomllib.loads(text)
    declared = get_coupling(coupling).quantities
    for q in declared:
        at = [i for i, line in enumerate(lines) if line.lstrip("# ").startswith(f"{q.name} = ")
              and lines[i - 1].startswith("#   ")]
        assert len(at) == 1, q.key
        first = max(i for i in range(at[0]) if not lines[i].startswith("#")) + 1  # the field's comment block
        comment = " ".join(line[2:].strip() for line in lines[first:at[0]])
        assert q.description in comment and (q.unit or "dimensionless") in comment, q.key
        assert f"valid {q.valid_range()}" in comment, q.key
        if q.default is REQUIRED:
            library = [r.fills for r in get_coupling(coupling).materials if r.key in data.get("library", {})]
            assert q.name in data.get(q.section, {}) or any(q.name in f.values() for f in library), q.key


def test_the_lever_case_says_where_each_value_comes_from():
    text = case_template("lever", "design")
    assert 'mode = "design"' in text.splitlines()  # --mode is written as an active option
    assert 'friction_pair = "organic_dry"' in text
    assert "# friction_coefficient = 0.3" in text  # filled by the library: commented, with the library's value
    assert "from the library: friction_pair organic_dry (friction_coefficient)" in text
    assert "typical at most 15 deg (the paper)" in text  # the starting table's typical range
    assert "# buckling_safety_factor = 3.0" in text and "default: clutchopt's" in text
    assert "# lever_length = [\"10 mm\", \"2000 mm\"]" in text  # bounds of the mode's variables, commented


def test_init_prints_without_out_refuses_to_overwrite_and_forces(tmp_path, cli):
    printed = cli("init", "cable")
    assert printed.returncode == 0 and printed.stdout.startswith("# A new case of the inertial-centrifugal cable")
    path = tmp_path / "mine.toml"
    path.write_text("keep me")
    refused = cli("init", "lever", "-o", str(path))
    assert refused.returncode == 2 and refused.stdout == ""
    assert refused.stderr == f"error: --out: {path} exists; give another name, or --force to overwrite it\n"
    assert path.read_text() == "keep me"
    forced = cli("init", "lever", "-o", str(path), "--force")
    assert forced.returncode == 0 and tomllib.loads(path.read_text())["coupling"] == "lever"


@pytest.mark.parametrize(("args", "message"), [
    (("init", "clutch"), "argument COUPLING: invalid choice: 'clutch'"),
    (("init", "wedge", "--mode", "design"), "error: mode: unknown mode 'design' for wedge; choose from paper, geometry"),
])
def test_bad_init_input(cli, args, message):
    result = cli(*args)
    assert result.returncode == 2 and message in result.stderr and result.stdout == ""


def test_version_and_help(cli):
    assert cli("--version").stdout == f"clutchopt {clutchopt.__version__}\n"
    top = cli("--help").stdout
    for command in ("init", "couplings", "materials", "solve", "compare", "sweep", "report"):
        assert f"\n    {command}" in top
    solve = cli("solve", "--help").stdout
    assert "lever: paper (default), design" in " ".join(solve.split()) and "examples:" in solve


def test_couplings_lists_modes_what_they_free_and_objectives():
    text = run("couplings")
    assert "    paper (default): frees weight_mass (m_r), finger_diameter (d_n)\n" in text
    assert "threads" in text and "objectives: mass [kg]" in text
    data = json.loads(run("couplings", "--json"))["couplings"]
    lever = next(c for c in data if c["name"] == "lever")
    assert [m["name"] for m in lever["modes"]] == ["paper", "design"]
    assert "lever_length" in lever["modes"][1]["variables"]
    assert {r["key"] for r in lever["library"]} == {"material", "friction_pair"}
