"""Crash files: the full report of an unexpected exception, so that a bug is reported in full while the user
sees one line (``internal error: ... (details in <file>)``, exit code 3).

The file goes to the system's temporary folder (``tempfile.gettempdir()``, e.g. ``/tmp``), named
``clutchopt-crash-<UTC time>-<pid>.txt``; it holds the command line, the working folder, the versions of
clutchopt and its solver stack, and the traceback.
"""

from __future__ import annotations

import os
import tempfile
import traceback
from datetime import datetime, timezone
from pathlib import Path


def write_crash_report(exc: BaseException, argv: list[str]) -> str:
    """Write the report of ``exc``; returns its path, or why it could not be written."""
    from clutchopt.store import versions

    stamp = datetime.now(timezone.utc).strftime("%Y%m%dT%H%M%SZ")
    path = Path(tempfile.gettempdir()) / f"clutchopt-crash-{stamp}-{os.getpid()}.txt"
    try:
        found = versions()
    except Exception as problem:  # the report must not fail on what it only adds
        found = {"versions": f"unknown ({problem!r})"}
    lines = [f"clutchopt internal error at {stamp}", f"command: {' '.join(map(repr, argv))}",
             f"working folder: {os.getcwd()}", *(f"{name}: {version}" for name, version in found.items()), "",
             *traceback.format_exception(exc)]
    try:
        with open(path, "x", encoding="utf-8", errors="backslashreplace") as handle:
            handle.write("\n".join(line.rstrip("\n") for line in lines) + "\n")
    except OSError as problem:
        return f"no crash file: {path} could not be written ({problem.strerror})"
    return str(path)
