"""Points solved alone that share a template (a region proof's points without a design: one design, one proof, one
solver status) are stored as one row of arrays, as a window's batched points are (``window_records.gathered``), and
read, listed, shown, exported and resumed exactly as their rows of JSON were."""

import copy
import json
import sqlite3
from contextlib import closing

import numpy as np
import pandas as pd
import pytest

from clutchopt.cases import load_case
from clutchopt.output import to_json
from clutchopt.store import RunStore
from clutchopt.window_records import LABELS, gathered
from conftest import CASES
from store_rows import forget_points

POINTS = 24


@pytest.fixture(scope="module")
def region():
    """The wedge over its resisting torque 20-400 N m (24 points): the points from 164 N m on have no design, most of
    them covered by region proofs (tests/test_region_search.py); solved once, recorded by each test."""
    from clutchopt.optimise.sweep import Sweep, solve_points
    from clutchopt.optimise.sweep_grid import parse_vary

    case = load_case(CASES / "wedge_paper.toml")
    sweep = Sweep(case, [parse_vary(f"resisting_torque=20:400:{POINTS}", "wedge", case.quantities)])
    parts = list(solve_points(sweep.case, sweep.formulation.mode, sweep.objective.name, sweep.tol, None, sweep.grid))
    return sweep, parts


def _record(path, sweep, parts, sweep_id: int | None = None, form: str = "stored") -> tuple[int, int]:
    """The points recorded into the store at ``path`` (a new sweep unless ``sweep_id``): the sweep's id, how many.
    ``form``: the records as the sweep gives them to the store (``stored``: a run of points solved alone that share a
    template already as arrays; ``held``: each as its ``Solution.as_dict()``, which the store gathers itself)."""
    with RunStore(path) as store:
        sweep_id = sweep_id or store.new_sweep(sweep.spec, len(sweep.points))
        return sweep_id, sum(store.record_points(sweep._inputs(), sweep._where(sweep_id), part.points.index,
                                                 part.points.columns, *getattr(part, form)()) for part in parts)


def _read(path, sweep, sweep_id: int, tmp_path) -> tuple:
    """All a store gives of a sweep (creation times left out: each store has its own): its points' outputs, the runs
    listed, each shown, every readable run, and the export's table."""
    from clutchopt.cli import main

    with RunStore(path, writable=False) as store:
        stored = store.sweep_outputs(sweep_id, sweep.points)
        listed = store.runs()
        shown = [store.run(run["id"]) for run in listed]
        readable = store.readable_runs()
    out = tmp_path / f"{path.stem}.csv"
    assert main(["runs", "export", "-o", str(out), "--store", str(path)]) == 0
    exported = pd.read_csv(out, dtype=str, keep_default_na=False).drop(columns="created")
    for run in (*listed, *shown, *readable[0]):
        run.pop("created")
    return stored, to_json(listed, None), to_json(shown, None), (to_json(readable[0], None), readable[1:]), \
        exported.to_csv(index=False)


def _rows(path) -> list[tuple]:
    with closing(sqlite3.connect(path)) as db:
        return db.execute("SELECT point, run_count, length(inputs) + length(outputs) + IFNULL(length(window), 0) "
                          "FROM runs WHERE kind = 'sweep' ORDER BY point").fetchall()


def test_points_without_a_design_are_one_row_read_back_as_their_rows_were(region, tmp_path, monkeypatch, capsys):
    # the region's points covered by proofs share the design of the first point without one, its proof's words
    # where one region proof covers them, solver "interval" with 0 iterations: one template; each was a row of
    # JSON (inputs and the full solution, 2.5 kB on the wedge), now the run of them is one row of arrays. Read back
    # through every reader, the store gives what the rows gave, byte for byte, and what the sweep solved (its JSON)
    import clutchopt.store

    sweep, parts = region
    full = json.loads(to_json([record for part in parts for record in part.records()], None))
    covered = [k for k, record in enumerate(full) if record["solver"]["name"] == "interval"
               and record["solver"]["iterations"] == 0]
    assert len(covered) >= 10 and covered == list(range(covered[0], covered[-1] + 1))
    assert all(full[k]["status"] == "infeasible" and full[k]["design"] == full[covered[0]]["design"]
               for k in covered)
    gathered_path, rows_path = tmp_path / "gathered.sqlite", tmp_path / "rows.sqlite"
    sweep_id, count = _record(gathered_path, sweep, parts)
    assert count == POINTS
    with monkeypatch.context() as patch:  # the layout before: a row of JSON for each point solved alone
        patch.setattr(clutchopt.store, "gathered", lambda alone: (alone, []))
        assert _record(rows_path, sweep, parts, form="held") == (sweep_id, POINTS)
    gathered_rows, each_rows = _rows(gathered_path), _rows(rows_path)
    assert (covered[0], len(covered)) in [(point, count) for point, count, _ in gathered_rows]
    assert len(each_rows) - len(gathered_rows) == len(covered) - 1
    covered_bytes = [size for point, count, size in gathered_rows if point == covered[0]][0]
    assert covered_bytes < sum(size for point, _, size in each_rows if point in covered) / 10
    gathered_read, rows_read = _read(gathered_path, sweep, sweep_id, tmp_path), _read(rows_path, sweep, sweep_id,
                                                                                       tmp_path)
    assert gathered_read[0] == dict(enumerate(full))
    for found, before in zip(gathered_read, rows_read):
        assert found == before
    capsys.readouterr()


def test_a_killed_sweep_resumes_around_its_gathered_points(region, tmp_path):
    # points lost from the gathered row (as a sweep killed before their window's commit, each other point left as a
    # row of its own) are recorded again, only they; the sweep resumed solves none and reads each point once
    sweep, parts = region
    path = tmp_path / "runs.sqlite"
    sweep_id, _ = _record(path, sweep, parts)
    full = json.loads(to_json([record for part in parts for record in part.records()], None))
    lost = [k for k, record in enumerate(full) if record["status"] == "infeasible"][1::3]
    forget_points(path, lambda point: point in lost)
    assert _record(path, sweep, parts, sweep_id) == (sweep_id, len(lost))
    assert _record(path, sweep, parts, sweep_id) == (sweep_id, 0)
    with RunStore(path) as store:
        assert store.sweep_outputs(sweep_id, sweep.points) == dict(enumerate(full))
        resumed = sweep.run(store, resume=True, progress=False)
    assert (resumed.solved, resumed.reused) == (0, POINTS)
    assert json.loads(to_json(list(resumed.solutions), None)) == full


def _covered_records(region) -> list[dict]:
    _, parts = region
    records = [record for part in parts for record in part.records()]
    return [record for record in records if record["solver"]["name"] == "interval"
            and record["solver"]["iterations"] == 0]


def test_only_records_whose_numbers_the_arrays_keep_bit_for_bit_are_gathered(region):
    # a run of records is kept as arrays only where reading them back gives their JSON, byte for byte: NumPy's
    # float64 is (JSON writes the same number); a whole number where a float goes is not (3 would read back 3.0), nor
    # a record with a key of its own (a design's choice), which stays a row, the runs on either side gathered
    covered = _covered_records(region)[:6]
    alone = {10 + k: copy.deepcopy(record) for k, record in enumerate(covered)}
    alone[11]["constraints"][0]["value"] = np.float64(alone[11]["constraints"][0]["value"])
    alone[12]["outputs"] = {name: np.float64(value) for name, value in alone[12]["outputs"].items()}
    kept, windows = gathered(alone)
    assert kept == {} and [positions.tolist() for positions, _ in windows] == [list(range(10, 16))]
    back = windows[0][1].records(json_numbers=True)
    assert [to_json(record, None) for record in back] == [to_json(alone[k], None) for k in range(10, 16)]

    whole = copy.deepcopy(alone)
    whole[13]["constraints"][1]["limit"] = 3
    assert gathered(whole)[0].keys() == whole.keys()  # (the run of them stays rows)
    chosen = copy.deepcopy(alone)
    chosen[12]["choice"] = {"lining": "moulded"}
    kept, windows = gathered(chosen)
    assert list(kept) == [12] and [positions.tolist() for positions, _ in windows] == [[10, 11], [13, 14, 15]]
    gap = {k: record for k, record in alone.items() if k != 12}  # (a row holds consecutive points only)
    assert [positions.tolist() for positions, _ in gathered(gap)[1]] == [[10, 11], [13, 14, 15]]
    assert gathered({10: alone[10]}) == ({10: alone[10]}, [])  # (one point: a row; a template of its own per point
    # would cost more than it saves)


def test_a_gathered_row_names_at_most_its_codes_diagnoses(region):
    # a point's diagnosis is an 8-bit code into the texts its row names: 130 points with a proof each (130 texts)
    # are two rows, of 127 and 3 points
    record = _covered_records(region)[0]
    alone = {k: {**record, "diagnosis": f"proven infeasible: proof {k}"} for k in range(LABELS + 3)}
    kept, windows = gathered(alone)
    assert kept == {} and [(positions[0], len(positions)) for positions, _ in windows] == [(0, LABELS), (LABELS, 3)]
    back = [record for _, window in windows for record in window.records(json_numbers=True)]
    assert [record["diagnosis"] for record in back] == [alone[k]["diagnosis"] for k in range(LABELS + 3)]
