"""Review 30 (every command with every aspect of a case, hostile): what a sweep's point records and shows."""

import json

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
    shown = json.loads(run_cli("runs", "show", "2", "--store", store).stdout)
    assert shown["point"] == 1 and shown["status"] == "infeasible" and shown["objective"] is None
    assert shown["outputs"]["objective"]["value"] is None and shown["outputs"]["design"] is None
