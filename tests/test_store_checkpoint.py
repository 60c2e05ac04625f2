"""The run store's log folded into its file by a thread of its own (clutchopt.store_checkpoint), not in a commit."""

import os
import threading
import time

import pytest

from clutchopt import store_checkpoint
from clutchopt.store import RunStore
from clutchopt.store_kept import close_kept

LIMIT = 64 << 10  # a log past 64 kB is folded in (the store's own: 4 MB)
RUN_BYTES = 20_000  # each run's outputs: 20 kB of JSON text, 2 runs a 16 kB page and more


@pytest.fixture
def counted(monkeypatch):
    """The checkpoints started, counted; the log's limit LIMIT."""
    monkeypatch.setattr(store_checkpoint, "CHECKPOINT_BYTES", LIMIT)
    started = []
    checkpoint = store_checkpoint._checkpoint
    monkeypatch.setattr(store_checkpoint, "_checkpoint", lambda path, key: (started.append(path),
                                                                           checkpoint(path, key)))
    yield started
    close_kept()


def _record(store: RunStore, runs: int) -> list[int]:
    """``runs`` runs recorded; the log's size after each."""
    sizes = []
    for k in range(runs):
        assert store.record("simulation", {"values": {}}, {"text": f"{k}x" + "x" * RUN_BYTES}) is not None
        sizes.append(os.path.getsize(f"{store.path}-wal"))
    return sizes


def test_commits_fold_nothing_and_a_thread_keeps_the_log_short(counted, tmp_path):
    # 40 runs of 20 kB (5 pages of 16 kB each in the log): 3.3 MB of log where nothing folds it in (SQLite's own
    # checkpoint comes at 1000 pages, 16 MB). A commit that leaves the log past 64 kB starts a checkpoint in a
    # thread; the first write once all of it is in the file begins the log again, cut to 64 kB: with a pause between
    # runs (the solve of the next points) the log never holds more than a few runs
    path = str(tmp_path / "runs.sqlite")
    with RunStore(path) as store:
        assert store._db.execute("PRAGMA wal_autocheckpoint").fetchone()[0] == 0
        sizes = []
        for k in range(40):
            sizes += _record(store, 1)
            store_checkpoint.wait(path)
    assert sizes[0] == 213_336 and max(sizes) <= 4 * LIMIT < 40 * RUN_BYTES, sizes  # the first: the schema too
    # (13 frames of 16,408 bytes and the log's 32-byte header; the sweep_starts table one of them)
    assert len(counted) >= 10
    close_kept()  # as at the end of the process: the rest of the log folded in, the log gone
    assert not os.path.exists(f"{path}-wal")
    with RunStore(path, writable=False) as store:
        assert len(store.runs()) == 40


def test_a_store_closed_while_its_log_is_folded_in_is_taken_up_unchanged(counted, tmp_path, monkeypatch):
    # a slow disk: the checkpoint takes 0.3 s, still under way when the store is closed. The file it writes is the
    # store as its kept connection left it: the next store takes the connection up with no quick_check; at the end
    # of the process the checkpoint is waited for, then the kept connection closed folds the rest of the log in
    slow = store_checkpoint._checkpoint
    monkeypatch.setattr(store_checkpoint, "_checkpoint", lambda path, key: (time.sleep(0.3), slow(path, key)))
    path = str(tmp_path / "runs.sqlite")
    with RunStore(path) as store:
        _record(store, 1)  # 197 kB of log (the schema and one run): past 64 kB, a checkpoint started
    running = [t for t in threading.enumerate() if t.name == "clutchopt-store-checkpoint"]
    assert len(running) == 1 and running[0].is_alive()
    checks = []
    monkeypatch.setattr(RunStore, "_quick_check", lambda self: checks.append(self.path))
    with RunStore(path) as store:
        _record(store, 1)
    running[0].join()
    assert len(counted) == 1 and os.path.getsize(path) > 16384  # the log's pages written into the file
    with RunStore(path) as store:
        assert [store.run(k)["outputs"]["text"][:2] for k in (1, 2)] == ["0x", "0x"]
    assert checks == []
    later = os.stat(path).st_mtime_ns + 10**9  # the file touched by another while the connection was kept: checked
    os.utime(path, ns=(later, later))
    with RunStore(path) as store:
        pass
    assert checks == [path]
    close_kept()
    assert not os.path.exists(f"{path}-wal")
