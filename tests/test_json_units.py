"""Every number in every command's JSON sits beside its unit, and every unit is SI (issue 23, 4).

The rule, as :func:`clutchopt.output.with_units` writes it and :func:`units_of` reads it: a number's unit is

1. named by a ``units`` mapping of an object on its path: ``units[key]`` of the object that holds ``key`` mirrors
   the value there (a string: the unit of every number below; a mapping: units by name, or by column for a list
   of rows); the nearest mapping that names it wins; else
2. the ``unit`` of the object it sits in (directly, or in a list there): ``{"value": 3.0, "unit": "m"}``, a
   constraint's value and limit, a compare row's columns.

A count, an id, a ratio, a relative margin or error has the unit ``""`` (``"1"`` as well: pint's dimensionless).
Every unit must be one pint reads whose 1 is exactly 1 in SI base units: ``rad/s``, ``Pa``, ``N*m``, not ``rpm``,
``MPa`` or ``mm``. Every command with ``--json`` (found in the parser, so a new one fails until it is walked here)
is run on real cases and scenes and walked; then some numbers are compared with the case's own values in SI.
"""

import contextlib
import io
import json
import math
import re

import pytest

from clutchopt.cli import main
from clutchopt.cli.main import build_parser
from clutchopt.formulations import get_coupling
from clutchopt.units import ureg
from tests.conftest import CASES, COUPLING_CASES, ROOT

CASE_FILES = COUPLING_CASES
SCENES = sorted((CASES / "scenes").glob("*.toml"))
ALWAYS_JSON = {"runs show"}  # prints JSON without being asked


def run(*argv) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main([*map(str, argv)]) == 0
    return out.getvalue()


def units_of(node, spec=None, unit=None, path="$"):
    """(path, unit) for every number below ``node``, the unit None where the rule gives it none; ``spec`` is what
    the ``units`` mappings above say about ``node``, ``unit`` the ``unit`` of the object holding it."""
    if isinstance(node, bool) or node is None or isinstance(node, str):
        return
    if isinstance(node, (int, float)):
        yield path, spec if isinstance(spec, str) else unit
    elif isinstance(node, list):
        for i, item in enumerate(node):
            yield from units_of(item, spec, unit, f"{path}[{i}]")
    else:
        own = node.get("units") if isinstance(node.get("units"), dict) else {}
        here = node.get("unit") if isinstance(node.get("unit"), str) else None
        for key, value in node.items():
            if key == "units":
                continue
            named = own[key] if key in own else spec if isinstance(spec, str) else (spec or {}).get(key)
            yield from units_of(value, named, None if isinstance(value, dict) else here, f"{path}.{key}")


def unit_strings(node, path="$"):
    """(path, text) for every unit named: each ``unit`` and ``display_unit``, each leaf of a ``units`` mapping."""
    if isinstance(node, dict):
        for key, value in node.items():
            if key in ("unit", "display_unit") and isinstance(value, str):
                yield f"{path}.{key}", value
            elif key == "units":
                yield from _leaves(value, f"{path}.units")
            else:
                yield from unit_strings(value, f"{path}.{key}")
    elif isinstance(node, list):
        for i, item in enumerate(node):
            yield from unit_strings(item, f"{path}[{i}]")


def _leaves(spec, path):
    if isinstance(spec, dict):
        for key, value in spec.items():
            yield from _leaves(value, f"{path}.{key}")
    else:
        yield path, spec


def is_si(unit) -> bool:
    return isinstance(unit, str) and ureg.Quantity(1.0, unit or "dimensionless").to_base_units().magnitude == \
        pytest.approx(1.0, rel=1e-15)


def dimension(unit: str):
    return ureg.Quantity(1.0, unit or "dimensionless").dimensionality


def assert_units(data) -> dict[str, str]:
    """Every number of ``data`` has an SI unit by the rule; each display unit has its unit's dimension. The unit
    of each number by path."""
    units = dict(units_of(data))
    missing = [path for path, unit in units.items() if unit is None]
    assert not missing, f"numbers without a unit: {missing[:10]}"
    named = dict(unit_strings(data))
    for path, unit in named.items():
        if path.endswith(".display_unit"):
            assert dimension(unit) == dimension(named[path.removesuffix("display_unit") + "unit"]), path
        else:
            assert is_si(unit), f"{path}: {unit!r} is not a coherent SI unit"
    return units


# -- the walker fails where it should -----------------------------------------------------------------------------


@pytest.mark.parametrize("data", [
    {"speed": 94.2},  # a bare number
    {"objective": {"name": "mass", "value": 0.6}},  # a value without its unit
    {"design": {"d": 0.01}, "units": {"outputs": {"d": "m"}}},  # units of another key
    {"rows": [{"mass": 1.0, "cost": 2.0}], "units": {"rows": {"mass": "kg"}}},  # a column left out
    {"row": {"unit": "m", "inner": {"x": 1.0}}},  # a unit covers its own object, not the ones inside it
    {"units": {"points": ""}, "point": [1, 2]},  # a near-miss of a key
], ids=["bare", "value", "other-key", "column", "nested", "misspelt"])
def test_the_walker_finds_a_number_without_a_unit(data):
    with pytest.raises(AssertionError, match="without a unit"):
        assert_units(data)


@pytest.mark.parametrize("unit", ["rpm", "MPa", "mm", "kJ", "deg", "min"])
def test_the_walker_refuses_units_that_are_not_si(unit):
    with pytest.raises(AssertionError, match="not a coherent SI unit"):
        assert_units({"speed": {"value": 1.0, "unit": unit}})
    with pytest.raises(AssertionError, match="not a coherent SI unit"):
        assert_units({"speed": 1.0, "units": {"speed": unit}})


def test_the_walker_reads_units_as_the_outputs_write_them():
    data = {"constraints": [{"value": 3.0, "limit": 4.0, "margin": 0.25, "unit": "Pa"}],
            "bounds": {"d": [0.001, 0.1]}, "sensitivities": {"speed": -1.3}, "solver": {"time_s": 0.01, "solves": 1},
            "units": {"constraints": {"margin": ""}, "bounds": {"d": "m"}, "sensitivities": "",
                      "solver": {"time_s": "s", "solves": ""}}}
    assert assert_units(data) == {"$.constraints[0].value": "Pa", "$.constraints[0].limit": "Pa",
                                  "$.constraints[0].margin": "", "$.bounds.d[0]": "m", "$.bounds.d[1]": "m",
                                  "$.sensitivities.speed": "", "$.solver.time_s": "s", "$.solver.solves": ""}


# -- every command ------------------------------------------------------------------------------------------------


def json_commands(parser=None, prefix="") -> set[str]:
    """The commands (``runs list``) whose parser has ``--json``, and those that print JSON anyway."""
    parser = parser or build_parser()
    found = set(ALWAYS_JSON) if not prefix else set()
    if "--json" in parser._option_string_actions:
        found.add(prefix.strip())
    for action in parser._subparsers._group_actions if parser._subparsers else ():
        for name, sub in action.choices.items():
            found |= json_commands(sub, f"{prefix}{name} ")
    return found


@pytest.fixture(scope="module")
def store(tmp_path_factory):
    """A run store with a run of every kind: a solve with a start-up and its check, sweep points, Pareto points and
    the simulations of every scene."""
    path = tmp_path_factory.mktemp("store") / "runs.sqlite"
    run("solve", CASES / "wedge_paper.toml", "--verify", "--store", path)
    run("solve", CASES / "wedge_motor_start.toml", "--store", path)
    run("sweep", CASES / "wedge_paper.toml", "--vary", "speed=900:1100:2", "--quiet", "--store", path)
    run("pareto", CASES / "wedge_centrifuge.toml", "--mode", "geometry", "--points", "3", "--store", path)
    for scene in SCENES:
        run("simulate", scene, "--store", path)
    return path


def bench_report(monkeypatch) -> dict:
    """``bench --json`` on the last full run's report (a run takes minutes; tests/test_bench.py walks a quick one)."""
    report = json.loads((ROOT / "benchmarks" / "latest.json").read_text())
    report.pop("units")
    monkeypatch.setattr("clutchopt.bench.run_bench", lambda *args, **kwargs: report)
    return json.loads(run("bench", "--quick", "--json"))


def outputs(command: str, store, monkeypatch) -> list[dict]:
    """The JSON of ``command`` on small real cases."""
    wedge, library = CASES / "wedge_paper.toml", store.parent / "library.toml"
    run("init", "wedge", "-o", library, "--force")  # a case with [library] entries: values and a friction scatter
    if command == "runs show":
        ids = [r["id"] for r in json.loads(run("runs", "list", "--limit", "0", "--json", "--store", store))["runs"]]
        return [json.loads(run("runs", "show", i, "--store", store)) for i in ids]
    argv = {
        "solve": [("solve", wedge, "--verify"), ("solve", CASES / "wedge_motor_start.toml"),
                  ("solve", CASES / "ball_crusher.toml"),  # options.choose: every choice
                  ("solve", library),
                  *[("solve", CASES / "wedge_centrifuge.toml", "--robust", method, "--samples", "1000")
                    for method in ("chance=0.99", "worst-case")]],
        "compare": [("compare", wedge)],
        "choose-coupling": [("choose-coupling", CASES / "conveyor_drive.toml")],
        "sweep": [("sweep", wedge, "--vary", "speed=900:1100:2", "--quiet")],
        "pareto": [("pareto", CASES / "wedge_centrifuge.toml", "--mode", "geometry", "--points", "3")],
        "simulate": [("simulate", scene) for scene in SCENES],
        "runs list": [("runs", "list", "--store", store)],
        "materials": [("materials",)],
        "couplings": [("couplings",)],
    }
    if command == "bench":
        return [bench_report(monkeypatch)]
    no_store = ("--no-store",) if command in ("solve", "simulate", "pareto", "sweep") else ()
    return [json.loads(run(*args, "--json", *no_store)) for args in argv[command]]


JSON_COMMANDS = sorted(json_commands())


def test_every_command_with_json_is_walked():
    assert set(JSON_COMMANDS) == {"solve", "choose-coupling", "compare", "sweep", "pareto", "simulate", "runs list", "runs show",
                                  "materials", "couplings", "bench"}


@pytest.mark.parametrize("command", JSON_COMMANDS)
def test_every_number_has_an_si_unit(command, store, monkeypatch):
    results = outputs(command, store, monkeypatch)
    assert results
    for data in results:
        assert assert_units(data) or dict(unit_strings(data))  # numbers, or at least units (couplings: objectives)


def test_the_numbers_are_si(store):
    """Values against the cases' own: 900 rpm is 94.25 rad/s wherever a speed is written."""
    sweep = json.loads(run("sweep", CASES / "wedge_paper.toml", "--vary", "speed=900:1100:2", "--json", "--quiet",
                           "--no-store"))
    units = assert_units(sweep)
    assert sweep["points"][0]["values"]["speed"] == pytest.approx(900 * math.pi / 30)
    assert units["$.points[0].values.speed"] == "rad/s"
    assert units["$.points[0].design.finger_diameter"] == "m" and sweep["points"][0]["design"]["finger_diameter"] < 0.1
    assert units["$.points[0].solver.time_s"] == "s" and units["$.points[0].constraints[1].margin"] == ""

    runs = json.loads(run("runs", "list", "--limit", "0", "--json", "--store", store))["runs"]
    point = json.loads(run("runs", "show", next(r["id"] for r in runs if r["kind"] == "sweep" and r["point"] == 0),
                           "--store", store))
    units = assert_units(point)
    assert point["inputs"]["values"]["speed"] == pytest.approx(900 * math.pi / 30)
    assert units["$.inputs.values.speed"] == "rad/s" and units["$.inputs.values.allowable_pressure"] == "Pa"
    assert point["inputs"]["values"]["allowable_pressure"] == pytest.approx(4e6)

    transient = json.loads(run("simulate", CASES / "scenes" / "paper_transient.toml", "--json", "--no-store"))
    units = assert_units(transient)
    assert transient["headline"]["lock_up_speed"] == pytest.approx(1500 * math.pi / 30)  # the scene's 1500 rpm
    assert units["$.headline.lock_up_speed"] == "rad/s" and units["$.headline.friction_work"] == "J"
    assert units["$.events[0].time"] == "s" and units["$.analytic.start_time"] == "s"

    front = json.loads(run("pareto", CASES / "wedge_centrifuge.toml", "--mode", "geometry", "--points", "2", "--json",
                           "--no-store"))
    units = assert_units(front)
    assert units["$.rows[0].mass"] == "kg" and units["$.rows[0].design.flank_angle"] == "rad"
    assert front["rows"][0]["design"]["flank_angle"] < math.pi / 2  # radians, not degrees


def test_relative_margins_are_unitless_and_energies_in_joules():
    """review 28: choose-coupling's margins, relative, took their check's unit (the lining temperature's 0.66 in K,
    its life's 0.86 in s), and every energy declared in J or kJ was labelled N*m (compare's simulated friction work,
    in J in solve's JSON beside it)."""
    choice = json.loads(run("choose-coupling", CASES / "conveyor_drive.toml", "--json"))
    margins = {path: unit for path, unit in assert_units(choice).items() if path.endswith(".margin")}
    assert len(margins) >= 5 and set(margins.values()) == {""}
    comparison = json.loads(run("compare", CASES / "wedge_motor_start.toml", "--json"))
    assert_units(comparison)
    work = next(row for row in comparison["rows"] if row["quantity"] == "friction_work_simulated")
    assert (work["unit"], work["display_unit"]) == ("J", "kJ") and work["nlp_start_up"] > 1000.0  # J, not kJ
    count = next(row for row in comparison["rows"] if row["quantity"] == "weight_count")
    assert count["unit"] == ""  # a count: "", not a case's dimensionless "1" (compare's margins, probabilities too)


# -- solve and compare on every case: the JSON's numbers are the printed ones ---------------------------------------


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
        assert_units(data)
        printed = printed_constraints(run("solve", case_file, "--mode", mode, "--no-store"))
        for c in data["constraints"]:
            value, display = printed[c["name"]]
            assert display == c["display_unit"]
            converted = ureg.Quantity(value, display or "dimensionless").to(c["unit"] if c["unit"] != "1" else "")
            assert converted.magnitude == pytest.approx(c["value"], rel=1e-5, abs=1e-12), (mode, c["name"])
            checked += 1
    assert checked > 5  # constraints compared


@pytest.mark.parametrize("case_file", CASE_FILES, ids=lambda p: p.stem)
def test_compare_json_rows_are_si(case_file):
    data = json.loads(run("compare", case_file, "--json"))
    units = assert_units(data)
    for i, row in enumerate(data["rows"]):
        relative = [c for c in data["columns"] if c != data["baseline"]]
        assert list(row["relative"]) == relative  # against the baseline, beside no row's ``unit``
        assert {units[f"$.rows[{i}].relative.{c}"] for c in relative if row["relative"][c] is not None} <= {""}
        if row["display_unit"] == "mm":
            assert row["unit"] == "m"
            values = [row[c] for c in data["columns"] if row[c] is not None]
            assert all(v < 10 for v in values), row  # metres: no coupling here is 10 m across


@pytest.mark.parametrize("argv", [
    ("sweep", "wedge_centrifuge.toml", "--vary", "speed=1400", "--robust", "chance=0.99", "--samples", "100",
     "--quiet"),
    ("pareto", "wedge_centrifuge.toml", "--points", "2", "--robust", "worst-case", "--samples", "100"),
    ("solve", "wedge_centrifuge.toml", "--robust", "worst-case", "--samples", "100"),
], ids=lambda argv: " ".join(argv[:1] + argv[2:]))
def test_the_aspects_carry_their_units(argv):
    """A robust design's result in sweep, pareto and solve (docs/composition.md) has the unit of every number."""
    command, case, *rest = argv
    assert_units(json.loads(run(command, CASES / case, *rest, "--json", "--no-store")))
