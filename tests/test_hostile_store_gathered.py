"""Hostile tests of the run store's gathered rows (``window_records.gathered``): points solved alone that share a
template, kept as one row of arrays. Each test is a finding of an attack (the command in its comment): a failing
test first, then its mend. Fast: the records are made by hand (a two-variable lever point without a design), no
solve."""

import copy
import sqlite3
from contextlib import closing

import numpy as np

from clutchopt.cli import main
from clutchopt.output import to_json
from clutchopt.store import RunStore

POINTS = 5


def _point(k: int) -> dict:
    """A point without a design as a region proof leaves it (``Solution.as_dict()``'s keys in its order): two design
    variables, two constraints, solver ``interval`` with 0 iterations; its numbers differ from point to point."""
    return {
        "coupling": "lever", "mode": "paper", "status": "infeasible",
        "objective": {"name": "mass", "value": 1.9 + k / 8, "unit": "kg"},
        "design": {"weight_mass": 0.0967 + k / 1024, "link_diameter": 0.0054},
        "outputs": {"torque": 107.9 + k},
        "units": {"design": {"weight_mass": "kg", "link_diameter": "m"}, "outputs": {"torque": "N*m"}},
        "constraints": [
            {"name": name, "equation": "m z (statics)", "sense": sense, "value": value + k, "limit": 267.4,
             "margin": -0.5 - k / 16, "active": True, "feasible": False, "unit": "N*m", "description": name,
             "scale": 267.4, "multiplier": None, "elasticity": None, "tolerance": 1e-08, "display_unit": "N*m"}
            for name, sense, value in (("torque", ">=", 107.9), ("weights_fit", "<=", 0.25))],
        "solver": {"name": "interval", "status": "proven", "iterations": 0, "time_s": 0.5 + k / 4, "solves": 0},
        "diagnosis": "proven infeasible for inertia 44.8-54.0 kg*m^2 (5 points, one proof)",
        "integer_search": [], "bounds": {"weight_mass": [0.0001, 100.0], "link_diameter": [0.0005, 0.1]},
        "sensitivities": {},
    }


def _recorded(path, records: list[dict]) -> int:
    """``records`` recorded as the points 0.. of a new sweep over inertia; how many were recorded."""
    with RunStore(path) as store:
        sweep_id = store.new_sweep({"case": "hostile", "points": len(records)}, len(records))
        return store.record_points({"values": {"speed": 151.8}, "free": [], "bounds": {}, "method": "nominal"},
                                   {"sweep_id": sweep_id}, np.arange(len(records)),
                                   {"inertia": np.linspace(12.0, 120.0, len(records))}, dict(enumerate(records)), [])


def _gathered_rows(path) -> list[tuple[int, int]]:
    with closing(sqlite3.connect(path)) as db:
        return db.execute("SELECT point, run_count FROM runs WHERE window IS NOT NULL ORDER BY point").fetchall()


def _shown(path, run_id: int, capsys) -> tuple[int, str, str]:
    code = main(["runs", "show", str(run_id), "--store", str(path)])
    out, err = capsys.readouterr()
    return code, out, err


def test_a_whole_number_beyond_64_bits_keeps_its_point_a_row(tmp_path):
    # attack: record_points with a point whose solver.solves is 2**64 (explore.py "bigint"): the WHOLE array (int64)
    # cannot hold it; WindowRecords.of raised OverflowError and the sweep's recording crashed with a traceback. The
    # run of points is kept as rows (JSON keeps the number: from_json reads it back as orjson does, a float beyond
    # 64 bits), the others as they were
    records = [_point(k) for k in range(POINTS)]
    records[1]["solver"]["solves"] = 2**64
    path = tmp_path / "runs.sqlite"
    assert _recorded(path, records) == POINTS
    assert _gathered_rows(path) == []
    with RunStore(path, writable=False) as store:
        back = {run["point"]: run["outputs"] for run in store.readable_runs()[0]}
    assert [to_json(back[k], None) for k in (0, 2, 3, 4)] == [to_json(records[k], None) for k in (0, 2, 3, 4)]
    assert back[1]["solver"]["solves"] == 2.0**64
