"""A resumed sweep's rows are the uninterrupted sweep's bit for bit: interrupted after a window is stored (at a
window's end) or while a window is solved (its points lost), `--resume` goes on from what the uninterrupted run
started the next window from, stored with the window before it (clutchopt/optimise/batch_carried.py). Before, a
resume started cold and its designs differed in the last digits (the kill test of test_store_faults.py compares
to 1e-7).

No hand calculation: the reference is the same sweep run once without an interruption, in this process.
"""

import json
import math
import sqlite3
from contextlib import closing

import numpy as np
import pytest

import clutchopt.optimise.batch as batch
import clutchopt.optimise.interval_proof as interval_proof
from clutchopt.cases import load_case
from clutchopt.cli import main
from clutchopt.optimise.batch import BatchSweep
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.region_proof import Regions
from clutchopt.optimise.sweep import Sweep, solve_points
from clutchopt.optimise.sweep_grid import parse_vary
from clutchopt.store import RunStore
from conftest import CASES, Interrupted, resumed_sweep, stopped_sweep

# the ball over 1x-10x its power in design mode, 100 points: its rows rise with the power (the integer search at each
# change, the pace aimed at the next), the last 9 points infeasible (region proofs); with a window's work cut to
# one solve's, 17 windows (their ends at points with a design) instead of 2
SWEEP = ("ball_compressor.toml", "power=1200:12000:100", "design")
WINDOW_WORK = 64


def _cut(patch) -> None:
    """A window's work cut to one solve's, its interval searches' boxes uncounted (batch.BOX_WORK: hundreds a region
    search, they would end a window at every point searched, where these windows end at points with a design)."""
    patch.setattr(batch, "WINDOW_WORK", WINDOW_WORK)
    patch.setattr(batch, "BOX_WORK", 0)


def _searched_not_carried(patch) -> None:
    """Each stretch's points searched (their regions' searches, the boxes they take), as in a sweep whose steps do not
    only tighten the limits (a speed, a friction coefficient): this sweep's stretches upwards in power would carry
    their first point's proof unsearched (``Regions._tightened``: tests/test_region_tightened.py)."""
    patch.setattr(Regions, "_tightened", lambda self, j, k, count=0: k)


def _sweep() -> Sweep:
    file, text, mode = SWEEP
    case = load_case(CASES / file)
    return Sweep(case, [parse_vary(text, case.coupling)], mode=mode)


def _rows(result) -> list[dict]:
    """Every point's record without its solver seconds (the only numbers a second run may change), nan as None (a
    stored point read back: the store's JSON spells nan null)."""
    def timeless(value):
        if isinstance(value, dict):
            return {key: timeless(item) for key, item in value.items() if key != "time_s"}
        if isinstance(value, list):
            return [timeless(item) for item in value]
        return None if isinstance(value, float) and math.isnan(value) else value
    return [timeless(record) for record in result.solutions]


@pytest.fixture(scope="module")
def uninterrupted(tmp_path_factory):
    with pytest.MonkeyPatch.context() as patch:
        _cut(patch)
        path = tmp_path_factory.mktemp("whole") / "runs.sqlite"
        with RunStore(path) as store:
            result = _sweep().run(store, progress=False)
    with closing(sqlite3.connect(path)) as db:
        starts = [row[0] for row in db.execute("SELECT point FROM sweep_starts ORDER BY point")]
    return result, starts


def _stopped(tmp_path, monkeypatch, cls, name: str, calls: int):
    """The store of the sweep stopped where the ``calls``-th call of ``cls.name`` raises (after it ran)."""
    _cut(monkeypatch)
    original, seen = getattr(cls, name), []

    def hook(*args, **kwargs):
        out = original(*args, **kwargs)
        seen.append(1)
        if len(seen) == calls:
            raise Interrupted
        return out

    return stopped_sweep(tmp_path / "runs.sqlite", _sweep, monkeypatch, cls, name, hook)


def _resumed(tmp_path, monkeypatch, cls, name: str, calls: int):
    """The sweep stored until the ``calls``-th call of ``cls.name`` raises (after it ran), then resumed."""
    return resumed_sweep(_stopped(tmp_path, monkeypatch, cls, name, calls), _sweep)


def test_the_uninterrupted_sweep_stores_each_window_s_start(uninterrupted):
    result, starts = uninterrupted
    assert result.frame["status"].value_counts().to_dict() == {"optimal": 91, "infeasible": 9}
    assert len(starts) >= 10  # (each window's end but the sweep's: where the next window starts)
    assert starts[-1] == 100  # (the last window's end: the sweep's)
    assert all(result.solutions[k - 1]["status"] == "optimal" for k in starts[:-1])  # windows end at a design


@pytest.mark.parametrize("windows", [1, 3, 6])
def test_a_sweep_resumed_after_a_stored_window_has_the_uninterrupted_rows(uninterrupted, windows, tmp_path,
                                                                          monkeypatch):
    resumed = _resumed(tmp_path, monkeypatch, RunStore, "record_points", windows)
    assert 0 < resumed.reused < 100 and resumed.solved == 100 - resumed.reused
    assert _rows(resumed) == _rows(uninterrupted[0])
    assert resumed.frame.drop(columns="iterations").equals(uninterrupted[0].frame.drop(columns="iterations"))


@pytest.mark.parametrize("hook, calls", [("_batch", 6), ("_batch", 15), ("_solve_alone", 5)])
def test_a_sweep_resumed_after_a_kill_inside_a_window_has_the_uninterrupted_rows(uninterrupted, hook, calls, tmp_path,
                                                                                 monkeypatch):
    # a chain (21 in all, from points 1 to 91: the 6th from point 42, the 15th from 70) or a point solved alone (10:
    # point 0 and the 9 infeasible ones, the 5th point 94) raises: its window is lost, the resume starts that window
    # again from the start stored with the window before
    resumed = _resumed(tmp_path, monkeypatch, BatchSweep, hook, calls)
    assert 0 < resumed.reused < 100
    assert _rows(resumed) == _rows(uninterrupted[0])


def test_a_resume_without_a_stored_start_solves_the_rest_from_cold(tmp_path, monkeypatch):
    # a store of an older clutchopt (no start beside its windows): the remaining points are solved as before, from
    # the case's own start, with the same statuses, and no start is stored for its windows (their points counted
    # from the first point resumed: a start stored at point 8 where its window began at 49, read by a later resume
    # as the start of another point)
    _cut(monkeypatch)
    original, seen = RunStore.record_points, []

    def record_without_start(self, *args, carried=None):
        seen.append(1)
        if len(seen) == 3:
            raise Interrupted
        return original(self, *args)

    path = stopped_sweep(tmp_path / "runs.sqlite", _sweep, monkeypatch, RunStore, "record_points",
                         record_without_start)
    resumed = resumed_sweep(path, _sweep)
    assert resumed.reused > 0
    assert resumed.frame["status"].value_counts().to_dict() == {"optimal": 91, "infeasible": 9}
    with closing(sqlite3.connect(path)) as db:
        assert db.execute("SELECT point FROM sweep_starts").fetchall() == []


def _short(start: dict) -> dict:
    return {**start, "x": start["x"][:-1]}


@pytest.mark.parametrize("damage, named", [
    (lambda body: {**body, "start": {"x": [1.0]}, "pace": {"size": 4}}, "'scale'"),  # the reviewer's repro
    (lambda body: {**body, "start": _short(body["start"])}, "x"),  # a number short of the design's
    (lambda body: {**body, "start": {**body["start"], "lam_g": body["start"]["lam_g"] + [0.0]}}, "lam_g"),
    (lambda body: {**body, "start": {**body["start"], "dx": [None] * len(body["start"]["dx"])}}, "dx"),
    (lambda body: {**body, "start": {**body["start"], "objective": "NaN"}}, "objective"),
    (lambda body: {**body, "pace": {**body["pace"], "size": 0}}, "size"),
    (lambda body: {**body, "pace": {**body["pace"], "breaks": ["39"]}}, "breaks"),
    (lambda body: {**body, "ahead": "3"}, "ahead"),
    (lambda body: {**body, "ahead": -1}, "ahead"),
    (lambda body: {**body, "point": body["point"] - 1}, "point"),
    (lambda body: {**body, "feasible": {"filling": 0.41}}, "feasible"),
    (lambda body: {**body, "undesigned": [[[5.0], 40, 7]]}, "undesigned"),
])
def test_a_damaged_stored_start_is_an_error_line_naming_it(damage, named, tmp_path, monkeypatch, capsys):
    # before: 'internal error: KeyError: 'scale'', exit 3 (the start read past the wrapper that names a damaged
    # store), a start of another point skipped (a resume from cold without a word)
    path = _stopped(tmp_path, monkeypatch, RunStore, "record_points", 3)
    with closing(sqlite3.connect(path)) as db, db:
        point, body = db.execute("SELECT point, body FROM sweep_starts ORDER BY point DESC LIMIT 1").fetchone()
        db.execute("UPDATE sweep_starts SET body = ? WHERE point = ?", (json.dumps(damage(json.loads(body))), point))
    file, text, mode = SWEEP
    code = main(["sweep", str(CASES / file), "--vary", text, "--mode", mode, "--store", str(path), "--resume",
                 "--quiet"])
    err = capsys.readouterr().err
    assert code == 2, err
    assert err.startswith("error: --store") and f"start at point {point} is damaged" in err and named in err, err
    assert "internal error" not in err and "Traceback" not in err


def test_a_resume_in_a_new_process_starts_its_windows_from_the_uninterrupted_run_s_last_proof(tmp_path, monkeypatch):
    # the ball compressor up past its edge (about 11.1 MW), back and up again (58 points): after its first stretch
    # without a design the last proof took 471 boxes, what a region search's budget grows from (REGION_BUDGET times
    # it, at least SURE_BOXES), kept by the built problem across windows in one process. A new process has none; a
    # resume there after that stretch started its windows from 0 boxes, where the uninterrupted run's had 471
    _cut(monkeypatch)
    _searched_not_carried(monkeypatch)
    case = load_case(CASES / "ball_compressor.toml")
    legs = [np.linspace(9000, 12500, 20), np.linspace(12500, 9000, 20)[1:], np.linspace(9000, 12500, 20)[1:]]
    vary = parse_vary("power=" + ",".join(f"{value:g}" for value in np.concatenate(legs)), case.coupling)
    posed = case_problem(case, "design", "mass").posed
    boxes: list[int] = []  # interval_proof.last_boxes at each window's start

    def regions(*args):
        boxes.append(interval_proof.last_boxes(posed))
        return Regions(*args)

    def run(store, resume=False):
        interval_proof.carry_boxes(posed, 0)  # (a new process)
        boxes.clear()
        return Sweep(case, [vary], mode="design").run(store, resume=resume, progress=False), list(boxes)

    monkeypatch.setattr(batch, "Regions", regions)
    with RunStore(tmp_path / "whole.sqlite") as store:
        whole, whole_boxes = run(store)
    original, seen = RunStore.record_points, []

    def stop_after_four(self, *args, **kwargs):
        original(self, *args, **kwargs)
        seen.append(1)
        if len(seen) == 5:  # (stored up to point 27, the start of the window from point 28 beside them; the
            # first stretch in two windows, 9-21 and 22-27: its work bound, STRETCH_WINDOWS windows' work)
            raise Interrupted

    with RunStore(tmp_path / "runs.sqlite") as store, monkeypatch.context() as patch:
        patch.setattr(RunStore, "record_points", stop_after_four)
        with pytest.raises(Interrupted):
            run(store)
    with RunStore(tmp_path / "runs.sqlite") as store:
        resumed, resumed_boxes = run(store, resume=True)
    assert resumed.reused == 28 and whole.frame["status"].iloc[[11, 12, 26, 27]].tolist() == [
        "optimal", "infeasible", "infeasible", "optimal"]  # (the first stretch: points 12-26)
    assert resumed_boxes[0] > 0 and resumed_boxes == whole_boxes[-len(resumed_boxes):]
    assert _rows(resumed) == _rows(whole)


def test_a_stretch_without_a_design_ends_its_window_after_its_searches_work(monkeypatch):
    """A stretch of points without a design runs its window on to a point with one within STRETCH_WINDOWS windows'
    work, its interval searches' boxes counted (batch.BOX_WORK): with a window's work cut to one solve's, the last 9
    points of the ball's sweep (infeasible, their region searches hundreds of boxes) are handed on in more than one
    window; their boxes uncounted, in one (review 20: uncounted, and a stretch not bound by work inside a window, the
    lever in design mode held 138 points without a design, 31 s, in one window)."""
    def window_starts(box_work: float) -> list[int]:
        with monkeypatch.context() as patch:
            _cut(patch)
            patch.setattr(batch, "BOX_WORK", box_work)
            sweep = _sweep()
            return [int(part.points.index[0]) for part in
                    solve_points(sweep.case, "design", "mass", sweep.tol, None, sweep.grid)]

    _searched_not_carried(monkeypatch)
    counted, uncounted = window_starts(0.5), window_starts(0)
    assert [k for k in uncounted if k > 91] == [] and [k for k in counted if k > 91] != []
