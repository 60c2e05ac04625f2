"""The run store's write-ahead log folded into its file by a thread of its own, while the sweep solves on.

SQLite folds the log into the file (a checkpoint) in the commit that takes the log past 1000 pages (16 MB with the
store's pages): it copies them and syncs the log and the file to disk, 50 ms on the benchmark's machine (12 ms of
it CPU), inside the commit of one window of sweep points: about 1 ms a 1000 stored wedge points on average, in
spikes. A writable store's connection does not (``PRAGMA wal_autocheckpoint=0``, :func:`manual`); instead a commit
that leaves the log past ``CHECKPOINT_BYTES`` starts a thread (:func:`note_written`) that opens a connection of its
own and runs a ``PASSIVE`` checkpoint while the next points are solved: it waits for no one and no one waits for it
(writers append to the log meanwhile, a reader keeps its snapshot). The first write that begins once the whole log
is in the file starts the log again from its beginning, and its commit cuts the log's file to ``CHECKPOINT_BYTES``
(``journal_size_limit``), so that the file's size says what the log holds. What a killed process leaves is SQLite's
as ever: the log holds what the file does not yet (a checkpoint cut off is done again). A checkpoint changes the
store's file, not its log: a kept connection (``clutchopt.store_kept``) asks :func:`ended` whether one of ours has
run since it was kept; :func:`wait` waits for one under way (before the process closes its last connection, which
folds the rest of the log in).
"""

from __future__ import annotations

import os
import sqlite3
import threading
from pathlib import Path

CHECKPOINT_BYTES = 16 << 20  # a log this large is folded in (SQLite's own 1000 pages of 16 kB: about 50 windows of 1000
# wedge points; 4 MB took more CPU time on 10,000-point sweeps, 0.830-0.845x the unstored sweep against 0.873-0.876x)
_running: dict[str, threading.Thread] = {}  # the checkpoint under way (or ended last), by the store's absolute path
_ended: dict[str, int] = {}  # how many of a store's checkpoints have ended in this process
_guard = threading.Lock()


def manual(connection: sqlite3.Connection) -> None:
    """A writable store's connection: no checkpoint inside its commits (:func:`note_written` starts them), and its
    log's file cut to CHECKPOINT_BYTES when it begins again."""
    connection.execute("PRAGMA wal_autocheckpoint=0")
    connection.execute(f"PRAGMA journal_size_limit={CHECKPOINT_BYTES}")


def note_written(path: str) -> None:
    """After a commit: start folding the store's log into its file in a thread where the log is past
    CHECKPOINT_BYTES and no checkpoint of it is under way (a thread that cannot be started: here, now)."""
    try:
        if os.path.getsize(f"{path}-wal") <= CHECKPOINT_BYTES:
            return
    except OSError:
        return
    key = os.path.abspath(path)
    with _guard:
        if key in _running and _running[key].is_alive():
            return
        thread = _running[key] = threading.Thread(target=_checkpoint, args=(path, key),
                                                  name="clutchopt-store-checkpoint")
        try:
            thread.start()  # not a daemon: the interpreter waits for it before its exit closes the store
            return
        except RuntimeError:
            del _running[key]
    _checkpoint(path, key)


def ended(path: str) -> tuple[int, bool]:
    """How many checkpoints of the store have ended in this process, and whether one is under way."""
    key = os.path.abspath(path)
    with _guard:
        return _ended.get(key, 0), key in _running and _running[key].is_alive()


def wait(path: str) -> None:
    """Wait for the store's checkpoint under way, if any."""
    with _guard:
        thread = _running.get(os.path.abspath(path))
    if thread is not None:
        thread.join()


def _checkpoint(path: str, key: str) -> None:
    """A PASSIVE checkpoint on a connection of its own; a store that cannot be checkpointed now (another process's
    checkpoint, a lock, a failing disk) is left for the next one, and for the close of the last connection."""
    try:
        connection = sqlite3.connect(f"{Path(path).resolve().as_uri()}?mode=rw", uri=True, timeout=0)  # a store
        # removed meanwhile is not created again
        try:
            connection.execute("PRAGMA wal_checkpoint(PASSIVE)").fetchall()
        finally:
            connection.close()
    except sqlite3.Error:
        pass
    finally:
        with _guard:
            _ended[key] = _ended.get(key, 0) + 1


def _forked() -> None:
    """In a forked child: no checkpoint of the parent's is this process's to wait for, and a lock of its own."""
    global _guard
    _running.clear()
    _ended.clear()
    _guard = threading.Lock()


os.register_at_fork(after_in_child=_forked)
