"""Hostile tests of the run store's gathered rows (``window_records.gathered``): points solved alone that share a
template, kept as one row of arrays. Each test is a finding of an attack (the command in its comment): a failing
test first, then its mend. Fast: the records are made by hand (a two-variable lever point without a design), no
solve."""

import json
import math
import sqlite3
from contextlib import closing

import numpy as np
import pytest

from clutchopt.cli import main
from clutchopt.output import to_json
from clutchopt.records import _older_template_key, template_of
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



def _damaged_everywhere(path, damage, tmp_path, capsys) -> None:
    """After ``damage(bytes)`` rewrites the bytes of the gathered row of POINTS points (run ids 1..) in place, each
    point is refused by ``runs show`` (one error line naming its run, exit 2) and skipped and counted by ``runs
    export``; none is shown wrong."""
    assert _recorded(path, [_point(k) for k in range(POINTS)]) == POINTS
    assert _gathered_rows(path) == [(0, POINTS)]
    with closing(sqlite3.connect(path)) as db, db:
        (data,), = db.execute("SELECT window FROM runs WHERE window IS NOT NULL").fetchall()
        db.execute("UPDATE runs SET window = ? WHERE window IS NOT NULL", (damage(bytearray(data)),))
    for run_id in range(1, POINTS + 1):
        code, out, err = _shown(path, run_id, capsys)
        assert (code, out) == (2, "")
        assert err.startswith(f"error: --store: {path}: run {run_id} is damaged (") and err.count("\n") == 1
    out = tmp_path / "rescued.csv"
    assert main(["runs", "export", "-o", str(out), "--store", str(path)]) == 0
    assert capsys.readouterr().out.startswith(f"0 runs written to {out}; {POINTS} damaged runs could not be read")


def test_a_gathered_rows_numbers_overwritten_in_place_are_refused(tmp_path, capsys):
    # attack: UPDATE runs SET window = zeroblob(length(window)) (the bytes of a gathered row zeroed, its length kept:
    # a page of zeros). The layout still fits, so `runs show 2` printed status optimal (code 0), objective 0.0,
    # inertia 0.0 (a point never solved) and the export wrote 5 such rows; a row of JSON so damaged is no JSON and
    # is refused. The row's bytes carry their CRC-32: what does not match is a damaged run
    _damaged_everywhere(tmp_path / "runs.sqlite", lambda data: bytes(len(data)), tmp_path, capsys)


def test_a_gathered_rows_numbers_with_one_bit_flipped_are_refused(tmp_path, capsys):
    # attack (/tmp/hostore/flip.py): each of the row's 447 bytes in turn with one bit flipped; every one was read
    # back without a word (a number, flag or code changed). Here a bit of the middle byte
    def flipped(data: bytearray) -> bytes:
        data[len(data) // 2] ^= 0x10
        return bytes(data)

    _damaged_everywhere(tmp_path / "runs.sqlite", flipped, tmp_path, capsys)


def _with_infinite_bound(record: dict) -> dict:
    """The point with link_diameter unbounded above (its template's JSON holds null there)."""
    return {**record, "bounds": {**record["bounds"], "link_diameter": [0.0005, math.inf]}}


@pytest.mark.parametrize("bounded", [True, False], ids=["finite bounds", "an infinite bound"])
def test_a_template_changed_in_place_is_refused(tmp_path, capsys, bounded):
    # attack: UPDATE templates SET body = replace(body, '"kg"', '"g"') (the template a gathered row's points share,
    # still JSON of its shape, one unit changed): `runs show 1` printed the point's mass in g, the export's column
    # "mass [g]". A template's key is the hash of its JSON (records.template_key): one that does not match its key is
    # refused as a damaged one is; so with an infinite bound (a reviewer's finding: a template with a null bound was
    # taken unchecked, since an older clutchopt hashed it as Infinity: that key is now made with the infinity)
    path = tmp_path / "runs.sqlite"
    records = [_point(k) if bounded else _with_infinite_bound(_point(k)) for k in range(POINTS)]
    assert _recorded(path, records) == POINTS
    with closing(sqlite3.connect(path)) as db, db:
        assert db.execute("""UPDATE templates SET body = replace(body, '"kg"', '"g"')""").rowcount == 1
    code, out, err = _shown(path, 1, capsys)
    assert (code, out) == (2, "")
    assert err.startswith(f"error: --store: {path}: run 1 is damaged (its template is missing, not JSON or changed)")
    out = tmp_path / "rescued.csv"
    assert main(["runs", "export", "-o", str(out), "--store", str(path)]) == 0
    assert capsys.readouterr().out.startswith(f"0 runs written to {out}; {POINTS} damaged runs could not be read")


def test_a_gathered_rows_run_count_made_huge_is_damage_an_export_counts(tmp_path, capsys):
    # attack: UPDATE runs SET run_count = 2**40 on the gathered row of 5 points: `runs export` listed the ids of the
    # damaged row one by one (list(range(...)): 'internal error: MemoryError', exit 3; 10**8 took 18 s and 4.8 GB,
    # 10**9 was killed). The ids counted lost stop where the file's size says no run can be (ROW_BYTES a run), as
    # those of a damaged largest id do; the row's points are lost, the point solved alone beside it is exported
    path = tmp_path / "runs.sqlite"
    records = [_point(k) for k in range(POINTS)]
    records[-1] = {**records[-1], "choice": {"lining": "moulded"}}  # (a key of its own: a row of its own)
    assert _recorded(path, records) == POINTS
    assert _gathered_rows(path) == [(0, POINTS - 1)]
    with closing(sqlite3.connect(path)) as db, db:
        db.execute("UPDATE runs SET run_count = ? WHERE window IS NOT NULL", (2**40,))
    out = tmp_path / "rescued.csv"
    assert main(["runs", "export", "-o", str(out), "--store", str(path)]) == 0
    printed = capsys.readouterr().out
    assert printed.startswith(f"1 runs written to {out}; ") and "damaged runs could not be read" in printed
    code, shown, err = _shown(path, 3, capsys)
    assert (code, shown) == (2, "") and "run 3 is damaged (its numbers do not fit their layout)" in err


def test_a_whole_number_beyond_64_bits_in_what_the_points_share_keeps_them_rows(tmp_path):
    # a reviewer's finding: the same number in a field the points share (solver.iterations, in their template)
    # reached the template's key, whose JSON (orjson) refuses it: a TypeError out of record_points. The points stay
    # rows of their own (each as a point solved alone is kept)
    records = [_point(k) for k in range(POINTS)]
    for record in records:
        record["solver"]["iterations"] = 2**64
    path = tmp_path / "runs.sqlite"
    assert _recorded(path, records) == POINTS
    assert _gathered_rows(path) == []
    with closing(sqlite3.connect(path)) as db:
        rows = db.execute("SELECT point, IFNULL(run_count, 1), outputs FROM runs ORDER BY point").fetchall()
    assert [(point, count) for point, count, _ in rows] == [(k, 1) for k in range(POINTS)]
    assert all('"iterations": 18446744073709551616' in text for _, _, text in rows)  # (the JSON of each)


@pytest.mark.parametrize("bounded", [True, False], ids=["finite bounds", "an infinite bound"])
def test_a_gathered_row_of_an_older_clutchopt_reads_as_it_was_recorded(tmp_path, bounded):
    # rows of a store recorded before the checksum and orjson's keys: no crc32 in a row's header, its template keyed
    # by the standard library's JSON (an infinite bound hashed as Infinity, its body holding null): read unchecked,
    # each point as it was recorded, none damaged
    path = tmp_path / "runs.sqlite"
    records = [_point(k) if bounded else _with_infinite_bound(_point(k)) for k in range(POINTS)]
    assert _recorded(path, records) == POINTS
    older = _older_template_key(template_of(records[0]))
    with closing(sqlite3.connect(path)) as db, db:
        db.execute("UPDATE templates SET key = ?", (older,))
        for run_id, text in db.execute("SELECT id, outputs FROM runs WHERE window IS NOT NULL").fetchall():
            header = json.loads(text)
            header.pop("crc32")
            db.execute("UPDATE runs SET outputs = ? WHERE id = ?", (json.dumps({**header, "template": older}), run_id))
    with RunStore(path, writable=False) as store:
        runs, damaged, _ = store.readable_runs()
    assert damaged == 0
    back = {run["point"]: run["outputs"] for run in runs}
    assert [to_json(back[k], None) for k in range(POINTS)] == [to_json(record, None) for record in records]
