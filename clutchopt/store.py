"""The run store: every solve, sweep point and simulation recorded in SQLite (an OpenMDAO-like recorder).

One database file (default ``./clutchopt-runs.sqlite``, or ``$CLUTCHOPT_STORE``), WAL mode so readers never
block the writer, one transaction per recorded run (a window of sweep points in one) so a killed sweep loses at most
the points in flight. Each run keeps its inputs (all case values, SI), its outputs (the solution as JSON; a batched
sweep point's compact, beside its window's template: ``clutchopt.records``), status, objective with its unit and
the versions of clutchopt and its solvers. A sweep is a row in ``sweeps``; its points are runs with a point
index, unique per sweep, so a resumed sweep cannot record a point twice (two resumes of one sweep running at
once both finish; the point solved twice is stored once).

What can go wrong with the file, and what happens:
- another process is writing: each write waits for the lock (up to ``BUSY_TIMEOUT_S``), then succeeds;
- the file or its folder cannot be written, the disk is full, the lock never comes: the run's result is still
  printed, and one warning says what was not recorded (``RunStore.failure``); nothing is lost half-written;
- the creation is cut off (a full disk, a file-size limit, a kill): the schema is created in one transaction, all
  of it or none; a store with part of it (ours only) is completed when opened, or where it cannot be written
  refused with the command that completes it;
- the file is damaged (``PRAGMA quick_check`` on open) or is not a run store: one ``StoreError`` line with the
  way out (another ``--store``; ``clutchopt runs export`` saves what can still be read). The check reads the whole
  file (about 0.25 ms a MB), so a store opened for recording is checked only up to ``QUICK_CHECK_BYTES``; a larger
  one is checked when read (``runs list``, ``runs show``), and a write that meets damage is not recorded (the
  warning above).
"""

from __future__ import annotations

import hashlib
import json
import os
import platform
import sqlite3
import stat
import time
import warnings
from dataclasses import dataclass
from datetime import datetime, timezone
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Callable

from clutchopt.errors import InputError
from clutchopt.files import status
from clutchopt.records import NOMINAL, TEMPLATE, check_solution, design_inputs, expand, is_compact, method_of

DEFAULT_STORE = "clutchopt-runs.sqlite"
STORE_ENV = "CLUTCHOPT_STORE"
BUSY_TIMEOUT_S = 60.0  # a write waits this long for another writer's lock (each holds it for one run or window)
LARGEST_ID = 2**63 - 1  # SQLite's INTEGER
PAGE_BYTES = 16384  # a new store's page: a run's row (2-8 kB) in one page, where 4 kB pages chained overflow pages
# (inserting a window of 1000 sweep points took 3x as long)
QUICK_CHECK_BYTES = 32 << 20  # stores opened for recording are checked on open up to this size (8 ms)
ROW_BYTES = 64  # fewer than any run's row takes in the file (its versions alone take more)
RESCUE_PROBE = 1000  # ids tried past the largest known before a rescue stops (a damaged last page hides it)
TEMPLATES_KEPT = 64  # templates a store keeps in memory once read (a window's is a few kB; a damaged one may be huge)
CAPPED_SUFFIX = "_capped"  # the mode of a Pareto point's formulation: the user's mode with a cost cap

_SCHEMA = """
CREATE TABLE IF NOT EXISTS sweeps (
    id INTEGER PRIMARY KEY, key TEXT NOT NULL, case_path TEXT, coupling TEXT, mode TEXT, objective TEXT,
    spec TEXT NOT NULL, points INTEGER NOT NULL, created TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS runs (
    id INTEGER PRIMARY KEY, kind TEXT NOT NULL, sweep_id INTEGER REFERENCES sweeps(id), point INTEGER,
    case_path TEXT, title TEXT, coupling TEXT, mode TEXT, objective_name TEXT, status TEXT, objective REAL,
    inputs TEXT NOT NULL, outputs TEXT NOT NULL, versions TEXT NOT NULL, created TEXT NOT NULL,
    objective_unit TEXT, method TEXT, UNIQUE (sweep_id, point));
CREATE INDEX IF NOT EXISTS runs_by_kind ON runs (kind);
CREATE TABLE IF NOT EXISTS templates (key TEXT PRIMARY KEY, body TEXT NOT NULL);
"""  # templates: a window's shared part of its compact sweep points (clutchopt.records)
ADDED_COLUMNS = {"runs": {"objective_unit": "TEXT", "method": "TEXT"}}  # columns newer than their table: a store
# of an older clutchopt lacks them, and gets them when opened for recording (read as NULL from one opened to read,
# and filled from the run's outputs where they say)

LIST_COLUMNS = ("id", "kind", "sweep_id", "point", "created", "coupling", "mode", "method", "objective_name", "status",
                "objective", "objective_unit", "case_path")
_SQLITE_HEADER = b"SQLite format 3\x00"


def default_path() -> str:
    return os.environ.get(STORE_ENV) or DEFAULT_STORE


def shown_mode(mode: str | None) -> str:
    """The mode as the user asked for it: ``geometry_capped`` (a Pareto point) is ``geometry (cost cap)``."""
    mode = mode or ""
    return f"{mode.removesuffix(CAPPED_SUFFIX)} (cost cap)" if mode.endswith(CAPPED_SUFFIX) else mode


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


@lru_cache(maxsize=1)
def _versions_json() -> str:
    return json.dumps(versions())


RECORD = ("INSERT INTO runs (kind, sweep_id, point, case_path, title, coupling, mode, objective_name, status,"
          " objective, objective_unit, method, inputs, outputs, versions, created)"
          " VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?) ON CONFLICT (sweep_id, point) DO NOTHING")


def _to_json(value) -> str:
    from clutchopt.output import to_json

    return to_json(value, None)


def _from_json(text: str):
    from clutchopt.output import from_json

    return from_json(text)


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


def spec_key(spec: dict) -> str:
    """A stable hash of what defines a sweep (case values, grid, mode, objective): the resume key."""
    return hashlib.sha256(json.dumps(spec, sort_keys=True, default=str).encode()).hexdigest()


def nested(data, *keys):
    """``data[k1][k2]...``, None where a level is missing or no mapping."""
    for key in keys:
        data = data.get(key) if isinstance(data, dict) else None
    return data


class StoreError(InputError):
    """The run store cannot be used as asked; the message says why and what to do instead."""

    def __init__(self, path: str, problem: str, way_out: str = ""):
        super().__init__("--store", f"{path}: {problem}" + (f"; {way_out}" if way_out else ""))


def _rescue(path: str) -> str:
    return (f"record elsewhere with --store OTHER.sqlite, and save what can still be read with "
            f"'clutchopt runs export --store {path} -o rescued.csv'")


def _size(path: str) -> int:
    try:
        return os.path.getsize(path)
    except OSError:
        return 0


def _text(data: bytes) -> str:
    return data.decode("utf-8", "replace")


def _printable(detail: object, limit: int = 160) -> str:
    """SQLite's message, as one short line of printable text (it may quote a damaged cell: control characters,
    terminal escapes, kilobytes of it)."""
    text = "".join(c if c.isprintable() else "?" for c in str(detail).strip().split("\n")[0])
    return text if len(text) <= limit else text[:limit] + "..."


@lru_cache(maxsize=1)
def _our_schema() -> "Schema":
    """The run store's schema as :data:`_SCHEMA` creates it."""
    db = sqlite3.connect(":memory:")
    try:
        db.executescript(_SCHEMA)
        return Schema.of(db)
    finally:
        db.close()


@dataclass(frozen=True)
class Schema:
    """What an SQLite file holds of the run store's schema: its tables with their columns, and its indexes
    (SQLite's own left out)."""

    tables: dict[str, frozenset[str]]
    indexes: frozenset[str]

    @classmethod
    def of(cls, db: sqlite3.Connection) -> "Schema":
        def named(kind: str) -> list[str]:
            return [row[0] for row in db.execute(
                "SELECT name FROM sqlite_master WHERE type = ? AND name NOT LIKE 'sqlite\\_%' ESCAPE '\\'", (kind,))]

        return cls({table: frozenset(row[0] for row in db.execute("SELECT name FROM pragma_table_info(?)", (table,)))
                    for table in named("table")}, frozenset(named("index")))

    def _fits(self, table: str) -> bool:
        """Whether a table of one of our names is ours: our columns, save those added since (ADDED_COLUMNS)."""
        ours = _our_schema().tables[table]
        return self.tables[table] <= ours and ours - self.tables[table] <= ADDED_COLUMNS.get(table, {}).keys()

    @property
    def readable(self) -> bool:
        return {"runs", "sweeps"} <= self.tables.keys()

    @property
    def foreign(self) -> bool:
        """Whether the file is another program's database: a table of one of our names is not ours, or tables of
        other names stand where ours are missing (beside a whole store of ours, they are kept)."""
        ours = _our_schema().tables
        return (any(not self._fits(table) for table in self.tables.keys() & ours.keys())
                or (bool(self.tables.keys() - ours.keys()) and not self.readable))

    @property
    def columns(self) -> list[tuple[str, str, str]]:
        """(table, column, type) of each column a table of an older store lacks."""
        return [(table, column, kind) for table, added in ADDED_COLUMNS.items() if table in self.tables
                for column, kind in added.items() if column not in self.tables[table]]

    @property
    def missing(self) -> str:
        """What the store lacks of its schema, in words ("" if nothing)."""
        ours = _our_schema()
        parts = [f"no {name} table" for name in sorted(ours.tables.keys() - self.tables.keys())]
        parts += [f"no {name} index" for name in sorted(ours.indexes - self.indexes)]
        parts += [f"no {table}.{column} column" for table, column, _ in self.columns]
        return ", ".join(parts)


class RunStore:
    """An open store. ``with RunStore(path) as store:`` closes it afterwards.

    ``writable``: the store is for recording (created if missing, its folder and file must be writable);
    otherwise it is only read (never created, read-only files and folders are fine; one cut off while it was
    created is completed, as it could not be read). ``check``: run SQLite's ``quick_check`` on open and refuse a
    damaged file (``runs export`` opens without it to rescue what it can; a store for recording larger than
    QUICK_CHECK_BYTES is not checked).
    ``warn`` receives the one message about runs that could not be recorded (default: a Python warning).
    """

    def __init__(self, path: str | Path | None = None, *, writable: bool = True, check: bool = True,
                 warn: Callable[[str], None] | None = None):
        self.path = str(path or default_path())
        self.writable, self.checked = writable, check
        self.failure: str | None = None  # why recording stopped; runs after it were not recorded
        self.unrecorded = 0
        self._templates: dict[str, dict | None] = {}  # read so far, by key (None: missing or not JSON)
        self._warn = warn or (lambda text: warnings.warn(text, RuntimeWarning, stacklevel=3))
        size = self._check_file()
        self._db = self._connect()
        self._db.text_factory = _text  # a damaged cell's bytes are no UTF-8: its JSON fails, named by its run
        try:
            self._prepare()
            if check and (not writable or size <= QUICK_CHECK_BYTES):
                self._quick_check()
        except BaseException:
            self._db.close()
            raise
        self._db.row_factory = sqlite3.Row

    # --- opening ------------------------------------------------------------------------------------------------
    def _check_file(self) -> int:
        """What can be said before SQLite opens the file: its kind, its header, whether it may be written; its size
        in bytes (0 if there is none yet)."""
        path = Path(self.path)
        try:
            found = status(path, "--store")
        except InputError as exc:
            raise StoreError(self.path[:200], exc.problem, "give another file name with --store") from None
        if found is not None:
            mode = found.st_mode
            if not stat.S_ISREG(mode):
                raise StoreError(self.path, "is not a regular file (a folder or a device)",
                                 "give a file name with --store")
            with open(path, "rb") as handle:
                header = handle.read(len(_SQLITE_HEADER))
            if header and header != _SQLITE_HEADER[:len(header)]:
                raise StoreError(self.path, "is not an SQLite database (perhaps another file given as --store)",
                                 "give a run store with --store, or a new file name to start one")
            if self.writable and not os.access(path, os.W_OK):
                raise StoreError(self.path, "the file is read-only", "record elsewhere with --store OTHER.sqlite")
        elif not self.writable:
            raise StoreError(self.path, "no such run store (nothing has been recorded here yet)",
                             "name the store with --store or $CLUTCHOPT_STORE")
        folder = path.parent if str(path.parent) else Path(".")
        if self.writable and not folder.is_dir():
            raise StoreError(self.path, f"the folder {str(folder)!r} does not exist",
                             "record elsewhere with --store OTHER.sqlite")
        if self.writable and not os.access(folder, os.W_OK | os.X_OK):
            raise StoreError(self.path, f"the folder {str(folder)!r} is not writable (SQLite keeps its journal "
                                        "beside the store)", "record elsewhere with --store OTHER.sqlite")
        return found.st_size if found is not None else 0

    def _connect(self) -> sqlite3.Connection:
        db = None
        try:
            db = sqlite3.connect(self.path, timeout=BUSY_TIMEOUT_S)
            db.execute("SELECT COUNT(*) FROM sqlite_master").fetchone()
            return db
        except sqlite3.OperationalError as exc:
            if db is not None:
                db.close()
            if self.writable or not ("unable to open" in str(exc) or "readonly" in str(exc)):
                raise self._damaged(exc) from None
        except sqlite3.DatabaseError as exc:
            if db is not None:
                db.close()
            raise self._damaged(exc) from None
        # read only: a WAL store in a read-only folder cannot get its shared-memory file; read it as immutable
        uri = Path(self.path).resolve().as_uri() + "?immutable=1"
        return sqlite3.connect(uri, uri=True, timeout=BUSY_TIMEOUT_S)

    def _prepare(self) -> None:
        """WAL mode, the schema (new store) and its newer columns (store of an older clutchopt), when writable;
        refuse an SQLite database of another program. Two processes opening a new store at once can meet SQLite's
        immediate 'database is locked' (switching to WAL takes the file alone, without the busy handler): wait and
        try again, up to BUSY_TIMEOUT_S."""
        deadline = time.monotonic() + BUSY_TIMEOUT_S
        while True:
            try:
                return self._prepare_once()
            except StoreError as error:
                if "stayed locked" not in str(error) or time.monotonic() > deadline:
                    raise
                time.sleep(0.05)

    def _prepare_once(self) -> None:
        try:
            found = Schema.of(self._db)
            if found.foreign:
                raise StoreError(self.path, f"is an SQLite database but not a clutchopt run store (its tables: "
                                            f"{', '.join(sorted(found.tables))})", "give a run store with --store")
            if not self.writable:
                if not found.tables:
                    raise StoreError(self.path, "is empty: nothing has been recorded in it yet")
                if not found.readable:  # cut off while it was created: completed even to be read
                    self._complete(found)
                return
            if not found.tables:  # set before the first write; a store of an older clutchopt keeps its pages
                self._db.execute(f"PRAGMA page_size={PAGE_BYTES}")
            self._db.execute("PRAGMA journal_mode=WAL")
            self._db.execute("PRAGMA synchronous=NORMAL")
            if found.missing:
                self._complete(found)
        except sqlite3.DatabaseError as exc:
            raise self._damaged(exc) from None

    def _complete(self, found: Schema) -> None:
        """Create what the store lacks of its schema in one transaction, all of it or (on any error) none: a new
        store's tables and index, the rest of one cut off while it was created, an older store's newer columns."""
        added = "".join(f"ALTER TABLE {table} ADD COLUMN {column} {kind};" for table, column, kind in found.columns)
        try:
            self._db.executescript(f"BEGIN IMMEDIATE;{_SCHEMA}{added}COMMIT;")
        except sqlite3.DatabaseError as exc:
            if self._db.in_transaction:
                self._db.rollback()
            if "locked" in str(exc) or "busy" in str(exc):
                raise  # waited for, then tried again (_prepare)
            if not found.tables:
                raise StoreError(self.path, f"the run store cannot be created ({_printable(exc)})",
                                 "record elsewhere with --store OTHER.sqlite") from None
            raise StoreError(self.path, f"its run store schema is incomplete ({found.missing}) and cannot be "
                                        f"completed here ({_printable(exc)})",
                             f"whoever may write it completes it with 'clutchopt runs list --store {self.path}'") \
                from None

    def _columns(self) -> set[str]:
        return {row[1] for row in self._db.execute("PRAGMA table_info(runs)")}

    def _quick_check(self) -> None:
        try:
            found = [row[0] for row in self._db.execute("PRAGMA quick_check")]
        except sqlite3.DatabaseError as exc:
            raise self._damaged(exc) from None
        if found != ["ok"]:
            raise self._damaged(found[0])

    def _damaged(self, detail: object) -> StoreError:
        text = _printable(detail)
        if "locked" in text or "busy" in text:
            return StoreError(self.path, f"stayed locked by another process for {BUSY_TIMEOUT_S:g} s ({text})",
                              "try again when the other clutchopt has finished, or record elsewhere with --store")
        if "readonly" in text or "unable to open" in text:
            return StoreError(self.path, f"cannot be opened for writing ({text})",
                              "record elsewhere with --store OTHER.sqlite")
        if not self.checked:  # opened to rescue what it can (runs export)
            return StoreError(self.path, f"nothing can be read ({text})", "record elsewhere with --store")
        return StoreError(self.path, f"the run store is damaged ({text})", _rescue(self.path))

    def __enter__(self) -> "RunStore":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        self._db.close()

    # --- writing: one transaction each; a failing store is reported once and the run goes on --------------------
    def _write(self, sql: str, args: tuple, runs: int = 1) -> int | None:
        """Execute one INSERT (of ``runs`` runs) in its own transaction; the new row's id, or None if it was not
        recorded."""
        cursor = self._transaction(lambda db: db.execute(sql, args), runs)
        return int(cursor.lastrowid) if cursor is not None and cursor.rowcount else None

    def _write_many(self, sql: str, rows: list[tuple], templates: dict[str, dict]) -> int:
        """Execute one INSERT per row, all in one transaction with the templates they use (those not yet stored);
        how many rows it inserted."""
        def execute(db: sqlite3.Connection) -> sqlite3.Cursor:
            if templates:
                db.executemany("INSERT OR IGNORE INTO templates (key, body) VALUES (?, ?)",
                               [(key, _to_json(body)) for key, body in templates.items()])
            return db.executemany(sql, rows)

        cursor = self._transaction(execute, len(rows))
        return max(cursor.rowcount, 0) if cursor is not None else 0

    def _transaction(self, execute, rows: int) -> sqlite3.Cursor | None:
        """``execute(connection)`` in one transaction; None if the store has failed, now (reported once) or before,
        and ``rows`` more runs were not recorded."""
        if self.failure is None:
            try:
                with self._db:
                    return execute(self._db)
            except sqlite3.Error as exc:
                self.failure = str(self._damaged(exc)).removeprefix("--store: ")
                self._warn(f"not recorded: {self.failure}")
        self.unrecorded += rows
        return None

    def new_sweep(self, spec: dict, points: int, case_path: str = "") -> int | None:
        """The new sweep's id (None if it was not recorded: its points will not be, and count as not recorded)."""
        return self._write(
            "INSERT INTO sweeps (key, case_path, coupling, mode, objective, spec, points, created) "
            "VALUES (?, ?, ?, ?, ?, ?, ?, ?)",
            (spec_key(spec), case_path, spec.get("coupling"), spec.get("mode"), spec.get("objective"),
             json.dumps(spec, default=str), points, _now()), runs=0)

    def record(self, kind: str, inputs: dict, outputs: dict, **where) -> int | None:
        """Record one run (solve, sweep point, pareto point, simulation) in its own transaction (see
        :meth:`record_many` for ``where``). Returns the run's id, or None if it was not recorded (already there, or
        the store failed: ``failure``)."""
        return self._write(RECORD, self._row(kind, inputs, outputs, _now(), **where))

    def record_many(self, runs: list[tuple[str, dict, dict, dict]], templates: dict[str, dict] | None = None) -> int:
        """Record runs ``(kind, inputs, outputs, where)`` in one transaction (a window of sweep points: all land or
        none). ``where``: status, objective, objective_unit, method, case_path, title, coupling, mode,
        objective_name, sweep_id, point. Outputs may be compact records (``clutchopt.records``) whose ``templates``
        are given by key; they are read back in full. A sweep point already stored (another process resuming the
        same sweep solved it too) is kept as it is. Returns how many were recorded."""
        created = _now()  # one transaction: one moment
        return self._write_many(RECORD, [self._row(kind, inputs, outputs, created, **where)
                                         for kind, inputs, outputs, where in runs], templates or {})

    @staticmethod
    def _row(kind: str, inputs: dict, outputs: dict, created: str, *, status: str | None = None,
             objective: float | None = None, objective_unit: str = "", method: str | None = None,
             case_path: str = "", title: str = "", coupling: str = "", mode: str = "", objective_name: str = "",
             sweep_id: int | None = None, point: int | None = None) -> tuple:
        return (kind, sweep_id, point, case_path, title, coupling, mode, objective_name, status, objective,
                objective_unit, method, _to_json(inputs), _to_json(outputs), _versions_json(), created)

    def record_solution(self, kind: str, case, solution, outputs: dict | None = None, method: str = NOMINAL,
                        **where) -> int | None:
        """Record a solved case: inputs are all its SI values (:func:`design_inputs`), outputs the solution's JSON
        (``outputs``, if given: a design's with its choice and robust result, its corners, samples and simulated
        starts); ``method``: how it was designed (nominal, worst-case, chance=P); ``where`` may name the mode as
        recorded (a Pareto point's, ``geometry_capped``)."""
        return self.record(kind, design_inputs(case, case.values, method), outputs or solution.as_dict(),
                           method=method, status=solution.status, objective=solution.objective,
                           objective_unit=solution.objective_unit, case_path=case.path, title=case.title,
                           coupling=case.coupling, mode=where.pop("mode", solution.mode),
                           objective_name=solution.objective_name, **where)

    # --- reading: a damaged file is a StoreError with the way out -------------------------------------------------
    def _read(self, sql: str, args: tuple | list = ()) -> list[sqlite3.Row]:
        try:
            return self._db.execute(sql, args).fetchall()
        except sqlite3.DatabaseError as exc:
            raise self._damaged(exc) from None

    def latest_sweep(self, spec: dict) -> int | None:
        """The most recent sweep with exactly this specification (for ``--resume``)."""
        rows = self._read("SELECT id FROM sweeps WHERE key = ? ORDER BY id DESC LIMIT 1", (spec_key(spec),))
        return int(rows[0]["id"]) if rows else None

    def sweep_outputs(self, sweep_id: int, points: list[dict[str, float]]) -> dict[int, dict]:
        """The stored solutions of a sweep by point index; ``points``: the sweep's varied values (SI) at each point.
        A run that is not one of these points with these values (a damaged point number or index, which
        ``quick_check`` does not see) is damaged: StoreError."""
        stored = {}
        for point, run_id, outputs, inputs in self._read(
                "SELECT point, id, outputs, inputs FROM runs WHERE sweep_id = ?", (sweep_id,)):
            values = self._json(inputs, run_id, "inputs")
            values = values.get("values") if isinstance(values, dict) else None
            if not (type(point) is int and 0 <= point < len(points) and isinstance(values, dict)
                    and all(values.get(name) == value for name, value in points[point].items())):
                raise StoreError(self.path, f"run {run_id} is damaged (its point number or inputs are not one of its "
                                            "sweep's points)", _rescue(self.path))
            stored[point] = self._outputs(outputs, run_id, "sweep")
        return stored

    def _json(self, text: str, run_id: int, column: str):
        try:
            return _from_json(text)
        except (TypeError, ValueError, RecursionError):
            raise StoreError(self.path, f"run {run_id} is damaged (its {column} are not JSON)",
                             _rescue(self.path)) from None

    def _outputs(self, text: str, run_id: int, kind: str) -> dict:
        """A run's outputs in full (a compact sweep point's expanded with its template), a solution's checked for
        the shape that tables and exports read."""
        outputs = self._json(text, run_id, "outputs")
        try:
            if is_compact(outputs):
                template = self._template(str(outputs[TEMPLATE]))
                if template is None:
                    raise ValueError("its template is missing or not JSON")
                outputs = expand(outputs, template)
            return outputs if kind == "simulation" else check_solution(outputs)
        except (KeyError, IndexError, TypeError, ValueError, AttributeError) as exc:
            problem = str(exc) if isinstance(exc, ValueError) and str(exc).startswith("its ") else \
                "its outputs do not fit their template"
            raise StoreError(self.path, f"run {run_id} is damaged ({problem})", _rescue(self.path)) from None

    def _template(self, key: str) -> dict | None:
        """A compact record's template (None if missing or not JSON), read once: the last TEMPLATES_KEPT are kept."""
        if key not in self._templates:
            rows = self._read("SELECT body FROM templates WHERE key = ?", (key,)) if self._has_templates() else []
            try:
                template = _from_json(rows[0][0]) if rows else None
            except (TypeError, ValueError, RecursionError):
                template = None
            if len(self._templates) >= TEMPLATES_KEPT:
                self._templates.pop(next(iter(self._templates)))
            self._templates[key] = template
        return self._templates[key]

    def _has_templates(self) -> bool:
        return bool(self._read("SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'templates'"))

    def runs(self, kind: str | None = None, sweep_id: int | None = None, limit: int | None = None) -> list[dict]:
        """Runs, newest first, without their JSON bodies; ``objective_unit`` and ``method`` filled for runs of older
        versions (from their outputs, where they say)."""
        present = self._columns()
        columns = [c if c not in ADDED_COLUMNS["runs"] or c in present else f"NULL AS {c}" for c in LIST_COLUMNS]
        query = f"SELECT {', '.join(columns)} FROM runs"
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
        listed = [dict(row) for row in self._read(query, args)]
        for run in listed:
            unit = run["objective_unit"] is None and run["objective"] is not None
            if (unit or run["method"] is None) and run["kind"] != "simulation":
                outputs = self._older_outputs(run["id"])
                run["method"] = method_of(outputs)
                if unit:
                    run["objective_unit"] = nested(outputs, "objective", "unit") or ""
            elif unit:
                run["objective_unit"] = "s"
        return listed

    def _older_outputs(self, run_id: int):
        """The outputs of a run recorded before the store had the columns it lacks (None where they are no JSON)."""
        rows = self._read("SELECT outputs FROM runs WHERE id = ?", (run_id,))
        try:
            return json.loads(rows[0][0])
        except (ValueError, TypeError, IndexError, RecursionError):
            return None

    def run(self, run_id: int) -> dict:
        if not 0 < run_id <= LARGEST_ID:
            raise InputError("run", f"run ids are whole numbers from 1, got {run_id}")
        rows = self._read("SELECT * FROM runs WHERE id = ?", (run_id,))
        if not rows:
            raise InputError("run", f"no run {run_id} in {self.path}")
        entry = dict(rows[0])
        for name in ("inputs", "versions"):
            entry[name] = self._json(entry[name], run_id, name)
        entry["outputs"] = self._outputs(entry["outputs"], run_id, entry["kind"])
        if entry.get("method") is None and entry["kind"] != "simulation":  # a run of an older version
            entry["method"] = method_of(entry["outputs"])
        return entry

    def readable_runs(self, kind: str | None = None,
                      sweep_id: int | None = None) -> tuple[list[dict], int, int | None]:
        """Every run that can still be read, oldest first, how many could not (a damaged store), and the id after
        which none could be read where the damage hides how many there were (else None). Each run is read on its
        own, so one damaged page loses only the runs on it. The ids are tried up to the largest the table names and
        on until RESCUE_PROBE in a row cannot be read (a damaged or missing last page hides the largest)."""
        try:
            largest = self._db.execute("SELECT MAX(id) FROM runs").fetchone()[0] or 0
        except sqlite3.DatabaseError:
            largest = 0
        largest = min(largest, (_size(self.path) + _size(f"{self.path}-wal")) // ROW_BYTES)  # a damaged largest id
        # cannot set off billions of reads: no row is smaller
        runs, damaged, run_id, missed = [], [], 0, 0
        while run_id < largest or missed < RESCUE_PROBE:
            run_id += 1
            try:
                entry = self.run(run_id)
            except (StoreError, InputError) as exc:  # damaged, or no run with this id (ids are not reused)
                damaged += [run_id] if isinstance(exc, StoreError) else []
                missed += run_id > largest
                continue
            largest, missed = max(largest, run_id), 0
            if (kind is None or entry["kind"] == kind) and (sweep_id is None or entry["sweep_id"] == sweep_id):
                runs.append(entry)
        open_end = largest if damaged and damaged[-1] > largest else None
        return runs, sum(run_id <= largest for run_id in damaged), open_end

    def sweeps(self) -> list[dict]:
        return [dict(row) for row in self._read(
            "SELECT s.id, s.created, s.case_path, s.coupling, s.mode, s.objective, s.points, COUNT(r.id) AS stored "
            "FROM sweeps s LEFT JOIN runs r ON r.sweep_id = s.id GROUP BY s.id ORDER BY s.id DESC")]
