"""The same sweep gives the same bits whatever the machine's load (clutchopt/optimise/batch.py: a window of a batched
sweep ends by its solver calls, not by the clock): every record's numbers, statuses and solver calls, the frame and
the stored window rows byte-equal between a run whose clock races (every window's time up at once) and one whose
clock crawls (no window's time ever up), timing fields aside."""

import json
import sqlite3
import time
from contextlib import closing

import numpy as np

from clutchopt.cases import load_case
from clutchopt.optimise import batch
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import Vary
from clutchopt.store import RunStore
from clutchopt.window_records import CHECKSUM, unpack
from conftest import CASES

TIMING = ("time", "_s")  # a record's keys that hold seconds (solver.time_s, diagnosis_s, ...)


def _timeless(value):
    """``value`` (a record) without its seconds, compared as bits (floats by their repr)."""
    if isinstance(value, dict):
        return {key: _timeless(item) for key, item in value.items()
                if not any(part in key for part in TIMING)}
    if isinstance(value, (list, tuple)):
        return [_timeless(item) for item in value]
    return repr(value) if isinstance(value, float) else value


def _swept(monkeypatch, rate: float, store_path):
    """The ball over 1x-10x its power (the benchmark's sweep into the infeasible: chains, integer searches, IPOPT, a
    region proof), its clock running ``rate`` times as fast as the real one."""
    real = time.perf_counter
    began = real()
    monkeypatch.setattr(time, "perf_counter", lambda: began + rate * (real() - began))
    case = load_case(CASES / "ball_compressor.toml")
    power = next(q for q in case.quantities if q.name == "power")
    sweep = Sweep(case, [Vary(power, tuple((case.values["power"] * np.geomspace(1.0, 10.0, 100)).tolist()))],
                  mode="design")
    with RunStore(store_path) as store:
        result = sweep.run(store=store, progress=False)
    monkeypatch.setattr(time, "perf_counter", real)
    with closing(sqlite3.connect(store_path)) as db:
        rows = db.execute("SELECT point, run_count, status, objective, outputs, window FROM runs "
                          "WHERE kind = 'sweep' ORDER BY point").fetchall()
    return result, [_stored(*row) for row in rows]


def _stored(point, count, status, objective, outputs, window):
    """A stored row (a point, or a window of points: its arrays unpacked) without its seconds, as bits (and without
    the checksum of its packed bytes, which hold the seconds)."""
    header = json.loads(outputs) if outputs else {}
    arrays = unpack(header["arrays"], window) if window is not None else {}
    return (point, count, status, repr(objective), _timeless({key: value for key, value in header.items()
                                                             if key not in ("arrays", CHECKSUM)}),
            {name: array.tobytes() for name, array in arrays.items() if not any(part in name for part in TIMING)})


def test_a_sweep_gives_the_same_bits_on_a_racing_and_a_crawling_clock(monkeypatch, tmp_path):
    # the ball's 100 points (96 with a design, 4 proven infeasible) spend about 100 solver calls: with a window ended
    # at a quarter of a second, 118 or 120 calls and designs 1.6e-15 apart from run to run on a loaded machine
    # windows of a sixteenth of the usual work, so that work ends one (the second window starts at point 81)
    monkeypatch.setattr(batch, "WINDOW_WORK", 8192 // 16, raising=False)
    firsts, window = [], batch.BatchSweep._window

    def recorded(sweep, blocks, alone, first, count):
        firsts.append(first)
        return window(sweep, blocks, alone, first, count)

    monkeypatch.setattr(batch.BatchSweep, "_window", recorded)
    racing, racing_rows = _swept(monkeypatch, 1e4, tmp_path / "racing.sqlite")
    racing_windows = list(firsts)
    firsts.clear()
    crawling, crawling_rows = _swept(monkeypatch, 1e-4, tmp_path / "crawling.sqlite")
    assert racing_windows == firsts == [0, 81]
    assert racing.spent["solves"] == crawling.spent["solves"]
    assert racing.frame.equals(crawling.frame)
    assert [_timeless(r) for r in racing.solutions] == [_timeless(r) for r in crawling.solutions]
    assert racing_rows == crawling_rows and len(racing_rows) >= 1
