"""Review 30 (every command with every aspect of a case, hostile): what a sweep's point records and shows."""

import json

import pytest

from conftest import CASES, run_cli


def test_a_sweep_point_without_a_design_shows_none_in_its_json_and_its_stored_run(tmp_path):
    """ball_crusher over 500, 800 and 300 kW: 800 kW is proven infeasible over a region carried from 500 kW, and its
    JSON and `runs show` gave 500 kW's optimum (950.755 kg, 23 rows), where `solve` of 800 kW alone shows its own
    last point and the table and `runs export` blank them: now none."""
    store = str(tmp_path / "runs.sqlite")
    swept = run_cli("sweep", str(CASES / "ball_crusher.toml"), "--vary", "power=500,800,300", "--store", store,
                    "--json", "--quiet")
    assert swept.returncode == 0, swept.stderr
    points = json.loads(swept.stdout)["points"]
    assert [p["status"] for p in points] == ["optimal", "infeasible", "optimal"]
    assert points[1]["objective"]["value"] is None and points[1]["design"] is None and points[1]["outputs"] is None
    assert points[0]["objective"]["value"] > 900 and points[1]["diagnosis"].startswith("proven infeasible")
    listed = json.loads(run_cli("runs", "list", "--json", "--store", store).stdout)["runs"]  # (review 31: it had)
    assert {run["point"]: run["objective"] for run in listed}[1] is None
    shown = json.loads(run_cli("runs", "show", "2", "--store", store).stdout)
    assert shown["point"] == 1 and shown["status"] == "infeasible" and shown["objective"] is None
    assert shown["outputs"]["objective"]["value"] is None and shown["outputs"]["design"] is None


def test_a_stored_sweep_point_keeps_the_defaults_that_follow_what_it_varies(tmp_path):
    """wedge_motor_start over the duty's inertia: the start-up's driven inertia follows it and each point was designed
    for it, but the store kept the case's 0.5 kg m^2 for both points (runs show, runs export)."""
    store = str(tmp_path / "runs.sqlite")
    swept = run_cli("sweep", str(CASES / "wedge_motor_start.toml"), "--vary", "inertia=0.4,0.6", "--store", store,
                    "--quiet")
    assert swept.returncode == 0, swept.stderr
    for run_id, inertia in (("1", 0.4), ("2", 0.6)):
        values = json.loads(run_cli("runs", "show", run_id, "--store", store).stdout)["inputs"]["values"]
        assert values["inertia"] == values["driven_inertia"] == inertia


def test_a_system_chance_design_whose_scatter_moves_only_start_up_limits():
    """The lever's start-up case with its friction coefficient scattered: the scatter moves no closed-form
    constraint, only start-up limits, which take their shares of 1 - P first; the allocation over none had a budget
    of 0 and its row divided by zero (internal error). Now no allocation: the start-up limits hold the system."""
    from composition import case_data

    from clutchopt.cases import parse_case
    from clutchopt.optimise.robust import SYSTEM_CHANCE, solve_robust

    case = parse_case(case_data("lever", ("start_up", "scatter")))
    result = solve_robust(case, SYSTEM_CHANCE, 0.999, samples=200, starts=10)
    assert result.status == "optimal" and result.allocation is None
    assert result.design_failure().probability <= 1e-3 and result.start_up_failure  # its start-up limits sampled


def test_a_robust_sweep_s_table_names_its_method():
    """The printed table of `sweep --robust chance=0.999` read as a nominal sweep's (its CSV and JSON said)."""
    swept = run_cli("sweep", str(CASES / "wedge_centrifuge.toml"), "--vary", "speed=1400,1500", "--robust",
                    "chance=0.999", "--samples", "200", "--no-store", "--quiet")
    assert swept.returncode == 0, swept.stderr
    assert "(paper mode, objective mass, chance 0.999 designs): 2 points" in swept.stdout


def test_a_stored_sweep_point_keeps_what_its_choice_fills_from_the_library(tmp_path):
    """options.choose: each point keeps its best choice (42CrMo4), but its stored inputs had the first choice's
    (C45) allowable link stress beside the 42CrMo4 design."""
    from composition import case_data

    from clutchopt.cases import parse_case
    from clutchopt.formulations import get_coupling
    from clutchopt.materials import variants
    from clutchopt.optimise.sweep import Sweep, parse_vary
    from clutchopt.store import RunStore

    case = parse_case(case_data("lever", ("choose",)))
    found = variants(case, get_coupling(case.coupling))
    filled = {choice["material"]: variant.values["allowable_link_stress"] for choice, variant in found}
    sweep = Sweep(case, [parse_vary("resisting_torque=16,24", case.coupling)], mode="design")
    with RunStore(str(tmp_path / "runs.sqlite")) as store:
        result = sweep.run(store, progress=False)
        stored = [store.run(k) for k in (1, 2)]
    entries = [solution["choice"]["material"] for solution in result.solutions]
    assert entries != [found[0][0]["material"]] * 2  # (a point kept another choice than the first)
    from clutchopt.cli.runs import export_row

    for entry, run in zip(entries, stored):
        assert run["outputs"]["choice"] == {"material": entry}
        assert run["inputs"]["values"]["allowable_link_stress"] == filled[entry]
        assert export_row(run)["choice"] == f"material = {entry}"  # (the export had no choice column)


def test_a_stored_sweep_point_keeps_what_follows_from_its_choice(tmp_path):
    """review 31: lever_motor_start choosing its friction pair: a point kept cermet_dry (friction coefficient 0.4,
    friction_max 0.55) but stored organic_dry's friction_max 0.45 beside it (derived from the pair, not filled)."""
    import tomllib

    from clutchopt.cases import parse_case
    from clutchopt.optimise.sweep import Sweep, parse_vary
    from clutchopt.store import RunStore

    data = tomllib.loads((CASES / "lever_motor_start.toml").read_text(encoding="utf-8"))
    data["start_up"].update(intervals=8, tolerance=1e-4)
    for key in ("friction_coefficient", "allowable_pressure"):
        data["material"].pop(key)
    data["library"].pop("friction_pair")
    data["options"]["choose"] = {"friction_pair": ["organic_dry", "cermet_dry"]}
    case = parse_case(data)
    with RunStore(str(tmp_path / "runs.sqlite")) as store:
        Sweep(case, [parse_vary("resisting_torque=40", case.coupling)]).run(store, progress=False)
        run = store.run(1)
    assert run["outputs"]["choice"] == {"friction_pair": "cermet_dry"}
    assert {q: run["inputs"]["values"][q] for q in ("friction_coefficient", "friction_max")} == {
        "friction_coefficient": 0.4, "friction_max": 0.55}


def test_runs_export_says_how_a_design_was_made(tmp_path):
    """review 30: an exported robust start-up design could not be told from a nominal one but by its method."""
    store = str(tmp_path / "runs.sqlite")
    solved = run_cli("solve", str(CASES / "wedge_motor_start_scatter.toml"), "--robust", "worst-case", "--samples",
                     "200", "--store", store)
    assert solved.returncode == 0, solved.stderr
    exported = tmp_path / "runs.csv"
    assert run_cli("runs", "export", "--store", store, "-o", str(exported)).returncode == 0
    row = _csv(exported)
    assert float(row["start_up.start_time_simulated [s]"]) == pytest.approx(10.0, rel=1e-6)
    assert row["robust verification"].startswith("verified: constraints at all 2 corners of the ranges")


def _csv(path) -> dict:
    """The first row of a table ``runs export`` wrote."""
    import csv

    return next(csv.DictReader(line for line in path.read_text().splitlines() if not line.startswith("#")))


def test_a_robust_front_says_where_its_cost_cap_holds():
    """pareto --robust worst-case of a case whose density scatters: the cap held at the density's high end (cost
    41.26 EUR there) while the table showed the nominal cost (41.21), unsaid."""
    import tomllib

    from clutchopt.cases import parse_case
    from clutchopt.optimise.design import Robustness
    from clutchopt.optimise.pareto import pareto_fronts

    data = tomllib.loads((CASES / "wedge_centrifuge.toml").read_text(encoding="utf-8"))
    data["scatter"] = {"density": ["7700 kg/m^3", "8000 kg/m^3"]}
    front = pareto_fronts(parse_case(data), "geometry", 3, robust=Robustness("worst-case", samples=200))[0]
    assert front.caveat.startswith("the cost cap holds where the scatter (density) makes the cost highest")
    cap, cost = front.frame.iloc[1][["cost_cap [EUR]", "cost [EUR]"]]
    assert cost < cap * (1 - 1e-4)  # the nominal cost below the cap the corner's meets
