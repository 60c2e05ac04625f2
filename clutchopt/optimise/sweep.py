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
from the windows' arrays; each point's record only when read (``SweepResult.solutions``) or stored. The grid comes
from ``clutchopt.optimise.sweep_grid``; the table is written and read back by ``clutchopt.optimise.sweep_table``.
"""

from __future__ import annotations

import math
import os
import signal
import threading
import time
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import dataclass, field, replace
from functools import cached_property, partial
from typing import Callable, Iterator

import numpy as np
import pandas as pd

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.formulations import get_coupling
from clutchopt.materials import chosen, variants
from clutchopt.model import Formulation, followed
from clutchopt.optimise.batch import BatchSweep, Solutions, batchable
from clutchopt.optimise.batch_carried import Carried, stored_design
from clutchopt.optimise.dask_client import connect
from clutchopt.optimise.design import Robustness, check_robustness, design_case, method_of
from clutchopt.optimise.entering import check_entering
from clutchopt.optimise.problem import case_formulation, case_problem
from clutchopt.optimise.region_proof import Regions
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.optimise.start_up_region import beyond, in_a_region, region_tested
from clutchopt.optimise.start_up_sweep import solved_along, started_warm
from clutchopt.optimise.sweep_table import ASPECTS, case_aspects
from clutchopt.optimise.sweep_grid import (Points, Vary, check_points, column_name, grid_points, grid_positions,
                                           parse_vary)  # parse_vary: the README's ``from ...sweep import parse_vary``
from clutchopt.optimise.table import joined_tables, record_table
from clutchopt.optimise.verdict import GIVEN, NEIGHBOUR, NEXT, one_more_start, retried
from clutchopt.records import DESIGN_STATUSES
from clutchopt.start_up.mesh import settled
from clutchopt.solver_tolerance import SOLVER_TOL
from clutchopt.records import design_inputs, scatter_record
from clutchopt.window_records import WindowRecords, in_order
from clutchopt.units import from_si

SPENT = ("solves", "solver_s", "check_s")  # what solving points costs: solver calls, seconds in them and in checks


def total_spent(parts: list["PointResults"]) -> dict:
    return {key: sum(part.spent[key] for part in parts) for key in SPENT}


class PointResults:
    """Solved points of a sweep, in point order: their indices and values, their rows of the sweep table (a batched
    window's read from its arrays), and their records, built when asked for: as the run store keeps them (a point
    solved alone's ``Solution.as_dict()`` by position, a window's batched points' as arrays with their positions:
    ``clutchopt.window_records``; ``stored``: the points solved alone that share a template gathered as arrays too,
    ``held``: kept as records) and in full (``Solution.as_dict()``: ``--json``, ``SweepResult.solutions``; kept
    once built). ``spent``: their solver calls (``solves``) and seconds in them (``solver_s``) and in the batches'
    compiled checks (``check_s``)."""

    def __init__(self, points: Points, names: list[str], alone: dict[int, dict] | None = None,
                 windows: list[tuple[np.ndarray, WindowRecords]] | None = None, solutions: Solutions | None = None,
                 spent: dict | None = None, carried: Carried | None = None):
        self.points, self.names, self.spent = points, names, spent or dict.fromkeys(SPENT, 0)
        self.carried = carried  # a batched window's: what the point after it starts from (batch_carried)
        self._alone, self._windows, self._solutions, self._records = alone or {}, windows or [], solutions, None

    def __len__(self) -> int:
        return len(self.points)

    def stored(self) -> tuple[dict[int, dict], list[tuple[np.ndarray, WindowRecords]]]:
        """The records as the run store keeps them (a window's built afresh from its arrays each time: not kept
        once written; its points solved alone that share a template as arrays too: ``Solutions.stored``)."""
        return (self._alone, self._windows) if self._solutions is None else self._solutions.stored()

    def held(self) -> tuple[dict[int, dict], list[tuple[np.ndarray, WindowRecords]]]:
        """The records as :meth:`records` builds them: each point solved alone's ``Solution.as_dict()`` by position,
        a window's batched points' as arrays with their positions."""
        return (self._alone, self._windows) if self._solutions is None else self._solutions.held()

    def records(self) -> list[dict]:
        """Each point's ``Solution.as_dict()``."""
        if self._records is None:
            self._records = in_order(len(self), *self.held())
        return self._records

    def table(self) -> dict[str, np.ndarray]:
        return self._solutions.table() if self._solutions is not None else record_table(self.records(), self.names)

    @classmethod
    def joined(cls, parts: list["PointResults"], names: list[str]) -> "PointResults":
        """Consecutive results as one, with their records as :meth:`held` keeps them (what a worker sends back; the
        store gathers its points solved alone from those records)."""
        alone, windows, offset = {}, [], 0
        for part in parts:
            part_alone, part_windows = part.held()
            alone.update((offset + position, record) for position, record in part_alone.items())
            windows += [(offset + positions, window) for positions, window in part_windows]
            offset += len(part)
        return cls(Points.joined([part.points for part in parts]), names, alone, windows, spent=total_spent(parts))


CONTINUATION_STEPS = 3  # from the last feasible point to one without a design, before its verdict


@dataclass(frozen=True)
class StoredDesign:
    """A stored point's design (SI): what a resumed run's first point takes of the last feasible point before it, its
    neighbour's design and the continuation's start (:func:`solve_points`' ``feasible``)."""

    design: dict[str, float]


def solve_points(case: Case, mode: str, objective: str, tol: float, robust: Robustness | None,
                 points: Points, carried: Carried | None = None,
                 feasible: tuple[dict, StoredDesign] | None = None) -> Iterator[PointResults]:
    """Solve points in order, each warm-started from the last optimum; yields the results as they are solved: a
    window of points at once where the problem allows batches (``clutchopt.optimise.batch``; each window's results
    with what the next window starts from, ``carried``), else one point each. With ``options.choose`` or
    ``robust``, each point is designed as ``solve`` designs a case (every choice, for the scatter:
    :func:`~clutchopt.optimise.design.design_case`), the best kept with its choice. ``carried``: a resumed batched
    sweep's window start (``points`` all of the sweep's; those from ``carried.point`` on are solved; only a batched
    window records one, and a sweep's key fixes whether it batches). ``feasible``: a resumed run's last feasible point
    before ``points`` (its values and stored design), whose design its first points without one are retried from as
    the uninterrupted run's are (the neighbour's design, the continuation)."""
    problem = case_problem(case, mode, objective, SolverOptions(tol=tol))
    names = [v.name for v in problem.formulation.variables]
    if robust is not None or case.options.get("choose"):
        for j, (index, values) in enumerate(points.pairs()):
            best = design_case(case.with_values(**values), mode, objective, SolverOptions(tol=tol), robust)[0]
            yield PointResults(points[j:j + 1], names, {0: best.as_dict()},
                               spent={"solves": best.solution.solver.solves, "solver_s": best.solution.solver.time_s,
                                      "check_s": 0})
        return
    if len(points) and batchable(problem, points.columns):
        sweep = BatchSweep(problem, case, points.columns)
        first, before = 0 if carried is None else carried.point, dict.fromkeys(SPENT, 0)
        for window in sweep.run(carried=carried):
            now = {key: getattr(sweep, key) for key in SPENT}
            yield PointResults(points[first:first + len(window)], names, solutions=window,
                               spent={key: now[key] - before[key] for key in SPENT}, carried=sweep.carried)
            first, before = first + len(window), now
        return
    with problem.failed_starts.along_a_run():  # (the paths a start-up run lost, for its later points alone)
        previous: Solution | None = None  # the last point's optimum (a warm start), None next to a failure
        # feasible: the last feasible point's values and design (a resumed run's: stored, ``StoredDesign``)
        designs: dict[tuple, Solution] = {}  # feasible designs by the point's values
        waiting: list[tuple[int, Case, Solution]] = []  # points without a design, until the next feasible one (those
        # proven infeasible recorded at once where none waits before them: :func:`_proven_first`)
        last_without: tuple[int, Solution] | None = None  # the last point without a design
        pairs = list(points.pairs())
        regions = Regions(problem, lambda k: case.with_values(**pairs[k][1]), len(pairs))
        for j, (index, values) in enumerate(pairs):
            point_case = regions.point_case(j)  # (built once: the regions keep it from their search on to its verdict)
            neighbour = designs.get(tuple(values.values())) or (feasible[1] if feasible else None)
            without = ((pairs[j - 1][1], last_without[1]) if last_without and last_without[0] == j - 1
                       and pairs[j - 1][0] == index - 1 else None)  # (the point before in the run and in the grid: a
            # resumed run's pending points may have a stored one between them)
            # next to a point without a design: proven with the points around it, or solved once and proven alone
            solution = regions.point(j, partial(_solved, problem, case, point_case, values, previous, feasible,
                                                neighbour, without), previous if problem.start_up is None else None)
            previous = solution if solution.status == "optimal" else None
            if solution.status not in DESIGN_STATUSES:
                settled(solution.mesh)  # (kept until the next feasible point: its simulation's columns let go)
                waiting.append((j, point_case, solution))
                last_without = j, solution
                yield from (_one(points, w, names, proven) for w, proven in _proven_first(waiting))
                continue
            feasible = values, solution
            designs[tuple(values.values())] = StoredDesign(solution.design)  # (a neighbour's design is all read)
            for k, (w, waited_case, waited) in enumerate(waiting):  # between feasible neighbours: from this one too
                if waited.status == "infeasible":  # proven: no design to find
                    continue
                if in_a_region(waited):  # (a start-up point its neighbour's reason decided: no solve alone behind it)
                    waited = alone_after_all(problem, waited_case, waited)
                    if waited.status in DESIGN_STATUSES or waited.status == "infeasible":  # (proven: none to find)
                        waiting[k] = (w, waited_case, waited)
                        continue
                alone = waited if problem.start_up is not None else None  # (a start-up's: its solve alone)
                retry = problem.solve(waited_case, start=solution.design, alone=alone)  # (``alone`` counted here)
                kept = beside(retry, alone) if retry.status in DESIGN_STATUSES else replace(
                    waited, starts=waited.starts + ((NEXT,) if _tried(problem, retry) else ()))  # (its start named
                # among those tried, where it was solved from)
                waiting[k] = (w, waited_case, replace(kept, solver=kept.solver.summed([waited.solver, retry.solver])))
            yield from (_one(points, w, names, waited) for w, _, waited in waiting)
            waiting = []
            yield _one(points, j, names, solution)
        yield from (_one(points, w, names, waited) for w, _, waited in waiting)


def _proven_first(waiting: list[tuple[int, Case, Solution]]) -> Iterator[tuple[int, Solution]]:
    """The points at the head of ``waiting`` (points without a design, in order) proven infeasible, taken out of it:
    no later design is tried from at them, so they are recorded at once, in order (a run through a region proven
    point by point had recorded nothing until its next feasible point: a store kept none of it, a kill lost it all;
    review 20)."""
    while waiting and waiting[0][2].status == "infeasible":
        w, _, proven = waiting.pop(0)
        yield w, proven


def _tried(problem, retry: Solution) -> bool:
    """A retry from a start given (``Problem.solve``'s ``start``) was solved from it: a start-up's names it first
    (``verdict.GIVEN``), unless its first simulation failed there (``solve`` then hands back its verdict alone)."""
    return problem.start_up is None or retry.starts[:1] == (GIVEN,)


def _solved(problem, case: Case, point_case: Case, values: dict, previous: Solution | None,
            feasible: tuple[dict, Solution | StoredDesign] | None, neighbour: Solution | StoredDesign | None,
            without: tuple[dict, Solution] | None, first: Solution | None) -> Solution:
    """A point's full verdict in a sweep solved point by point (continuing from ``first``, a solve already made:
    ``Problem.solve``'s ``first``): falls back to the case's own start by itself; a start-up design starts from the
    point before's optimum on the first mesh (clutchopt.optimise.start_up_sweep), else as `solve` does, from the papers'
    sizing at the point: either way solve's design whatever the points before it. A start-up's point the warm start
    brings to no optimum is solved as ``solve`` solves it alone (its starts, the sampled design last:
    :mod:`clutchopt.optimise.sampled_start`), at every point without a design, not only the first past one; only then
    from the starts the sweep adds, which reach the local optimum nearest the points before, not always ``solve``'s
    (:func:`from_the_neighbour`): the neighbour's design, then the continuation. Without a design, followed from the
    last feasible point (:func:`continued`; ball_motor_start in paper mode from 507.9 to 605.7 kW: its continuation
    lost 554.69 kg, which the sampled design reaches). A start-up point beyond a point without a design (``without``:
    its values and verdict) that ``solve``'s first solve leaves without one is tested against that point's reason
    (:mod:`clutchopt.optimise.start_up_region`): that first solve's own least relaxation decides the point where it
    violates a constraint the point before's did; else a solve from the point before's least relaxation, then from
    the first one's, each deciding where its least relaxation does; else the full verdict follows from that first
    solve, the test's solves counted with it and named among its starts. ``point_case``: ``case`` with ``values``."""
    alone, tested = None, []  # a start-up point's verdict as ``solve`` of it alone gives it, where that has no
    # design; the solves of its test against the reason of the point before without a design (each with its label)
    if problem.start_up is None:
        solution = problem.solve(point_case, warm=previous, first=first,
                                 neighbour=neighbour.design if neighbour is not None else None)
    else:
        if without is not None and beyond(values, feasible[0] if feasible else None, without[1], without[0]):
            first = first or problem.refined(point_case)  # (``solve``'s first solve, from the papers' sizing)
            if first.status not in DESIGN_STATUSES and first.diagnosed is not None and not first.diagnosed.proven:
                decided, tested = region_tested(problem, point_case, first, without[1])
                if decided is not None:
                    return decided
        along = solved_along(problem, point_case, previous)
        solution = along if along is not None and along.status == "optimal" else problem.solve(
            point_case, first=first).counted(along)  # (a warm start that failed counted too)
        alone = solution if solution.status not in DESIGN_STATUSES else None
        if neighbour is not None and not problem.failed_starts.lost_beyond(point_case, neighbour.design):
            solution = from_the_neighbour(problem, point_case, solution, neighbour.design)
    if solution.status not in DESIGN_STATUSES and solution.status != "infeasible" and feasible is not None:
        followed = continued(problem, case, feasible, values)  # (a proven point: no design to follow)
        solution = followed.counted(solution) if followed is not None and followed.status in DESIGN_STATUSES \
            else solution.counted(followed)
    for label, made in tested:  # (each solve counted and named; a design one found kept where the verdict has none)
        solution = one_more_start(solution, made, label) if solution.status not in DESIGN_STATUSES else \
            solution.counted(made)
    return beside(solution, alone)


def alone_after_all(problem, case: Case, decided: Solution) -> Solution:
    """A start-up point the test against its neighbour's reason ``decided`` (``start_up_region``), once a later point
    of the run has a design: ``solve`` of it alone, whose verdict comes first (the later point's start is tried only
    where it has no design, kept and said so where it reaches one: :func:`beside`; the neighbour's design and the
    continuation, which a point without a design solved at its turn tries, are not); without a design, the test's
    starts named among its starts; every solve counted (the test's first solve made again: not handed on)."""
    alone = problem.solve(case)
    starts = alone.starts + tuple(s for s in decided.starts if s not in alone.starts) \
        if alone.status not in DESIGN_STATUSES else alone.starts
    return replace(alone, starts=starts, solver=alone.solver.summed([decided.solver, alone.solver]))


def beside(solution: Solution, alone: Solution | None) -> Solution:
    """A start-up sweep point's ``solution``, saying what ``solve`` of the point alone ended with (``alone``: its
    verdict without a design; ``Solution.beside_alone``) where a start the sweep adds (the neighbour's design, the
    continuation, the next feasible point's design) reached a design ``solve`` alone did not; said once."""
    if alone is None or solution.status not in DESIGN_STATUSES:
        return solution
    return solution.beside_alone(alone)


def from_the_neighbour(problem, case: Case, verdict: Solution, design: dict[str, float]) -> Solution:
    """A start-up point's ``verdict`` from ``solve``'s own starts (its last the sampled design), where it has no design
    and no proof, retried from ``design`` (the last feasible point's): the retry's design where it reaches one, else
    ``verdict`` with that start named among those tried; the solver calls of both summed. Tried after ``solve``'s
    starts, not among them: a start of the sweep's own reaches the local optimum nearest the point before, which need
    not be the one ``solve`` of the point alone reaches (ball_motor_start in paper mode at 1.5 GPa over the service
    factor, on NumPy's AVX2 loops: at 1.55 the neighbour's design, tried before the interval search's and the sampled
    one, reached 745.45 kg, the torque alone active, where ``solve`` reaches 672.62 kg, the start time active too; at
    1.44 the continuation 545.449 kg where ``solve`` reaches 541.127 kg: tests/test_start_up_sweep_local.py)."""
    if verdict.status in DESIGN_STATUSES or verdict.status == "infeasible":
        return verdict
    return one_more_start(verdict, retried(problem, case, design), NEIGHBOUR)


def continued(problem, case: Case, feasible: tuple[dict, Solution | StoredDesign], values: dict,
              steps: int = CONTINUATION_STEPS) -> Solution | None:
    """The design at ``values`` followed from a feasible point's (its values, its design) in ``steps`` equal steps
    of the varied quantities, each started from the last: the last step's solve, with every step's solver calls (a
    step that finds no design ends it, without one); None where no step is solved (a path already lost). A start-up's
    step starts warm from the step before's optimum (the feasible point's first), as a sweep's point starts from the
    point before's (``start_up_sweep.started_warm``: its multipliers, collocation states, mesh and moved limits), where
    that is an optimum of this problem; else (a stored design, an optimum of the loop's doubled problem) from its design
    alone, its loop from the first mesh (wedge_motor_start from 0.4 to 0.6 kg m^2: 4 solver calls, 41 IPOPT
    iterations, warm 3 and 14; ball_motor_start from 300 to 370: 20 and 697, warm 8 and 111; the same designs)."""
    (before, solution), found, spent = feasible, None, []
    lost = problem.failed_starts if problem.start_up is not None else None  # (a path already lost: not followed
    # beyond, clutchopt.optimise.failed_starts)
    for step in range(1, steps + 1):
        share = step / steps
        moved = {name: before[name] + share * (value - before[name]) for name, value in values.items()}
        if lost is not None and step == 1 and lost.lost_beyond(case, solution.design, before, moved):
            return None
        at = case.with_values(**moved)
        warm = started_warm(problem, at, solution) if lost is not None else None  # (from the step before's optimum)
        found = warm if warm is not None else problem.refined(at, solution.design, diagnosed=False)
        spent.append(found.solver)
        if found.status not in DESIGN_STATUSES:
            if lost is not None:
                lost.lose(case, feasible[1].design, before, moved)
            break
        solution = found
    return replace(found, solver=found.solver.summed(spent))


def _one(points: Points, j: int, names: list[str], solution: Solution) -> PointResults:
    return PointResults(points[j:j + 1], names, {0: solution.as_dict()},
                        spent={"solves": solution.solver.solves, "solver_s": solution.solver.time_s, "check_s": 0})


def solve_chunk(case: Case, mode: str, objective: str, tol: float, robust: Robustness | None,
                chunk: Points) -> PointResults:
    """A chunk of neighbouring points solved in one worker (process pool, Dask), with its records."""
    names = [v.name for v in case_formulation(case, mode).variables]
    return PointResults.joined(list(solve_points(case, mode, objective, tol, robust, chunk)), names)


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


def _in_order(kept: np.ndarray, pending: Points) -> bool:
    """Whether the points stored (``kept``, their indices in order) are those before the first pending one."""
    first = int(pending.index[0])
    return len(kept) == first and (not len(kept) or int(kept[-1]) == first - 1)


def _last_feasible(points: list[dict], stored: dict[int, dict], kept: np.ndarray, pending: Points,
                   names: list[str]) -> tuple[dict, StoredDesign] | None:
    """Where a sweep solved point by point resumes after its first points, stored in order: the last of them with a
    design (its varied values and stored design), as the uninterrupted run's points after it see it (its neighbour's
    design, the continuation's start); None where there is none, or the points stored are not those before the first
    pending one (a pool's), or its stored design is not one of the problem's (``names``, each a finite number:
    ``batch_carried.stored_design``; a damaged or hand-edited store: the first points then solved cold)."""
    if not _in_order(kept, pending):
        return None
    for index in reversed(kept.tolist()):
        record = stored[index]
        if isinstance(record, dict) and record.get("status") in DESIGN_STATUSES:
            try:
                return points[index], StoredDesign(stored_design(record.get("design"), names))
            except ValueError:
                return None
    return None


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
                 tol: float = SOLVER_TOL, zipped: bool = False, robust: Robustness | None = None):
        varies = [varies] if isinstance(varies, Vary) else list(varies)  # (one Vary, or any iterable of them)
        if not all(isinstance(v, Vary) for v in varies):
            raise InputError("--vary", "give Vary objects (parse_vary('speed=500:3000:26', coupling))")
        self.case = case = case.given(*(v.quantity.name for v in varies))
        self.varies, self.robust = varies, robust
        self.formulation: Formulation = case_formulation(case, mode)
        self.objective = self.formulation.objective(case.objective_of(objective))
        case.require(self.objective.name)
        self.tol = tol
        self.grid, self.zipped = grid_points(varies, zipped), zipped
        sets, _ = chosen(case, get_coupling(case.coupling))
        for v in varies:
            if v.quantity.name in sets:
                raise InputError(f"--vary {v.quantity.name}", f"options.choose.{sets[v.quantity.name]} sets it for "
                                 "each choice; vary it in a case that names one entry")
        problem = case_problem(case, self.formulation.mode, self.objective.name, SolverOptions(tol=tol))
        check_entering(case, problem, [v.quantity.name for v in varies], "--vary {}")  # (before the points: a
        check_points(case, varies, self.grid, scattered=robust is not None)  # quantity no point could set is named)
        check_robustness(case, robust, problem)
        if robust is not None:
            scattered = {s.name for s in case.scatter} & {v.quantity.name for v in varies}
            if scattered:
                raise InputError(f"--vary {sorted(scattered)[0]}", "also scatters in the case's [scatter], which a "
                                 "robust design spreads around its own value: vary it without --robust, or edit "
                                 "its range")

    def identity(self) -> dict:
        """What a table of this sweep carries to say which case it was swept from (see :func:`check_swept_from`):
        the coupling, the case's path and SI values, mode, objective, robust method (empty: nominal designs) and the
        varied columns."""
        return {"coupling": self.case.coupling, "case": self.case.path, "values": self.case.values,
                "mode": self.formulation.mode, "objective": self.objective.name,
                "robust": self.robust.label if self.robust is not None else "",
                "varies": [v.column for v in self.varies], ASPECTS: case_aspects(self.case)}

    @cached_property
    def points(self) -> list[dict[str, float]]:
        """Each point's varied values (SI) by quantity name."""
        return self.grid.values()

    @property
    def spec(self) -> dict:
        """What defines the sweep, its resume key: coupling, mode, objective, tolerance, the case (values, free
        variables, bounds, choices), the robust method and the points (each varied quantity's SI values by name)."""
        return {**self._defined, "points": {name: column.tolist() for name, column in self.grid.columns.items()}}

    @property
    def older_spec(self) -> dict:
        """:attr:`spec` as an older clutchopt wrote it (the points a dict each): its key finds a sweep it stored."""
        return {**self._defined, "points": self.points}

    @property
    def _defined(self) -> dict:
        return {"coupling": self.case.coupling, "mode": self.formulation.mode, "objective": self.objective.name,
                "tol": self.tol, "case": {"values": self.case.values, "free": list(self.case.free),
                                          "bounds": self.case.bounds,
                                          **({"choose": self.case.options["choose"]}
                                             if self.case.options.get("choose") else {})},
                **({"robust": {**self.robust.as_dict(self.case), "scatter": scatter_record(self.case)}}
                   if self.robust is not None else {})}

    def run(self, store=None, resume: bool = False, jobs: int = 1, runner: Callable | None = None,
            progress: bool = True, chunk_size: int | None = None) -> SweepResult:
        """Solve every point not already stored; ``runner`` (e.g. :func:`dask_runner`) overrides ``jobs``."""
        from tqdm import tqdm

        sweep_id, stored = None, {}
        if store is not None:
            sweep_id = store.latest_sweep(self.spec, self.older_spec) if resume else None
            if sweep_id is not None:
                stored = store.sweep_outputs(sweep_id, self.points)
            else:  # a new sweep (None: the store failed), nothing of it stored yet
                sweep_id = store.new_sweep(self.spec, len(self.grid), self.case.path)
        kept = np.array(sorted(stored), dtype=int)
        pending = self.grid[np.isin(self.grid.index, kept, invert=True)] if stored else self.grid
        workers = max(jobs, 1)
        size = chunk_size or max(1, min(25, math.ceil(len(pending) / (4 * workers))))
        task = (self.case, self.formulation.mode, self.objective.name, self.tol, self.robust)
        names = [v.name for v in self.formulation.variables]
        parts = [PointResults(self.grid[kept], names, dict(enumerate(stored[i] for i in kept.tolist())))]
        bar = tqdm(total=len(self.grid), initial=len(stored), unit="point", desc="sweep", disable=not progress,
                   mininterval=0.5)
        sequential = runner is None and jobs <= 1  # (windows one after another: each starts from the one before)
        resumed = bool(stored) and sequential and len(pending) > 0  # (after its first points, in this process)
        carried = self._carried(store, sweep_id, kept, pending) if resumed else None
        feasible = _last_feasible(self.points, stored, kept, pending, names) if resumed else None
        starts = sequential and (not stored or carried is not None)  # (windows from point 0 or from a stored start
        # record where the next starts: a cold resume's count their points from its first, over other points)
        started = time.perf_counter()
        with bar, interrupt_between_points() as check:
            solving = (solve_points(*task, self.grid, carried) if carried is not None
                       else solve_points(*task, pending, feasible=feasible) if feasible is not None
                       else (runner or local_runner(jobs))(task, pending, size))
            for results in solving:
                if store is not None and sweep_id is not None:  # the results in hand in one transaction
                    store.record_points(self._inputs(), self._where(sweep_id), results.points.index,
                                        self._recorded(results), *results.stored(),
                                        carried=results.carried.as_dict() if starts and results.carried else None)
                elif store is not None:  # the sweep itself could not be recorded
                    store.unrecorded += len(results)
                parts.append(results)
                bar.update(len(results))
                check()
        elapsed = time.perf_counter() - started
        order = np.argsort(np.concatenate([part.points.index for part in parts]), kind="stable")  # pool: any order
        parts = [part for part in parts if len(part)]
        frame, records = self.frame(joined_tables([part.table() for part in parts]), order), SweepRecords(parts, order)
        self._aspect_columns(frame, records)
        return SweepResult(sweep_id, frame, len(pending), len(stored), elapsed, records, total_spent(parts))

    def _carried(self, store, sweep_id: int, kept: np.ndarray, pending: Points) -> Carried | None:
        """Where a sweep resumes after its first points, stored in order, at a batched window's start: what the
        uninterrupted run started that window from, as recorded with the window before (``batch_carried``), so that
        the resumed points are the uninterrupted run's bit for bit. None (the points solved from cold, as before)
        where the store holds none: points stored out of order (a pool), or by an older clutchopt. A damaged one
        (``Carried.from_dict`` refuses it): StoreError."""
        if not _in_order(kept, pending):
            return None
        first = int(pending.index[0])
        posed = case_problem(self.case, self.formulation.mode, self.objective.name, SolverOptions(tol=self.tol)).posed
        return store.sweep_start(sweep_id, first, partial(Carried.from_dict, point=first, variables=posed.names,
                                                          rows=len(posed.lbg)))

    def _aspect_columns(self, frame: pd.DataFrame, records: "SweepRecords") -> None:
        """Where each point was designed as ``solve`` designs (``options.choose``, ``--robust``): the choice kept
        and the robust design's largest failure probability (Monte Carlo), after the objective (a table's layout:
        point, the varied inputs, status, the objective, ...)."""
        at = frame.columns.get_loc("status") + 2
        if self.robust is not None:  # Monte Carlo: the estimate, and its 95 % upper bound beside it
            from clutchopt.optimise.robust_models import largest_failure

            largest = [largest_failure(record["robust"]["failure_probability"]) if "robust" in record else None
                       for record in records]
            for column, index in (("largest P(fail) 95% high", 3), ("largest P(fail)", 1)):
                frame.insert(at, column, [np.nan if row is None else row[index] for row in largest])
        if self.case.options.get("choose"):
            frame.insert(at, "choice", pd.Series([", ".join(f"{key} = {name}" for key, name in
                                                           record.get("choice", {}).items()) for record in records],
                                                 dtype=object))

    def _inputs(self) -> dict:
        """What the points' inputs share as the store keeps them (:func:`~clutchopt.records.design_inputs`): the case's
        SI values (each point's varied values, checked when the sweep was made, replace the case's), its free
        variables and bounds, how it was designed."""
        return design_inputs(self.case, self.case.values, method_of(self.robust))

    def _recorded(self, results: PointResults) -> dict[str, np.ndarray]:
        """The points' own values the store keeps beside the case's: the varied ones, each default that follows one
        and, with options.choose, what each point's choice fills from the library (review 30: a start-up's load
        following the swept resisting torque had been stored at the case's value, a 42CrMo4 design beside the first
        choice's C45 allowable stress)."""
        recorded = dict(results.points.columns)
        for _ in self.case.follows:  # (a chain: one more link a pass)
            recorded = followed(recorded, self.case.follows)
        if self._chosen_values:
            picked = [self._chosen_values.get(tuple(sorted(record.get("choice", {}).items())), {})
                      for record in results.records()]
            for name in {name for values in self._chosen_values.values() for name in values}:
                recorded[name] = np.array([values.get(name, self.case.values[name]) for values in picked])
        return recorded

    @cached_property
    def _chosen_values(self) -> dict[tuple, dict[str, float]]:
        """What each choice of options.choose sets, by its (role, entry) pairs (none without): what it fills from the
        library and what follows from that (review 31: a friction pair's friction_max, derived from the pair, had
        been the first choice's)."""
        coupling = get_coupling(self.case.coupling)
        found = [(choice, variant) for choice, variant in variants(self.case, coupling) if choice]
        names = set(chosen(self.case, coupling)[0]) | {name for _, variant in found for name, value in
                                                        variant.values.items() if value != self.case.values.get(name)}
        return {tuple(sorted(choice.items())): {name: variant.values[name] for name in names if name in variant.values}
                for choice, variant in found}

    def _where(self, sweep_id: int) -> dict:
        """The store's fields every point of the sweep shares."""
        return {"method": method_of(self.robust), "objective_unit": self.objective.unit, "case_path": self.case.path,
                "title": self.case.title, "coupling": self.case.coupling, "mode": self.formulation.mode,
                "objective_name": self.objective.name, "sweep_id": sweep_id}

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
