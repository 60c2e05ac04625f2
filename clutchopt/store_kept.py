"""The run store's connection kept open from one store to the next of the same file, in one process.

Closing the last connection to a store checkpoints its write-ahead log (two fsyncs) and the next store's first write
starts a new log (two more): 5-20 ms each time, about as long as a 1000-point sweep of the wedge takes, and opening
checks the whole file (``quick_check``, 0.25 ms a MB). A process that records again and again (the Python API, a
notebook, the benchmark) keeps the connection of the store it closed last instead: the next store of the same file
takes it up without opening or checking the file again where no one has changed it since (its size and times, its
log's, and SQLite's count of other connections' changes). The kept connection is closed when another is kept, and
when the process ends: SQLite then folds the log into the file. Until then the log beside the file holds the latest
runs (any reader sees them; a copy of the file alone would not). A checkpoint of this process's own
(``clutchopt.store_checkpoint``) changes the file's size and time, not its log: that alone leaves the store unchanged.
"""

from __future__ import annotations

import atexit
import os
import sqlite3
import threading
from dataclasses import dataclass

from clutchopt.store_checkpoint import ended, wait


@dataclass(frozen=True)
class _Kept:
    """A closed store's connection, kept open: the store's file as it left it (``_stamp``), SQLite's count of
    changes by other connections then (``PRAGMA data_version``), and the checkpoints of this process's that had
    ended then (``clutchopt.store_checkpoint.ended``)."""

    path: str
    connection: sqlite3.Connection
    stamp: tuple
    version: int
    checkpoints: int


_kept: list[_Kept] = []  # at most one: the connection of the writable store closed last in this process
_keeping = threading.Lock()  # stores of several threads
_inherited: list[_Kept] = []  # a forked child's copy of its parent's, never used or closed (SQLite's rule)


def close_kept() -> None:
    """Close the kept connection now (as at the end of the process, or before another is kept): SQLite folds the
    write-ahead log into the store's file."""
    with _keeping:
        closing = _kept[:]
        _kept.clear()
    for kept in closing:
        wait(kept.path)  # then this connection is the store's last: closing it folds the log into the file
        kept.connection.close()


def _stamp(path: str) -> tuple:
    """What changes when anyone writes the store's file or its log: their device, inode, size and time."""
    found = []
    for name in (path, f"{path}-wal"):
        try:
            info = os.stat(name)
            found.append((info.st_dev, info.st_ino, info.st_size, info.st_mtime_ns))
        except OSError:
            found.append(None)
    return tuple(found)


def keep(path: str, connection: sqlite3.Connection) -> None:
    """Keep a closed store's connection (the one kept before is closed)."""
    try:
        checkpoints, _ = ended(path)
        kept = _Kept(os.path.abspath(path), connection, _stamp(path),
                     connection.execute("PRAGMA data_version").fetchone()[0], checkpoints)
    except sqlite3.Error:
        connection.close()
        return
    close_kept()
    with _keeping:
        _kept.append(kept)


def take_kept(path: str) -> tuple[sqlite3.Connection | None, bool]:
    """The kept connection if it is this file's (else None), and whether the store is unchanged since it was kept:
    the same file, of the same size and time, as its log, and no other connection has written it."""
    with _keeping:
        if not _kept or _kept[0].path != os.path.abspath(path):
            return None, False
        kept = _kept.pop()
    stamp = _stamp(path)
    if stamp[0] is None or stamp[0][:2] != kept.stamp[0][:2]:  # another file now has the name
        kept.connection.close()
        return None, False
    try:
        version = kept.connection.execute("PRAGMA data_version").fetchone()[0]
    except sqlite3.Error:
        kept.connection.close()
        return None, False
    return kept.connection, version == kept.version and (stamp == kept.stamp or _checkpointed(kept, stamp))


def _checkpointed(kept: _Kept, stamp: tuple) -> bool:
    """Whether only a checkpoint of this process's has changed the store since it was kept: one under way then or
    since, the same log as then (the store's file the same file: :func:`take_kept` has seen to it; a checkpoint
    writes the log's pages into the file, changing its size and time, and leaves the log as it is)."""
    checkpoints, running = ended(kept.path)
    return (running or checkpoints != kept.checkpoints) and stamp[1] == kept.stamp[1]


def _forked() -> None:
    """In a forked child: the parent's connection set aside, a lock of its own (another thread may have held it)."""
    global _keeping
    _inherited.extend(_kept)
    _kept.clear()
    _keeping = threading.Lock()


atexit.register(close_kept)
os.register_at_fork(after_in_child=_forked)
