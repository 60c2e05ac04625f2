"""Sweeps: one case re-solved over a grid of requirements, warm-started, recorded point by point.

A sweep varies case quantities, each given in its display unit (speed in rpm, pressures in MPa, lengths in mm):
``speed=500:3000:26`` is 26 evenly spaced values from 500 to 3000, ``speed=900,1450,3000`` a list. Several
``--vary`` make a full-factorial grid (the last one varies fastest), or with ``zipped=True`` a listed sweep (the
i-th point takes the i-th value of each list). Points run in chunks of neighbours; within a chunk one built
problem is re-solved, each point warm-started from the one before: in batches of chained SQP re-solves checked
together (``clutchopt.optimise.batch``), by ``Problem.solve`` where a batch stops and for problems with a start-up
(``Problem.solve`` starts cold again if the warm start fails).
Chunks run in this process, in a local process pool, or on a Dask cluster. The points are stored in the run store
as they arrive, a window of them in one transaction, so a killed sweep resumes where it stopped. The table is built
from the windows' arrays; each point's record only when read (``SweepResult.solutions``) or stored.
"""

from __future__ import annotations

import json
import math
import os
import re
import signal
import socket
import struct
import threading
import time
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import dataclass, field
from functools import cached_property, partial
from typing import Callable, Iterator

import numpy as np
import pandas as pd

from clutchopt.cases import Case
from clutchopt.errors import InputError, Problems
from clutchopt.files import TABLE_BYTES, check_output, read_bytes, write_whole
from clutchopt.formulations import get_coupling
from clutchopt.model import Formulation, Quantity
from clutchopt.optimise.batch import BatchSweep, Solutions, batchable
from clutchopt.optimise.entering import check_entering
from clutchopt.optimise.problem import Solution, SolverOptions, case_formulation, case_problem
from clutchopt.optimise.table import joined_tables, record_table
from clutchopt.optimise.verify import DESIGN_STATUSES
from clutchopt.records import STATUSES, expanded, status_and_objective
from clutchopt.units import from_si, si_factor

MAX_POINTS = 100_000  # points of one sweep: hours of solving; more is a mistake (1e12 would not fit in memory)


@dataclass(frozen=True)
class Vary:
    """One varied quantity: its declaration, its values in SI and, as given in its display unit, the same values (by
    :func:`parse_vary`; without them the table converts the SI values back, e.g. 3000 rpm to 3000.0000000000005)."""

    quantity: Quantity
    values: tuple[float, ...]
    shown: tuple[float, ...] | None = None

    @property
    def column(self) -> str:
        return column_name(self.quantity.name, self.quantity.unit)


def column_name(name: str, unit: str) -> str:
    return f"{name} [{unit}]" if unit else name


def parse_vary(text: str, coupling: str, quantities: tuple[Quantity, ...] | None = None) -> Vary:
    """``name=start:stop:count`` or ``name=v1,v2,...``, values in the quantity's display unit; ``quantities``:
    those a case may vary (default: the coupling's; ``Case.quantities`` adds a start-up's)."""
    field = f"--vary {text}"
    name, sep, spec = text.partition("=")
    declared = {q.name: q for q in quantities or get_coupling(coupling).quantities}
    if not sep or not spec.strip():
        raise InputError(field, "expected name=start:stop:count or name=v1,v2,...")
    quantity = declared.get(name.strip())
    if quantity is None:
        raise InputError(field, f"unknown quantity {name.strip()!r}; the {coupling} coupling has "
                                f"{', '.join(sorted(declared))}")
    numbers = _numbers(field, spec)
    if ":" in spec:
        if len(numbers) != 3 or numbers[2] != int(numbers[2]) or numbers[2] < 1:
            raise InputError(field, "a range is start:stop:count with a whole count >= 1")
        if numbers[2] > MAX_POINTS:
            raise InputError(field, f"{numbers[2]:.15g} values; a sweep has at most {MAX_POINTS:,} points")
        with np.errstate(all="ignore"):
            numbers = np.linspace(numbers[0], numbers[1], int(numbers[2])).tolist()
        if not all(math.isfinite(n) for n in numbers):
            raise InputError(field, "the range's span is beyond the float64 range")
    elif len(numbers) > MAX_POINTS:
        raise InputError(field, f"{len(numbers)} values; a sweep has at most {MAX_POINTS:,} points")
    factor = si_factor(quantity.unit) if quantity.unit else 1.0
    values = tuple(value * factor for value in numbers)
    if not all(math.isfinite(value) for value in values):
        raise InputError(field, "values beyond the float64 range once converted to SI")
    return Vary(quantity, values, tuple(numbers))


def _numbers(field: str, spec: str) -> list[float]:
    try:
        numbers = [float(part) for part in (spec.split(":") if ":" in spec else spec.split(","))]
    except ValueError:
        raise InputError(field, f"not a number in {spec!r} (values are plain numbers in the quantity's "
                                "display unit)") from None
    if not all(math.isfinite(n) for n in numbers):
        raise InputError(field, "values must be finite")
    return numbers


def check_grid(varies: list[Vary], zipped: bool = False) -> int:
    """The number of points of the sweep's grid (at most MAX_POINTS; each quantity varied once; a listed sweep's
    lists equally long)."""
    names = [v.quantity.name for v in varies]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise InputError("--vary", f"{', '.join(twice)} varied twice; give all its values in one --vary")
    count = len(varies[0].values) if zipped and varies else math.prod(len(v.values) for v in varies)
    if count > MAX_POINTS:
        raise InputError("--vary", f"the grid has {count:,} points; a sweep has at most {MAX_POINTS:,} "
                                   "(split it, or use fewer values)")
    if zipped:
        lengths = {len(v.values) for v in varies}
        if len(lengths) > 1:
            raise InputError("--zip", f"listed sweeps need equally many values per --vary, got {sorted(lengths)}")
    return count


def grid_points(varies: list[Vary], zipped: bool = False) -> "Points":
    """The sweep's points (see :func:`check_grid`), each varied quantity's values as an array (SI)."""
    count = check_grid(varies, zipped)
    return Points(np.arange(count), {v.quantity.name: np.array(v.values, dtype=float)[taken]
                                     for v, taken in zip(varies, grid_positions(varies, zipped))})


def grid_positions(varies: list[Vary], zipped: bool = False) -> list[np.ndarray | slice]:
    """Which of its values each varied quantity takes at each point of the grid (all of them in order for one
    quantity or a listed sweep)."""
    if zipped or len(varies) < 2:
        return [slice(None)] * len(varies)
    return [a.ravel() for a in np.meshgrid(*(np.arange(len(v.values)) for v in varies), indexing="ij")]


def check_points(case: Case, varies: list[Vary], points: "Points") -> None:
    """A value out of a quantity's valid range is bad input before any solve: each varied quantity's values are
    checked as an array; where one fails, the error names the first point that fails."""
    try:
        for vary in varies:
            vary.quantity.check_all(points.columns[vary.quantity.name])
    except InputError:
        for index, values in points.pairs():
            try:
                case.with_values(**values)
            except InputError as exc:
                raise InputError(f"--vary (point {index})", str(exc)) from None
        raise


@dataclass(frozen=True)
class Points:
    """Points of a sweep: their indices, and each varied quantity's SI values at them (an array by name)."""

    index: np.ndarray
    columns: dict[str, np.ndarray]

    def __len__(self) -> int:
        return len(self.index)

    def __getitem__(self, part: slice | np.ndarray) -> "Points":
        return Points(self.index[part], {name: column[part] for name, column in self.columns.items()})

    def values(self) -> list[dict[str, float]]:
        """Each point's values by quantity name."""
        names = list(self.columns)
        if len(names) == 1:  # the common case, without a tuple per point
            return [{names[0]: value} for value in self.columns[names[0]].tolist()]
        rows = zip(*(column.tolist() for column in self.columns.values())) if names else [()] * len(self)
        return [dict(zip(names, row)) for row in rows]

    def pairs(self) -> Iterator[tuple[int, dict[str, float]]]:
        """Each point's index and values."""
        return zip(self.index.tolist(), self.values())

    @classmethod
    def joined(cls, parts: list["Points"]) -> "Points":
        return cls(np.concatenate([p.index for p in parts]),
                   {name: np.concatenate([p.columns[name] for p in parts]) for name in parts[0].columns})


SPENT = ("solves", "solver_s", "check_s")  # what solving points costs: solver calls, seconds in them and in checks


def total_spent(parts: list["PointResults"]) -> dict:
    return {key: sum(part.spent[key] for part in parts) for key in SPENT}


class PointResults:
    """Solved points of a sweep, in point order: their indices and values, their rows of the sweep table (a batched
    window's read from its arrays), and their records, built when asked for: as the run store keeps them (a batched
    point's compact, with its template: ``clutchopt.records``) and in full (``Solution.as_dict()``: ``--json``,
    ``SweepResult.solutions``; kept once built). ``spent``: their solver calls (``solves``) and seconds in them
    (``solver_s``) and in the batches' compiled checks (``check_s``)."""

    def __init__(self, points: Points, names: list[str],
                 stored: tuple[list[dict], dict[str, dict]] | None = None, solutions: Solutions | None = None,
                 spent: dict | None = None):
        self.points, self.names, self.spent = points, names, spent or dict.fromkeys(SPENT, 0)
        self._stored, self._solutions, self._records = stored, solutions, None

    def __len__(self) -> int:
        return len(self.points)

    def stored(self) -> tuple[list[dict], dict[str, dict]]:
        """Each point's record as the run store keeps it, and the templates of the compact ones by key (a window's
        built afresh from its arrays each time: not kept once written)."""
        return self._stored if self._solutions is None else self._solutions.compact_records()

    def records(self) -> list[dict]:
        """Each point's ``Solution.as_dict()``."""
        if self._records is None:
            self._records = expanded(*self.stored())
        return self._records

    def table(self) -> dict[str, np.ndarray]:
        return self._solutions.table() if self._solutions is not None else record_table(self.records(), self.names)

    @classmethod
    def joined(cls, parts: list["PointResults"], names: list[str]) -> "PointResults":
        """Consecutive results as one, with their records as the store keeps them (what a worker sends back)."""
        records, templates = [], {}
        for part in parts:
            stored, used = part.stored()
            records += stored
            templates.update(used)
        return cls(Points.joined([part.points for part in parts]), names, (records, templates),
                   spent=total_spent(parts))


def solve_points(case: Case, mode: str, objective: str, tol: float,
                 points: Points) -> Iterator[PointResults]:
    """Solve points in order, each warm-started from the last optimum; yields the results as they are solved: a
    window of points at once where the problem allows batches (``clutchopt.optimise.batch``), else one point each."""
    problem = case_problem(case, mode, objective, SolverOptions(tol=tol))
    names = [v.name for v in problem.formulation.variables]
    if len(points) and batchable(problem, points.columns):
        sweep = BatchSweep(problem, case, points.columns)
        first, before = 0, dict.fromkeys(SPENT, 0)
        for window in sweep.run():
            now = {key: getattr(sweep, key) for key in SPENT}
            yield PointResults(points[first:first + len(window)], names, solutions=window,
                               spent={key: now[key] - before[key] for key in SPENT})
            first, before = first + len(window), now
        return
    previous: Solution | None = None
    for j, (index, values) in enumerate(points.pairs()):
        point_case = case.with_values(**values)
        # falls back to the case's own start by itself; a start-up design starts as `solve` does, from the papers'
        # sizing at the point (its collocation mesh follows its own solves), so it is solve's design whatever the
        # points before it
        solution = problem.solve(point_case, warm=previous if problem.start_up is None else None)
        previous = solution if solution.status == "optimal" else None  # next to a failure, start from the case
        yield PointResults(points[j:j + 1], names, ([solution.as_dict()], {}),
                           spent={"solves": solution.solver.solves, "solver_s": solution.solver.time_s, "check_s": 0})


def solve_chunk(case: Case, mode: str, objective: str, tol: float,
                chunk: Points) -> PointResults:
    """A chunk of neighbouring points solved in one worker (process pool, Dask), with its records."""
    names = [v.name for v in case_formulation(case, mode).variables]
    return PointResults.joined(list(solve_points(case, mode, objective, tol, chunk)), names)


def _chunks(pending: Points, size: int) -> list[Points]:
    return [pending[i:i + size] for i in range(0, len(pending), size)]


def local_runner(jobs: int) -> Callable:
    """In this process (the points recorded as they are solved: a window of batched points at a time) or in a pool
    of ``jobs`` processes."""
    def run(task: tuple, pending: Points, size: int) -> Iterator[PointResults]:
        if jobs <= 1:
            yield from solve_points(*task, pending)
            return
        pool = ProcessPoolExecutor(max_workers=jobs, initializer=die_with_parent)
        try:
            futures = [pool.submit(solve_chunk, *task, chunk) for chunk in _chunks(pending, size)]
            for future in as_completed(futures):
                yield future.result()
        finally:  # on Ctrl-C do not wait for the chunks not started
            pool.shutdown(wait=False, cancel_futures=True)
    return run


def die_with_parent(poll_s: float = 0.5) -> None:
    """Pool-worker initializer: a watchdog thread ends this worker once the process that started it is gone.

    A sweep killed with ``kill -9`` cannot shut its pool down; without this its workers would wait forever for
    work. The parent's death shows as a change of ``os.getppid()`` (the worker is re-parented)."""
    parent = os.getppid()

    def watch() -> None:
        while os.getppid() == parent:
            time.sleep(poll_s)
        os._exit(1)

    threading.Thread(target=watch, name="clutchopt-parent-watchdog", daemon=True).start()


@contextmanager
def interrupt_between_points() -> Iterator[Callable[[], None]]:
    """Ctrl-C stops a sweep between points. Inside a solve CasADi would catch the KeyboardInterrupt and report
    the point as failed; here the signal only sets a flag, and ``check()`` raises it before the next record."""
    if threading.current_thread() is not threading.main_thread() or signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
        yield lambda: None
        return
    pressed = []
    previous = signal.signal(signal.SIGINT, lambda *_: pressed.append(True))

    def check() -> None:
        if pressed:
            raise KeyboardInterrupt

    try:
        yield check
    finally:
        signal.signal(signal.SIGINT, previous)


def dask_runner(address: str) -> Callable:
    """Run chunks on an existing Dask distributed cluster (clutchopt must be importable on its workers)."""
    client = connect(address)

    def run(task: tuple, pending: Points, size: int) -> Iterator[PointResults]:
        from distributed import as_completed as dask_completed

        try:
            futures = client.map(partial(solve_chunk, *task), _chunks(pending, size), pure=False)
            for future in dask_completed(futures):
                yield future.result()
        finally:
            client.close()
    return run


def connect(address: str, timeout: float = 4.0):
    """A Dask client for ``tcp://host:port``; a malformed or unreachable address, or one where something other than
    a Dask scheduler answers, is bad input, reported within about 10 s (see :func:`probe_scheduler`)."""
    if not re.fullmatch(r"(tcp|tls|inproc)://[^\s:/]+(:\d{1,5})?(/\S*)?", address):
        raise InputError("--dask", f"expected an address like tcp://host:8786, got {address!r}")
    try:
        from distributed import Client
    except ImportError:
        raise InputError("--dask", "needs dask.distributed (pip install 'clutchopt[dask]')") from None
    if address.startswith("tcp://"):
        probe_scheduler(address, timeout)
    try:
        return Client(address, timeout=timeout)
    except (OSError, TimeoutError) as exc:
        raise InputError("--dask", f"cannot reach a Dask scheduler at {address} ({type(exc).__name__})") from None


DASK_GREETING_BYTES = 1 << 20  # a scheduler's handshake is a few hundred bytes


def probe_scheduler(address: str, timeout: float) -> None:
    """Check that a Dask scheduler answers at ``tcp://host:port`` before ``distributed`` connects.

    A scheduler greets each new connection first: 8 bytes (native ``Q``, as distributed writes them) giving the
    length of its handshake, then the handshake. A web server says nothing until asked (``distributed`` would then
    wait), other servers greet with text whose first 8 bytes read as an absurd length (``distributed`` would try
    to allocate it). Both are refused here in one line, each wait bounded by ``timeout``."""
    host, port = re.match(r"tcp://([^\s:/]+)(?::(\d+))?", address).groups(default="8786")
    if not 0 < int(port) < 65536:
        raise InputError("--dask", f"port {port} is out of range (1 to 65535)")
    try:
        connection = socket.create_connection((host, int(port)), timeout=timeout)
    except TimeoutError:
        raise InputError("--dask", f"cannot reach a Dask scheduler at {address}: no answer within {timeout:g} s") \
            from None
    except OSError as exc:
        raise InputError("--dask", f"cannot reach a Dask scheduler at {address} ({exc.strerror or exc})") from None
    with connection:
        connection.settimeout(timeout)
        try:
            head = _receive(connection, 8)
        except TimeoutError:
            raise InputError("--dask", f"{address} is not a Dask scheduler: it accepted the connection but sent "
                                       f"no Dask greeting within {timeout:g} s (a web server?)") from None
        except OSError as exc:
            raise InputError("--dask", f"{address} closed the connection ({exc.strerror or exc}): not a Dask "
                                       "scheduler") from None
        (length,) = struct.unpack("Q", head)
        if not 0 < length <= DASK_GREETING_BYTES:
            raise InputError("--dask", f"{address} is not a Dask scheduler: it greets with {head!r}")


def _receive(connection: socket.socket, count: int) -> bytes:
    data = b""
    while len(data) < count:
        chunk = connection.recv(count - len(data))
        if not chunk:
            raise ConnectionError("the connection closed")
        data += chunk
    return data


@dataclass
class SweepResult:
    sweep_id: int | None
    frame: pd.DataFrame
    solved: int  # points solved by this invocation
    reused: int  # points found already stored (resume)
    elapsed_s: float  # wall time of the solves
    solutions: Sequence[dict]  # every point's solution (``Solution.as_dict()``, SI), in point order
    spent: dict = field(default_factory=dict)  # solver calls and seconds in them and in batch checks (:data:`SPENT`;
    # a pool's or Dask's are its workers')

    def _repr_html_(self) -> str:
        """Jupyter shows a sweep as its table, one row per point (the columns of ``clutchopt sweep --out``)."""
        from html import escape

        counts = ", ".join(f"{count} {status}" for status, count in self.frame["status"].value_counts().items())
        table = self.frame.to_html(index=False, float_format=lambda v: f"{v:.6g}", na_rep="-")
        return f"<div><p>{escape(f'Sweep: {len(self.frame)} points, {counts}')}</p>{table}</div>"


class SweepRecords(Sequence):
    """Every point's record (``Solution.as_dict()``) in point order, built when a first one is read."""

    def __init__(self, parts: list[PointResults], order: np.ndarray):
        self._parts, self._order, self._records = parts, order, None

    def __len__(self) -> int:
        return len(self._order)

    def __getitem__(self, i):
        if self._records is None:
            solved = [record for part in self._parts for record in part.records()]
            self._records = [solved[k] for k in self._order.tolist()]
        return self._records[i]


class Sweep:
    """A case, the varied quantities, mode and objective: what defines a sweep and its resume key."""

    def __init__(self, case: Case, varies: list[Vary], mode: str | None = None, objective: str | None = None,
                 tol: float = 1e-10, zipped: bool = False):
        self.case = case = case.given(*(v.quantity.name for v in varies))
        self.varies = varies
        self.formulation: Formulation = case_formulation(case, mode)
        self.objective = self.formulation.objective(objective or case.options.get("objective", "mass"))
        case.require(self.objective.name)
        self.tol = tol
        self.grid, self.zipped = grid_points(varies, zipped), zipped
        check_points(case, varies, self.grid)
        check_entering(case, case_problem(case, self.formulation.mode, self.objective.name, SolverOptions(tol=tol)),
                       [v.quantity.name for v in varies], "--vary")

    def identity(self) -> dict:
        """What a table of this sweep carries to say which case it was swept from (see :func:`check_swept_from`):
        the coupling, the case's path and SI values, mode, objective and the varied columns."""
        return {"coupling": self.case.coupling, "case": self.case.path, "values": self.case.values,
                "mode": self.formulation.mode, "objective": self.objective.name,
                "varies": [v.column for v in self.varies]}

    @cached_property
    def points(self) -> list[dict[str, float]]:
        """Each point's varied values (SI) by quantity name."""
        return self.grid.values()

    @property
    def spec(self) -> dict:
        return {"coupling": self.case.coupling, "mode": self.formulation.mode, "objective": self.objective.name,
                "tol": self.tol, "case": {"values": self.case.values, "free": list(self.case.free),
                                          "bounds": self.case.bounds},
                "points": self.points}

    def run(self, store=None, resume: bool = False, jobs: int = 1, runner: Callable | None = None,
            progress: bool = True, chunk_size: int | None = None) -> SweepResult:
        """Solve every point not already stored; ``runner`` (e.g. :func:`dask_runner`) overrides ``jobs``."""
        from tqdm import tqdm

        sweep_id, stored = None, {}
        if store is not None:
            sweep_id = store.latest_sweep(self.spec) if resume else None
            if sweep_id is None:
                sweep_id = store.new_sweep(self.spec, len(self.grid), self.case.path)  # None: store failed
            stored = store.sweep_outputs(sweep_id, self.points) if sweep_id is not None else {}
        kept = np.array(sorted(stored), dtype=int)
        pending = self.grid[np.isin(self.grid.index, kept, invert=True)] if stored else self.grid
        workers = max(jobs, 1)
        size = chunk_size or max(1, min(25, math.ceil(len(pending) / (4 * workers))))
        task = (self.case, self.formulation.mode, self.objective.name, self.tol)
        names = [v.name for v in self.formulation.variables]
        parts = [PointResults(self.grid[kept], names, ([stored[i] for i in kept.tolist()], {}))]
        bar = tqdm(total=len(self.grid), initial=len(stored), unit="point", desc="sweep", disable=not progress,
                   mininterval=0.5)
        started = time.perf_counter()
        with bar, interrupt_between_points() as check:
            for results in (runner or local_runner(jobs))(task, pending, size):
                if store is not None and sweep_id is not None:  # the results in hand in one transaction
                    records, templates = results.stored()
                    store.record_many([("sweep", self._inputs(values), record, self._where(index, record, sweep_id))
                                       for (index, values), record in zip(results.points.pairs(), records)],
                                      templates)
                elif store is not None:  # the sweep itself could not be recorded
                    store.unrecorded += len(results)
                parts.append(results)
                bar.update(len(results))
                check()
        elapsed = time.perf_counter() - started
        order = np.argsort(np.concatenate([part.points.index for part in parts]), kind="stable")  # pool: any order
        parts = [part for part in parts if len(part)]
        return SweepResult(sweep_id, self.frame(joined_tables([part.table() for part in parts]), order),
                           len(pending), len(stored), elapsed, SweepRecords(parts, order),
                           total_spent(parts))

    def _inputs(self, values: dict[str, float]) -> dict:
        """A point's inputs as the store keeps them: the case's SI values with the point's (checked when the sweep
        was made), its free variables and bounds."""
        values = {**self.case.values, **{name: float(value) for name, value in values.items()}}
        return {"values": values, "free": list(self.case.free), "bounds": self.case.bounds}

    def _where(self, point: int, record: dict, sweep_id: int) -> dict:
        status, objective = status_and_objective(record)
        return {"status": status, "objective": objective,
                "objective_unit": self.objective.unit, "case_path": self.case.path, "title": self.case.title,
                "coupling": self.case.coupling, "mode": self.formulation.mode, "objective_name": self.objective.name,
                "sweep_id": sweep_id, "point": point}

    def frame(self, table: dict[str, np.ndarray], order: np.ndarray | None = None) -> pd.DataFrame:
        """One row per point (``table``'s points taken in ``order``): inputs (as given: :class:`Vary`), status,
        objective, design (display units; ``design.NAME [unit]`` where a varied input has its name), active
        constraints; a point without a design (infeasible, solver failed) has its status and diagnosis, and blanks
        for objective and design."""
        if order is not None and (order[1:] < order[:-1]).any():  # out of point order (a pool's chunks)
            table = {key: column[..., order] for key, column in table.items()}
        status = table["status"]
        designed = np.any([status == design for design in DESIGN_STATUSES], axis=0)  # infeasible: a diagnosis only
        columns = {"point": self.grid.index}
        for v, taken in zip(self.varies, grid_positions(self.varies, self.zipped)):  # as given, where they were
            columns[v.column] = (np.array(v.shown, dtype=float)[taken] if v.shown is not None
                                 else from_si(self.grid.columns[v.quantity.name], v.quantity.unit))
        columns["status"] = status
        columns[column_name(self.objective.name, self.objective.unit)] = np.where(designed, table["objective"], np.nan)
        for variable, design in zip(self.formulation.variables, table["design"]):
            name = column_name(variable.name, variable.unit)  # a varied quantity may be a design variable too
            columns[f"design.{name}" if name in columns else name] = np.where(designed, from_si(design, variable.unit),
                                                                              np.nan)
        columns["active"] = np.where(designed, table["active"], "")
        columns["diagnosis"] = np.where(np.equal(table["diagnosis"], None), "", table["diagnosis"])
        blank = np.equal(table["iterations"], None)  # solved in a batch
        columns["iterations"] = pd.arrays.IntegerArray(np.where(blank, 0, table["iterations"]).astype(np.int64), blank)
        for key in ("status", "active", "diagnosis"):  # Python strings: pandas 3 would convert each to an Arrow
            columns[key] = pd.Series(columns[key], dtype=object, copy=False)  # string (a third of the table's time)
        return pd.DataFrame(columns, copy=False)


TABLE_SUFFIXES = (".csv", ".parquet", ".md")


def table_format(path: str, option: str = "--out") -> str:
    """csv, parquet or md, from the file's suffix; the folder must exist and be writable (checked before any
    solve, so that a long sweep does not end in a table it cannot write)."""
    return check_output(option, path, TABLE_SUFFIXES)


IDENTITY = "clutchopt_sweep"  # the frame attribute (and Parquet metadata) that identifies a sweep table's case
CSV_IDENTITY = f"# {IDENTITY} "  # a CSV sweep table's first line: this, then the identification as JSON


def write_frame(frame: pd.DataFrame, path: str, option: str = "--out", identity: dict | None = None) -> None:
    """CSV, Parquet or Markdown by the file's suffix, written whole or not at all; ``identity`` (a sweep's, see
    :meth:`Sweep.identity`) goes into a CSV's first line and a Parquet file's metadata."""
    suffix = table_format(path, option)

    def write(target: str) -> None:
        if suffix == "csv":
            with open(target, "w", encoding="utf-8", newline="") as handle:
                if identity is not None:
                    handle.write(CSV_IDENTITY + json.dumps(identity) + "\n")
                frame.to_csv(handle, index=False)
        elif suffix == "parquet":
            identified = frame.copy(deep=False)
            identified.attrs = {IDENTITY: identity} if identity is not None else {}
            identified.to_parquet(target, index=False)
        else:
            with open(target, "w", encoding="utf-8") as handle:
                handle.write(markdown_table(frame) + "\n")

    try:
        write_whole(option, path, write)
    except ImportError as exc:
        raise InputError(option, f"Parquet needs pyarrow (pip install 'clutchopt[parquet]'): {exc}") from None


def read_frame(path: str) -> pd.DataFrame:
    """A sweep table written by :func:`write_frame` (CSV or Parquet), checked column by column: ``point``, the
    varied inputs (numbers), ``status``, the objective (numbers, empty where there is no design). Its identification,
    if it has one, is ``frame.attrs[IDENTITY]``."""
    import io

    if not path.lower().endswith((".csv", ".parquet")):
        raise InputError(path, "a sweep table is read from .csv or .parquet (written by clutchopt sweep --out)")
    data = read_bytes(path, TABLE_BYTES)
    identity = None
    if data.startswith(CSV_IDENTITY.encode()):
        first, _, data = data.partition(b"\n")
        identity = _identity(first[len(CSV_IDENTITY):], path)
    data = io.BytesIO(data)
    try:
        frame = pd.read_parquet(data) if path.lower().endswith(".parquet") else pd.read_csv(data)
    except ImportError as exc:
        raise InputError(path, f"Parquet needs pyarrow (pip install 'clutchopt[parquet]'): {exc}") from None
    except (ValueError, OSError, UnicodeDecodeError) as exc:  # pandas' and pyarrow's parse errors
        raise InputError(path, f"cannot read a sweep table ({_first_line(exc)})") from None
    if identity is None and frame.attrs.get(IDENTITY) is not None:
        identity = _identity(json.dumps(frame.attrs[IDENTITY]).encode(), path)
    frame.attrs = {IDENTITY: identity} if identity is not None else {}
    _check_sweep_table(frame, path)
    return frame


def _identity(text: bytes, path: str) -> dict:
    """A sweep table's identification (JSON), checked: the keys :meth:`Sweep.identity` writes, of their kinds."""
    try:
        identity = json.loads(text)
    except (ValueError, RecursionError):
        identity = None
    kinds = {"coupling": str, "case": str, "values": dict, "mode": str, "objective": str, "varies": list}
    if not (isinstance(identity, dict) and set(identity) == set(kinds)
            and all(isinstance(identity[key], kind) for key, kind in kinds.items())
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in identity["values"].values())
            and all(isinstance(column, str) for column in identity["varies"])):
        raise InputError(path, "cannot read a sweep table: its identification (the case it was swept from) is "
                               "damaged; write it again with clutchopt sweep --out")
    return identity


def check_swept_from(frame: pd.DataFrame, case: Case, path: str, warn: Callable[[str], None]) -> None:
    """Refuse a sweep table (:func:`read_frame`) swept from another case than ``case``, in one line naming what
    differs: the coupling, the case's values, the varied quantities. A table without identification (written
    before clutchopt identified its tables) is taken with a warning."""
    identity = frame.attrs.get(IDENTITY)
    if identity is None:
        warn(f"{path} does not say which case it was swept from (a table of an older clutchopt); it is shown as "
             f"a sweep of {case.path}")
        return
    differs = []
    if identity["coupling"] != case.coupling:
        differs.append(f"coupling {identity['coupling']!r}, not {case.coupling!r}")
    else:
        names = sorted(set(identity["values"]) ^ set(case.values)
                       | {name for name, value in case.values.items() if identity["values"].get(name, value) != value})
        if names:
            differs.append(f"case: swept from {identity['case']!r}, whose {_listed(names)} differ from this case's")
    status = list(frame.columns).index("status")
    if list(frame.columns[1:status]) != identity["varies"]:
        differs.append(f"quantities: its columns vary {_listed(frame.columns[1:status])}, its identification says "
                       f"{_listed(identity['varies'])}")
    if differs:
        raise InputError(path, f"not a sweep of {case.path}: {'; '.join(differs)}")


def _listed(names, shown: int = 5) -> str:
    names = list(names)
    return ", ".join(names[:shown]) + (f" and {len(names) - shown} more" if len(names) > shown else "")


def _first_line(exc: Exception) -> str:
    return (str(exc).strip().splitlines() or [type(exc).__name__])[0][:200]


def _check_sweep_table(frame: pd.DataFrame, path: str) -> None:
    columns = [str(c) for c in frame.columns]
    layout = "written by clutchopt sweep --out: point, the varied inputs, status, the objective, ..."
    if columns[:1] != ["point"] or "status" not in columns:
        raise InputError(path, f"not a sweep table ({layout})")
    status = columns.index("status")
    if status < 2 or status + 1 >= len(columns):
        raise InputError(path, f"not a sweep table: no varied input before status or no objective after it ({layout})")
    if not 0 < len(frame) <= MAX_POINTS:
        raise InputError(path, f"a sweep table has 1 to {MAX_POINTS:,} rows, this one {len(frame):,}")
    problems = Problems()
    for column in columns[:status] + [columns[status + 1]]:
        values = pd.to_numeric(frame[column], errors="coerce")
        blank = frame[column].isna()
        if (values.isna() & ~blank).any() or (column != columns[status + 1] and blank.any()):
            problems.errors.append(InputError(f"{path}: column {column!r}", "must hold numbers in every row"))
        elif not np.isfinite(values[~blank]).all():
            problems.errors.append(InputError(f"{path}: column {column!r}", "must hold finite numbers"))
    unknown = sorted(set(map(str, frame["status"].dropna())) - set(STATUSES))
    if unknown or frame["status"].isna().any():
        problems.errors.append(InputError(f"{path}: column 'status'", f"must be one of {', '.join(STATUSES)} "
                                                                      f"in every row, got {unknown[:3] or 'blanks'}"))
    problems.raise_any()


def table_cell(value) -> str:
    """A sweep table's cell: numbers to 6 digits, ``-`` where a point has no value (no design: an infeasible point;
    no iteration count: a point solved in a batch)."""
    if value is pd.NA or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def markdown_table(frame: pd.DataFrame) -> str:
    lines = ["| " + " | ".join(frame.columns) + " |", "|" + "---|" * len(frame.columns)]
    lines += ["| " + " | ".join(table_cell(v) for v in row) + " |" for row in frame.itertuples(index=False)]
    return "\n".join(lines)
