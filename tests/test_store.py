"""The run store: solves recorded with inputs, outputs and versions; WAL; list/show/export; kill -9 and resume."""

import json
import math
import os
import signal
import sqlite3
import subprocess
import sys
import time
from contextlib import closing
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.store import RunStore
from conftest import CASES, ROOT
from store_rows import forget_points, sweep_points as _stored


def test_solve_is_recorded_with_inputs_outputs_and_versions(cli, run_store):
    solved = cli("solve", str(CASES / "wedge_paper.toml"), "--json")
    assert solved.returncode == 0, solved.stderr
    listed = cli("runs", "list")
    assert listed.returncode == 0 and str(run_store) in listed.stdout
    with RunStore(run_store) as store:
        (run,) = store.runs()
        entry = store.run(run["id"])
    assert entry["kind"] == "solve" and entry["status"] == "optimal"
    assert entry["objective"] == pytest.approx(0.667951, rel=1e-6)  # the worked example, paper mode
    assert entry["inputs"]["values"]["inertia"] == 0.5
    assert entry["outputs"]["design"] == json.loads(solved.stdout)["design"]
    assert set(entry["versions"]) >= {"clutchopt", "casadi", "python"}
    shown = cli("runs", "show", str(run["id"]))
    assert json.loads(shown.stdout)["outputs"]["objective"]["value"] == pytest.approx(0.667951, rel=1e-6)
    with sqlite3.connect(run_store) as db:
        assert db.execute("PRAGMA journal_mode").fetchone()[0] == "wal"


def test_no_store_and_store_path(cli, run_store, tmp_path):
    assert cli("solve", str(CASES / "wedge_paper.toml"), "--no-store").returncode == 0
    assert not run_store.exists()
    other = tmp_path / "other.sqlite"
    assert cli("solve", str(CASES / "wedge_fan.toml"), "--store", str(other)).returncode == 0
    with RunStore(other) as store:
        assert [run["case_path"] for run in store.runs()] == [str(CASES / "wedge_fan.toml")]


def test_export_and_bad_store(cli, tmp_path):
    assert cli("solve", str(CASES / "wedge_paper.toml")).returncode == 0
    out = tmp_path / "runs.csv"
    exported = cli("runs", "export", "-o", str(out))
    assert exported.returncode == 0 and "1 runs written" in exported.stdout
    table = pd.read_csv(out)
    assert table["status"].tolist() == ["optimal"] and table["input.inertia [kg*m^2]"].tolist() == [0.5]
    assert table["design.finger_diameter [m]"].iloc[0] == pytest.approx(5.46156e-3, rel=1e-5)  # the worked example
    assert table["mass [kg]"].iloc[0] == pytest.approx(0.667951, rel=1e-6) and table["id"].dtype.kind == "i"
    assert table["active"].iloc[0] == "torque finger_bending"
    not_a_db = tmp_path / "notes.txt"
    not_a_db.write_text("not a database, just text " * 100)
    result = cli("runs", "list", "--store", str(not_a_db))
    assert result.returncode == 2 and "is not an SQLite database" in result.stderr and result.stderr.count("\n") == 1
    missing = cli("runs", "show", "99")
    assert missing.returncode == 2 and "no run 99" in missing.stderr


def test_a_sweep_point_cannot_be_recorded_twice(tmp_path):
    """A second record of a stored point (another resume of the same sweep solved it too) keeps the first."""
    def solution(mass: float) -> dict:  # the least a solution has
        return {"status": "optimal", "objective": {"value": mass}, "design": {}, "constraints": [],
                "solver": {"iterations": 1, "time_s": 0.0}, "diagnosis": None}

    with RunStore(tmp_path / "s.sqlite") as store:
        sweep = store.new_sweep({"points": [{"speed": 100.0}]}, 1)
        inputs = {"values": {"speed": 100.0}}
        assert store.record("sweep", inputs, solution(1.0), sweep_id=sweep, point=0) == 1
        assert store.record("sweep", inputs, solution(2.0), sweep_id=sweep, point=0) is None
        assert store.sweep_outputs(sweep, [{"speed": 100.0}]) == {0: solution(1.0)} and store.failure is None


SWEEP = ["sweep", str(CASES / "wedge_paper.toml"), "--vary", "speed=500:3000:40", "--vary",
         "allowable_pressure=2:8:125", "--quiet"]  # 5000 points: 5 windows, each recorded in one transaction


def test_killed_sweep_resumes_without_losing_duplicating_or_recomputing(run_store, tmp_path, cli):
    process = subprocess.Popen([sys.executable, "-m", "clutchopt", *SWEEP], cwd=ROOT, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline:
        time.sleep(0.02)
        try:
            if len(_stored(run_store)) >= 150:
                break
        except sqlite3.OperationalError:  # the table is not there yet
            continue
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    before = _stored(run_store)
    assert 150 <= len(before) < 5000, "the sweep was not killed half-way"
    out = tmp_path / "resumed.csv"
    resumed = cli(*SWEEP, "--resume", "--out", str(out))
    assert resumed.returncode == 0, resumed.stderr
    assert f"solved {5000 - len(before)} points" in resumed.stdout
    assert f"{len(before)} taken from the store" in resumed.stdout
    after = _stored(run_store)
    assert after[:len(before)] == before  # finished points untouched, not solved again
    assert sorted(point for _, point, _ in after) == list(range(5000))  # none lost, none twice
    frame = pd.read_csv(out, skiprows=1)  # below the sweep's identification
    failed = frame[frame["status"] != "optimal"]  # proven infeasible where the flank pressure caps m_r below the mass
    # whose real weight is wide enough for its finger (fast and low [p]; the README's sweep, docs/errata.md)
    assert len(frame) == 5000 and 0 < len(failed) < 50 and (failed["status"] == "infeasible").all()
    assert (failed["speed [rpm]"] > 2800).all() and (failed["allowable_pressure [MPa]"] < 2.5).all()
    with RunStore(run_store) as store:
        assert len(store.sweeps()) == 1


def test_interrupted_sweep_says_how_to_continue(run_store):
    process = subprocess.Popen([sys.executable, "-m", "clutchopt", *SWEEP], cwd=ROOT, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True,  # Ctrl-C reaches it even if this shell ignores it
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and not (run_store.exists() and _has_points(run_store)):
        time.sleep(0.02)
    process.send_signal(signal.SIGINT)
    _, stderr = process.communicate(timeout=60)
    assert process.returncode == 130  # as a shell reports SIGINT
    assert stderr.strip().endswith(f"sweep interrupted; the points solved so far are in {run_store}, "
                                   "continue with --resume")
    with RunStore(run_store, writable=False) as store:
        statuses = {run["status"] for run in store.runs()}
    assert statuses == {"optimal"}  # the point in flight is not recorded as a failure


def _has_points(path) -> bool:
    try:
        return len(_stored(path)) > 0
    except sqlite3.OperationalError:
        return False


def test_simulations_are_recorded(cli, run_store):
    assert cli("simulate", str(CASES / "scenes" / "wedge_ideal.toml")).returncode == 0
    assert cli("solve", str(CASES / "wedge_paper.toml"), "--verify").returncode == 0
    with RunStore(run_store) as store:
        verify, solve, scene = (store.run(run["id"]) for run in store.runs())
    assert (verify["kind"], solve["kind"], scene["kind"]) == ("simulation", "solve", "simulation")
    assert scene["status"] == "locks up" and scene["inputs"]["scene"]["title"].startswith("Wedge coupling")
    assert scene["objective"] == pytest.approx(10.0, rel=1e-6)  # reaches speed in t_p = 10 s
    assert verify["status"] == "verified" and verify["objective"] == pytest.approx(10.0, rel=1e-6)


def test_runs_are_listed_and_exported_for_a_person(tmp_path, capsys):
    """Whole-number ids, the objective with its unit, the mode as asked (a Pareto point's cost cap named), no
    objective or design for an infeasible point (its diagnosis kept), export columns with their SI units."""
    from clutchopt.cli import main

    store = str(tmp_path / "runs.sqlite")
    assert main(["solve", str(CASES / "wedge_paper.toml"), "--store", store]) == 0
    assert main(["sweep", str(CASES / "wedge_paper.toml"), "--mode", "geometry", "--vary", "speed=800,1000",
                 "--vary", "outer_diameter_max=100", "--quiet", "--store", store]) == 0  # both infeasible
    assert main(["pareto", str(CASES / "wedge_centrifuge.toml"), "--mode", "geometry", "--points", "3",
                 "--store", store]) == 0
    capsys.readouterr()
    assert main(["runs", "list", "--store", store]) == 0
    lines = capsys.readouterr().out.splitlines()
    rows = {int(line.split()[0]): line for line in lines[2:8]}  # ids are whole numbers
    assert sorted(rows) == [1, 2, 3, 4, 5, 6]
    assert rows[1].split()[1:4] == ["solve", "-", "-"] and "mass 0.667951 kg" in rows[1]  # the worked example
    assert rows[2].split()[1:4] == ["sweep", "1", "0"] and rows[2].split()[8:11] == ["nominal", "not_found", "-"]
    assert "geometry (cost cap)" in rows[5] and "mass 0.689202 kg" in rows[5]  # README's front, cap 39.3164 EUR
    assert "geometry (cost cap)" not in rows[6] and "cost 39.1863 EUR" in rows[6]  # the cost end
    out = tmp_path / "runs.csv"
    assert main(["runs", "export", "-o", str(out), "--store", store]) == 0
    table = pd.read_csv(out)
    assert table["id"].tolist() == [1, 2, 3, 4, 5, 6] and table["sweep"].dtype.kind in "if"
    assert (table["method"] == "nominal").all() and table["scatter"].isna().all()
    assert table.loc[0, "input.speed [rad/s]"] == pytest.approx(1000 * 2 * 3.141592653589793 / 60, rel=1e-12)
    assert table.loc[0, "design.finger_diameter [m]"] == pytest.approx(5.46156e-3, rel=1e-5)
    infeasible = table[table["status"] == "not_found"]
    assert len(infeasible) == 2 and infeasible["design.finger_diameter [m]"].isna().all()
    assert infeasible["mass [kg]"].isna().all()
    assert infeasible["diagnosis"].str.startswith("no feasible design found (not proven infeasible)").all()
    assert table.loc[5, "cost [EUR]"] == pytest.approx(39.1863, rel=1e-5) and pd.isna(table.loc[5, "mass [kg]"])


def test_the_stores_json_reads_back_as_the_standard_librarys():
    # the run store's compact JSON (orjson) and the indented JSON of --json (the standard library) hold the same
    # values: NaN and infinities as null, NumPy scalars as plain numbers, tuples as lists, integer keys as text;
    # what orjson refuses (an integer beyond 64 bits, nesting deeper than 254) goes through the standard library
    import numpy as np

    from clutchopt.output import to_json

    data = {"a": [1e-05, 1e16, math.nan, -math.inf, np.float64(0.1), np.int64(3), np.bool_(True), (1, 2)], 7: "x",
            "big": 10 ** 30, "nested": {"deep": [0.1, None]}}
    assert json.loads(to_json(data, None)) == json.loads(to_json(data))
    assert json.loads(to_json(data, None)) == {"a": [1e-05, 1e16, None, None, 0.1, 3, True, [1, 2]], "7": "x",
                                               "big": 10 ** 30, "nested": {"deep": [0.1, None]}}
    deep = [0.5]
    for _ in range(300):
        deep = [deep]
    assert json.loads(to_json({"deep": deep}, None)) == {"deep": deep}


def test_a_windows_batched_points_are_one_row_read_back_in_full(tmp_path):
    # a window's batched points are one row: their numbers as arrays beside the template they share
    # (clutchopt.window_records), a fifth of their full records' bytes or less; each is read back as its full record,
    # a run of its own (listed, shown, taken by a resumed sweep)
    from clutchopt.cases import load_case
    from clutchopt.optimise.batch import BATCHED
    from clutchopt.optimise.sweep import Sweep
    from clutchopt.optimise.sweep_grid import parse_vary
    from clutchopt.output import to_json

    case = load_case(CASES / "cable_conveyor.toml")
    sweep = Sweep(case, [parse_vary("torque=220:880:40", "cable")])
    with RunStore(tmp_path / "runs.sqlite") as store:
        result = sweep.run(store, progress=False)
        stored = store.sweep_outputs(result.sweep_id, sweep.points)
        listed = store.runs(sweep_id=result.sweep_id)
        shown = [store.run(run["id"]) for run in listed]
    full = json.loads(to_json(list(result.solutions), None))
    assert [stored[i] for i in range(40)] == full
    assert {entry["point"]: entry["outputs"] for entry in shown} == dict(enumerate(full))
    assert [(run["id"], run["point"], run["status"]) for run in listed] == [(40 - i, 39 - i, "optimal") for i in
                                                                            range(40)]
    with sqlite3.connect(tmp_path / "runs.sqlite") as db:
        rows = db.execute("SELECT point, run_count, length(outputs) + IFNULL(length(window), 0), outputs FROM runs"
                          ).fetchall()
        (templates,) = db.execute("SELECT COUNT(*) FROM templates").fetchone()
    batched = [i for i, record in enumerate(full) if record["solver"]["status"] == BATCHED]
    windows = [(point, count, size) for point, count, size, _ in rows if count is not None]
    assert len(batched) >= 30 and templates == 1 and len(windows) == 1
    (point, count, size), = windows
    assert list(range(point, point + count)) == batched
    assert size < sum(len(to_json(full[i], None)) for i in batched) / 5
    for point, count, _, outputs in rows:  # solved alone by Problem.solve: a row each, in full
        assert count is not None or json.loads(outputs) == full[point]


def test_a_window_records_only_its_points_not_stored_yet(tmp_path):
    # two resumes of one sweep at once solve the same points: a window that meets points another process has stored
    # records the others only (a row for each run of consecutive ones), each point once, with its own record
    from clutchopt.cases import load_case
    from clutchopt.optimise.sweep import Sweep, solve_points
    from clutchopt.optimise.sweep_grid import parse_vary
    from clutchopt.output import to_json

    sweep = Sweep(load_case(CASES / "wedge_paper.toml"), [parse_vary("speed=500:3000:40", "wedge")])
    parts = list(solve_points(sweep.case, sweep.formulation.mode, sweep.objective.name, sweep.tol, None, sweep.grid))
    path = tmp_path / "runs.sqlite"

    def record(store: RunStore, sweep_id: int) -> int:
        return sum(store.record_points(sweep._inputs(), sweep._where(sweep_id), part.points.index, part.points.columns,
                                       *part.stored()) for part in parts)

    with RunStore(path) as store:
        sweep_id = store.new_sweep(sweep.spec, 40)
        assert record(store, sweep_id) == 40 and record(store, sweep_id) == 0
    forgotten = [point for point in range(40) if point % 7 in (2, 3) or point > 30]
    forget_points(path, lambda point: point in forgotten)
    with RunStore(path) as store:
        assert record(store, sweep_id) == len(forgotten) and record(store, sweep_id) == 0
        stored = store.sweep_outputs(sweep_id, sweep.points)
    assert sorted(point for _, point, _ in _stored(path)) == list(range(40))
    full = [record for part in parts for record in part.records()]
    assert stored == dict(enumerate(json.loads(to_json(full, None))))


def test_a_store_of_a_row_per_point_is_read_and_resumed(tmp_path, capsys):
    # a store an older clutchopt recorded (a row per point, batched ones compact: tests/older_store.sql) is listed,
    # shown, exported and resumed; a resume after points were lost adds them as a window row beside the older rows,
    # with the ids after the last, and every point is read once
    from clutchopt.cli import main

    store = tmp_path / "older.sqlite"
    with closing(sqlite3.connect(store)) as db:
        db.executescript((Path(__file__).parent / "older_store.sql").read_text())
        db.execute("PRAGMA journal_mode=WAL")
    capsys.readouterr()
    assert main(["runs", "export", "-o", str(tmp_path / "older.csv"), "--store", str(store)]) == 0
    assert main(["runs", "show", "5", "--store", str(store)]) == 0
    shown = json.loads(capsys.readouterr().out.split("\n", 1)[1])
    assert shown["point"] == 3 and shown["outputs"]["solver"]["status"] == "batched, KKT verified"
    sweep = ["sweep", str(CASES / "wedge_paper.toml"), "--vary", "speed=500:3000:12", "--quiet", "--store", str(store),
             "--resume"]
    assert main(sweep) == 0 and "solved 0 points in" in capsys.readouterr().out
    with closing(sqlite3.connect(store)) as db, db:
        db.execute("DELETE FROM runs WHERE point >= 5")  # as a sweep killed half-way
    assert main(sweep) == 0 and "solved 7 points" in capsys.readouterr().out
    assert [(run_id, point) for run_id, point, _ in _stored(store)] == [(k + 2, k) for k in range(12)]
    with RunStore(store, writable=False) as opened:
        assert [(run["id"], run["point"]) for run in opened.runs()] == [(k + 2, k) for k in range(11, -1, -1)] + [
            (1, None)] and opened.sweeps()[0]["stored"] == 12
    assert main(["runs", "export", "-o", str(tmp_path / "resumed.csv"), "--store", str(store)]) == 0
    older, resumed = pd.read_csv(tmp_path / "older.csv"), pd.read_csv(tmp_path / "resumed.csv")
    assert list(resumed.columns) == list(older.columns) and len(resumed) == len(older) == 13
    # the points it kept as recorded; those it solved again as this version solves them: from 1864 rpm on, the
    # finger's width sets the weight (finger_fits_width at b(m_r), posed in paper mode since the older store)
    kept = resumed["mass [kg]"].to_numpy()[:7]
    pd.testing.assert_series_equal(pd.Series(kept), pd.Series(older["mass [kg]"].to_numpy()[:7]), rtol=1e-8)
    case = load_case(CASES / "wedge_paper.toml")
    for k, speed in enumerate(np.linspace(500, 3000, 12)[6:], start=7):
        assert resumed["mass [kg]"][k] == pytest.approx(solve_case(case.with_values(speed=speed * math.pi / 30))
                                                        .objective, rel=1e-8)


def test_a_process_keeps_its_stores_connection_and_sees_what_others_changed(tmp_path):
    # a closed store's connection is kept for the next store of the file in the process (its write-ahead log not
    # checkpointed: two fsyncs saved, and two more at the next first write); a store that another connection has
    # changed since is prepared and checked again; closing the kept connection folds the log into the file
    from clutchopt.store_kept import close_kept

    path = tmp_path / "runs.sqlite"
    with RunStore(path) as store:
        store.record("solve", {"values": {}}, {"status": "optimal"}, status="optimal")
    assert Path(f"{path}-wal").stat().st_size > 0
    with closing(sqlite3.connect(path)) as other, other:
        other.execute("DROP TABLE templates")
    with RunStore(path) as store:
        assert store.record("solve", {"values": {}}, {"status": "optimal"}, status="optimal") == 2
    with closing(sqlite3.connect(path)) as other:
        assert other.execute("SELECT name FROM sqlite_master WHERE name = 'templates'").fetchall()  # prepared again
    close_kept()
    assert not Path(f"{path}-wal").exists()
    with closing(sqlite3.connect(path)) as other:
        assert other.execute("SELECT COUNT(*) FROM runs").fetchone() == (2,)


def test_a_store_of_an_older_clutchopt_gets_the_templates_table(tmp_path):
    path = tmp_path / "runs.sqlite"
    RunStore(path).close()
    with sqlite3.connect(path) as db:
        db.execute("DROP TABLE templates")
    with RunStore(path, writable=False) as store:  # read only: nothing compact to read, nothing added
        assert store.runs() == []
    with sqlite3.connect(path) as db:
        assert not db.execute("SELECT 1 FROM sqlite_master WHERE name = 'templates'").fetchall()
    RunStore(path).close()
    with sqlite3.connect(path) as db:
        assert db.execute("SELECT 1 FROM sqlite_master WHERE name = 'templates'").fetchall()


def test_stored_json_is_read_by_orjson_and_else_by_the_standard_library():
    # what orjson refuses (NaN and Infinity tokens an older clutchopt wrote) the standard library reads; what neither
    # reads raises ValueError or RecursionError, which the store reports as a damaged run
    from clutchopt.output import from_json

    assert from_json('{"a": [1.5, null], "b": "x"}') == {"a": [1.5, None], "b": "x"}
    nan, infinite = from_json('[NaN, -Infinity]')
    assert math.isnan(nan) and infinite == -math.inf
    assert from_json(str(10 ** 30)) == 1e30  # orjson: a float (the store writes none; a solve count must be whole)
    with pytest.raises((ValueError, RecursionError)):  # nested deeper than either reads
        from_json("[" * 1100 + "]" * 1100)
    with pytest.raises(ValueError):
        from_json('{"a": ')
