"""Every ``unit`` in every JSON output is the unit of the value beside it (issue "An engineer's first hour", 3).

The JSON of every command that has ``--json`` is walked on every case file, mode and scene: each ``unit`` must
be a coherent SI unit (pint converts 1 of it to 1 base unit) and ``display_unit`` beside it of the same dimension.
Then the numbers themselves: the constraint values printed in the text table (display units) are converted by
pint into the JSON's unit and must equal the JSON value, so a label that contradicts its value cannot pass.
"""

import contextlib
import io
import json
import re

import pytest

from clutchopt.cli import main
from clutchopt.formulations import get_coupling
from clutchopt.units import ureg
from tests.conftest import CASES

CASE_FILES = sorted(CASES.glob("*.toml"))
SCENES = sorted((CASES / "scenes").glob("*.toml"))


def run(*argv) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main([*map(str, argv)]) == 0
    return out.getvalue()


def unit_pairs(node, path="$"):
    """(path, dict) for every JSON object that carries a ``unit``."""
    if isinstance(node, dict):
        if "unit" in node:
            yield path, node
        for key, value in node.items():
            yield from unit_pairs(value, f"{path}.{key}")
    elif isinstance(node, list):
        for i, value in enumerate(node):
            yield from unit_pairs(value, f"{path}[{i}]")


def assert_si_units(data) -> int:
    count = 0
    for path, node in unit_pairs(data):
        unit = node["unit"]
        one = ureg.Quantity(1.0, unit)
        assert one.to_base_units().magnitude == pytest.approx(1.0, rel=1e-15), f"{path}: {unit!r} is not SI"
        if "display_unit" in node:
            assert one.dimensionality == ureg.Quantity(1.0, node["display_unit"]).dimensionality, path
        count += 1
    for group in ("design", "outputs"):
        for name, unit in data.get("units", {}).get(group, {}).items():
            assert ureg.Quantity(1.0, unit).to_base_units().magnitude == pytest.approx(1.0), f"{group}.{name}: {unit}"
            count += 1
    return count


def modes(case_file):
    coupling = re.search(r'^coupling\s*=\s*"(\w+)"', case_file.read_text(), re.M).group(1)
    return list(get_coupling(coupling).formulations)


def printed_constraints(text: str) -> dict[str, tuple[float, str]]:
    """Constraint name -> (value, display unit) from the text table of ``solve``."""
    table = text.split("Constraints (re-evaluated")[1].split("\n\n")[0].splitlines()[2:]
    rows = {}
    for line in table:
        tokens = line.split()
        sense = next(i for i, t in enumerate(tokens) if t in ("<=", ">="))
        unit = tokens[sense + 2]
        rows[tokens[0]] = (float(tokens[sense - 1]), "" if re.match(r"^[+-]\d", unit) else unit)
    return rows


@pytest.mark.parametrize("case_file", CASE_FILES, ids=lambda p: p.stem)
def test_solve_json_units_agree_with_the_printed_values(case_file):
    checked = 0
    for mode in modes(case_file):
        data = json.loads(run("solve", case_file, "--mode", mode, "--json", "--no-store"))
        checked += assert_si_units(data)
        printed = printed_constraints(run("solve", case_file, "--mode", mode, "--no-store"))
        for c in data["constraints"]:
            value, display = printed[c["name"]]
            assert display == c["display_unit"]
            converted = ureg.Quantity(value, display or "dimensionless").to(c["unit"] if c["unit"] != "1" else "")
            assert converted.magnitude == pytest.approx(c["value"], rel=1e-5, abs=1e-12), (mode, c["name"])
            checked += 1
    assert checked > 10


@pytest.mark.parametrize("case_file", CASE_FILES, ids=lambda p: p.stem)
def test_compare_json_rows_are_si(case_file):
    data = json.loads(run("compare", case_file, "--json"))
    assert assert_si_units(data) == len(data["rows"]) > 0
    for row in data["rows"]:
        if row["display_unit"] == "mm":
            assert row["unit"] == "m"
            values = [row[c] for c in data["columns"] if row[c] is not None]
            assert all(v < 10 for v in values), row  # metres: no coupling here is 10 m across


@pytest.mark.parametrize("scene", SCENES, ids=lambda p: p.stem)
def test_simulate_json_units(scene):
    assert_si_units(json.loads(run("simulate", scene, "--json", "--no-store")))


def test_sweep_pareto_and_runs_json_units(tmp_path):
    store = tmp_path / "runs.sqlite"
    sweep = json.loads(run("sweep", CASES / "wedge_paper.toml", "--vary", "speed=900,1000", "--json", "--quiet",
                           "--store", store))
    assert assert_si_units(sweep) >= 2 * 4
    pressure = next(c for c in sweep["points"][1]["constraints"] if c["name"] == "flank_pressure")
    assert pressure["unit"] == "Pa" and pressure["value"] == pytest.approx(346974.26, rel=1e-6)
    assert_si_units(json.loads(run("pareto", CASES / "wedge_centrifuge.toml", "--mode", "geometry", "--points", "3",
                                   "--json", "--store", store)))
    listed = json.loads(run("runs", "list", "--json", "--store", store))
    assert_si_units(listed)
    shown = json.loads(run("runs", "show", str(listed["runs"][0]["id"]), "--store", store))
    assert_si_units(shown)


def test_robust_json_units():
    data = json.loads(run("solve", CASES / "wedge_centrifuge.toml", "--robust", "chance=0.99", "--json", "--no-store",
                          "--samples", "1000"))
    assert assert_si_units(data) >= 2 * 3  # the robust and the nominal design's constraint checks
    pressure = next(c for c in data["robust"]["checks"] if c["name"] == "flank_pressure")
    assert pressure["unit"] == "Pa" and pressure["value"] > 1e4
