"""The run store: every solve, sweep point and simulation recorded in SQLite (an OpenMDAO-like recorder).

One database file (default ``./clutchopt-runs.sqlite``, or ``$CLUTCHOPT_STORE``), WAL mode so readers never
block the writer, one transaction per recorded run (a window of sweep points in one) so a killed sweep loses at most
the points in flight. Each run keeps its inputs (all case values, SI), its outputs (the solution as JSON), status,
objective with its unit and the versions of clutchopt and its solvers. A sweep is a row in ``sweeps``; its points
are runs with a point index. The batched points of a window are one row of ``runs`` for each run of consecutive
point indices: their numbers as arrays (``clutchopt.window_records``), beside the template they share (table
``templates``); so are consecutive points solved alone that share a template (``window_records.gathered``: e.g. a
region proof's points without a design; a batched sweep's window hands them over so already, read from their
Solutions: ``window_records.gathered_solutions``). A row's ``run_count`` points have the ids ``id ..`` and the
point indices ``point ..`` onwards, and each is read back as a run of its own, in full. A store of an older
clutchopt (a row per point, a batched one compact: ``clutchopt.records``) is read as it is and gets the newer
columns when first written. A sweep's points are read and written in one transaction, so a resumed sweep cannot
record a point twice (two resumes of one sweep running at once both finish; the point solved twice is stored
once). The connection of a store closed last is kept for the next store of the same file in the process
(``clutchopt.store_kept``).

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
import math
import os
import platform
import sqlite3
import stat
import time
import warnings
from dataclasses import dataclass
from datetime import datetime, timezone
from functools import lru_cache, partial
from importlib import metadata
from pathlib import Path
from typing import Callable, TypeVar

import numpy as np

from clutchopt.errors import InputError
from clutchopt.files import status
from clutchopt.records import (NOMINAL, STATUSES, TEMPLATE, check_solution, design_inputs, expand, is_compact,
                               is_keyed_by, method_of)
from clutchopt.store_checkpoint import manual, note_written
from clutchopt.store_kept import keep, take_kept
from clutchopt.window_records import CHECKSUM, WindowRecords, checksum, gathered, pack, unpack

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
    objective_unit TEXT, method TEXT, run_count INTEGER, window BLOB, UNIQUE (sweep_id, point));
CREATE INDEX IF NOT EXISTS runs_by_kind ON runs (kind);
CREATE TABLE IF NOT EXISTS templates (key TEXT PRIMARY KEY, body TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS sweep_starts (
    sweep_id INTEGER NOT NULL REFERENCES sweeps(id), point INTEGER NOT NULL, body TEXT NOT NULL,
    PRIMARY KEY (sweep_id, point)) WITHOUT ROWID;
"""  # templates: a window's shared part of its compact sweep points (clutchopt.records). A row of runs holds
# run_count runs (NULL: one), ids id .. id + run_count - 1 and sweep points point .. point + run_count - 1: a window's
# batched points, their numbers as arrays in window (clutchopt.window_records; outputs: their layout). sweep_starts:
# what a batched sweep's window starting at a point starts from, recorded with the window before it
# (clutchopt.optimise.batch_carried: a resume goes on from it)
ADDED_COLUMNS = {"runs": {"objective_unit": "TEXT", "method": "TEXT", "run_count": "INTEGER", "window": "BLOB"}}
# columns newer than their table: a store of an older clutchopt lacks them, and gets them when opened for recording
# (read as NULL from one opened to read, and objective_unit and method filled from the run's outputs where they say)

LIST_COLUMNS = ("id", "kind", "sweep_id", "point", "created", "coupling", "mode", "method", "objective_name", "status",
                "objective", "objective_unit", "case_path")
_SQLITE_HEADER = b"SQLite format 3\x00"


T = TypeVar("T")  # what a stored sweep start is read as (RunStore.sweep_start)


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


RECORD = ("INSERT INTO runs (id, kind, sweep_id, point, case_path, title, coupling, mode, objective_name, status,"
          " objective, objective_unit, method, inputs, outputs, versions, created, run_count, window)"
          " VALUES (IFNULL((SELECT id + IFNULL(run_count, 1) FROM runs ORDER BY id DESC LIMIT 1), 1),"  # the next id
          " ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?) ON CONFLICT (sweep_id, point) DO NOTHING")


def _to_json(value) -> str:
    from clutchopt.output import to_json

    return to_json(value, None)


def _from_json(text: str):
    from clutchopt.output import from_json

    return from_json(text)


def _now() -> str:
    return datetime.now(timezone.utc).isoformat(timespec="milliseconds")


def spec_key(spec: dict) -> str:
    """A stable hash of what defines a sweep (case values, grid, mode, objective): the resume key. Its JSON by orjson
    (0.05 ms for 1000 points; what orjson refuses by the standard library, as an older clutchopt hashed every
    sweep: :func:`older_spec_key`)."""
    import orjson

    try:
        return hashlib.sha256(orjson.dumps(spec, default=str, option=orjson.OPT_SORT_KEYS | orjson.OPT_NON_STR_KEYS
                                           | orjson.OPT_SERIALIZE_NUMPY)).hexdigest()
    except orjson.JSONEncodeError:
        return older_spec_key(spec)


def older_spec_key(spec: dict) -> str:
    """The resume key of a sweep an older clutchopt recorded: the hash of the standard library's JSON (0.7 ms for
    1000 points)."""
    return hashlib.sha256(json.dumps(spec, sort_keys=True, default=str).encode()).hexdigest()


def _unstored(db: sqlite3.Connection, sweep_id: int, start: int, stop: int) -> list[tuple[int, int]]:
    """The runs ``(start, stop)`` of the points ``start .. stop - 1`` of a sweep that no row stores yet (rows do not
    overlap: the row of the last point before ``stop`` is the only one that can reach ``start`` unless one lies
    within)."""
    last = db.execute("SELECT point, IFNULL(run_count, 1) FROM runs WHERE sweep_id = ? AND point < ? "
                      "ORDER BY point DESC LIMIT 1", (sweep_id, stop)).fetchone()
    if last is None or last[0] + last[1] <= start:
        return [(start, stop)]
    free, at = [], start  # another process stored some of them
    for point, count in db.execute("SELECT point, IFNULL(run_count, 1) FROM runs WHERE sweep_id = ? AND point < ? "
                                   "AND point + IFNULL(run_count, 1) > ? ORDER BY point", (sweep_id, stop, start)):
        if point > at:
            free.append((at, point))
        at = max(at, point + count)
    return free + [(at, stop)] if at < stop else free


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
        self._templates: dict[str, dict | None] = {}  # read so far, by key (None: missing, not JSON or changed)
        self._warn = warn or (lambda text: warnings.warn(text, RuntimeWarning, stacklevel=3))
        size = self._check_file()
        self._db, unchanged = take_kept(self.path) if writable and check else (None, False)
        self._db = self._db or self._connect()
        self._db.text_factory = _text  # a damaged cell's bytes are no UTF-8: its JSON fails, named by its run
        try:
            if not unchanged:  # a kept connection's store, as this process left it, was prepared and checked then
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
        try:  # a connection may be kept, and taken up by a store of another thread (one at a time)
            db = sqlite3.connect(self.path, timeout=BUSY_TIMEOUT_S, check_same_thread=False)
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
            manual(self._db)  # its log folded into the file by a thread of its own (clutchopt.store_checkpoint)
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
        """Close the store; a writable one's connection is kept for the next store of the file in this process (see
        :func:`clutchopt.store_kept.close_kept`)."""
        if self.writable and self.checked and self.failure is None and not self._db.in_transaction:
            keep(self.path, self._db)
        else:
            self._db.close()

    # --- writing: one transaction each; a failing store is reported once and the run goes on --------------------
    def _write(self, sql: str, args: tuple, runs: int = 1) -> int | None:
        """Execute one INSERT (of ``runs`` runs) in its own transaction; the new row's id, or None if it was not
        recorded."""
        cursor = self._transaction(lambda db: db.execute(sql, args), runs)
        return int(cursor.lastrowid) if cursor is not None and cursor.rowcount else None

    def _transaction(self, execute, rows: int):
        """``execute(connection)`` in one transaction, and what it returns; None if the store has failed, now
        (reported once) or before, and ``rows`` more runs were not recorded."""
        if self.failure is None:
            try:
                with self._db:
                    done = execute(self._db)
                note_written(self.path)  # a log grown large folded into the file while the next points solve
                return done
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
             _to_json(spec), points, _now()), runs=0)

    def record(self, kind: str, inputs: dict, outputs: dict, **where) -> int | None:
        """Record one run (solve, sweep point, pareto point, simulation) in its own transaction. ``where``: status,
        objective, objective_unit, case_path, title, coupling, mode, objective_name, sweep_id, point. Returns the
        run's id, or None if it was not recorded (already there, or the store failed: ``failure``)."""
        return self._write(RECORD, self._row(kind, inputs, outputs, _now(), **where))

    def record_points(self, inputs: dict, where: dict, index: np.ndarray, varied: dict[str, np.ndarray],
                      alone: dict[int, dict], windows: list[tuple[np.ndarray, WindowRecords]],
                      carried: dict | None = None) -> int:
        """Record sweep points in one transaction (a window of them: all land or none). ``index``: their point
        numbers, ``varied``: their values (SI) by name, ``inputs``: what they share (the case's values, free
        variables, bounds), ``where``: the fields of :meth:`record` they share (sweep_id among them). A point solved
        alone (``alone``: its record by position) is a row; the batched points of a window (``windows``: their
        records as arrays, by position) a row for each run of consecutive point numbers, their numbers as arrays
        (``clutchopt.window_records``) beside their template (once per store). A point already stored (another
        process resuming the same sweep solved it too) is kept as it is. Points solved alone one after another that
        share a template (a region proof's points without a design) are a window's too (``window_records.gathered``:
        the numbers of their records, where the arrays keep them bit for bit). ``carried``: what the window after
        these points starts from (``Carried.as_dict()``, its ``point`` the first point after them), recorded with
        them. Returns how many were recorded."""
        created, pieces, templates = _now(), [], {}  # one transaction: one moment
        alone, gathered_windows = gathered(alone)  # (points without a design, one proof: as a window's)
        for position, record in alone.items():
            values = {**inputs["values"], **{name: float(column[position]) for name, column in varied.items()}}
            row = self._row("sweep", {**inputs, "values": values}, record, created, status=record["status"],
                            objective=record["objective"]["value"], point=int(index[position]), **where)
            pieces.append((int(index[position]), 1, lambda start, stop, row=row: row))
        for positions, window in windows + gathered_windows:
            templates[window.key] = window.template
            numbers = index[positions]
            breaks = np.flatnonzero(np.diff(numbers) != 1) + 1  # a row holds consecutive points only
            for columns in np.split(np.arange(len(positions)), breaks):
                first = int(numbers[columns[0]])
                pieces.append((first, len(columns), partial(self._window_row, window, columns, positions[columns],
                                                            varied, inputs, created, first, where)))
        pieces.sort(key=lambda piece: piece[0])

        def execute(db: sqlite3.Connection) -> int:
            db.execute("BEGIN IMMEDIATE")  # what is stored is read and written in one transaction
            db.executemany("INSERT OR IGNORE INTO templates (key, body) VALUES (?, ?)",
                           [(key, _to_json(body)) for key, body in templates.items()])
            free = [(build, start, stop) for first, count, build in pieces
                    for start, stop in _unstored(db, where["sweep_id"], first, first + count)]
            db.executemany(RECORD, [build(start, stop) for build, start, stop in free])
            if carried is not None:
                db.execute("INSERT OR IGNORE INTO sweep_starts (sweep_id, point, body) VALUES (?, ?, ?)",
                           (where["sweep_id"], carried["point"], _to_json(carried)))
            return sum(stop - start for _, start, stop in free)

        return self._transaction(execute, len(index)) or 0

    def _window_row(self, window: WindowRecords, columns: np.ndarray, positions: np.ndarray,
                    varied: dict[str, np.ndarray], inputs: dict, created: str, first: int, where: dict, start: int,
                    stop: int) -> tuple:
        """The row of the points ``start .. stop - 1`` of a run of consecutive points from point ``first`` (the
        window's ``columns``, at ``positions`` among the points recorded): what they share as the row's inputs, their
        varied values and records as arrays."""
        taken = slice(start - first, stop - first)
        part = window if stop - start == len(window) else window.take(columns[taken])
        layout, data = pack({**part.arrays, "inputs": np.array([column[positions[taken]] for column in varied.values()],
                                                               dtype=float).reshape(len(varied), stop - start)})
        header = {TEMPLATE: window.key, "arrays": layout, "varied": list(varied), **part.labels,
                  CHECKSUM: checksum(data)}
        return self._row("sweep", inputs, header, created, point=start, run_count=stop - start, window=data, **where)

    @staticmethod
    def _row(kind: str, inputs: dict, outputs: dict, created: str, *, status: str | None = None,
             objective: float | None = None, objective_unit: str = "", method: str | None = None,
             case_path: str = "", title: str = "", coupling: str = "", mode: str = "", objective_name: str = "",
             sweep_id: int | None = None, point: int | None = None, run_count: int | None = None,
             window: bytes | None = None) -> tuple:
        return (kind, sweep_id, point, case_path, title, coupling, mode, objective_name, status, objective,
                objective_unit, method, _to_json(inputs), _to_json(outputs), _versions_json(), created, run_count,
                window)

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

    def latest_sweep(self, spec: dict, older_spec: dict | None = None) -> int | None:
        """The most recent sweep with exactly this specification (for ``--resume``), or one an older clutchopt
        recorded with ``older_spec`` (its form of the same specification)."""
        rows = self._read("SELECT id FROM sweeps WHERE key IN (?, ?) ORDER BY id DESC LIMIT 1",
                          (spec_key(spec), older_spec_key(older_spec or spec)))
        return int(rows[0]["id"]) if rows else None

    def sweep_outputs(self, sweep_id: int, points: list[dict[str, float]]) -> dict[int, dict]:
        """The stored solutions of a sweep by point index; ``points``: the sweep's varied values (SI) at each point.
        A run that is not one of these points with these values, or a second run of one (a damaged point number or
        index, which ``quick_check`` does not see), is damaged: StoreError."""
        stored = {}
        for row in self._read("SELECT * FROM runs WHERE sweep_id = ?", (sweep_id,)):
            for entry in self._entries(dict(row)):
                point, values = entry["point"], entry["inputs"]
                values = values.get("values") if isinstance(values, dict) else None
                if not (type(point) is int and 0 <= point < len(points) and point not in stored
                        and isinstance(values, dict)
                        and all(values.get(name) == value for name, value in points[point].items())):
                    raise StoreError(self.path, f"run {entry['id']} is damaged (its point number or inputs are not one "
                                                "of its sweep's points)", _rescue(self.path))
                stored[point] = entry["outputs"]
        return stored

    def sweep_start(self, sweep_id: int, point: int, read: Callable[[dict], T]) -> T | None:
        """What the window of a batched sweep that starts at ``point`` starts from, as recorded with the window
        before it (``record_points``' ``carried``), as ``read`` reads its JSON (ValueError naming what is wrong:
        ``Carried.from_dict``); None where none was recorded (the store of an older clutchopt, a sweep solved point by
        point or in a pool). One that is not JSON or that ``read`` refuses is damaged: StoreError."""
        if not self._has_table("sweep_starts"):  # (an older store opened to read)
            return None
        rows = self._read("SELECT body FROM sweep_starts WHERE sweep_id = ? AND point = ?", (sweep_id, point))
        if not rows:
            return None
        try:
            body = _from_json(rows[0]["body"])
        except (TypeError, ValueError, RecursionError):
            body = None
        try:
            if not isinstance(body, dict):
                raise ValueError("not JSON")
            return read(body)
        except ValueError as exc:
            raise StoreError(self.path, f"sweep {sweep_id}'s start at point {point} is damaged ({exc})",
                             "run the sweep again without --resume") from None

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
                outputs = expand(outputs, self._template(str(outputs[TEMPLATE])))
            return outputs if kind == "simulation" else check_solution(outputs)
        except (KeyError, IndexError, TypeError, ValueError, AttributeError) as exc:
            raise self._damaged_run(run_id, exc) from None

    def _entries(self, row: dict, start: int = 0, stop: int | None = None) -> list[dict]:
        """The runs a row of ``runs`` holds (one, or a window's points from its ``start``-th to before its
        ``stop``-th), each with its inputs, outputs and versions read and checked (``_outputs``); StoreError for a
        damaged row."""
        window, count = row.pop("window", None), row.pop("run_count", None)
        run_id = row["id"]
        named = run_id + start  # a damaged row is named by the first run asked for
        entry = {**row, **{name: self._json(row[name], named, name) for name in ("inputs", "versions")}}
        if window is None:
            entry["outputs"] = self._outputs(row["outputs"], run_id, row["kind"])
            if entry.get("method") is None and entry["kind"] != "simulation":  # a run of an older version
                entry["method"] = method_of(entry["outputs"])
            return [entry]
        header, arrays = self._window(row, count, window, named)
        stop = count if stop is None else stop
        try:
            template = self._template(str(header[TEMPLATE]))
            values, varied = arrays.pop("inputs"), header["varied"]
            if values.shape != (len(varied), count) or not all(type(name) is str for name in varied):
                raise ValueError("its numbers do not fit their layout")
            window = WindowRecords.read(template, arrays, header)
            records = window.take(np.arange(start, stop)).records(json_numbers=True)
            inputs = entry["inputs"]
            return [{**entry, "id": run_id + k, "point": row["point"] + k, "status": record["status"],
                     "objective": record["objective"]["value"], "outputs": check_solution(record),
                     "inputs": {**inputs, "values": {**inputs["values"], **dict(zip(varied, point))}}}
                    for k, record, point in zip(range(start, stop), records, values[:, start:stop].T.tolist())]
        except (KeyError, IndexError, TypeError, ValueError, AttributeError) as exc:
            raise self._damaged_run(named, exc) from None

    def _window(self, row: dict, count, data, named: int) -> tuple[dict, dict[str, np.ndarray]]:
        """A window row's header (its outputs: the layout, the template's key, labels, the checksum of its bytes) and
        arrays, unpacked; the row's point, run count (whole numbers) and bytes (their checksum, where the row has one)
        checked; a damaged one named by run ``named``."""
        header = self._json(row["outputs"], named, "outputs")
        try:
            if type(count) is not int or count < 1:
                raise ValueError("its run count is not a whole number")
            if type(row["point"]) is not int:
                raise ValueError("its point number or inputs are not one of its sweep's points")
            if CHECKSUM in header and type(data) is bytes and header[CHECKSUM] != checksum(data):  # (changed in place)
                raise ValueError("its numbers do not match their checksum")
            arrays = unpack(header["arrays"], data)
            if not all(array.shape[-1:] == (count,) for array in arrays.values()):
                raise ValueError("its numbers do not fit their layout")
            return header, arrays
        except (KeyError, IndexError, TypeError, ValueError, AttributeError) as exc:
            raise self._damaged_run(named, exc) from None

    def _damaged_run(self, run_id: int, exc: Exception) -> StoreError:
        problem = str(exc) if isinstance(exc, ValueError) and str(exc).startswith("its ") else \
            "its outputs do not fit their template"
        return StoreError(self.path, f"run {run_id} is damaged ({problem})", _rescue(self.path))

    def _template(self, key: str) -> dict:
        """A compact record's template, read once (the last TEMPLATES_KEPT are kept); ValueError where it is missing,
        not JSON or not the one of its key (a damaged run, to its caller)."""
        if key not in self._templates:
            rows = self._read("SELECT body FROM templates WHERE key = ?", (key,)) if self._has_table("templates") else []
            try:
                template = _from_json(rows[0][0]) if rows else None
            except (TypeError, ValueError, RecursionError):
                template = None
            if template is not None and not is_keyed_by(template, key):
                template = None  # (changed in place)
            if len(self._templates) >= TEMPLATES_KEPT:
                self._templates.pop(next(iter(self._templates)))
            self._templates[key] = template
        if self._templates[key] is None:
            raise ValueError("its template is missing, not JSON or changed")
        return self._templates[key]

    def _has_table(self, name: str) -> bool:
        """The store has table ``name`` (an older store, opened to read, may lack the newer ones)."""
        return bool(self._read("SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?", (name,)))

    def _span(self) -> str:
        """SQL for how many runs a row holds (a store of an older clutchopt, read only, has one a row)."""
        return "IFNULL(run_count, 1)" if "run_count" in self._columns() else "1"

    def runs(self, kind: str | None = None, sweep_id: int | None = None, limit: int | None = None) -> list[dict]:
        """Runs, newest first, without their JSON bodies; ``objective_unit`` and ``method`` filled for runs of older
        versions (from their outputs, where they say). A window's points are read from its arrays (a damaged one:
        StoreError)."""
        present = self._columns()
        columns = [c if c not in ADDED_COLUMNS["runs"] or c in present else f"NULL AS {c}" for c in LIST_COLUMNS]
        columns += (["run_count", "CASE WHEN window IS NULL THEN NULL ELSE outputs END AS outputs", "window"]
                    if "run_count" in present else ["NULL AS run_count", "NULL AS outputs", "NULL AS window"])
        query = f"SELECT {', '.join(columns)} FROM runs"
        where, args = [], []
        if kind:
            where.append("kind = ?"), args.append(kind)
        if sweep_id is not None:
            where.append("sweep_id = ?"), args.append(sweep_id)
        if where:
            query += " WHERE " + " AND ".join(where)
        query += " ORDER BY id DESC" + (" LIMIT ?" if limit else "")  # a row holds one run or more
        if limit:
            args.append(limit)
        listed = [run for row in self._read(query, args) for run in self._listed(dict(row))][:limit]
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

    def _listed(self, row: dict) -> list[dict]:
        """The runs of a row as ``runs`` lists them, newest first."""
        window, count, header = row.pop("window"), row.pop("run_count"), row.pop("outputs")
        if window is None:
            return [row]
        _, arrays = self._window({**row, "outputs": header}, count, window, row["id"])
        try:
            codes, objectives = arrays["status"].tolist(), arrays["objective"].tolist()
            if not all(0 <= code < len(STATUSES) for code in codes):
                raise ValueError("its numbers do not fit their layout")
        except (KeyError, TypeError, ValueError) as exc:
            raise self._damaged_run(row["id"], exc) from None
        statuses = [STATUSES[code] for code in codes]
        return [{**row, "id": row["id"] + k, "point": row["point"] + k, "status": statuses[k],
                 "objective": objectives[k] if math.isfinite(objectives[k]) else None} for k in reversed(range(count))]

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
        row = self._row_of(run_id)
        return self._entries(row, run_id - row["id"], run_id - row["id"] + 1)[0]

    def _row_of(self, run_id: int, columns: str = "*") -> dict:
        """The ``columns`` of the row of ``runs`` that holds run ``run_id`` (InputError if none does)."""
        rows = self._read(f"SELECT {self._span()} AS span, {columns} FROM runs WHERE id <= ? ORDER BY id DESC LIMIT 1",
                          (run_id,))
        row = dict(rows[0]) if rows else {"id": run_id, "span": 0}
        span = row.pop("span")
        if type(span) is not int or span < 1:
            if run_id == row["id"]:
                raise self._damaged_run(run_id, ValueError("its run count is not a whole number"))
            raise InputError("run", f"no run {run_id} in {self.path}")  # beyond a damaged row: it may hold it
        if run_id >= row["id"] + span:
            raise InputError("run", f"no run {run_id} in {self.path}")
        return row

    def readable_runs(self, kind: str | None = None,
                      sweep_id: int | None = None) -> tuple[list[dict], int, int | None]:
        """Every run that can still be read, oldest first, how many could not (a damaged store), and the id after
        which none could be read where the damage hides how many there were (else None). Each row is read on its
        own, so one damaged page loses only the runs on it (a damaged window: all its points). The ids are tried up
        to the largest the table names and on until RESCUE_PROBE in a row cannot be read (a damaged or missing last
        page hides the largest)."""
        try:
            largest = self._db.execute(f"SELECT id + {self._span()} - 1 FROM runs ORDER BY id DESC LIMIT 1"
                                       ).fetchone()[0] or 0
        except (sqlite3.DatabaseError, TypeError):
            largest = 0
        largest = min(largest, (_size(self.path) + _size(f"{self.path}-wal")) // ROW_BYTES)  # a damaged largest id
        # cannot set off billions of reads: no run takes fewer bytes
        runs, damaged, run_id, missed = [], [], 0, 0
        while run_id < largest or missed < RESCUE_PROBE:
            run_id += 1
            try:
                row = self._row_of(run_id)
                entries = self._entries(row, run_id - row["id"])
            except InputError as exc:  # damaged (a StoreError), or no run with this id (ids are not reused)
                lost = self._lost(run_id, largest) if isinstance(exc, StoreError) else []
                damaged += lost
                run_id += max(len(lost) - 1, 0)
                missed += run_id > largest
                continue
            run_id = entries[-1]["id"]
            largest, missed = max(largest, run_id), 0
            runs += [entry for entry in entries
                     if (kind is None or entry["kind"] == kind) and (sweep_id is None or entry["sweep_id"] == sweep_id)]
        open_end = largest if damaged and damaged[-1] > largest else None
        return runs, sum(run_id <= largest for run_id in damaged), open_end

    def _lost(self, run_id: int, largest: int) -> list[int]:
        """The ids of a damaged row from ``run_id`` on: as many as it holds where that much can be read (not its
        numbers), else one; none past the next row's first or ``largest`` (a damaged run count may say 2**40)."""
        try:
            row = self._row_of(run_id, f"id, {self._span()} AS count")
            following = self._read("SELECT MIN(id) FROM runs WHERE id > ?", (run_id,))[0][0]
            end = min(row["id"] + row["count"], largest + 1, following if type(following) is int else largest + 1)
            return list(range(run_id, max(end, run_id + 1)))
        except InputError:
            return [run_id]

    def sweeps(self) -> list[dict]:
        stored = "COUNT(r.id) + IFNULL(SUM(r.run_count - 1), 0)" if "run_count" in self._columns() else "COUNT(r.id)"
        return [dict(row) for row in self._read(
            f"SELECT s.id, s.created, s.case_path, s.coupling, s.mode, s.objective, s.points, {stored} AS stored "
            "FROM sweeps s LEFT JOIN runs r ON r.sweep_id = s.id GROUP BY s.id ORDER BY s.id DESC")]
