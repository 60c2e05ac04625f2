"""Sweeps solved in batches: neighbouring points re-solved in one compiled call, then verified together.

Along a sweep each point is re-solved next to the optimum of the one before. ``Problem.solve`` does that one point
at a time, and there a 20-40 us SQP re-solve sits inside about 0.3 ms of Python (argument conversion, the float64
check, outputs, sensitivities, bookkeeping). Here a batch of consecutive points goes to one CasADi function that
chains the SQP re-solves inside CasADi (``chain.chained_sqp``: ``mapaccum`` over the ``sqpmethod`` solver; each
point starts from the primal-dual optimum of the one before, moved on by a secant predictor, so that one SQP
iteration usually does), its NumPy arrays read and written in place (``clutchopt.optimise.in_place``), and the
tests of ``Problem.solve`` run afterwards on all points of the batch at once:

- in one mapped CasADi evaluation (``chain.chain_verdict``): the KKT conditions of every point, apart from the
  solver; the integer test of the warm integer search (a point whose fixed integers' bound multipliers point to a
  neighbouring integer the search would solve ends the chain); without integers, whether the optimum has moved
  more than tenfold from the variable scales (the solve is repeated with new scales there); and, where fewer rows
  and bounds hold a point than it has variables, that no direction they leave free curves down (``chain.curvature``,
  in a call of its own where it is compiled, the ball's; a chained SQP had kept a maximum along one: the point fails
  its test);
- a batch stops short of the point where its integers break a constraint of fixed variables alone that they enter
  (the search excludes them there without a solve), found ahead of the batch by a mapped CasADi evaluation (the
  exclusion tables); where one neighbouring combination is left there (the cable count, one cable more, as its
  torque rises), the chain goes on with it instead, its bounds a column each, and that point is settled from its
  column as the search's first attempt (``BatchSweep._changed``, or the search itself where its outcome is not
  certain): one chained call through the changes, not one that ends at each and a one-point re-solve there;
- at the end of a window of points (up to 1024, or about a quarter of a second's work, counted), the float64 re-evaluation
  of every constraint and the objective by the formulation's own equations (``verify``'s arithmetic), vectorised
  over the points.

A batch is kept up to its first point that fails a test. Where the integer search decides that point (its
integers excluded there, or a neighbour to try), the batch runs the search itself, with ``Problem.solve``'s steps
(``integers.descend``, then the relaxation and ``integers.nearest_integers``): each integer combination is excluded
by the tables or re-solved by a one-point chained SQP and KKT-checked (the relaxation with its Hessian
convexified; the batch's own integers not again where the chain solved them at that point: its column there is
the first attempt; a combination the search verified at the point before from its own optimum there, not from the
search's: the wedge's weights over its inertia in geometry mode, 4 promised by 3's multipliers, 2.5 -> 0.13 ms a
solve). A combination the one-point SQP does not settle goes to SQP on its least largest violation
(``feasibility``): a verified local minimum above 1e-6 keeps it out of the search (IPOPT's
``Infeasible_Problem_Detected`` at 0.3 ms instead of 5-15 ms: the ball's rows, each time they carry no more), a design
found there is re-solved by SQP from it; otherwise it is solved as ``Problem.solve``'s search solves a neighbour, by
IPOPT from cold: kept out of the search where IPOPT finds no design (and at the next point tried again directly, or
not at all where the sweep has only tightened the constraints since: ``tightening``, whose combinations ruled out so
also do not end a chain), else re-solved by SQP from IPOPT's optimum (the ball's rows: one row fewer promised by the
multipliers but infeasible, point after point, had sent each point to ``Problem.solve``). A combination the search
found heavier at an earlier point than a chained point's optimum, the sweep having only tightened the constraints
since, cannot be lighter there, and does not end a chain either (the wedge's weights over its inertia, 300 points over
6x-10x: 299 -> 119 points where the neighbour was solved; at 100 points a step raises the mass more than the gap).
Where the neighbour the multipliers promise stops being excluded by a constraint of fixed variables alone (the cable
count one fewer as the allowable stress rises), the chain ends before that point and the search starts there at the
neighbour.
Where the batch's integers are excluded, or IPOPT finds no design with them, and one neighbouring combination is left,
the search starts there, without the relaxation (the cable count, one cable more; the ball's rows, one more where the
row fewer is ruled out). The next chain then ends where the next such point is expected (``batch_pace``; a point that
fails at the batch's integers is such a point too), or sooner where the active set is expected to change
(``batch_pace.until_active``). Otherwise,
and where a re-solve of that search fails its check, the point is solved by ``Problem.solve``, warm from the last
kept point (SQP, warm IPOPT, the integer search, the cold solve and the infeasibility diagnosis), and the next
batch starts after it, 8 points long, doubling while batches pass (up to 256). A chain's length is a power of two
(few functions to build): rather than leave a remainder of up to PADDING points to another call, it is padded with
columns that call no solver (``chain.chained_sqp``). After a point without a design the points are solved cold,
one by one, until one is optimal. A point that passes the KKT test but not the float64 check (rare) is solved again by
``Problem.solve`` at the end of its window. A chained call that CasADi ends with an evaluation error counts as a
batch whose first point failed. A window's points are checked and built into solutions by
``clutchopt.optimise.batch_window``.

The optima equal ``Problem.solve``'s to the solver's tolerance: a batch keeps the variable scales of the point it
starts from and normalises the objective by that point's objective, where ``Problem.solve`` takes both afresh from
each previous point. A design variable that the objective does not price at the optimum (the ball clutch's groove
conformity where the contact stress does not bind) may be left elsewhere by the batch's SQP than by
``Problem.solve``'s IPOPT, both verified optimal. A point solved in a batch reports ``sqpmethod`` with the status
``batched, KKT verified``, its share of the batch's time, its solver calls (1, or its integer search's re-solves),
the integer search where the batch ran one, and no iteration count (the
chained solver reports none per point).
"""

from __future__ import annotations

import math
import time
from typing import Iterator

import numpy as np

from clutchopt.cases import Case
import clutchopt.optimise.attempts as attempts
from clutchopt.optimise.attempts import warm_multipliers
from clutchopt.optimise.batch_carried import Carried
from clutchopt.optimise.batch_pace import BatchPace, until_active
from clutchopt.optimise.batch_window import BATCHED, Block, Checked, Solutions
from clutchopt.optimise.chain import (chain_verdict, chained_sqp, compiled_apart, curvature, curved_up,
                                      leaves_free)
from clutchopt.optimise.feasibility import LOCALLY_INFEASIBLE, Least, infeasible, least
from clutchopt.optimise.integers import (EXCLUDED, descend, downhill, excluded_entry, nearest_integers,
                                         relaxation_seed, search_entry)
from clutchopt.optimise.interval_proof import boxes_evaluated, carry_boxes, last_boxes
from clutchopt.optimise.posed import Box, ScaledData, off_scale
from clutchopt.optimise.problem import Problem
from clutchopt.optimise.region_proof import Regions, SharedBox
from clutchopt.optimise.solution import Solution, WarmStart
from clutchopt.optimise.tightening import tightening
from clutchopt.records import DESIGN_STATUSES
from clutchopt.optimise.verify import FEASIBILITY_TOL

FIRST_BATCH = 8  # points in the batch after a point solved one by one
LONGEST_BATCH = 256  # doubling stops here: a longer batch saves little call overhead and risks more waste
WINDOW = 1024  # points whose float64 checks run together; results are handed on (and recorded) per window,
WINDOW_WORK = 8192  # or once this much work is done, whichever comes first (a progress bar moves on): work counted,
# not the clock, ends a window, so that the same sweep gives the same bits on a loaded or an idle machine (where a
# window ends, its last chain is cut short, and the next starts from its last column)
STRETCH_WINDOWS = 8  # a stretch of points without a design runs on past a window's end up to this many windows'
# points and work: a window ends at a point with a design where it can, since a window starts its region proofs afresh
# (batch_carried; ended inside the lever's 2,516 points without a design, its proof across the end was lost: 2 solves)
CHAINED_POINT_WORK, CHAIN_CALL_WORK, SOLVE_WORK = 1, 8, 64  # the work of a chained point, of a chained call besides
# its points, of any other solver call: about 30 us, 0.25 ms and 2 ms on the benchmark's machine (1000-point user
# sweeps: chains of 256 points 3-9 ms, of one point 0.2-0.3 ms; a point solved alone 0.2-15 ms, most 2 ms), so that
# WINDOW_WORK is about the quarter of a second that ended a window before (docs/tradeoffs.md, "Windows by work")
BOX_WORK = 0.5  # the work of a box an interval search evaluates (10-20 us: the lever in design mode proves a point
# in about 15,000 boxes, 150-290 ms; uncounted, a stretch of such points held its window for 26 s: review 20; a
# resumed search's boxes counted once, as evaluated: interval_proof.Emptiness.paused)
EXCLUSION_SPAN = LONGEST_BATCH  # points ahead whose exclusion of an integer combination is evaluated at once (a batch's
# points at least; fewer cost less where the integers change often, since each table is a mapped CasADi call)
PADDING = 64  # a chain may be padded with this many columns that call no solver to save a call (a padded column
# costs under 4 us, its verdict included, against 0.1-0.2 ms of a call and its checks)


def chain_length(count: int) -> int:
    """The chained function for ``count`` points: a power of two (few functions to build), ``count`` rounded up
    where that pads at most PADDING columns, else down (the rest go to the next batch)."""
    up = 1 << (count - 1).bit_length()
    return up if up - count <= PADDING else up >> 1


def batchable(problem: Problem, names) -> bool:
    """Batches serve problems without a start-up (its refinement loop is per point), whose warm re-solves try SQP,
    along case quantities that are not design variables (a varied fixed variable, e.g. the cable's lead angle,
    moves the bounds)."""
    f = problem.formulation
    quantities = {q.name for q in f.quantities} - {v.name for v in f.variables}
    return problem.start_up is None and problem.options.warm_sqp and set(names) <= quantities


class _Chain(Block):
    """Chained points with their KKT verdicts (``ok``) and whether the warm integer search would go on from them, or
    without integers re-scale (``moves``, see ``chain.chain_verdict``)."""

    def __init__(self, index: np.ndarray, ok: np.ndarray, moves: np.ndarray, **arrays: np.ndarray):
        super().__init__(index, **arrays)
        self.ok, self.moves = ok, moves

    def __getattr__(self, key: str) -> np.ndarray:
        try:
            return self.arrays[key]
        except KeyError:
            raise AttributeError(key) from None

    def run(self, j: int) -> dict:
        """Point ``j`` as a run (:func:`_run`)."""
        return _run(self, j)

    def column(self, j: int, f_scale: float) -> "_Chain":
        """Point ``j`` alone, its objective normalised by ``f_scale`` (the scaled problem's objective and multipliers
        are the chain's times its normaliser over ``f_scale``: the same optimum)."""
        a = {key: value[:, j:j + 1].copy() for key, value in self.arrays.items()}
        ratio = a["p"][-1, 0] / f_scale
        for key in ("f", "lam_x", "lam_g", "dlam_x", "dlam_g"):
            a[key] *= ratio
        a["p"][-1, 0] = f_scale
        return _Chain(self.index[j:j + 1], self.ok[j:j + 1], self.moves[j:j + 1], **a)


def _run(block: Block, j: int) -> dict:
    """Point ``j`` of a block as a run of ``integers.descend`` (its arrays' column, ``f`` a number): what the integer
    search and ``integers.downhill`` read."""
    return {key: value[:, j] for key, value in block.arrays.items()} | {"f": float(block.arrays["f"][0, j])}


def _zero_step(x: np.ndarray, lam_x: np.ndarray, lam_g: np.ndarray) -> dict:
    """No step to predict from at the primal-dual point ``x``, ``lam_x``, ``lam_g``: zeros of their shapes."""
    return {"dx": np.zeros_like(x), "dlam_x": np.zeros_like(lam_x), "dlam_g": np.zeros_like(lam_g)}


def _seed(x: np.ndarray, lam_x: np.ndarray, lam_g: np.ndarray) -> dict:
    """A start for SQP at the primal-dual point ``x``, ``lam_x``, ``lam_g`` (scaled), without a step to predict
    from."""
    return {"x": x, "lam_x": lam_x, "lam_g": lam_g, **_zero_step(x, lam_x, lam_g)}


def _from_design(x: np.ndarray, seed: dict) -> dict:
    """A start for SQP at the design ``x`` (scaled) with ``seed``'s constraint multipliers, without bound multipliers
    or a step to predict from. (From the least violation's design at the ball's rows, its multipliers zero, SQP
    stopped on a search direction too small at 2 of 3 combinations; with the previous optimum's constraint
    multipliers each converged in 2 iterations, with the Hessian's negative eigenvalues clipped.)"""
    return _seed(x, np.zeros_like(seed["lam_x"]), seed["lam_g"])


def _last_two(blocks: list[Block], integer: list[int]) -> Block | None:
    """The last two kept points as a block, where they are consecutive, with the same integers (SI) and variable
    scales (each from a chain or an integer search), so that each slack's step between them is the sweep's; None
    where they are not."""
    columns = [(block, j) for block in blocks[-2:] for j in range(max(len(block.index) - 2, 0), len(block.index))][-2:]
    if len(columns) < 2:
        return None
    pair = Block(np.array([block.index[j] for block, j in columns]),
                 **{key: np.concatenate([block.arrays[key][:, j:j + 1] for block, j in columns], axis=1)
                    for key in ("x", "lam_x", "lam_g", "p", "lbx", "ubx")})
    p, x, n = pair.arrays["p"], pair.arrays["x"], len(pair.arrays["lbx"])
    m = len(p) - n - 1
    scale = p[m:m + n]
    if pair.index[1] - pair.index[0] != 1 or not np.array_equal(scale[:, 0], scale[:, 1]):
        return None
    combos = np.round(x[integer] * scale[integer])
    return pair if np.array_equal(combos[:, 0], combos[:, 1]) else None


class _Unsettled(Exception):
    """A re-solve of the batched integer search that did not pass its check: ``Problem.solve`` decides the point."""


class _Start:
    """Where a batch starts: a primal-dual point that passed the tests, in its own scaling, and the same as the warm
    start of a point solved by ``Problem.solve``."""

    def __init__(self, sweep: "BatchSweep", solution: Solution | None = None, block: Block | None = None,
                 at: int = -1, carried: dict | None = None):
        n, m = len(sweep.names), len(sweep.posed.formulation.quantities)
        if solution is not None:
            self.scale = solution.scale
            self.x = np.array([solution.design[name] for name in sweep.names]) / self.scale
            self.lam_x, self.lam_g = warm_multipliers(sweep.posed, *solution.multipliers)
            self.objective = solution.objective
            self.step = _zero_step(self.x, self.lam_x, self.lam_g)  # nothing to predict from
        elif block is not None:  # its point ``at`` (its last)
            a, p = block.arrays, block.arrays["p"][:, at]
            self.scale, self.x, self.lam_x, self.lam_g = p[m:m + n], a["x"][:, at], a["lam_x"][:, at], a["lam_g"][:, at]
            self.objective = float(a["f"][0, at] * p[m + n])  # the scaled objective times its normaliser
            self.step = {key: a[key][:, at] for key in ("dx", "dlam_x", "dlam_g")}
        else:  # as :attr:`carried` gave it (a resumed sweep: ``batch_carried``)
            self.scale, self.x, self.lam_x, self.lam_g = (np.array(carried[key], dtype=float)
                                                          for key in ("scale", "x", "lam_x", "lam_g"))
            self.objective = float(carried["objective"])
            self.step = {key: np.array(carried[key], dtype=float) for key in ("dx", "dlam_x", "dlam_g")}
        self.names, self.integer = sweep.names, sweep.posed.integer
        self.combo = np.round(self.x[sweep.integer] * self.scale[sweep.integer])  # the free integers (SI)
        objective = self.objective
        self.f_scale = abs(objective) if math.isfinite(objective) and objective != 0 else 1.0  # the batch's normaliser

    @property
    def carried(self) -> dict:
        """The start as numbers (what ``_Start(sweep, carried=...)`` takes back, bit for bit through JSON)."""
        arrays = {"scale": self.scale, "x": self.x, "lam_x": self.lam_x, "lam_g": self.lam_g, **self.step}
        return {**{key: np.asarray(value, dtype=float).tolist() for key, value in arrays.items()},
                "objective": float(self.objective)}

    @property
    def run(self) -> dict:
        """The point as ``integers.downhill`` reads a run: its objective scaled by the batch's normaliser."""
        return {"x": self.x, "lam_x": self.lam_x, "f": self.objective / self.f_scale}

    @property
    def seed(self) -> dict:
        """The primal-dual point and the step that led to it."""
        return {"x": self.x, "lam_x": self.lam_x, "lam_g": self.lam_g, **self.step}

    @property
    def warm(self) -> WarmStart:
        design = self.x[: len(self.names)] * self.scale
        design[self.integer] = np.round(design[self.integer])
        return WarmStart(dict(zip(self.names, map(float, design))), self.scale, (self.lam_x, self.lam_g))


class BatchSweep:
    """A built problem solved at every point of a sweep of case quantities, in batches (see the module text).

    ``varied``: SI values by quantity name, one per point (all the same length); the case gives the rest. Every
    value is checked against its quantity's valid range first. ``solves`` and ``solver_s`` count the solver calls
    and the time inside them, ``check_s`` the time of the batches' CasADi evaluations of their tests (the KKT
    verdicts, the exclusion tables)."""

    def __init__(self, problem: Problem, case: Case, varied: dict[str, np.ndarray]):
        if not batchable(problem, varied):
            raise ValueError("this problem and sweep are solved point by point (Problem.solve)")
        self.problem, self.posed, self.case = problem, problem.posed, case
        self.varied = {name: np.asarray(values, dtype=float).ravel() for name, values in varied.items()}
        self.count = len(next(iter(self.varied.values()))) if self.varied else 1
        declared = {q.name: q for q in case.quantities}
        for name, values in self.varied.items():
            if len(values) != self.count:
                raise ValueError("every varied quantity needs one value per point")
            declared[name].check_all(values)
        f = problem.formulation
        base = self.posed.params(case)
        self._by_point = np.tile(np.array([getattr(base, q.name) for q in f.quantities], dtype=float),
                                 (self.count, 1))  # a point's case values, a row each (CasADi's memory of columns)
        for j, q in enumerate(f.quantities):
            if q.name in self.varied:
                self._by_point[:, j] = self.varied[q.name]
        self.values = self._by_point.T  # a quantity a row
        self.names = [v.name for v in f.variables]
        self.lower, self.upper, _ = self.posed.bounds_and_start(case, None)
        self._shared = SharedBox(self._by_point, [q.name for q in f.quantities], self.lower, self.upper, {})  # (the
        # region proofs' reading of the points)
        self.integer = [i for i in self.posed.integer if self.lower[i] < self.upper[i]]
        fixed = self.lower == self.upper
        fixed[self.integer] = True
        self._free = ~fixed  # the continuous variables the case leaves free
        # the constraints of fixed variables alone that the batch's integers enter (one of the case alone that breaks
        # at a point stops a batch there by its KKT check, and Problem.solve diagnoses it)
        entered = np.zeros_like(fixed)
        entered[self.integer] = True
        rows, self._fixed_values = self.posed.fixed_only(fixed, entered)
        self._verdict = chain_verdict(self.posed, self.integer, fixed)
        self._fixed_names = np.array([self.posed.row_names[row] for row in rows])
        self._span = min(EXCLUSION_SPAN, self.count)
        self._exclusions: dict[tuple, tuple[int, np.ndarray, list[bool]]] = {}
        self.searches: dict[int, list[dict]] = {}  # the integer search of each point settled in the batch
        self._optima: dict[tuple, tuple[int, _Chain]] = {}  # integer combination -> the last point where the batch's
        # search verified an optimum with it in this window, and its column there (:meth:`_own_start`)
        self._bounded: dict[tuple, int] = {}  # integer combination -> the last point where it could not beat the
        # chain's (:meth:`_heavier`), in this window
        self._undesigned: dict[tuple, tuple[int, str]] = {}  # integer combination -> the last point where IPOPT or
        # the least violation found no design, and the status there
        varied = self.values[[q.name in self.varied for q in f.quantities]]
        with np.errstate(all="ignore"):  # each point's step in the case from the one before, relative
            moves = np.diff(varied, axis=1) / np.abs(varied[:, 1:])
        moves[~np.isfinite(moves)] = 0.0
        norm = np.sum(moves[:, :-1] ** 2, axis=0)
        ratio = np.sum(moves[:, 1:] * moves[:, :-1], axis=0) / np.where(norm > 0, norm, 1.0)
        self._ratio = np.concatenate([[0.0, 0.0], np.where(np.abs(ratio) <= 4.0, ratio, 0.0)])[: self.count]
        # the predictor's ratio of each point: its step in the case against the step before it, projected on it (0
        # where there is none, and where the steps differ more than fourfold)
        self.solves, self.solver_s, self.check_s = 0, 0.0, 0.0
        self.work = 0  # the solving done, counted (CHAINED_POINT_WORK, ...): what ends a window (WINDOW_WORK)
        self._regions: Regions | None = None  # the window's (a window's afresh: BatchSweep.run)
        self.feasible: dict[str, float] | None = None  # the last feasible design in order: a start for a failed point
        self._limits: tuple[np.ndarray, np.ndarray] | None = None  # the tightening's limits and scales per point
        self.carried: Carried | None = None  # what the window after the last one yielded starts from

    def point_case(self, k: int) -> Case:
        return self.case.with_values(**{name: float(values[k]) for name, values in self.varied.items()})

    def run(self, window: int = WINDOW, carried: Carried | None = None) -> Iterator["Solutions"]:
        """Solve every point in order (from ``carried.point``, as the window that started there did: a resumed
        sweep); yields the solutions window by window, each window checked in float64. After each window
        :attr:`carried` is what the next one starts from (``batch_carried``)."""
        start: _Start | None = None  # where the next batch starts; None: after a point without a design
        pace, k = BatchPace(FIRST_BATCH, LONGEST_BATCH), 0
        ahead = None  # points until an inactive constraint or bound is expected to become active (with integers,
        # where the pace expects no break)
        if carried is not None:
            k, ahead, self.feasible = carried.point, carried.ahead, carried.feasible
            start = None if carried.start is None else _Start(self, carried=carried.start)
            pace.carry(carried.pace)
            self._undesigned = {combo: (j, status) for combo, j, status in carried.undesigned}
            carry_boxes(self.posed, carried.boxes)
        while k < self.count:
            first, end, spent = k, min(k + window, self.count), self.work + WINDOW_WORK
            left = self._regions.uncharged() if self._regions is not None else (0, 0.0)  # (the window before's)
            longest, most = min(first + STRETCH_WINDOWS * window, self.count), self.work + STRETCH_WINDOWS * WINDOW_WORK
            self._regions = Regions(self.problem, self.point_case, self.count, self._shared, longest)  # infeasible
            # regions proven at once, each window's afresh (what it takes from the windows before is ``carried``)
            self._regions.carry(left)
            self._optima, self._bounded = {}, {}  # (a window's afresh, as a sweep resumed at its first point has
            # them)
            blocks: list[Block] = []
            alone: dict[int, Solution] = {}
            failed = False  # the last point is without a design: the window waits for a feasible point after it
            while k < end and self.work < spent or failed and k < longest and self.work < most:  # each turn
                # solves at least one point; a stretch without a design runs on to a point with one (the region
                # proofs searched ahead end there; the next window starts them afresh: ``carried``), within
                # STRETCH_WINDOWS windows' points and work (its interval searches' boxes counted: BOX_WORK; review 20:
                # the lever in design mode, 138 points without a design in one window, 31 s without a record)
                wanted, reach = min(pace.size, ahead or pace.size, end - k), min(2 * pace.size, LONGEST_BATCH, end - k)
                forecast = ahead is not None and ahead < pace.size  # the chain ends at a forecast change
                block, chained, searching, tried, origin = (self._batch(start, k, wanted, reach) if start is not None
                                                            else (None, 0, False, None, None))
                passed = 0 if block is None else len(block.index)
                if passed:
                    blocks.append(block)
                    start, k = _Start(self, block=block), k + passed
                    self.feasible, failed = start.warm.design, False
                if chained and passed == chained:
                    pace.passed(chained)
                    ahead = self._until_active(blocks, pace.size, start.combo) if pace.size > 1 else None  # (one:
                    # no shorter)
                    if not searching or k == end:  # (a batch that passes up to its integers' exclusion hands the
                        continue  # next point to the search)
                settled = self._settle(start, k, tried, origin) if searching else None
                if settled is not None:  # the integer search decided point k in the batch
                    kept, start = start, _Start(self, block=settled)
                    if not (np.array_equal(start.combo, kept.combo) and self._tightens(k)):  # (where it kept the
                        pace.broke(k)  # batch's integers and the neighbours it found without a design stay ruled
                        # out, the relaxed integers crossed no boundary: no break to pace the chains by)
                        if k + 1 < self.count and self._promised(_run(settled, 0), start, k + 1, heavier=False):
                            pace.near()  # the integers it changed to promise a gain still, at a neighbour the next
                            # point's search would solve (its objective there unknown yet; the wedge over its inertia
                            # in geometry mode, 4 weights after 3 promising 3 again, worse, at each of the next 8
                            # points: a chain of 8 aimed past the change had spent 7 solves for nothing; not the
                            # ball's rows fewer, ruled out there)
                    elif sum(bool(entry["feasible"]) for entry in self.searches[k]) > 1:  # a neighbour promised a
                        pace.near()  # gain has a design, worse: a boundary close by (ball_crusher's rows: one row
                        # more promised and worse at one point, the rows kept without a design at the next)
                    blocks.append(settled)
                    k, ahead = k + 1, (1 if forecast else None)  # (a forecast change of the active set often
                    # comes with another at the next point, the ball at 4.5x its power: the contact stress active at
                    # one, the filling off its bound at the next; the forecast was from the points before it: a probe)
                    self.feasible, failed = start.warm.design, False
                    continue
                if passed == 0 < chained and self.integer:  # its first point failed at the batch's integers: a
                    pace.broke(k)  # break too (Problem.solve's search decides it), the next one expected as far on
                elif passed < chained:  # point k failed a test in the batch: the next batch starts short
                    pace.restart()
                undesigned = start is not None and self._undesigned_at(start.combo, k)  # (IPOPT found none with
                # the batch's integers here: solved as `solve` solves the point, from the case's own start; warm, it
                # would try them again first)
                alone[k] = self._solve_alone(k, start.warm if start is not None and not undesigned else None,
                                             start is not None)  # (a chain from a design failed at k)
                ahead = None
                start, k = self._start_of(alone[k]), k + 1
                failed = alone[k - 1].status not in DESIGN_STATUSES
            if k >= self.count and alone:  # (the sweep's last window: what no later verdict takes, its last point
                last = max(alone)  # solved alone's: the runs searched ahead and not used, the probes' uncharged)
                calls, seconds = self._regions.uncharged()
                alone[last] = self._regions.charged_with_the_rest(alone[last])
                self._spent(calls, seconds, 0)
            solutions = self._window(blocks, alone, first, k - first)
            self.carried = Carried(k, None if start is None else start.carried, pace.state, ahead, self.feasible,
                                   [(combo, j, status) for combo, (j, status) in self._undesigned.items()],
                                   last_boxes(self.posed))
            yield solutions

    def _until_active(self, blocks: list[Block], size: int, combo: np.ndarray) -> int | None:
        """With free integers, the points after the last kept one until its active set is expected to change
        (``batch_pace.until_active``, from the last two kept points where they are consecutive, with the same integers
        and scales: :func:`_last_two`): the next chain ends there. A change of the active set is what makes a fixed
        integer's multiplier promise a neighbour, and where a slack of the design closes at fixed integers the
        integers stop serving (the ball over its power past 7.5x: each point where the rows carry no more, one row
        more, was foreseen to the point). None otherwise (the integer breaks are paced by their gaps), and where the
        exclusion tables end the next chain of ``size`` points anyway (the cable count as its torque rises).
        ``combo``: the integers of the last kept point (the batch's start)."""
        pair = _last_two(blocks, self.integer) if self.integer else None
        if pair is None:
            return None
        last = int(pair.index[-1]) + 1
        if last < self.count and self._excluded(combo, last, min(size, self.count - last)).any():
            return None
        return until_active(self.posed, pair, self._ratio[last:last + LONGEST_BATCH], self._free,
                            self.posed.kkt_tolerance)

    def _start_of(self, solution: Solution) -> _Start | None:
        return _Start(self, solution) if solution.status == "optimal" else None

    def _solve_alone(self, k: int, warm: Solution | WarmStart | None, failed: bool = False) -> Solution:
        """Point k by ``Problem.solve``, the last feasible design in order its neighbour before a verdict. After a
        point without a design, the points from k are first searched as one region (``region_proof.Regions``): a
        point a proof covers is infeasible without a solve; another is solved once, and searched alone before its
        full verdict where that solve finds no design. Where a chain from the point before, with a design, ``failed``
        at k, the point's own interval search goes first (``Regions.point``'s ``beside``: a stretch without designs
        often starts there)."""
        def solved(first: Solution | None) -> Solution:  # (the case its region's search built, if it did; none is
            # built where a region proof covers the point: SharedBox)
            return self.problem.solve(self._regions.point_case(k), warm=warm, neighbour=self.feasible, first=first)

        boxes = boxes_evaluated(self.posed)
        solution = self._regions.point(k, solved, warm, self.feasible if failed else None)
        self._counted(solution, boxes_evaluated(self.posed) - boxes)
        if solution.status in DESIGN_STATUSES:
            self.feasible = solution.design
        for entry in solution.integer_search:  # (its search's combinations without a design: IPOPT's verdicts)
            names = [self.names[i] for i in self.integer]
            if not entry["feasible"] and not entry["status"].startswith(EXCLUDED) and all(n in entry for n in names):
                self._undesigned[tuple(float(entry[n]) for n in names)] = (k, entry["status"])
        return solution

    def _counted(self, solution: Solution, boxes: int = 0) -> Solution:
        """``solution``'s solver calls counted, their work and that of the ``boxes`` its interval searches evaluated."""
        self._spent(solution.solver.solves, solution.solver.time_s,
                    SOLVE_WORK * solution.solver.solves + BOX_WORK * boxes)
        return solution

    def _spent(self, calls: int, seconds: float, work: int) -> None:
        """Solver calls and their seconds counted, and their work (what ends a window: WINDOW_WORK)."""
        self.solves, self.solver_s, self.work = self.solves + calls, self.solver_s + seconds, self.work + work

    def _batch(self, start: _Start, k: int, count: int, reach: int
               ) -> tuple[Block | None, int, bool, "_Chain | None", np.ndarray | None]:
        """Chain ``count`` points from ``start`` (as many as up to a point within ``reach`` where the batch's
        integers are excluded): the columns up to the first that fails a test (None if it is the first), how many
        were chained (none if the integers are excluded at ``k``, see :func:`chain_length`), whether the first point
        left is the integer search's to decide (its integers excluded there, or a neighbouring combination to try;
        also where every chained point passed and the next one excludes them), and in the second case that point's
        chained column (KKT-verified at its integers: the search's first attempt), and the combination the search
        starts from there where it is not the batch's (a neighbour that opens at that point: :meth:`_opening`; None:
        the batch's). Where the integers are excluded at a point and one neighbouring combination is left there
        (:meth:`_changes`), the chain goes on with it: the point is settled from its column (:meth:`_replayed`)."""
        lower, upper = self.lower.copy(), self.upper.copy()
        lower[self.integer] = upper[self.integer] = start.combo
        first = -1  # the first point ahead where the batch's integers are excluded, or a neighbour opens
        changes: list[tuple[int, np.ndarray]] = []  # (offset, combination) where the chain changes its integers
        opens, neighbour = None, None  # (the offset where a neighbour opens, if the chain ends there; no changes then)
        if self.integer:  # the batch stops short of a point its integers cannot serve whatever the rest (the search
            # excludes them there without a solve), or changes them there to the one neighbour left
            excluded = self._excluded(start.combo, k, max(count, reach))
            if excluded.any():
                first = int(np.argmax(excluded))
            opens, neighbour = self._opening(start, k, max(count, reach))
            if opens is not None and (first < 0 or opens < first):
                first = opens
            else:
                opens = None
            if opens is None and first >= 0:
                count = max(count, first + 1)
                changes, first = self._changes(start.combo, k, count, first)
            if first == 0:
                return None, 0, True, None, (neighbour if opens == 0 else None)  # foreseen: nothing chained
            if first > 0:
                count = first  # (a break known ahead, within reach: the chain ends there)
        chain = self._chain(start, k, count, lower, upper, start.seed, changes=changes)
        if chain is None:
            return None, min(count, chain_length(count)), False, None, None
        count = len(chain.index)
        ok = chain.ok & ~self._unruled_moves(chain, start)
        passed = int(np.argmin(ok)) if not ok.all() else count
        pieces, before, passed, cut = self._replayed(chain, start, [c for c in changes if c[0] < passed], passed)
        if cut:  # (the points after it left to the next batch, as after a chain that ended there)
            count = passed
        if passed < count and not ok[passed]:
            searching = bool(chain.ok[passed]) or len(self.integer) > 0
        else:  # (passed up to the exclusion, or a replayed search that found other integers)
            searching = passed == count == first
        # (a point that fails at the batch's integers: the search tries them by IPOPT)
        tried = None  # normalised as the batch that starts after the passed points
        if searching and passed < count:
            tried = chain.column(passed, before.f_scale)
        block = (pieces[0] if len(pieces) == 1 else Block.joined(pieces)) if pieces else None
        return block, count, searching, tried, (neighbour if passed == opens else None)

    def _changes(self, combo: np.ndarray, k: int, count: int, first: int) -> tuple[list[tuple[int, np.ndarray]], int]:
        """Where the integers ``combo`` are excluded at point k + ``first`` (and the next ones at later points, up to
        ``count`` points from k), the one neighbouring combination left there (:meth:`_past_exclusion`, where the
        search would step at once; the cable count, one cable more, as its torque rises): the offsets and
        combinations the chain changes to, and the offset of the first exclusion not so passed (-1: none)."""
        changes, j = [], first
        while 0 <= j < count:
            past = self._past_exclusion(combo, k + j)
            if past is None or self._last_undesigned(past) == k + j - 1:
                return changes, j  # (a combination IPOPT left without a design at the point before: its search)
            changes.append((j, past))
            combo = past
            ahead = (self._excluded(combo, k + j + 1, count - j - 1) if j + 1 < count
                     else np.zeros(0, dtype=bool))
            j = j + 1 + int(np.argmax(ahead)) if ahead.any() else -1
        return changes, -1

    def _replayed(self, chain: "_Chain", start: _Start, changes: list[tuple[int, np.ndarray]],
                  passed: int) -> tuple[list[Block], _Start, int, bool]:
        """The first ``passed`` points of ``chain`` as blocks, each point where it changed its integers
        (``changes``) settled with its column as the first attempt: in place, where the outcome of the search
        ``Problem.solve`` runs there is certain (:meth:`_changed`), else by :meth:`_settle` (the search; the kept
        points end with that point, or before it where the search does not settle it); the start after them, how many
        points are kept, and whether they end there by choice (after a search). The kept columns are one copy of
        the chain's, a change's column normalised as the search's first attempt is (:meth:`_Chain.column`): the
        numbers a block per piece had held (the cable over its torque changes its count at 42 of 100 points)."""
        kept = Block(chain.index[:passed], **{key: value[:, :passed].copy() for key, value in chain.arrays.items()})
        for j, _ in changes:
            before = _Start(self, block=kept, at=j - 1) if j > 0 else start
            tried = chain.column(j, before.f_scale)  # (the search's first attempt)
            changed = self._changed(before, tried, bool(chain.ok[j]))
            if changed is not None:
                for key, value in changed.arrays.items():
                    kept.arrays[key][:, j] = value[:, 0]
                continue
            pieces = [kept.block(j)] if j > 0 else []  # (the search decides point j: the kept points end there)
            settled = self._settle(before, int(chain.index[j]), tried)
            if settled is None:
                return pieces, before, j, False
            return pieces + [settled], _Start(self, block=settled), j + 1, True
        return ([kept] if passed else []), (_Start(self, block=kept) if passed else start), passed, False

    def _opening(self, start: _Start, k: int, count: int) -> tuple[int | None, np.ndarray | None]:
        """Where, among points k .. k + count - 1, the neighbouring combination that ``start``'s multipliers promise a
        gain at (``integers.downhill``) stops being excluded by a constraint of fixed variables alone that it broke at
        the point before k (the cable count one fewer as the allowable cable stress rises): its offset from k and the
        combination, or (None, None). There the warm search would step to it from the batch's integers; it starts
        there instead (:meth:`_settle`), with the same outcome where f*(n) is convex in the integers (the search's
        premise): from the neighbour, whose multipliers then promise a gain the other way or none, the batch's own
        integers are tried again as its downhill step only where the tangent there does not already show them worse.
        One solve at that point instead of two."""
        if k == 0 or not len(self._fixed_names):
            return None, None
        for combo in self._downhill(start.run, start):
            table = self._excluded(combo, k - 1, min(count, self._span - 1) + 1)  # (one table
            # from k - 1)
            if table[0] and not table[1:].all():
                return int(np.argmin(table[1:])), combo
        return None, None

    def _chain(self, start: _Start, k: int, count: int, lower: np.ndarray, upper: np.ndarray,
               seed: dict, method: str = "sqp_chain", predict: bool = True,
               changes: list[tuple[int, np.ndarray]] = ()) -> "_Chain | None":
        """Points k .. k + count - 1 (fewer: :func:`chain_length`) re-solved by the chained SQP from ``seed``'s
        primal-dual point (``x``, ``lam_x``, ``lam_g``) and the step that led to it (``dx``, ``dlam_x``,
        ``dlam_g``, for the predictor unless ``predict`` is false), scaled as ``start``, in the box ``lower``,
        ``upper`` (SI), each point's KKT conditions checked; None after an evaluation error inside CasADi (the points
        go to Problem.solve, which reports it). ``changes``: (offset, combination) where the free integers change
        from that point on, each such point and the next started without a prediction (as after the integer
        search)."""
        length = chain_length(count)
        count = min(count, length)
        points = np.minimum(np.arange(k, k + length), k + count - 1)  # the padding's parameters: the last point's
        lbx, ubx = lower / start.scale, upper / start.scale
        ratio = self._ratios(points) if predict else 0.0
        if changes:  # the integers' bounds a column each
            lbx, ubx = lbx[:, None].repeat(length, axis=1), ubx[:, None].repeat(length, axis=1)
            for j, combo in changes:
                lbx[self.integer, j:] = ubx[self.integer, j:] = (combo / start.scale[self.integer])[:, None]
                if predict:
                    ratio[j:j + 2] = 0.0
        m, n = len(self.values), len(start.scale)
        p_rows = np.empty((length, m + n + 1))  # the NLP parameters, a point a row: CasADi's memory of the columns
        p_rows[:, :m], p_rows[:, m:m + n], p_rows[:, -1] = self._by_point[points], start.scale, start.f_scale
        p = p_rows.T
        live = (np.arange(length) < count).astype(float)  # the padding calls no solver
        began = time.perf_counter()
        try:
            x, lam_x, lam_g, dx, dlam_x, dlam_g, f = chained_sqp(self.posed, length, method)(
                live, *(seed[key] for key in ("x", "lam_x", "lam_g", "dx", "dlam_x", "dlam_g")), ratio, p, lbx, ubx)
        except RuntimeError:
            x = None
        seconds = time.perf_counter() - began
        self._spent(count, seconds, CHAINED_POINT_WORK * count + CHAIN_CALL_WORK)
        if x is None:
            return None
        began = time.perf_counter()
        kkt, moves, held = self.posed.mapped(self._verdict, length)(x, p, lam_x, lam_g, lbx, ubx, f, self.lower,
                                                                       self.upper)
        curved, free = np.ones(length, dtype=bool), leaves_free(self.posed, lam_x, lam_g, lbx, ubx)
        if free.any():  # (a chain of vertices: nothing to test)
            if compiled_apart(self.posed):
                held = self.posed.mapped(curvature(self.posed, batched=True), length)(x, p, lam_x, lam_g, lbx, ubx)[0]
            curved[free] = curved_up(held[:, free])
        self.check_s += time.perf_counter() - began
        arrays = dict(x=x, lam_x=lam_x, lam_g=lam_g, dx=dx, dlam_x=dlam_x, dlam_g=dlam_g, f=f, p=p)
        if count < length:
            arrays = {key: value[:, :count] for key, value in arrays.items()}
        return _Chain(np.arange(k, k + count), (kkt[0, :count] > 0.5) & curved[:count],
                      moves[0, :count] > 0.5, **arrays,
                      **{key: (bound[:, :count] if bound.ndim == 2 else bound[:, None].repeat(count, axis=1))
                         for key, bound in (("lbx", lbx), ("ubx", ubx))},
                      time=np.full((1, count), seconds / count), solves=np.ones((1, count)))

    def _ratios(self, points: np.ndarray) -> np.ndarray:
        """Per chained point, the predictor's ratio (0 for a repeated point)."""
        ratio = self._ratio[points]
        ratio[1:][points[1:] == points[:-1]] = 0.0
        return ratio

    def _settle(self, start: _Start, k: int, tried: _Chain | None = None,
                origin: np.ndarray | None = None) -> Block | None:
        """Point k, where a batch ended for the integer search: ``Problem.solve``'s warm search (``integers.descend``
        from the batch's integers, or from ``origin``, a neighbour that opens at k: :meth:`_opening`; should they
        fail, the relaxation and ``integers.nearest_integers``), each combination excluded by the batch's tables or
        re-solved by a one-point chained SQP from the previous point's optimum and KKT-checked; the batch's integers
        are not solved again where the chain solved them at k (``tried``, its column there). None where a re-solve
        does not pass its check or no integer point is found (``Problem.solve`` decides the point; also where a
        constraint of the case alone breaks, which fails the relaxation); the search is kept for the point's
        Solution."""
        search: list[dict] = []
        box, seed = Box(start.scale, self.lower, self.upper), start.seed
        runs: list[_Chain] = []
        cold: list[float] = []  # the seconds of each call beside the one-point SQPs (the least violation, IPOPT)
        if tried is not None:  # its integers (SI; scaled as ``start``: the same chain's)
            tried_combo = np.round(tried.x[self.integer, 0] * start.scale[self.integer])

        def attempt(combo, seed, methods=None) -> dict | None:
            lower, upper = self.lower.copy(), self.upper.copy()
            lower[self.integer] = upper[self.integer] = combo
            excluded = self._excluded_names(combo, k)
            if excluded:
                search.append(excluded_entry(self.posed, self.integer, combo, excluded))
                return None
            key = tuple(combo.tolist())
            ruled = self._ruled_out(key, k)
            if ruled:
                search.append(search_entry(self.posed, self.integer, combo, ruled, False, math.nan))
                return None
            if tried is not None and np.array_equal(combo, tried_combo):
                chain = tried  # (its chained column: the first attempt, verified or not)
            elif self._last_undesigned(combo) != k - 1:  # (one left without a design at the point before goes to
                own = self._own_start(key, k, start, seed)  # its least violation directly)
                chain = self._chain(start, k, 1, lower, upper, own, "sqp_chain", predict=False)
                if own is not seed and (chain is None or not chain.ok[0]):  # from the search's optimum, as before
                    chain = self._chain(start, k, 1, lower, upper, seed, "sqp_chain", predict=False)
            else:
                chain = None
            if chain is None or not chain.ok[0]:  # its least violation: without a design, or SQP from the design
                found, seconds = self._least_violation(start, k, lower, upper, seed)  # it found; else as
                cold.append(seconds)  # Problem.solve tries a neighbour: IPOPT, cold
                if found.without_design:
                    status = LOCALLY_INFEASIBLE.format(found.violation)
                    self._undesigned[key] = (k, status)
                    search.append(search_entry(self.posed, self.integer, combo, status, False, math.nan))
                    return None
                chain = (self._chain(start, k, 1, lower, upper, _from_design(found.x, seed), "sqp_search",
                                     predict=False) if found.feasible else None)
            if chain is None or not chain.ok[0]:
                entry, seconds, optimum = self._cold(start, k, lower, upper, seed)
                cold.append(seconds)
                if optimum is None:
                    self._undesigned[key] = (k, entry["status"])
                    search.append(entry)
                    return None
                chain = self._chain(start, k, 1, lower, upper, optimum, "sqp_chain", predict=False)
            run = used(chain)
            self._optima[key] = (k, chain)
            search.append(search_entry(self.posed, self.integer, combo, BATCHED, True, run["value"]))
            return run

        def solved(lower, upper, seed, method) -> dict:
            return used(self._chain(start, k, 1, lower, upper, seed, method, predict=False))

        def used(chain: _Chain | None) -> dict:
            if chain is None or not chain.ok[0]:
                raise _Unsettled
            runs.append(chain)
            return chain.run(0) | {"value": float(chain.f[0, 0]) * start.f_scale, "chain": chain}

        try:
            kept = descend(self.posed, box, self.integer, start.combo if origin is None else origin, seed, search,
                           attempt)
            past = self._past_exclusion(start.combo, k) if kept is None else None
            if past is not None:  # the only neighbour its exclusion leaves: the search from there
                kept = descend(self.posed, box, self.integer, past, seed, search, attempt)
                if kept is None and self._undesigned_at(start.combo, k):  # it too without a design: the point is
                    return None  # Problem.solve's from the case's own start, whose relaxation IPOPT solves first
            if kept is None:  # the batch's integers fail here: the relaxation, from the same point
                relaxed = solved(self.lower, self.upper, relaxation_seed(seed, self.integer), "sqp_search")
                if off_scale(relaxed["x"][: len(self.names)]):
                    return None
                kept = nearest_integers(self.posed, box, self.integer, relaxed, search, attempt)
        except _Unsettled:
            return None
        if kept is None:
            return None
        return self._searched(kept["chain"], k, search, sum(float(run.arrays["time"][0, 0]) for run in runs)
                              + sum(cold), len(runs) + len(cold))

    def _own_start(self, key: tuple, k: int, start: _Start, seed: dict) -> dict:
        """Where the search solves the integers ``key`` at point k by a one-point SQP: from their own optimum at the
        point before, where the search verified one there in the same variable scales (normalised as ``start``, as
        :meth:`_Chain.column` normalises), or at the last point it solved them, where they could not beat the chain's
        at each point since (:meth:`_heavier`); else from ``seed`` (the search's: the optimum it keeps so far at k).
        The wedge over its inertia in geometry mode, 4 weights promised by 3's multipliers at each of 70 .. 74: from
        3's optimum SQP took 2.5 ms, from 4's own at the point before 0.13 ms."""
        found = self._optima.get(key)
        if found is None or k - 1 not in (found[0], self._bounded.get(key)):
            return seed
        column, m = found[1], len(self.values)
        if not np.array_equal(column.p[m:m + len(start.scale), 0], start.scale):
            return seed
        a = column.column(0, start.f_scale).arrays
        return _seed(a["x"][:, 0], a["lam_x"][:, 0], a["lam_g"][:, 0])

    def _searched(self, chain: "_Chain", k: int, search: list[dict], seconds: float, solves: int) -> Block:
        """Point k as the integer search ``search`` kept it: ``chain``'s column, its time and solver calls those of
        the search, without a step to predict from (across a change of the integers); the search is recorded."""
        block = chain.block(1)
        block.arrays["time"][:] = seconds
        block.arrays["solves"][:] = solves
        for key in ("dx", "dlam_x", "dlam_g"):
            block.arrays[key] = np.zeros_like(block.arrays[key])
        self.searches[k] = search
        return block

    def _changed(self, start: _Start, tried: _Chain, ok: bool) -> Block | None:
        """The point of ``tried`` (a chain's column normalised as ``start``'s: :meth:`_Chain.column`), where the chain
        changed its integers from ``start``'s (excluded there) to the one neighbour left, settled as :meth:`_settle`
        settles it, without running the search, because its outcome is certain: the column is the search's first
        attempt, KKT-verified (``ok``), and every neighbour its multipliers promise a gain at (``integers.downhill``)
        is ``start``'s integers, tried already; then the search's record is those excluded and the column kept, as
        :meth:`_searched` keeps it (its own time and solver call). None otherwise (:meth:`_settle` runs the
        search)."""
        k, run = int(tried.index[0]), tried.run(0)
        if not ok or any(not np.array_equal(combo, start.combo) for combo in self._downhill(run, start)):
            return None
        combo = np.round(tried.x[self.integer, 0] * start.scale[self.integer])
        search = [excluded_entry(self.posed, self.integer, start.combo, self._excluded_names(start.combo, k)),
                  search_entry(self.posed, self.integer, combo, BATCHED, True, run["f"] * start.f_scale)]
        return self._searched(tried, k, search, float(tried.time[0, 0]), int(tried.solves[0, 0]))

    def _ruled_out(self, combo: tuple, k: int) -> str:
        """Why the integers ``combo`` are not solved at point k (empty: they are): IPOPT or their least violation
        (``feasibility``) found them infeasible at an earlier point (that verdict, not another failure: an iteration
        limit, a restoration that failed, a design the float64 check refused), and the step from there to k only
        tightens the constraints (``tightening``): no design meets at k what none met there."""
        found = self._undesigned.get(combo)
        if found is None or found[0] >= k or not infeasible(found[1]):
            return ""
        if not self._tightened(found[0], k):
            return ""
        return f"ruled out: {found[1]} at point {found[0]}, whose limits the sweep has only tightened since"

    @property
    def _tightening(self):
        """The sweep's :class:`~clutchopt.optimise.tightening.Tightening`, built on first use (kept by the posed
        problem): only a sweep with integers asks."""
        return tightening(self.posed, self.varied)

    def _tightens(self, k: int) -> bool:
        """The step from point k to the next only tightens the constraints (``tightening``)."""
        return k + 1 < self.count and self._tightened(k, k + 1)

    def _tightened(self, j: int, k: int) -> bool:
        """The step from point j to point k only tightens the constraints (``tightening``), from the limits of every
        point evaluated at once on first use (``Tightening.limits``)."""
        t = self._tightening
        if not t.known:
            return False
        if self._limits is None:
            self._limits = t.limits(self._by_point)
        limits, scales = self._limits
        return t.holds(limits[:, j], scales[:, j], limits[:, k], scales[:, k])

    def _unruled_moves(self, chain: _Chain, start: _Start) -> np.ndarray:
        """Per chained point, whether ``Problem.solve``'s warm search would go on from it (the chain verdict's
        ``moves``), but for the points up to the first whose every neighbour the search would step to
        (``integers.downhill``) is excluded there, ruled out (:meth:`_ruled_out`) or heavier (:meth:`_heavier`): the
        search would keep the chain's integers there (without a solve, or after one that cannot win)."""
        moves = chain.moves.copy()
        if not (self._undesigned or self._optima):
            return moves
        for j in np.flatnonzero(moves):
            if self._promised(chain.run(j), start, int(chain.index[j])):
                return moves
            moves[j] = False
        return moves

    def _promised(self, run: dict, start: _Start, k: int, heavier: bool = True) -> bool:
        """A neighbour ``run``'s multipliers promise a gain at (:meth:`_downhill`; ``run`` in ``start``'s scaling) is
        neither excluded at point k nor ruled out there (:meth:`_ruled_out`), nor, where ``heavier`` (``run`` a point
        k's), heavier there than ``run`` (:meth:`_heavier`): the warm search would solve it and could keep it."""
        value = float(run["f"] * run["p"][-1])  # (SI: the scaled objective times its normaliser)
        return any(not (self._ruled_out(key, k) or self._excluded_at(combo, k)
                        or heavier and self._heavier(key, k, value))
                   for combo in self._downhill(run, start) for key in [tuple(combo.tolist())])

    def _heavier(self, combo: tuple, k: int, value: float) -> bool:
        """The integers ``combo`` cannot beat ``value`` (an objective at point k): the search verified an optimum with
        them at an earlier point of the window heavier than ``value`` (beyond the solver's tolerance of each), and the
        sweep has only tightened the constraints since (``tightening``), so no design with them is lighter at k than
        there."""
        found = self._optima.get(combo)
        if found is None or found[0] >= k:
            return False
        column = found[1]
        theirs = float(column.f[0, 0] * column.p[-1, 0])
        if not (theirs - self.posed.negligible(theirs) > value + self.posed.negligible(value)
                and self._tightened(found[0], k)):
            return False
        self._bounded[combo] = k
        return True

    def _downhill(self, run: dict, start: _Start) -> list[np.ndarray]:
        """The neighbouring integers ``integers.downhill`` steps to from ``run`` (a point in ``start``'s scaling)."""
        return downhill(self.posed, run, Box(start.scale, self.lower, self.upper), self.integer)

    def _past_exclusion(self, combo: np.ndarray, k: int) -> np.ndarray | None:
        """Where the integers ``combo`` are left out at point k (:meth:`_left_out`: e.g. the cable stress of too few
        cables, or the ball's rows that IPOPT has just found without a design), the one neighbouring combination (one
        integer one unit either way, within the bounds) that is not: the search starts there, without the
        relaxation, which would round to it. None where the integers are not left out, or none or several neighbours
        are left (the relaxation decides)."""
        if not self._left_out(combo, k):
            return None
        left = []
        for j, i in enumerate(self.integer):
            for step in (-1.0, 1.0):
                neighbour = combo.copy()
                neighbour[j] += step
                if self.lower[i] <= neighbour[j] <= self.upper[i] and not self._left_out(neighbour, k):
                    left.append(neighbour)
        return left[0] if len(left) == 1 else None

    def _left_out(self, combo: np.ndarray, k: int) -> bool:
        """The integers ``combo`` have no design at point k: a constraint of fixed variables alone breaks, or IPOPT
        found none (:meth:`_undesigned_at`)."""
        return self._excluded_at(combo, k) or self._undesigned_at(combo, k)

    def _excluded_names(self, combo: np.ndarray, k: int) -> list[str]:
        """The constraints of fixed variables alone that the integers ``combo`` (SI) break at point k, each named
        once."""
        return list(dict.fromkeys(self._fixed_names[self._broken(combo, k, 1)[:, 0]]))

    def _undesigned_at(self, combo: np.ndarray, k: int) -> bool:
        """IPOPT found no design with the integers ``combo`` at point k, or at one before it and the sweep has only
        tightened the constraints since (:meth:`_ruled_out`)."""
        if not self._undesigned:  # (none found yet: most sweeps, each integer change asks)
            return False
        return self._last_undesigned(combo) == k or bool(self._ruled_out(tuple(combo.tolist()), k))

    def _last_undesigned(self, combo: np.ndarray) -> int | None:
        """The last point where IPOPT or the least violation found no design with the integers ``combo``, if any."""
        return self._undesigned.get(tuple(combo.tolist()), (None,))[0]

    def _least_violation(self, start: _Start, k: int, lower: np.ndarray, upper: np.ndarray,
                         seed: dict) -> tuple[Least, float]:
        """The least largest violation of an integer combination (fixed in ``lower``, ``upper``) that the one-point
        chained SQP did not settle at point k, from ``seed``'s point (``feasibility.least``: whether the combination
        is without a design, IPOPT's verdict at a few QP solves, or where a design was found), and the seconds of the
        call."""
        began = time.perf_counter()
        found = least(self.posed, seed["x"], self._p(k, start), lower / start.scale, upper / start.scale)
        seconds = time.perf_counter() - began
        self._spent(1, seconds, SOLVE_WORK)
        return found, seconds

    def _p(self, k: int, start: _Start) -> np.ndarray:
        """The NLP's parameter vector at point k, scaled as ``start``: the point's case values, the variable scales,
        the objective's normaliser."""
        return np.concatenate([self._by_point[k], start.scale, [start.f_scale]])

    def _cold(self, start: _Start, k: int, lower: np.ndarray, upper: np.ndarray,
              seed: dict) -> tuple[dict, float, dict | None]:
        """The ``integer_search`` entry of an integer combination (fixed in ``lower``, ``upper``) that the one-point
        chained SQP did not settle at point k: solved as ``Problem.solve``'s search solves a neighbour (IPOPT, cold,
        from ``seed``'s point), and kept out of the search where IPOPT ends without a verified optimum (most often
        ``Infeasible_Problem_Detected``: fewer balls than the torque needs): its entry, the seconds of the call, and
        None; where IPOPT finds a verified-feasible optimum, its primal-dual point instead (multipliers within the KKT
        tolerance set to 0, as a warm start of SQP: ``attempts.warm_multipliers``), from which the one-point chained
        SQP gives the column (a combination that became feasible along the sweep: the ball's fewer rows as the
        allowable contact stress rises)."""
        lbx, ubx = lower / start.scale, upper / start.scale
        x0 = np.clip(seed["x"], lbx, ubx)
        data = ScaledData(self.posed.params(self.point_case(k)), lower, upper, x0 * start.scale, start.scale,
                          start.f_scale, self._p(k, start))
        solved = attempts.run(self.posed, data, lbx, ubx, x0, None)
        self._spent(1, solved["time"], SOLVE_WORK)
        if solved["ok"] and solved["feasible"]:
            return {}, solved["time"], _seed(solved["x"], *warm_multipliers(self.posed, solved["lam_x"],
                                                                              solved["lam_g"]))
        return search_entry(self.posed, self.integer, lower[self.integer], solved["status"], False,
                            solved["f"] * start.f_scale), solved["time"], None

    def _excluded(self, combo: np.ndarray, k: int, count: int) -> np.ndarray:
        """Per point k .. k + count - 1: the integers ``combo`` (SI) with the variables the case fixes break a
        constraint that depends on them alone there, so the integer search would exclude them without a solve (the
        test of ``integers.violated_whatever_the_rest``)."""
        return self._broken(combo, k, count).any(axis=0)

    def _broken(self, combo: np.ndarray, k: int, count: int) -> np.ndarray:
        """Which of those constraints break at points k .. k + count - 1 (a row per constraint, a column per point)
        with the integers ``combo`` (SI)."""
        first, table, _ = self._exclusion_table(tuple(combo.tolist()), k, count)
        return table[:, k - first:k - first + count]

    def _excluded_at(self, combo: np.ndarray, k: int) -> bool:
        """``_excluded(combo, k, 1)[0]``, read from the table's list of its points' verdicts (an
        integer change asks it of a combination and its neighbours: no array work)."""
        first, _, excluded = self._exclusion_table(tuple(combo.tolist()), k, 1)
        return excluded[k - first]

    def _exclusion_table(self, key: tuple, k: int, count: int) -> tuple[int, np.ndarray, list[bool]]:
        """The exclusion table of the integers ``key`` (SI) covering points k .. k + count - 1: its first point, which
        constraints of fixed variables alone break at each point from there (a row per constraint, a column per
        point) and whether any does (a list); evaluated EXCLUSION_SPAN points ahead at once, per integer
        combination, the rest of the design the case's fixed variables."""
        entry = self._exclusions.get(key)
        if entry is None or not (entry[0] <= k and k + count <= entry[0] + entry[1].shape[1]):
            began = time.perf_counter()
            design = self.lower.copy()  # (the case's fixed variables, the integers at ``key``)
            design[self.integer] = key
            p_rows = np.ones((self._span, len(self.values) + len(design) + 1))  # unit scales: x is SI
            p_rows[:, : len(self.values)] = self._by_point[np.minimum(np.arange(k, k + self._span), self.count - 1)]
            g, = self.posed.mapped(self._fixed_values, self._span)(design, p_rows.T)  # past the end: the last point
            self.check_s += time.perf_counter() - began
            table = g > 10 * FEASIBILITY_TOL
            entry = self._exclusions[key] = (k, table, table.any(axis=0).tolist())
        return entry

    def _window(self, blocks: list[Block], alone: dict[int, Solution], first: int, count: int) -> "Solutions":
        """The solutions of points first .. first + count - 1: batched points checked in float64 together; one that
        fails the check is solved again by ``Problem.solve``, warm from the point before."""
        block = Block.joined(blocks) if blocks else None
        checked = None if block is None else Checked(self.posed, block, self.values[:, block.index],
                                                     (self.lower, self.upper), self.searches)
        solutions = Solutions(first, count, alone, checked, self.names)
        for k in solutions.unverified:
            before = solutions[k - first - 1] if k > first else None
            warm = before if before is not None and before.status == "optimal" else None
            solutions.replace(k - first, self._solve_alone(k, warm))
        self._between_feasible(solutions, alone, first, count)
        return solutions

    def _between_feasible(self, solutions: "Solutions", alone: dict[int, Solution], first: int, count: int) -> None:
        """A point without a design followed by a feasible point in the window: solved again from that design, so
        that its verdict does not depend on the order of the points (point by point: ``sweep.solve_points``)."""
        for k in sorted(alone):
            if solutions[k - first].status in DESIGN_STATUSES + ("infeasible",):  # (proven: no design to find)
                continue
            later = next((j for j in range(k + 1, first + count) if solutions[j - first].status in DESIGN_STATUSES),
                         None)
            if later is not None:
                retry = self._counted(self.problem.refined(self.point_case(k), solutions[later - first].design,
                                                           diagnosed=False))
                if retry.status in DESIGN_STATUSES:
                    solutions.replace(k - first, retry)
