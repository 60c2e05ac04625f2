"""Faults of the run store and of the processes writing it: kill -9 at random moments of a sweep, concurrent
writers, damaged files, read-only files and folders; the pool workers of a killed sweep.

The writers are forked from this process (``multiprocessing`` with ``fork``) and run ``clutchopt.cli.main`` as
the command line would, so each starts in milliseconds with the solver stack already imported; ``kill -9`` is
a real SIGKILL of that process, in the middle of a solve or of an SQLite transaction."""

import multiprocessing
import os
import random
import shlex
import shutil
import signal
import sqlite3
import stat
import subprocess
import sys
import tempfile
import time
from contextlib import closing
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from clutchopt.cli import main
from clutchopt.store import RunStore, Schema
from clutchopt.store_kept import close_kept
from conftest import CASES, ROOT
from hostile_runtime import FOREIGN_SQL, PARTIAL_SQL, store_with
from store_rows import rewrite_windows, sweep_points, window_ids

FORK = multiprocessing.get_context("fork")
CASE = str(CASES / "wedge_paper.toml")
GRID = ["--vary", "speed=500:3000:40", "--vary", "allowable_pressure=2:8:125"]  # 5000 points: 5 windows of
# up to 1024, each recorded in one transaction
SMALL = ["--vary", "speed=500:3000:15", "--vary", "allowable_pressure=2:8:10"]  # 150 points
NOBODY = 65534


def _child(argv: list[str], output: str, user: int | None) -> None:
    """Run the CLI in a forked process: its streams to ``output``, optionally as another user; never returns."""
    code = 70
    try:
        handle = os.open(output, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o666)
        os.dup2(handle, 1), os.dup2(handle, 2)
        sys.stdout, sys.stderr = open(1, "w", closefd=False), open(2, "w", closefd=False)
        if user is not None:
            os.setgid(user), os.setuid(user)
        code = main(argv)
    except SystemExit as stop:
        code = stop.code if isinstance(stop.code, int) else 1
    finally:
        sys.stdout.flush(), sys.stderr.flush()
        os._exit(code)


class Writer:
    """One forked ``clutchopt`` command."""

    def __init__(self, argv: list[str], folder: Path, user: int | None = None):
        self.output = folder / f"out-{time.monotonic_ns()}.txt"
        self.process = FORK.Process(target=_child, args=(argv, str(self.output), user))
        self.process.start()

    def kill(self) -> None:
        if self.process.is_alive():
            os.kill(self.process.pid, signal.SIGKILL)
        self.process.join()

    def finish(self, timeout: float = 120) -> tuple[int, str]:
        self.process.join(timeout)
        assert not self.process.is_alive(), "the command hangs"
        return self.process.exitcode, self.output.read_text()


@pytest.fixture(scope="module", autouse=True)
def built_problems():
    """Build the problems once here, so that every forked writer starts solving at once."""
    main(["sweep", CASE, "--vary", "speed=900,1000", "--no-store", "--quiet"])


def _points(store: Path) -> list[int]:
    return sorted(point for _, point, _ in sweep_points(store))


def _reference(grid: list[str]) -> pd.DataFrame:
    from clutchopt.cases import load_case
    from clutchopt.optimise.sweep import Sweep
    from clutchopt.optimise.sweep_grid import parse_vary

    case = load_case(CASE)
    return Sweep(case, [parse_vary(text, "wedge") for text in grid[1::2]]).run(progress=False).frame


# --- kill -9 ---------------------------------------------------------------------------------------------------------
def test_kill_9_at_random_moments_then_resume_loses_and_duplicates_nothing(tmp_path):
    # each run resumes the same sweep and is killed at a random moment (reproducible) up to 15 ms after it has stored
    # a window of its own (while it solves the next or inside that window's transaction), until the sweep is complete
    store, out = tmp_path / "runs.sqlite", tmp_path / "sweep.csv"
    argv = ["sweep", CASE, *GRID, "--resume", "--quiet", "--store", str(store)]
    seen = []
    for i in range(20):
        if seen and seen[-1] == 5000:
            break
        before = len(_points_or_none(store)) if store.exists() else 0
        writer, deadline = Writer(argv, tmp_path), time.monotonic() + 60
        while writer.process.is_alive() and time.monotonic() < deadline and (
                not store.exists() or len(_points_or_none(store)) <= before):
            time.sleep(0.002)
        time.sleep(random.Random(12 + i).uniform(0.0, 0.015))  # a window takes about as long to solve and store
        writer.kill()
        stored = _points(store) if store.exists() else []
        assert stored == list(range(len(stored)))  # a prefix: a killed transaction left no part of its window
        seen.append(len(stored))
    assert len([count for count in seen if 0 < count < 5000]) >= 2, seen
    code, text = Writer([*argv, "--out", str(out)], tmp_path).finish()
    assert code == 0, text
    assert _points(store) == list(range(5000))  # none lost, none twice
    with RunStore(store, writable=False) as opened:
        assert len(opened.sweeps()) == 1  # every resume continued the same sweep
    with sqlite3.connect(store) as db:
        assert db.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    resumed, reference = pd.read_csv(out, skiprows=1), _reference(GRID)  # below the sweep's identification
    # the uninterrupted run's statuses: optimal but where the flank pressure caps m_r below the mass whose real weight
    # is wide enough for its finger, proven infeasible (fast, low [p]; docs/errata.md)
    assert resumed["status"].tolist() == reference["status"].tolist()
    assert (resumed["status"] == "optimal").mean() > 0.99 and set(resumed["status"]) == {"optimal", "infeasible"}
    # bit for bit: each resume starts its first window from what the uninterrupted run started it from
    # (optimise/batch_carried.py, stored with the window before; tests/test_resume_agrees.py)
    pd.testing.assert_series_equal(resumed["mass [kg]"], reference["mass [kg]"], check_exact=True)


def _children(pid: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        try:
            fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
        except (OSError, IndexError):
            continue
        if int(fields[1]) == pid:
            found.append(int(entry.name))
    return found


def _alive(pid: int) -> bool:
    try:
        return (Path("/proc") / str(pid) / "stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads the process table from /proc (Linux)")
def test_pool_workers_die_with_a_killed_sweep(tmp_path):
    writer = Writer(["sweep", CASE, *GRID, "--jobs", "2", "--quiet", "--no-store"], tmp_path)
    deadline, workers = time.monotonic() + 30, []
    while time.monotonic() < deadline and len(workers) < 2:
        time.sleep(0.05)
        workers = _children(writer.process.pid)
    assert len(workers) >= 2, "the pool did not start"
    writer.kill()
    deadline = time.monotonic() + 10
    while time.monotonic() < deadline and any(_alive(pid) for pid in workers):
        time.sleep(0.1)
    assert not any(_alive(pid) for pid in workers), "pool workers outlived the killed sweep"


# --- concurrent writers ----------------------------------------------------------------------------------------------
def _sweep(store: Path, grid: list[str], *extra: str) -> list[str]:
    return ["sweep", CASE, *grid, "--quiet", "--store", str(store), *extra]


def test_two_resumes_of_one_sweep_at_once(tmp_path):
    # the first writer is killed once its first window is stored; both resumes then solve the missing points at
    # once, and each point is stored once
    store = tmp_path / "runs.sqlite"
    first = Writer(_sweep(store, GRID), tmp_path)
    while not (store.exists() and _points_or_none(store)):
        time.sleep(0.01)
    first.kill()
    stored = len(_points(store))
    assert 0 < stored < 5000, "the first sweep was not killed half-way"
    racing = [Writer(_sweep(store, GRID, "--resume"), tmp_path) for _ in range(2)]
    for writer in racing:
        code, text = writer.finish()
        assert code == 0 and "5000 points" in text, text
    assert _points(store) == list(range(5000))
    with RunStore(store, writable=False) as opened:
        assert len(opened.sweeps()) == 1


def _points_or_none(store: Path) -> list[int]:
    try:
        return _points(store)
    except sqlite3.OperationalError:  # no table yet
        return []


def test_two_different_sweeps_at_once(tmp_path):
    store = tmp_path / "runs.sqlite"
    other = ["--vary", "speed=600:2000:15", "--vary", "density=7000:8000:10"]
    writers = [Writer(_sweep(store, SMALL), tmp_path), Writer(_sweep(store, other), tmp_path)]
    for writer in writers:
        code, text = writer.finish()
        assert code == 0 and "warning" not in text, text
    with RunStore(store, writable=False) as opened:
        assert sorted(sweep["stored"] for sweep in opened.sweeps()) == [150, 150]


def test_a_sweep_and_three_solves_at_once(tmp_path):
    store = tmp_path / "runs.sqlite"
    writers = [Writer(_sweep(store, SMALL), tmp_path)]
    writers += [Writer(["solve", CASE, "--store", str(store)], tmp_path) for _ in range(3)]
    for writer in writers:
        code, text = writer.finish()
        assert code == 0 and "warning" not in text, text
    with RunStore(store, writable=False) as opened:
        kinds = [run["kind"] for run in opened.runs()]
    assert kinds.count("sweep") == 150 and kinds.count("solve") == 3


def test_six_solves_at_once(tmp_path):
    store = tmp_path / "runs.sqlite"
    writers = [Writer(["solve", str(CASES / name), "--store", str(store)], tmp_path)
               for name in ("wedge_paper.toml", "wedge_fan.toml", "lever_centrifuge.toml") * 2]
    assert [writer.finish()[0] for writer in writers] == [0] * 6
    with RunStore(store, writable=False) as opened:
        assert len(opened.runs()) == 6


def test_readers_while_a_sweep_writes(tmp_path):
    store = tmp_path / "runs.sqlite"
    assert main(["solve", CASE, "--store", str(store)]) == 0
    writer = Writer(_sweep(store, GRID), tmp_path)
    readers = [Writer(["runs", "list", "--store", str(store)], tmp_path),
               Writer(["runs", "export", "-o", str(tmp_path / "runs.csv"), "--store", str(store)], tmp_path),
               Writer(["runs", "show", "1", "--store", str(store)], tmp_path)]
    for reader in readers:
        code, text = reader.finish()
        assert code == 0, text
    writer.kill()


# --- damaged files -------------------------------------------------------------------------------------------------
SWEEP = ["sweep", CASE, "--vary", "speed=500:3000:20", "--quiet"]  # the good store's sweep
RESUME = [*SWEEP, "--resume"]


@pytest.fixture(scope="module")
def good_store(tmp_path_factory) -> Path:
    """A store with a solve and a 20-point sweep, closed (its WAL checkpointed into the file)."""
    path = tmp_path_factory.mktemp("good") / "runs.sqlite"
    assert main(["solve", CASE, "--store", str(path)]) == 0
    assert main([*SWEEP, "--store", str(path)]) == 0
    close_kept()  # as at the end of a command's process: the write-ahead log folded into the file
    return path


def _tampered(good_store: Path, folder: Path, damage) -> Path:
    """A copy of the good store in ``folder`` with ``damage`` done to it: SQL statements, or a change of its windows'
    headers and arrays (``store_rows.rewrite_windows``)."""
    store = folder / "runs.sqlite"
    shutil.copy(good_store, store)
    if callable(damage):
        rewrite_windows(store, damage)
        return store
    with closing(sqlite3.connect(store)) as db, db:
        db.executescript(damage)
    return store


def _command(capsys, argv: list[str], store: Path) -> tuple[int, str, str]:
    """``clutchopt ARGV --store STORE`` in this process: its exit code, output and errors."""
    code = main([*argv, "--store", str(store)])
    out, err = capsys.readouterr()
    return code, out, err


def _overwrite(offset, count: int, byte: int = 0xA5):
    def damage(data: bytearray) -> bytearray:
        start = offset(data) if callable(offset) else offset
        data[start:start + count] = bytes([byte]) * count
        return data
    return damage


def _page(data: bytearray) -> int:
    """The file's page size, from its header (16 kB in a new store)."""
    size = int.from_bytes(data[16:18], "big")
    return 65536 if size == 1 else size


def _truncate(fraction: float):
    return lambda data: data[:int(len(data) * fraction)]


def _inside_a_run(data: bytearray) -> int:
    return data.index(b'"outputs"' if b'"outputs"' in data else b'"design"') + 20


DAMAGE = {  # (damage, whether opening must already refuse the file)
    "header-zeroed": (_overwrite(0, 16, 0), True),
    "page-size-field": (_overwrite(16, 2, 0x03), True),
    "schema-page-b-tree-header": (_overwrite(100, 12), True),
    "second-page": (_overwrite(_page, 512), True),
    "middle-page": (_overwrite(lambda d: len(d) // 2 // _page(d) * _page(d), 4096), True),
    "last-page": (_overwrite(lambda d: len(d) - _page(d), 4096), True),
    "inside-a-run's-json": (_overwrite(_inside_a_run, 8, ord("}")), False),
    "truncated-to-half": (_truncate(0.5), True),
    "truncated-to-1000-bytes": (lambda data: data[:1000], True),
    "truncated-to-nothing": (_truncate(0.0), True),
}


@pytest.mark.parametrize("name", DAMAGE)
def test_damaged_store(name, good_store, tmp_path, capsys):
    damage, refused = DAMAGE[name]
    store = tmp_path / "runs.sqlite"
    store.write_bytes(bytes(damage(bytearray(good_store.read_bytes()))))

    def run(*argv: str) -> tuple[int, str, str]:
        try:
            code = main([*argv, "--store", str(store)])
        except SystemExit as stop:
            code = stop.code
        out, err = capsys.readouterr()
        assert "Traceback" not in err and code in (0, 2), (code, err)
        return code, out, err

    code, _, err = run("runs", "list")
    if refused:
        assert code == 2 and err.count("\n") == 1 and "--store" in err, err
        assert ("runs export" in err or "not an SQLite database" in err or "empty" in err), err
    for argv in (("runs", "show", "1"), ("runs", "show", "2")):
        code, _, err = run(*argv)
        assert code == 0 or (err.count("\n") == 1 and "--store" in err), err
    code, out, err = run("runs", "export", "-o", str(tmp_path / "rescued.csv"))
    if code == 0:
        rescued = pd.read_csv(tmp_path / "rescued.csv") if "0 runs written" not in out else pd.DataFrame()
        assert len(rescued) <= 21 and "runs written" in out
    code, out, err = run("solve", CASE)
    assert code == 0 and "status: optimal" in out, err  # the result is never lost
    assert err == "" or err.startswith("warning: this run will not be recorded"), err


def test_a_large_store_is_checked_when_read_not_when_recording(good_store, tmp_path, monkeypatch, capsys):
    # the check reads the whole file (0.25 ms a MB): a store larger than QUICK_CHECK_BYTES opened for recording is
    # not checked, a damaged one still refused when read, and a solve still prints its result
    import clutchopt.store

    store = tmp_path / "runs.sqlite"
    store.write_bytes(bytes(DAMAGE["middle-page"][0](bytearray(good_store.read_bytes()))))
    with pytest.raises(clutchopt.store.StoreError, match="runs export"):
        RunStore(store)  # small: checked
    monkeypatch.setattr(clutchopt.store, "QUICK_CHECK_BYTES", store.stat().st_size - 1)
    RunStore(store).close()  # large: opened for recording unchecked
    with pytest.raises(clutchopt.store.StoreError, match="runs export"):
        RunStore(store, writable=False)
    assert main(["runs", "list", "--store", str(store)]) == 2
    assert main(["solve", CASE, "--store", str(store)]) == 0
    out, err = capsys.readouterr()
    assert "status: optimal" in out
    assert err.count("warning:") <= 1 and "Traceback" not in err, err


# --- read-only files and folders ------------------------------------------------------------------------------------
@pytest.fixture
def shared_folder():
    """A folder another user may enter (pytest's own temporary folders are private to their owner)."""
    folder = Path(tempfile.mkdtemp(prefix="clutchopt-readonly-"))
    folder.chmod(0o755)
    yield folder
    for path in [folder, *folder.rglob("*")]:
        path.chmod(0o777) if path.is_dir() else None
    shutil.rmtree(folder)


def _others_may_run_clutchopt() -> bool:
    """Whether a user other than root can read Python, clutchopt and the cases (each folder on the way enterable)."""
    import clutchopt

    for target in (Path(sys.prefix).resolve(), Path(clutchopt.__file__).resolve().parent, CASES.resolve()):
        for folder in (target, *target.parents):
            if not folder.stat().st_mode & stat.S_IXOTH:
                return False
    return True


@pytest.fixture(autouse=True)
def _unprivileged_user_possible(request):
    if "shared_folder" in request.fixturenames and os.geteuid() == 0 and not _others_may_run_clutchopt():
        pytest.skip("run as root from a folder other users cannot enter: no user without write rights to test with")


def _as_a_user(argv: list[str], output: Path) -> tuple[int, str]:
    """Run a command as a user without the right to write what root owns (root writes any file); its output goes
    to a file in ``output``, opened before it becomes that user."""
    return Writer(argv, output, NOBODY if os.geteuid() == 0 else None).finish()


def _prepare_store(folder: Path) -> Path:
    store = folder / "runs.sqlite"
    assert main(["solve", CASE, "--store", str(store)]) == 0
    close_kept()
    return store


def test_read_only_store_file(shared_folder, tmp_path):
    work = shared_folder / "work"
    work.mkdir()
    work.chmod(0o777)
    store = _prepare_store(work)
    store.chmod(0o444)
    before = store.read_bytes()
    code, text = _as_a_user(["solve", CASE, "--store", str(store)], tmp_path)
    assert code == 0 and "status: optimal" in text, text
    warnings = [line for line in text.splitlines() if line.startswith("warning:")]
    assert warnings == [f"warning: this run will not be recorded: {store}: the file is read-only; record "
                        "elsewhere with --store OTHER.sqlite"], text
    code, text = _as_a_user(["sweep", CASE, *SMALL, "--quiet", "--store", str(store)], tmp_path)
    assert code == 0 and "150 points, 149 optimal, 1 infeasible" in text and "recorded as sweep" not in text, text
    code, text = _as_a_user(["runs", "list", "--store", str(store)], tmp_path)
    assert code == 0 and " solve " in text, text
    assert store.read_bytes() == before


def test_read_only_store_folder(shared_folder, tmp_path):
    store = _prepare_store(shared_folder)
    shared_folder.chmod(0o555)
    code, text = _as_a_user(["solve", CASE, "--store", str(store)], tmp_path)
    assert code == 0 and "status: optimal" in text and "warning: this run will not be recorded" in text, text
    code, text = _as_a_user(["solve", CASE, "--store", str(shared_folder / "new.sqlite")], tmp_path)
    assert code == 0 and "status: optimal" in text and "is not writable" in text, text
    assert not (shared_folder / "new.sqlite").exists()
    code, text = _as_a_user(["runs", "list", "--store", str(store)], tmp_path)
    assert code == 0 and " solve " in text, text
    assert stat.S_IMODE(shared_folder.stat().st_mode) == 0o555


def _set(name: str, position: tuple, value):
    def change(header: dict, arrays: dict) -> None:
        arrays[name][position] = value
    return change


WINDOWS = "WHERE window IS NOT NULL"
TAMPER = {  # damage to a copy of the good store: each makes its window of sweep points (or one full run) unreadable
    "template deleted": "DELETE FROM templates",
    "template not JSON": "UPDATE templates SET body = '{not json'",
    "template of another window": "UPDATE templates SET body = json_set(body, '$.constraints', json_array())",
    "a constraint's name a number": "UPDATE templates SET body = json_set(body, '$.constraints[0].name', 5)",
    "design units a list": "UPDATE templates SET body = json_set(body, '$.units.design', json_array('kg'))",
    "design names numbers": "UPDATE templates SET body = json_set(body, '$.design', json_array(1, 2))",
    "numbers cut short": f"UPDATE runs SET window = substr(window, 1, length(window) - 8) {WINDOWS}",
    "numbers as text": f"UPDATE runs SET window = 'heavy' {WINDOWS}",
    "layout not JSON": f"UPDATE runs SET outputs = '{{\"template\": ' {WINDOWS}",
    "objective of another type": f"UPDATE runs SET outputs = json_set(outputs, '$.arrays.objective[0]', '<i8') "
                                 f"{WINDOWS}",
    "a shape of text": f"UPDATE runs SET outputs = json_set(outputs, '$.arrays.design[1][0]', 'x') {WINDOWS}",
    "a diagnosis a number": f"UPDATE runs SET outputs = json_set(outputs, '$.diagnoses[0]', 5) {WINDOWS}",
    "status unknown": _set("status", (0,), 99),
    "diagnosis unknown": _set("diagnosis", (1,), 7),
    "full solutions a list": "UPDATE runs SET outputs = '[1, 2]' WHERE window IS NULL",
}


@pytest.mark.parametrize("damage", TAMPER)
def test_a_tampered_solution_is_a_damaged_run(damage, good_store, tmp_path, capsys):
    # what a window's points need (their template, the layout, types and codes of their numbers) and what a full
    # solution needs (its shape) is checked when read: each run that fails is one damaged run, named by `runs show`,
    # skipped and counted by `runs export`, and a resumed sweep stops at it with one line
    store = _tampered(good_store, tmp_path, TAMPER[damage])
    before, after, windows = _rows(good_store), _rows(store), window_ids(store)
    changed = [run for run in after if after[run] != before[run]]
    damaged = windows if "templates" in str(TAMPER[damage]) or set(changed) & set(windows) else changed
    assert damaged and set(damaged) & {run for run, _, _ in sweep_points(store)}
    code, _, err = _command(capsys, ["runs", "show", str(damaged[-1])], store)
    assert code == 2 and err.count("\n") == 1 and f"run {damaged[-1]} is damaged" in err, err
    code, out, _ = _command(capsys, ["runs", "export", "-o", str(tmp_path / "rescued.csv")], store)
    assert code == 0 and f"; {len(damaged)} damaged runs could not be read" in out, out
    code, _, err = _command(capsys, RESUME, store)
    assert code == 2 and err.count("\n") == 1 and "is damaged" in err, err


def _rows(store: Path) -> dict[int, tuple]:
    with closing(sqlite3.connect(store)) as db:
        return {row[0]: row[1:] for row in db.execute("SELECT id, outputs, window FROM runs")}


def test_a_broken_template_is_read_once(good_store, tmp_path, monkeypatch):
    # an export of many points of one unreadable template (50 MB in a hostile store) reads and parses it once
    store = tmp_path / "runs.sqlite"
    shutil.copy(good_store, store)
    with sqlite3.connect(store) as db:
        db.execute("UPDATE templates SET body = '[' || body")
    reads = []
    original = RunStore._read
    monkeypatch.setattr(RunStore, "_read", lambda self, sql, args=(): reads.append(sql) or original(self, sql, args))
    with RunStore(store, writable=False, check=False) as opened:
        runs, lost, _ = opened.readable_runs()
    assert lost >= 10 and sum("FROM templates" in sql for sql in reads) == 1


def _shifted_inputs(header: dict, arrays: dict) -> None:
    arrays["inputs"][:] = np.roll(arrays["inputs"], 1, axis=-1)


MISPLACED = {  # damage to a copy of the good store: a sweep run that is not the point it claims (quick_check passes)
    "point beyond the sweep": "UPDATE runs SET point = 500 WHERE point = 0",
    "window beyond the sweep": f"UPDATE runs SET point = point + 10 {WINDOWS}",
    "point negative": "UPDATE runs SET point = -1 WHERE point = 0",
    "window's point missing": f"UPDATE runs SET point = NULL {WINDOWS}",
    "point text": "UPDATE runs SET point = 'x' WHERE point = 0",
    "window's point text": f"UPDATE runs SET point = 'x' {WINDOWS}",
    "two points swapped": "UPDATE runs SET point = 1000 WHERE point = 0; UPDATE runs SET point = 0 WHERE point = 1; "
                          "UPDATE runs SET point = 1 WHERE point = 1000",
    "inputs of another point": "UPDATE runs SET inputs = json_set(inputs, '$.values.speed', 1.0) WHERE point = 0",
    "a window's inputs of other points": _shifted_inputs,
}


@pytest.mark.parametrize("damage", MISPLACED)
def test_a_resumed_sweep_takes_no_point_for_another(damage, good_store, tmp_path, capsys):
    # a damaged point number, or an index that maps a point to another run, would give a point another's design:
    # each stored run's inputs must be those of the point it stands for, else the resume stops in one line
    store = _tampered(good_store, tmp_path, MISPLACED[damage])
    with closing(sqlite3.connect(store)) as db:
        assert db.execute("PRAGMA quick_check").fetchone()[0] == "ok"
    code, _, err = _command(capsys, RESUME, store)
    assert code == 2 and err.count("\n") == 1 and "is damaged (its point number or inputs" in err, err


def test_export_rescues_runs_when_the_last_page_is_gone(good_store, tmp_path, capsys):
    # the largest id lives on the table's last leaf page: with it zeroed, SELECT MAX(id) fails and the export used to
    # read nothing; it now tries the ids on, says where reading stopped, and writes what it read
    store = tmp_path / "runs.sqlite"
    shutil.copy(good_store, store)
    with RunStore(store) as opened:  # solves after the sweep, on leaf pages of their own (a window is one row)
        solution = opened.run(1)["outputs"]
        for k in range(12):
            opened.record("solve", {"values": {}, "free": [], "bounds": {}, "marker": f"solve {k:02d}"}, solution,
                          status="optimal", objective=solution["objective"]["value"])
    close_kept()
    data = bytearray(store.read_bytes())
    last = data.index(b"solve 11") // _page(data) * _page(data)
    data[last:last + _page(data)] = bytes(_page(data))
    store.write_bytes(bytes(data))
    assert main(["runs", "export", "-o", str(tmp_path / "rescued.csv"), "--store", str(store)]) == 0
    out, err = capsys.readouterr()
    rescued = pd.read_csv(tmp_path / "rescued.csv")
    assert 21 <= len(rescued) < 33 and rescued["id"].tolist() == list(range(1, len(rescued) + 1)), out
    assert f"nothing after run {len(rescued)} could be read" in out and err == "", (out, err)
    assert main(["runs", "export", "-o", str(tmp_path / "all.csv"), "--store", str(good_store)]) == 0
    assert capsys.readouterr().out.strip().endswith("21 runs written to " + str(tmp_path / "all.csv"))


def test_a_run_whose_text_is_no_utf8_is_named_and_nothing_of_it_printed(good_store, tmp_path, capsys):
    # damaged bytes (a terminal escape, a byte no UTF-8 text has) in a run's outputs: the run is named as damaged
    # in one printable line, skipped by the export, and a resume stops at it
    with closing(sqlite3.connect(good_store)) as db:
        (run,) = db.execute("SELECT id FROM runs WHERE point = 0").fetchone()  # the sweep's first point: a row
    store = _tampered(good_store, tmp_path,
                      f"UPDATE runs SET outputs = CAST(x'7b0a1b5b33316d4641494c0d0aff' AS TEXT) WHERE id = {run}")
    for argv, code in ((["runs", "show", str(run)], 2), (["runs", "export", "-o", str(tmp_path / "r.csv")], 0),
                       (RESUME, 2)):
        found, out, err = _command(capsys, argv, store)
        text = out + err
        assert found == code, text
        assert "\x1b" not in text and "\r" not in text and text.count("\n") == 1, text
        assert (f"run {run} is damaged (its outputs are not JSON)" in err) if code else "1 damaged runs" in out, text


@pytest.mark.parametrize("table, held", [("sweeps", None), ("runs", 0)])
def test_a_sweep_the_store_refuses_counts_every_point_not_recorded(table, held, tmp_path, capsys):
    # a write that fails (here a trigger): the sweep's own row, or its points; the summary counts the points
    store = tmp_path / "runs.sqlite"
    assert main(["solve", CASE, "--store", str(store)]) == 0
    with sqlite3.connect(store) as db:
        db.execute(f"CREATE TRIGGER refuse BEFORE INSERT ON {table} BEGIN SELECT RAISE(ABORT, 'refused'); END")
    capsys.readouterr()
    code, out, err = _command(capsys, SWEEP, store)
    assert code == 0, err
    assert "20 points not recorded" in out and err.count("warning: not recorded") == 1, (out, err)
    assert ("recorded as sweep" not in out) and ((f"holds {held} of its 20 points" in out) == (held is not None))


# --- a store cut off while it was created, an older one, another program's --------------------------------------------
def _store_with(folder: Path, sql: str) -> Path:
    """A new run store in ``folder`` with the SQL statements ``sql`` run on it."""
    store = folder / "runs.sqlite"
    store.write_bytes(store_with(sql))
    return store


@pytest.mark.parametrize("name", PARTIAL_SQL)
def test_a_partial_store_is_completed_when_opened(name, tmp_path, capsys):
    store = _store_with(tmp_path, PARTIAL_SQL[name])
    code, out, err = _command(capsys, ["runs", "list"], store)
    assert code == 0 and err == "" and "(none)" in out, err
    code, out, err = _command(capsys, ["solve", CASE], store)
    assert code == 0 and err == "" and "status: optimal" in out, err
    with closing(sqlite3.connect(store)) as db:
        found = Schema.of(db)
    assert found.missing == "" and not found.foreign
    code, out, err = _command(capsys, ["runs", "list"], store)
    assert code == 0 and " solve " in out, err


@pytest.mark.parametrize("name", FOREIGN_SQL)
def test_another_programs_database_is_refused_untouched(name, tmp_path, capsys):
    store = _store_with(tmp_path, FOREIGN_SQL[name])
    before = store.read_bytes()
    code, _, err = _command(capsys, ["runs", "list"], store)
    assert code == 2 and err.startswith(f"error: --store: {store}: is an SQLite database but not a clutchopt run "
                                        "store (its tables: "), err
    code, out, err = _command(capsys, ["solve", CASE], store)
    assert code == 0 and "status: optimal" in out and err.startswith("warning: this run will not be recorded"), err
    assert store.read_bytes() == before and not Path(f"{store}-wal").exists()


@pytest.mark.parametrize("kib", [16, 48, 112])
def test_a_store_cut_off_by_a_file_size_limit_heals(kib, tmp_path, capsys):
    # ulimit -f: the creation (or the points) cannot be written; the schema is there whole or not at all, and the
    # next command records
    store = tmp_path / "runs.sqlite"
    sweep = f"{shlex.quote(sys.executable)} -m clutchopt sweep {shlex.quote(CASE)} --vary speed=800,900 --quiet"
    result = subprocess.run(["bash", "-c", f"ulimit -f {kib}; exec {sweep} --store {shlex.quote(str(store))}"],
                            capture_output=True, text=True, timeout=120, env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert result.returncode == 0 and "2 optimal" in result.stdout, result.stderr
    assert result.stderr.count("warning:") <= 1 and "Traceback" not in result.stderr, result.stderr
    if store.exists():
        with closing(sqlite3.connect(store)) as db:
            found = Schema.of(db)
        assert not found.tables or found.missing == "", found
    code, out, err = _command(capsys, ["solve", CASE], store)
    assert code == 0 and err == "" and "status: optimal" in out, err
    code, out, err = _command(capsys, ["runs", "list"], store)
    assert code == 0 and " solve " in out, err


def test_a_partial_store_that_cannot_be_written_names_the_command_that_completes_it(shared_folder, tmp_path):
    store = _store_with(shared_folder, PARTIAL_SQL["only-sweeps"])  # a WAL store in a folder the user cannot write
    before = store.read_bytes()
    code, text = _as_a_user(["runs", "list", "--store", str(store)], tmp_path)
    assert code == 2 and text == (
        f"error: --store: {store}: its run store schema is incomplete (no runs table, no templates table, no "
        "runs_by_kind index) and cannot be completed here (attempt to write a readonly database); whoever may write "
        f"it completes it with 'clutchopt runs list --store {store}'\n"), text
    assert store.read_bytes() == before
    assert main(["runs", "list", "--store", str(store)]) == 0  # its owner
    code, text = _as_a_user(["runs", "list", "--store", str(store)], tmp_path)
    assert code == 0 and "(none)" in text, text
