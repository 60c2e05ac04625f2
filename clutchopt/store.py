"""The run store: every solve, sweep point and simulation recorded in SQLite (an OpenMDAO-like recorder).

One database file (default ``./clutchopt-runs.sqlite``, or ``$CLUTCHOPT_STORE``), WAL mode so readers never
block the writer, one transaction per recorded run so a killed sweep loses at most the point in flight. Each
run keeps its inputs (all case values, SI), its outputs (the solution as JSON), status, objective and the
versions of clutchopt and its solvers. A sweep is a row in ``sweeps``; its points are runs with a point index,
unique per sweep, so a resumed sweep cannot record a point twice.
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import sqlite3
from datetime import datetime, timezone
from functools import lru_cache
from importlib import metadata
from pathlib import Path

from clutchopt.errors import InputError

DEFAULT_STORE = "clutchopt-runs.sqlite"
STORE_ENV = "CLUTCHOPT_STORE"

_SCHEMA = """
CREATE TABLE IF NOT EXISTS sweeps (
    id INTEGER PRIMARY KEY, key TEXT NOT NULL, case_path TEXT, coupling TEXT, mode TEXT, objective TEXT,
    spec TEXT NOT NULL, points INTEGER NOT NULL, created TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY, kind TEXT NOT NULL, sweep_id INTEGER REFERENCES sweeps(id), point INTEGER,
    case_path TEXT, title TEXT, coupling TEXT, mode TEXT, objective_name TEXT, status TEXT, objective REAL,
    inputs TEXT NOT NULL, outputs TEXT NOT NULL, versions TEXT NOT NULL, created TEXT NOT NULL,
    UNIQUE (sweep_id, point));
CREATE INDEX IF NOT EXISTS runs_by_kind ON runs (kind);
"""

LIST_COLUMNS = ("id", "kind", "sweep_id", "point", "created", "coupling", "mode", "objective_name", "status",
                "objective", "case_path")


def default_path() -> str:
    return os.environ.get(STORE_ENV) or DEFAULT_STORE


@lru_cache(maxsize=1)
def versions() -> dict[str, str]:
    """Versions that decide a result: clutchopt, its solver stack, Python."""
    found = {"python": platform.python_version()}
    for package in ("clutchopt", "casadi", "numpy", "scipy"):
        try:
            found[package] = metadata.version(package)
        except metadata.PackageNotFoundError:
            found[package] = "not installed"
    return found


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


def spec_key(spec: dict) -> str:
    """A stable hash of what defines a sweep (case values, grid, mode, objective): the resume key."""
    return hashlib.sha256(json.dumps(spec, sort_keys=True, default=str).encode()).hexdigest()


class RunStore:
    """An open store. ``with RunStore(path) as store:`` closes it afterwards."""

    def __init__(self, path: str | Path | None = None):
        self.path = str(path or default_path())
        try:
            self._db = sqlite3.connect(self.path, timeout=30)
            self._db.execute("PRAGMA journal_mode=WAL")
            self._db.execute("PRAGMA synchronous=NORMAL")
            self._db.executescript(_SCHEMA)
        except sqlite3.DatabaseError as exc:
            raise InputError("--store", f"cannot use {self.path!r} as a run store ({exc})") from None
        self._db.row_factory = sqlite3.Row

    def __enter__(self) -> "RunStore":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        self._db.close()

    # --- writing: one transaction each ---------------------------------------------------------------------------
    def new_sweep(self, spec: dict, points: int, case_path: str = "") -> int:
        with self._db:
            cursor = self._db.execute(
                "INSERT INTO sweeps (key, case_path, coupling, mode, objective, spec, points, created) "
                "VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
                (spec_key(spec), case_path, spec.get("coupling"), spec.get("mode"), spec.get("objective"),
                 json.dumps(spec, default=str), points, _now()))
        return int(cursor.lastrowid)

    def latest_sweep(self, spec: dict) -> int | None:
        """The most recent sweep with exactly this specification (for ``--resume``)."""
        row = self._db.execute("SELECT id FROM sweeps WHERE key = ? ORDER BY id DESC LIMIT 1",
                               (spec_key(spec),)).fetchone()
        return None if row is None else int(row["id"])

    def sweep_outputs(self, sweep_id: int) -> dict[int, dict]:
        """The stored solutions of a sweep by point index."""
        return {row[0]: json.loads(row[1]) for row in
                self._db.execute("SELECT point, outputs FROM runs WHERE sweep_id = ?", (sweep_id,))}

    def record(self, kind: str, inputs: dict, outputs: dict, *, status: str | None = None,
               objective: float | None = None, case_path: str = "", title: str = "", coupling: str = "",
               mode: str = "", objective_name: str = "", sweep_id: int | None = None,
               point: int | None = None) -> int:
        """Record one run (solve, sweep point, pareto point, simulation) in its own transaction."""
        from clutchopt.output import to_json

        with self._db:
            cursor = self._db.execute(
                "INSERT INTO runs (kind, sweep_id, point, case_path, title, coupling, mode, objective_name, status,"
                " objective, inputs, outputs, versions, created) VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (kind, sweep_id, point, case_path, title, coupling, mode, objective_name, status, objective,
                 to_json(inputs), to_json(outputs), json.dumps(versions()), _now()))
        return int(cursor.lastrowid)

    def record_solution(self, kind: str, case, solution, **where) -> int:
        """Record a solved case: inputs are all its SI values, outputs the solution's JSON."""
        return self.record(kind, {"values": case.values, "free": list(case.free), "bounds": case.bounds},
                           solution.as_dict(), status=solution.status, objective=solution.objective,
                           case_path=case.path, title=case.title, coupling=case.coupling, mode=solution.mode,
                           objective_name=solution.objective_name, **where)

    # --- reading -------------------------------------------------------------------------------------------------
    def runs(self, kind: str | None = None, sweep_id: int | None = None, limit: int | None = None) -> list[dict]:
        """Runs, newest first, without their JSON bodies."""
        query = f"SELECT {', '.join(LIST_COLUMNS)} FROM runs"
        where, args = [], []
        if kind:
            where.append("kind = ?"), args.append(kind)
        if sweep_id is not None:
            where.append("sweep_id = ?"), args.append(sweep_id)
        if where:
            query += " WHERE " + " AND ".join(where)
        query += " ORDER BY id DESC" + (" LIMIT ?" if limit else "")
        if limit:
            args.append(limit)
        return [dict(row) for row in self._db.execute(query, args)]

    def run(self, run_id: int) -> dict:
        row = self._db.execute("SELECT * FROM runs WHERE id = ?", (run_id,)).fetchone()
        if row is None:
            raise InputError("run", f"no run {run_id} in {self.path}")
        entry = dict(row)
        for name in ("inputs", "outputs", "versions"):
            entry[name] = json.loads(entry[name])
        return entry

    def flat(self, kind: str | None = None, sweep_id: int | None = None) -> list[dict]:
        """Runs oldest first, flattened for a table: the listed columns, ``input.<name>`` (SI case values),
        ``design.<name>`` (SI) and the active constraints."""
        rows = []
        for run in reversed(self.runs(kind, sweep_id)):
            entry = self.run(run["id"])
            outputs = entry["outputs"]
            row = dict(run)
            row.update({f"input.{k}": v for k, v in entry["inputs"].get("values", {}).items()})
            row.update({f"design.{k}": v for k, v in outputs.get("design", {}).items()})
            row["active"] = " ".join(c["name"] for c in outputs.get("constraints", []) if c.get("active"))
            rows.append(row)
        return rows

    def sweeps(self) -> list[dict]:
        return [dict(row) for row in self._db.execute(
            "SELECT s.id, s.created, s.case_path, s.coupling, s.mode, s.objective, s.points, COUNT(r.id) AS stored "
            "FROM sweeps s LEFT JOIN runs r ON r.sweep_id = s.id GROUP BY s.id ORDER BY s.id DESC")]
