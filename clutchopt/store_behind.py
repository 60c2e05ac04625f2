"""The run store's writes of a sweep's windows done by a thread of its own, one at a time, while the sweep goes on.

A window's transaction (SQLite's insert of its row and the commit that writes its pages to the log: 0.5-0.8 ms for
the wedge's 1000 points, 300 kB) holds no Python lock: in a thread it runs while the next window is solved, or the
sweep's table is built, on another core. One write at a time (:meth:`Behind.submit` waits for the one before), so a
killed sweep loses the window being written and the one being solved, as it lost the one being solved and, killed
inside a commit, the one being written; the store holds whole windows only (SQLite's transactions). The writes of a
process go through one thread (:func:`_writer`, started on first use, again in a forked child).
"""

from __future__ import annotations

import os
from concurrent.futures import Future, ThreadPoolExecutor
from typing import Callable

_executor: list[ThreadPoolExecutor] = []  # the process's writer, once started


def _writer() -> ThreadPoolExecutor:
    if not _executor:  # its thread is waited for when the interpreter exits, before the store's connection closes
        _executor.append(ThreadPoolExecutor(max_workers=1, thread_name_prefix="clutchopt-store-writer"))
    return _executor[0]


class Behind:
    """A store's write under way in the writer thread, if any."""

    def __init__(self):
        self._pending: Future | None = None

    def submit(self, write: Callable[[], object]) -> None:
        """Start ``write()`` in the writer thread once the write before it has ended."""
        self.settle()
        self._pending = _writer().submit(write)

    def settle(self):
        """Wait for the write under way; what it returned (None if none), or what it raised, raised here."""
        pending, self._pending = self._pending, None
        return pending.result() if pending is not None else None


def _forked() -> None:
    """In a forked child: the parent's writer thread is not this process's."""
    _executor.clear()


os.register_at_fork(after_in_child=_forked)
