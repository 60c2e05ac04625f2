"""Infeasible regions of a sweep proven at once (issue 26 item 3): one interval search for a run of points.

Along a sweep the points without a design come in runs (a duty beyond what any design within the bounds carries).
Each point of such a run once cost a full verdict (``clutchopt.optimise.verdict.shown``): the failed solve, its
elastic diagnosis, the retries from every start, then the interval search that proves it. Here, after a point
proven infeasible, the next points are searched together *as one box*: the hull of their design boxes times the
interval of their parameters, from the smallest to the largest value each takes over the run
(``interval_proof.searches`` with a parameter interval, split within the search only where it spreads the rows
more than the design does). Every interval bound holds for every parameter
vector in it, so a proof for the interval is a proof for each point of the run: each gets ``infeasible`` with the
region's proof, which names the interval (e.g. "proven infeasible for power 600.503-626.884 kW (8 points, one
proof): ..."), without a solve.

A run that cannot be proven whole (it reaches past the region's edge, where no proof exists, or its bounds are too
loose over the whole interval) is bisected and the halves searched together, down to pairs; where its search met a
design at one end of the interval (``Emptiness.reached``: the region ends within the run), only its first half is
searched again, and the other half's points, most of them with designs, are solved as usual (the back-off: on the
ball over its allowable contact stress the run reaching past the region's edge had been bisected into 12 more
searches, 9 of them over points that all have designs); a region's search may take REGION_BUDGET times the boxes of
the last proof (at least SURE_BOXES, at most MAX_BOXES), so one reaching past the edge gives up early. Runs start
FIRST_RUN points long, the next twice the longest proven (from 2, doubling while they are proven whole, up to
LONGEST_RUN): where a region's bounds are loose over wide intervals (the lever over its speed, which its centrifugal
force takes squared) the runs stay as short as proofs allow. Without integer variables a stretch's first run is
preceded by one search of the whole stretch (up to LONGEST_RUN points, within REGION_BUDGET times the boxes of the
last point's own proof: :meth:`Regions._whole_stretch`): where a region's proof costs about what its point nearest
the edge does whatever its length (the wedge over its speed), one search covers what the runs took one each for;
not proven, the runs go on as they would have. Where the design has integer variables (the ball, whose
region's search costs about what a point's own does), the RUNS_AHEAD runs that follow a run if it is proven whole are
searched with it, in one call (:meth:`Regions._runs_ahead`): an iteration costs per call, so they take the
iterations of the longest; each outcome is kept for the call that searches its run, and taken where that search
would make the same steps (:func:`_holds`).

Where a run's search meets a design at one end, probes look for the region's edge within it (:meth:`Regions._edge`):
one solve at the run's last point (as ``Problem.solve`` starts cold; none where the design the search met, within
the point's bounds, meets every constraint there in float64); where it has a design, the run's first two points are
searched as one region (:meth:`Regions._head`: proven, the second needs no probe, which had been a failed solve), then
the points after them in growing steps, then bisection, find the first point with one, and only the points before it
are searched again, none where the two proven reach it (the bisection of such a run by searches had cost seconds
where a solve costs 20-40 ms; a probe before every run cost a failed solve on each run inside a region). A probe only
shortens the run searched; its calls are charged to the next point's verdict.

Where a batched sweep's steps from a proven point only tighten the limits they move, each constraint they move
normalised by its limit or by a scale they do not move (``clutchopt.optimise.tightening``: a duty upwards, an
allowable downwards), the points up to the first that is not tighter carry that point's proof, no search
(:meth:`Regions._tightened`): no design meets at them what none met there. The lever in design mode over 1x-10x its
inertia, whose regions' searches near the edge gave up and each point's own took 0.1-3 s: 6.7 -> 1.4 s (with the
backward pass in C). Where a step moves a row through its value (the cable's torque), the points at which every
row it moves rises along it for every design of the box carry the proof too (``tightening.Slopes``).

A point left over next to a proven one is tested against that proof first (:meth:`Regions._quick`): solved once, as
``Problem.solve`` starts (its design, if it finds one, is ``solve``'s), else its own interval search, the one its full
verdict would run, before the retries: proven, it gets the verdict ``solve`` gives ("proven infeasible: ..."), else
its full verdict goes on from that solve (``Problem.solve``'s ``first``: the retries, then the kept search), not
from the same solve again (20-40 ms each time it had been repeated). A point whose case
breaks a requirement that no design variable enters ("whatever the design"), or (a start-up) whose drive proofs
hold, is left to its own verdict, which says so.

A sweep's first point, with nothing before it to go by, is solved as ``Problem.solve`` starts but undiagnosed; where
that solve ends without a design, its own interval search (within SURE_BOXES) goes before the elastic diagnosis
(:meth:`Regions._first`): proven, it gets the verdict ``solve`` gives, at the same design, without the diagnosis.

A covered point reports the design of the last point without a design (its least relaxation) with every constraint
re-evaluated in float64 at the point's own values (those of a run's points and of the runs searched ahead and
proven together, one NumPy column a point: ``verdict.figures_at``; a batched sweep's read from its arrays, no Case
a point: :class:`SharedBox`), solver ``interval`` (no solver call where a region covers it, the one solve where its
own search proved it) and its share of the search's seconds. A verdict is the
same whatever the order of the points: a region's proof is a proof of each point, and a point its region does not
cover gets its own. The seconds of a search no point's verdict takes (a run it did not prove, a point's own search
that did not prove it, runs searched ahead and not used) go to the next verdict (:meth:`Regions._unclaimed`; a
batched sweep's to its next window's, its last window's to its last point solved alone), so that the records' seconds
add up to what the searches took (the lever's design-mode grid had reported a fifth of them: review 20b).
"""

from __future__ import annotations

import time
from dataclasses import replace
from typing import Callable, NamedTuple

import numpy as np

from clutchopt.model import namespace
from clutchopt.optimise.interval_proof import (FEW_BOXES, MAX_BOXES, SURE_BOXES, Emptiness, _same, _search_problem,
                                               keep_search, last_boxes, proofs_recorded, search_along, searched_along,
                                               searches)
from clutchopt.optimise.proofs import start_up_proofs
from clutchopt.optimise.solution import Solution, SolverInfo
from clutchopt.optimise.tightening import ProofCarry
from clutchopt.optimise.verdict import emptied, figures_at, figures_over, infeasible_at
from clutchopt.records import DESIGN_STATUSES
from clutchopt.optimise.verify import check_design
from clutchopt.units import from_si

FIRST_RUN = 8  # points searched as one region after a point without a design,
LONGEST_RUN = 256  # the next run twice the longest proven, up to this many
RUNS_AHEAD = 3  # runs searched ahead with a run (designs with integer variables: Regions._runs_ahead)
# a run is searched point by point where its points' own proofs take no more boxes in all than its region's search
# (before a region proof to compare with: interval_proof.FEW_BOXES)
REGION_BUDGET = 4  # a region's search may evaluate this many times the boxes of the last point's own search
# (at least interval_proof.SURE_BOXES): one reaching past the region's edge gives up there and is bisected


class SharedBox(NamedTuple):
    """A batched sweep's points as its arrays (no varied quantity is a design variable: ``batch.batchable``): each
    point's case values, a row a point in the order of the formulation's quantities (what ``Posed.params`` reads of
    its case), and the design box every point shares. A run's search problems, float64 figures and conflicts are read
    from them, the same numbers as from each point's Case, which is then built only for a point solved or searched
    alone (the ball beyond its edge: a Case, a search problem and its values read twice more, 30 us a point, had
    been a tenth of its CPU)."""

    values: np.ndarray  # points x quantities
    names: list[str]  # the quantities (the formulation's, in order)
    lower: np.ndarray  # the design box (SI), every point's
    upper: np.ndarray
    kept: dict  # what the sweep's windows share, worked out once (``Regions._carry``)

    def problem(self, j: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Point j's search problem, as ``interval_proof._search_problem`` builds it from its case."""
        return np.concatenate([self.values[j], np.ones(len(self.lower)), [1.0]]), self.lower, self.upper

    def params_of(self, points: list[int]):
        """The values of ``points`` as ``Posed.params_of`` reads them from their cases: an array over them by name."""
        return namespace({name: self.values[points, i] for i, name in enumerate(self.names)})


class Regions:
    """Along a sweep (points 0 .. count - 1 in order, ``point_case(k)`` the case of point k, ``problem`` its built
    problem): :meth:`point` gives point k's solution, from a region proof that covers it (searching the run from k
    where the point before has no design), a search of its own or its solve."""

    def __init__(self, problem, point_case, count: int, shared: SharedBox | None = None, until: int | None = None):
        self.problem, self.posed, self._case_of, self.count = problem, problem.posed, point_case, count
        self._shared = shared  # (a batched sweep's arrays: SharedBox)
        self._until = count if until is None else until  # (a batched window's last point and the stretch it may run
        # on to: the next window's regions begin afresh, so no proof is carried past it)
        self._cases: dict = {}  # point -> its case, from its run's search on until its verdict (built once)
        self._problems: dict[int, tuple] = {}  # point -> its search problem, built once (a point's run and the runs
        # ahead of it are searched again from later calls: the ball over its contact stress built 148 for 57 points)
        self._without: Solution | None = None  # the last point's solution where it has no design
        self._without_at = -2
        self._to, self._length = 0, FIRST_RUN  # the end of the points searched; how many to search next
        self._proven: dict[int, tuple[str, float]] = {}  # point -> its proof's text, its share of the seconds
        self._probed = (0, 0.0)  # the solver calls and seconds of the probes for a region's edge, and the seconds of
        # searches no point's verdict took (:meth:`_unclaimed`), not yet charged
        self._found = -1  # the point a probe found with a design (the region's edge)
        self._entered = False  # a point with a design came before: a stretch without designs is entered from one
        self._edge_probe: Solution | None = None  # the solve of the last probe that found a design (the edge's,
        # for that point's own, uncharged; None where the design the run's search met decided it)
        self._alone = 0  # the boxes of the last proof of one point (its own verdict's or its own search's; the mean
        # of the last run searched point by point)
        self._region: int | None = None  # the boxes of the last region proof
        self._figures: dict[int, tuple] = {}  # proven point -> its float64 figures at the design of self._without
        self._figured_design: dict[str, float] | None = None  # (that design)
        self._ahead: dict[tuple[int, int], tuple] = {}  # a run searched ahead -> its problem, outcome and
        # seconds a point (its share of the call that searched it)
        self._origins: dict[int, int] = {}  # a point a proof is carried to -> the point proven by its own or a
        # region's search whose proof it is
        self._origin_designs: dict[int, dict] = {}  # such a proof's point -> the design the points it is carried to
        # show (that of the point it was first carried from: not that of a point between left to its own verdict,
        # review 22c)

    def point_case(self, k: int):
        """Point k's case, built once for its run's search, its float64 figures and its verdict."""
        case = self._cases.get(k)
        if case is None:
            case = self._cases[k] = self._case_of(k)
        return case

    def covered(self, k: int) -> Solution | None:
        """Point k's verdict from a region proof, or None (solve it). No region is searched after a point that breaks
        a requirement no design variable enters (:func:`_given`): point k is tested against that requirement first
        (:meth:`_quick`), and a proof does not cover a point that breaks it (:func:`_covered`)."""
        if self._without_at == k - 1 and not _given(self._without) and not self._carried(k) and k >= self._to:
            self._search_from(k)
        proven = self._proven.pop(k, None)
        if proven is None or self._without is None or not proven[0]:  # (a point left to its own verdict among
            return None  # those a proof was carried to: _carried)
        problem = self._problems.get(k)  # (its search problem: its design box, the bounds its verdict shows; a
        # batched sweep's box, every point's, where none was built: a point a proof is carried to)
        bounds = (problem[1:3] if problem is not None else None if self._shared is None
                  else (self._shared.lower, self._shared.upper))
        figures, conflicting = self._figures_at(k) or (None, None)
        known = figures is not None and conflicting is not None and bounds is not None
        solution = _covered(self.problem, None if known else self.point_case(k), self._shown(k), *proven,
                            figures=figures, conflicting=conflicting, bounds=bounds)
        if solution is not None:
            self.after(k, solution)
        return self.charged(solution)

    def charged(self, solution: Solution | None) -> Solution | None:
        """``solution`` with the solver calls and seconds of the probes for a region's edge not yet charged to a
        point (:meth:`_edge`) added to its own, and the seconds of searches no point's verdict took
        (:meth:`_unclaimed`): the sweep's count of solver calls and its seconds are the sums over its points."""
        calls, seconds = self._probed
        if solution is None or not (calls or seconds):
            return solution
        self._probed = (0, 0.0)
        return replace(solution, solver=replace(solution.solver, solves=solution.solver.solves + calls,
                                                time_s=solution.solver.time_s + seconds))

    def point(self, k: int, solve: Callable[[Solution | None], Solution], warm=None,
              beside: dict[str, float] | None = None) -> Solution:
        """Point k's solution, the one sequence of a sweep's point that is not batched: its region proof where one
        covers it (:meth:`covered`), else its own interval search before any solve where a stretch without designs
        likely starts at it (:meth:`_early`: ``beside``, the design of the point before, given), else one solve and
        its own interval search where the point before has no design (:meth:`_quick`), else ``solve(first)``: the
        point's full verdict, continuing from that first solve where there was one (``first``, see
        ``Problem.solve``'s ``first``), else from the start; the probes' calls charged to it, and the regions told
        (:meth:`after`). ``warm``: the point's warm start (a static problem's)."""
        solution, first = self.covered(k), None
        if solution is None and beside is not None:
            solution = self._early(k, beside)
        if solution is None:
            solution = self._first(k, warm)
        if solution is not None:
            return solution
        proofs = proofs_recorded(self.posed)
        solution, first = self._quick(k, warm)
        if solution is None:
            along = self._along(k)
            try:
                solved = solve(first)
            except BaseException:
                search_along(self.posed, None)  # (the hook not left for another point's search)
                raise
            solution = self.charged(self._took(along, solved))
            self.after(k, solution)
        if solution.status == "infeasible" and proofs_recorded(self.posed) > proofs:  # (proven by its own search:
            self._alone = last_boxes(self.posed)  # its boxes; not a verdict "whatever the design", nor a drive's)
        return solution

    def _along(self, k: int) -> tuple[list[tuple[int, int]], dict, dict]:
        """The runs after point k (:meth:`_next_runs`), given to its full verdict's first interval search to search
        in the same call (``interval_proof.search_along``; their problems built only if it runs): where that search
        proves point k, the runs are those :meth:`_search_from` searches next (``ball_crusher`` over 250-1000 kW:
        point 84's proof, 11 iterations, and its 115 points after it, 11, in one call)."""
        runs, built = self._next_runs(k), {}
        return runs, built, search_along(self.posed, (lambda: self._regions(runs, built)) if runs else None)

    def _regions(self, runs: list[tuple[int, int]], built: dict) -> list[tuple]:
        """The search problems of ``runs`` as regions, also kept in ``built`` (its "regions")."""
        points = self._point_problems(runs)
        built["regions"] = [_region_problem([points[j] for j in range(a, b)]) for a, b in runs]
        return built["regions"]

    def _took(self, along: tuple, solution: Solution) -> Solution:
        """The outcomes of :meth:`_along`'s runs kept for :meth:`_search_from` where the verdict's search took them,
        each point its share of that call's seconds, taken from ``solution``'s (which measured the call); the hook
        cleared."""
        runs, built, taken = along
        outcomes, seconds = taken.get("outcomes"), taken.get("seconds", 0.0)
        search_along(self.posed, None)
        if outcomes is None:
            return solution
        taken_along = self._kept_along(runs, built["regions"], outcomes, seconds)
        return replace(solution, solver=replace(solution.solver, time_s=solution.solver.time_s - taken_along))

    def _kept_along(self, runs: list[tuple[int, int]], regions: list, outcomes: list, seconds: float) -> float:
        """The outcomes of ``runs`` (their ``regions``), searched along a point's own search in one call of
        ``seconds``, kept for :meth:`_search_from`, each point its share of the call (the point's own one share);
        the seconds they take from the call."""
        points = sum(b - a for a, b in runs) if outcomes else 0
        share = seconds / (1 + points)
        self._ahead.update((run, (region, outcome, share)) for run, region, outcome in zip(runs, regions, outcomes))
        return share * points

    def _early(self, k: int, design: dict[str, float]) -> Solution | None:
        """Point k, where a batch's chain from the point before (with ``design``) failed: the interval search its full
        verdict runs first (``verdict.shown``: within SURE_BOXES; with integer variables the runs after it in the same
        call, :meth:`_next_runs`), before any solve instead of after the failed ones. Proven, it gets the verdict its
        full verdict gives ("proven infeasible: ...", the same search, whose budget did not bind), with ``design``
        re-evaluated in float64 at its values (where its full verdict shows its failed solve's), no solver call, and
        the runs' outcomes kept as that verdict would leave them: without the failed solves (warm SQP, warm and cold
        IPOPT), the integer search and the elastic diagnosis. The wedge over its speed at 1,905 rpm, where its finger
        no longer fits: 257 boxes, 2 ms, where the full verdict took 14 ms; the ball over 1x-10x its power at 11,190
        kW: 24 of the sweep's 82 ms of CPU; the lever at the first point of a stretch without designs, 20 ms, one box.
        Else None (solved as usual), its outcome kept for that verdict where any budget from SURE_BOXES on gives the
        same (a design met): a point with a design costs this search, which meets one (the chains failed next to a
        design at points with designs in none of the sweeps of the user sweeps' benchmark; a search met one in 1-2
        ms without integers, 3-14 ms on the ball)."""
        self._entered = True  # (the point before has a design)
        if self.problem.start_up is not None:
            return None
        solution, own, problem = self._own_proof(self.point_case(k), design, SURE_BOXES, None, self._next_runs(k))
        if solution is None:
            self._kept_for_its_verdict(problem, own)
        if solution is not None:
            self.after(k, solution)
        return solution

    def _kept_for_its_verdict(self, problem: tuple, own: Emptiness | None) -> None:
        """A point's own search within SURE_BOXES that did not prove it, kept for its full verdict's search before
        the retries (``verdict.shown``: the same search), where it ended by its outcome (a design met) or by that
        budget (``Emptiness.paused``, which the verdict's search after the retries resumes: review 22b, the lever's
        design grid searching 2,135-2,309 boxes twice at three points)."""
        if _holds(own, SURE_BOXES) or own is not None and own.paused is not None:
            keep_search(self.posed, problem, own)

    def _first(self, k: int, warm=None) -> Solution | None:
        """The sweep's first point (static, no warm start: nothing before it to go by) solved as ``Problem.solve``
        starts, undiagnosed; where that solve ends without a design, the point's own interval search within
        SURE_BOXES (what ``verdict.shown`` evaluates before the retries) before the elastic diagnosis: proven, the
        verdict ``solve`` gives ("proven infeasible: ...", the same search's words, at the same design: the failed
        solve's, which its full verdict shows), without the diagnosis, which there only lets that search go first and
        is not shown (the lever over its friction coefficient: 3-6 ms of the 10 its first point took; the runs after
        it searched in the same call: :meth:`_next_runs`); a design:
        that solve's, ``solve``'s. Else None: its full verdict from the start, the first solve's calls charged to it
        (a sweep whose first point has no design and no proof, the wedge's geometry mode, pays that solve again; its
        search kept for it: :meth:`_kept_for_its_verdict`)."""
        if k != 0 or warm is not None or self.problem.start_up is not None:
            return None
        case = self.point_case(k)
        first = self.problem.refined(case, diagnosed=False)
        if first.status in DESIGN_STATUSES:
            self.after(k, first)
            return first
        solution, own, problem = self._own_proof(case, first.design, SURE_BOXES, first.solver, self._next_runs(k))
        if solution is None:
            self._kept_for_its_verdict(problem, own)
            self._charge(first)
            return None
        self.after(k, solution)
        return solution

    def _quick(self, k: int, warm=None) -> tuple[Solution | None, Solution | None]:
        """Point k, not covered, next to a point without a design (a static problem): one solve (``Problem.solve``'s
        first, ``warm`` its warm start), and where it ends without a design the point's own interval search before
        the retries (the runs after it searched in the same call: :meth:`_next_runs`): the solve's design, or the
        verdict its proof gives, and None; or None and that solve (its
        verdict follows from it: ``Problem.solve`` given it as ``first``, which finds this search kept; unsearched
        where it breaks a requirement no design variable enters, :func:`_given`: the wedge over its friction
        coefficient, past self-locking, 34 -> 21 ms of CPU); or None, None where the point before has a design."""
        quick = self._without_at == k - 1 and self.problem.start_up is None
        probe = self._edge_solve(k, quick and warm is None)
        if not quick:
            return None, None
        case = self.point_case(k)
        first = self.charged(probe or self.problem.refined(case, warm=warm))
        if first.status in DESIGN_STATUSES:
            self.after(k, first)
            return first, None
        if _given(first):  # (its verdict as it is: ``verdict.shown``; a proof would not cover it)
            return None, first
        solution, own, problem = self._own_proof(case, first.design, None, first.solver, self._next_runs(k))
        if own is None or not own.proven:
            keep_search(self.posed, problem, own)
        if solution is None:
            return None, first
        self.after(k, solution)
        return solution, None

    def _own_proof(self, case, design: dict[str, float], budget: int | None, spent: SolverInfo | None = None,
                   ahead: list[tuple[int, int]] = ()) -> tuple[Solution | None, Emptiness | None, tuple]:
        """A point's own interval search (within ``budget`` boxes; None: the search's own), and where it proves the
        point, the verdict it gives ("proven infeasible: ...") showing ``design`` (``spent``: the calls and seconds
        of the solve that gave it), its boxes the last point's alone (``_alone``): (verdict or None, the search's
        outcome, its problem). ``ahead``: runs searched as regions in the same call (within SURE_BOXES, the least
        budget :meth:`_search_from` gives; given up where the point's first box decides it:
        ``interval_proof.searched_along``), their outcomes kept for it (as :meth:`_runs_ahead`'s: :func:`_holds`),
        each point its share of the call's seconds."""
        problem, built = _search_problem(self.posed, case), {}
        began = time.perf_counter()
        if ahead:
            own, outcomes, seconds = searched_along(self.posed, problem, MAX_BOXES if budget is None else budget,
                                                    lambda: self._regions(ahead, built))
        else:
            own, outcomes, seconds = searches(self.posed, [problem], None if budget is None else [budget])[0], [], 0.0
        own_seconds = time.perf_counter() - began - self._kept_along(ahead, built.get("regions", []), outcomes,
                                                                      seconds)
        if own is None or not own.proven:
            self._unclaimed(own_seconds)
            return None, own, problem
        self._alone = last_boxes(self.posed, own.boxes)
        return (_covered(self.problem, case, design, "proven infeasible: " + emptied(own), own_seconds, spent), own,
                problem)

    def _next_runs(self, k: int) -> list[tuple[int, int]]:
        """Where point k, next to be proven by its own search, has integer design variables: the runs
        :meth:`_search_from` searches next if it is (that from point k + 1, ``_length`` points, and its runs ahead,
        :meth:`_runs_ahead`), searched with its own search in one call (:meth:`_own_proof`). An iteration costs per
        call, and the ball's proof of one point takes about as many as its runs' (over 9.3x-18.7x its power, all
        without a design: 11 and 11 iterations in two calls; over 1x-10x, the first point without a design and the
        three after it, 11 and 9). Where it is not proven, or the next point has a design, they are not used; a run
        whose search is kept already is not searched again."""
        end = min(k + 1 + self._length, self.count)
        if not self.posed.integer or self.problem.start_up is not None or end - k <= 2 \
                or self._tightened(k, k + 1, 1) > k + 1:  # (proven, point k's proof holds at the next: _tightened)
            return []
        return [run for run in ((k + 1, end), *self._runs_ahead(k + 1, end)) if run not in self._ahead]

    def after(self, k: int, solution: Solution) -> None:
        """Point k's solution: one proven infeasible starts (or goes on with) the regions searched after it (after
        one not found, a proof is not expected); a design ends a run of proven regions (the next run starts
        FIRST_RUN points long)."""
        self._cases.pop(k, None)
        if solution.status in DESIGN_STATUSES:
            self._length, self._entered = FIRST_RUN, True
        elif solution.status == "infeasible":
            self._without, self._without_at = solution, k

    def _search_from(self, k: int) -> None:
        """The runs from point k (``_length`` points), bisected where not proven whole, their searches together; the
        next runs twice as long as the longest proven (FIRST_RUN again after a design)."""
        if k == self._found:  # the edge a probe found: solved as usual (Regions._quick)
            self._to = k + 1
            return
        end = min(k + self._length, self.count)
        self._cases = {j: case for j, case in self._cases.items() if j >= k}  # (those of points solved as usual)
        self._problems = {j: problem for j, problem in self._problems.items() if j >= k}
        self._to, runs = end, [(k, end)] if end - k > 1 else []  # (a last point alone: Regions._quick)
        points = self._point_problems([(k, end)])
        if runs and self._one_by_one(end - k):
            self._search_each(k, end, points)
            return
        if runs and self._whole_stretch(k, end):
            return
        longest = 1  # the longest run proven
        ahead = [run for run in self._runs_ahead(k, end) if run not in self._ahead] if runs else []
        points.update(self._point_problems(ahead))
        while runs:
            budget = _budget(last_boxes(self.posed), SURE_BOXES)
            known = {run: self._ahead.pop(run) for run in runs if run in self._ahead}
            self._unclaimed(sum(kept[2] * (b - a) for (a, b), kept in known.items() if not _holds(kept[1], budget)))
            known = {run: kept for run, kept in known.items() if _holds(kept[1], budget)}
            fresh = [run for run in runs if run not in known]
            problems = [_region_problem([points[j] for j in range(a, b)]) for a, b in fresh + ahead]
            began = time.perf_counter()
            outcomes = searches(self.posed, problems, [budget] * len(problems)) if problems else []
            share = (time.perf_counter() - began) / max(1, sum(b - a for a, b in fresh + ahead))  # a point's
            # seconds: the call's over the points of every run it searched (an ahead run's kept with it)
            self._ahead.update((run, (problem, outcome, share)) for run, problem, outcome
                               in zip(ahead, problems[len(fresh):], outcomes[len(fresh):]))
            found = {**{run: (problem, outcome, share) for run, problem, outcome in zip(fresh, problems, outcomes)},
                     **known}
            ahead, halves = [], []
            for (a, b), (problem, outcome, seconds) in ((run, found[run]) for run in runs):
                if outcome is not None and outcome.proven:
                    self._proved(a, b, problem, outcome, seconds)
                    longest = max(longest, b - a)
                    continue
                self._unclaimed(seconds * (b - a))  # (not proven: its share of the call to the next verdict)
                if b - a > 1 and outcome is not None and outcome.feasible is None:  # (a design met for the whole
                    # run: every point has one, solved as usual)
                    middle = (a + b) // 2  # (a design at one end: the region ends within the run: the run up to
                    # the edge the probes find is searched again, else only its first half, the points of the other
                    # solved as usual)
                    edge, head = self._edge(a, b, points, outcome.witness) if outcome.reached else (b, a)
                    if head >= edge:  # (the run up to the edge proven by the probes' search of its head)
                        longest = max(longest, edge - a)
                        continue
                    kept = (((a, edge),) if edge < b else ((a, middle),) if outcome.reached
                            else ((a, middle), (middle, b)))
                    halves += [run for run in kept if run[1] - run[0] > 1]  # a single point: solved as usual (a
                    # design found by a solve, else its own verdict with its own search)
            runs = halves
        self._length = min(2 * longest, LONGEST_RUN)

    def _carried(self, k: int) -> bool:
        """Point k, not proven yet, after point k - 1 proven infeasible: the proof k - 1's rests on (its own, a
        region's, or the one carried to it: its origin) carried to k and the points after it up to the first that the
        sweep has not only tightened since the origin (:meth:`_tightened`), that a region proof holds already, or
        LONGEST_RUN points on; none searched; whether it reached k. Also where a run searched before had left k to be
        solved (a list of values up and down: review 21). A point among them that breaks a requirement no design
        variable enters is left to its own verdict (:func:`_apart`); the others take the proof in runs between such
        points, each run's words its own points and values, naming the origin (review 22: a point carried to had been
        named as the proof's)."""
        if k in self._proven or not (self._without.diagnosis or "").startswith("proven"):
            return False
        origin = self._origins.get(k - 1, k - 1)
        end = min([self._tightened(origin, k), k + LONGEST_RUN, self._until, *(j for j in self._proven if j > k)])
        if end <= k:
            return False
        design = self._origin_designs.setdefault(origin, self._without.design)
        figured = self._figured(list(range(k, end)), design)  # (kept for their verdicts)
        apart = [_apart(self.posed, {c.name for c in figured[j][0][0] if not c.feasible}, lambda: figured[j][1])
                 for j in range(k, end)]
        for a, b in _runs(apart, k):
            text = self._tightened_text(origin, a, b)
            self._proven.update((j, (text, 0.0)) for j in range(a, b))
            self._origins.update((j, origin) for j in range(a, b))
        self._proven.update((k + i, ("", 0.0)) for i, left in enumerate(apart) if left)  # (its own verdict follows:
        # _covered declines it)
        self._to = max(self._to, end)
        return True

    def _tightened(self, j: int, k: int, count: int = LONGEST_RUN) -> int:
        """The end of the points from k on at which a proof of infeasibility at point j holds: the sweep has only
        tightened the limits of the constraints it moves since point j, each normalised by its limit or by a scale
        it does not move (``tightening.Tightening``), and each row it moves through its value (or a scale apart from
        its limit) rises along the step for every design of the box (``tightening.Slopes``: the cable beyond its edge
        over its torque; looked at up to ``count`` points on), the two together (``tightening.ProofCarry``: the
        ball's power, in its torque's limit, with its shell thickness, in its outer diameter's value), so no design
        meets at them what none met at point j (within the proof's tolerance of each row's scale); k where none. A
        batched sweep's (its points' values read from its arrays); the ball beyond its edge, 9.33x-18.7x its power:
        five region searches (1,393 boxes) -> none past the first point's proof."""
        if self._shared is None:
            return k
        return self._carry.held_from(self._shared.lower, self._shared.upper, j, k, count)

    @property
    def _carry(self) -> ProofCarry:
        """What carries a proof along this batched sweep (its limits at every point: once a sweep, whatever its
        windows: ``SharedBox.kept``)."""
        shared, kept = self._shared, self._shared.kept
        if "carry" not in kept:
            varied = [name for i, name in enumerate(shared.names) if _moves(shared.values[:, i], shared.values[0, i])]
            kept["carry"] = ProofCarry(self.posed, varied, shared.values)
        return kept["carry"]

    def _tightened_text(self, j: int, start: int, end: int) -> str:
        """The proof of point j (``_without``'s verdict, the proof it rests on) in words, for the points ``start`` to
        ``end`` - 1 after it."""
        values, diagnosis = self._shared.values, self._without.diagnosis or ""
        moved = [(i, q) for i, q in enumerate(self.posed.formulation.quantities)
                 if _moves(values[start:end, i], values[j, i])]
        spans = ", ".join(f"{q.name} {_span(values[start:end, i], q.unit)}{_unit(q.unit)}" for i, q in moved)
        at = ", ".join(f"{q.name} {_shown(values[j, i], q.unit)}{_unit(q.unit)}" for i, q in moved)
        proof = diagnosis.split(": ", 1)[1] if diagnosis.startswith("proven infeasible") and ": " in diagnosis \
            else diagnosis
        how = self._carry.how
        count = f"{end - start} point{'s' if end - start > 1 else ''}"
        if not moved:  # (the proven point's values again)
            return f"proven infeasible ({count} at the values of a point proven before, by its proof): {proof}"
        return f"proven infeasible for {spans} ({count}, by the proof at {at}; {how}): {proof}"

    def _whole_stretch(self, k: int, end: int) -> bool:
        """Where a stretch without designs entered from a design starts at point k (its first run, FIRST_RUN points up
        to ``end``, searched as a region) in a design without integer variables: the points from k up to LONGEST_RUN on
        (or the sweep's end) searched first as one region, within REGION_BUDGET times the boxes of the last point's own
        proof. A sweep that meets such a stretch after designs has moved into its infeasible region and most often stays
        in it (a duty or a speed past what any design carries); one that starts without designs most often moves out of
        it, where this search would meet a design at the far end for nothing (the wedge from 300 N m down,
        test_region_search). Where a region's proof costs about what its point nearest the edge does whatever its
        length, the doubling runs cost a search each for the same proof (the wedge centrifuge over its speed: 257 boxes
        for 1,905 rpm alone, 809 for the 8 points after it, 731 for the next 16, 551 for the last 6; 705 for those 30 at
        once: 3 searches, 16 of the sweep's 33 ms of CPU, to 1). Proven, each point gets that proof (and the next run is
        twice as long); else (a design met at an end of the interval, or the budget spent: its bounds too loose over it)
        the runs from k as before, nothing of this search used, its boxes spent for nothing. With integer variables the
        runs ahead are searched in the call of the first instead (:meth:`_runs_ahead`: an iteration costs per call
        there)."""
        whole = min(k + LONGEST_RUN, self.count)
        if self.posed.integer or self._length != FIRST_RUN or whole <= end or not self._entered:
            return False
        points = self._point_problems([(k, whole)])
        problem = _region_problem([points[j] for j in range(k, whole)])
        began = time.perf_counter()
        outcome, = searches(self.posed, [problem], [_budget(self._alone, FEW_BOXES)])
        if outcome is None or not outcome.proven:
            self._unclaimed(time.perf_counter() - began)
            return False
        self._proved(k, whole, problem, outcome, (time.perf_counter() - began) / (whole - k))
        self._to, self._length = whole, min(2 * (whole - k), LONGEST_RUN)
        return True

    def _point_problems(self, runs: list[tuple[int, int]]) -> dict[int, tuple[np.ndarray, ...]]:
        """The search problem of each point of ``runs`` (``(a, b)``: points a .. b - 1), by its number (each built
        once a sweep)."""
        for j in (j for a, b in runs for j in range(a, b) if j not in self._problems):
            self._problems[j] = (self._shared.problem(j) if self._shared is not None
                                 else _search_problem(self.posed, self.point_case(j)))
        return {j: self._problems[j] for a, b in runs for j in range(a, b)}

    def _runs_ahead(self, k: int, end: int) -> list[tuple[int, int]]:
        """The runs after k .. end - 1 that :meth:`_search_from` searches next where each before it is proven whole
        (twice as long each, up to LONGEST_RUN; RUNS_AHEAD of them: ball_crusher over 250-1000 kW, its 115 points
        after its first without a design in one call, where two had left the last 59 to a call of 8 iterations),
        searched with it where the design has integer variables: an iteration costs per call, and a region's search
        there costs about a point's own (the ball's: 121-473 boxes, 8-16 iterations), so the runs together take the
        iterations of the longest, not their sum;
        their outcomes are kept for the calls that search them (:func:`_holds`; the others dropped with the
        sweep). None after a run whose kept search met a design (:func:`_met`): the runs after it are searched only
        where it is proven whole (the ball over its contact stress: points 57-99, all with designs, 77 boxes, three
        iterations, 3 ms for nothing)."""
        if not self.posed.integer or self.problem.start_up is not None:
            return []
        runs, length = [], end - k
        while len(runs) < RUNS_AHEAD and end < self.count - 1 and not _met((k, end), self._ahead):
            length = min(2 * length, LONGEST_RUN)
            runs.append((end, min(end + length, self.count)))
            k, end = runs[-1]
        return runs

    def _proved(self, a: int, b: int, problem: tuple, outcome: Emptiness, seconds: float) -> None:
        """Points a .. b - 1 proven by one search (``outcome``, of the region ``problem``): each gets its text
        and ``seconds``; the search's boxes are the last proof's."""
        last_boxes(self.posed, outcome.boxes)
        self._region = outcome.boxes
        text = _region_text(self.posed, a, b, problem, outcome)
        for j in range(a, b):
            self._proven[j] = (text, seconds)

    def _one_by_one(self, count: int) -> bool:
        """The ``count`` points of a run are searched each alone (:meth:`_search_each`): their own proofs, at the
        boxes of the last point's own, are expected to take fewer boxes than the run's search, as many as the last
        region proof took (before one, as the last point's own, or FEW_BOXES). Where one point's design space is
        emptied in a few boxes, the interval of the varied quantity can cost far more: the lever over its speed, one
        point in 1 box, 8 points together in 2,101 (its centrifugal torque takes the speed squared), 16 in 1,461.
        Where a point's own proof takes hundreds of boxes, a region's takes about as many: the wedge over its
        resisting torque (257 and 129 for 8 points), the ball (121 and 167 for 8 points over its contact stress;
        435 and 439 before its searches evaluated 32 boxes an iteration: ``interval_proof._batch``)."""
        alone = max(self._alone, 1)
        return count * alone <= (self._region if self._region is not None else max(alone, FEW_BOXES))

    def _search_each(self, k: int, end: int, points: dict) -> None:
        """Points k .. end - 1 searched each alone, in one call (``interval_proof.searches``): a point proven gets its
        own proof's verdict ("proven infeasible: ...", the words of its full verdict), another is solved as usual;
        the next run twice as long where all are proven."""
        budget = _budget(self._alone, FEW_BOXES)  # (a point past the region's edge gives up after its first box where
        # one proved in 1: the split to 128 passes the budget)
        began = time.perf_counter()
        outcomes = searches(self.posed, [points[j] for j in range(k, end)], [budget] * (end - k))
        seconds = (time.perf_counter() - began) / (end - k)
        proven = [(j, outcome) for j, outcome in zip(range(k, end), outcomes) if outcome is not None and outcome.proven]
        self._unclaimed(seconds * (end - k - len(proven)))
        for j, outcome in proven:
            self._proven[j] = ("proven infeasible: " + emptied(outcome), seconds)
        if proven:
            self._alone = round(sum(outcome.boxes for _, outcome in proven) / len(proven))
        self._length = min(2 * (end - k), LONGEST_RUN) if len(proven) == end - k else FIRST_RUN

    def _edge(self, k: int, end: int, points: dict, witness: np.ndarray | None = None) -> tuple[int, int]:
        """The end of the run from point k to ``end`` whose search met a design at one end: ``end``, or the first
        point before it found with a design by one solve (as ``Problem.solve`` starts cold), located where the run's
        last point has one: points k + 1, k + 2, k + 4, ... until one has a design, then bisection; and the end of
        the points from k its probes proved (k where none: :meth:`_head`). A run reaching
        past the region's edge cannot be proven, and its bisection by interval searches cost seconds (the ball over
        its allowable contact stress: four searches, 7.7 s, for the last two points of its region) where a solve
        costs 20-40 ms. A probe only shortens the run searched: a proof is still a proof of each point of it, and a
        point after the edge is solved as usual (its design is ``solve``'s, whatever the probe found). A point where
        the design the run's search met (``witness``) meets every constraint in float64 has a design without a probe
        (the ball over its allowable contact stress: the run's last point, a cold solve with its integer search, 12
        ms)."""
        if end - k <= 2 or self.problem.start_up is not None or not self._designed(end - 1, witness):
            return end, k
        without, designed, step = k, end - 1, 1  # (point k: searched from, next to a proven one)
        headed = self._head(k, points)
        if headed:  # (points k, k + 1 proven: the probes from k + 2 on)
            without = k + 1
        while without + step < designed:  # from k on in growing steps (an edge is most often near the run's start)
            if self._designed(without + step, witness):
                designed = without + step
                break
            without, step = without + step, 2 * step
        while designed - without > 1:
            middle = (without + designed) // 2
            without, designed = (without, middle) if self._designed(middle, witness) else (middle, designed)
        self._found = designed  # (the last probe with a design: self._edge_probe)
        self._charge(self._edge_probe, -1)  # (charged to the edge's point, whose solve it is: :meth:`_edge_solve`)
        return designed, k + 2 if headed else k

    def _head(self, k: int, points: dict) -> bool:
        """Points k and k + 1 of a run reaching past its region's edge searched as one region before any probe
        (within REGION_BUDGET times the last proof's boxes): proven, point k + 1 needs no probe, and where the edge is
        k + 2 the run up to it is proven (the ball over its allowable contact stress: a failed solve at k + 1, 9 ms,
        a solve at k + 3 that the bisection then passed over, 15 ms, and the search of the same two points after
        them, which this one is). Not proven (a design at k + 1, most often met at once), the probes go on from
        k + 1."""
        problem = _region_problem([points[k], points[k + 1]])
        began = time.perf_counter()
        outcome, = searches(self.posed, [problem], [_budget(last_boxes(self.posed), FEW_BOXES)])
        if outcome is None or not outcome.proven:
            self._unclaimed(time.perf_counter() - began)
            return False
        self._proved(k, k + 2, problem, outcome, (time.perf_counter() - began) / 2)
        return True

    def _designed(self, j: int, witness: np.ndarray | None = None) -> bool:
        """Point j has a design: ``witness``, within j's bounds and its integers whole, meets every constraint at j in
        float64, else by one solve (cold, undiagnosed), whose calls are charged to the next verdict."""
        posed, case = self.posed, self.point_case(j)
        if witness is not None and np.all(witness[posed.integer] == np.round(witness[posed.integer])):
            lower, upper, _ = posed.bounds_and_start(case, None)
            checks = check_design(posed.formulation, dict(zip(posed.names, witness.tolist())), posed.params(case))
            if np.all((lower <= witness) & (witness <= upper)) and all(c.feasible for c in checks):
                self._edge_probe = None
                return True
        solution = self.problem.refined(case, diagnosed=False)
        self._charge(solution)
        if solution.status in DESIGN_STATUSES:
            self._edge_probe = solution
        return solution.status in DESIGN_STATUSES

    def _edge_solve(self, k: int, usable: bool) -> Solution | None:
        """At the region's edge found by the probes (point k), the probe's solve where it is the point's first
        (``usable``: cold, as ``Problem.solve`` starts next to a point without a design; the same call, the same
        design: the ball over its contact stress, 20 ms); else None, its calls then charged to the next verdict."""
        probe = self._edge_probe if k == self._found else None
        if probe is None:
            return None
        self._edge_probe = None
        if usable:
            return probe
        self._charge(probe)
        return None

    def _figures_at(self, k: int) -> tuple[tuple, bool] | None:
        """Proven point k's float64 figures at the design of the last point without one and whether two limits of
        one quantity leave no room between at its values (:func:`_covered`), those of every point proven with it
        evaluated together, one NumPy column a point (static problems; None otherwise): a region's points share that
        design, and one evaluation of the formulation's equations over arrays costs what one over floats does (the
        lever over 1x-10x its inertia: 84 covered points, each evaluated alone, were half the sweep's time); with them
        the points of the runs searched ahead and proven (:meth:`_runs_ahead`), which their turn covers with the same
        design (the ball beyond its edge: its 99 covered points in one evaluation, not four)."""
        if self.posed.start_up is not None:  # (its own drive proofs come first: ``_covered``)
            return None
        design = self._shown(k)
        if k not in self._figures or self._figured_design != design:
            ahead = (j for (a, b), (_, outcome, _) in self._ahead.items() if outcome is not None and outcome.proven
                     for j in range(a, b))
            points = sorted({k, *(j for j in (*self._proven, *ahead) if j > k)})[:LONGEST_RUN]  # (a proof carried
            # to the sweep's end: its points figured a run's length at a time, not past a window's end for nothing)
            self._figured(points, design)
        return self._figures.pop(k)

    def _shown(self, k: int) -> dict[str, float]:
        """The design proven point k shows: that of the point its proof was carried from, else that of the last point
        without a design (a region's points: its least relaxation)."""
        origin = self._origins.get(k)
        return self._without.design if origin is None else self._origin_designs[origin]

    def _figured(self, points: list[int], design: dict[str, float]) -> dict[int, tuple]:
        """The float64 figures of ``design`` at ``points`` and whether two limits of one quantity leave no room
        between at each, by point, kept for their verdicts (:meth:`_figures_at`)."""
        if self._shared is not None and len(points) > 1:  # (read from the sweep's arrays: no Case a point)
            figures = figures_over(self.posed, self._shared.params_of(points), len(points), design)
            conflicting = self.posed.conflicting_over(self._shared.values[points])
        else:
            cases = [self.point_case(j) for j in points]
            figures, conflicting = figures_at(self.posed, cases, design), self.posed.conflicting_at(cases)
        self._figures, self._figured_design = dict(zip(points, zip(figures, conflicting))), dict(design)
        return self._figures

    def _unclaimed(self, seconds: float) -> None:
        """Seconds of an interval search that no point's verdict takes (a run it did not prove, a point's own search
        that did not prove it, the runs searched ahead and not used): charged to the next verdict (:meth:`charged`;
        uncharged, the lever's design-mode grid had reported half its searches' seconds: review 20b)."""
        self.carry((0, seconds))

    def uncharged(self) -> tuple[int, float]:
        """The solver calls and seconds not yet charged to a point, those of the runs searched ahead and not used
        with them: what a batched sweep's next window charges (:meth:`carry`)."""
        calls, seconds = self._probed
        return calls, seconds + sum(share * (b - a) for (a, b), (_, _, share) in self._ahead.items())

    def charged_with_the_rest(self, solution: Solution) -> Solution:
        """``solution`` with everything not yet charged (:meth:`uncharged`): a sweep's last verdict."""
        self._probed, self._ahead = self.uncharged(), {}
        return self.charged(solution)

    def carry(self, uncharged: tuple[int, float]) -> None:
        """Calls and seconds charged to the next verdict (:meth:`charged`): a window before's left uncharged
        (:meth:`uncharged`), a probe's, a search's no verdict took."""
        calls, seconds = self._probed
        self._probed = (calls + uncharged[0], seconds + uncharged[1])

    def _charge(self, solution: Solution | None, sign: int = 1) -> None:
        """The calls and seconds of a probe's ``solution`` added to those not yet charged (``sign`` -1: taken out)."""
        if solution is not None:
            self.carry((sign * solution.solver.solves, sign * solution.solver.time_s))


def _given(solution: Solution | None) -> bool:
    """``solution``'s verdict needs no search: a requirement no design variable enters broken ("infeasible whatever
    the design", before any solve: ``Problem._given``), or a start-up's drive proofs (``Problem.proven``); verdicts
    that ``Problem.solve`` gives as they are, and that no region proof covers (:func:`_covered`)."""
    return solution is not None and solution.diagnosed is not None and solution.diagnosed.proven


def _budget(boxes: int, least: int) -> int:
    """The most boxes of a search near a proof of ``boxes`` boxes: REGION_BUDGET times as many, at least ``least``
    (a region's search: SURE_BOXES; a point's of a run searched point by point, next to its last point's own proof:
    FEW_BOXES), at most MAX_BOXES."""
    return min(max(REGION_BUDGET * boxes, least), MAX_BOXES)


def _holds(outcome: Emptiness | None, budget: int) -> bool:
    """A search made ahead (:meth:`Regions._runs_ahead`) is the one a search within ``budget`` makes: it ended by
    its outcome (proven, or a design met), not by a budget or its growth, within ``budget`` boxes (a search's steps do
    not depend on its budget until it passes it)."""
    return (outcome is not None and (outcome.proven or outcome.reached or outcome.feasible is not None)
            and outcome.boxes <= budget)


def _met(run: tuple[int, int], ahead: dict) -> bool:
    """The kept search of ``run`` (in ``ahead``: :meth:`Regions._runs_ahead`) met a design (for the whole interval or
    at one end): no search of the run proves it, whatever its budget."""
    kept = ahead.get(run)
    return kept is not None and kept[1] is not None and (kept[1].reached or kept[1].feasible is not None)


def _region_problem(points: list[tuple[np.ndarray, ...]]) -> tuple[np.ndarray, ...]:
    """One search over a run's points: the hull of their design boxes, their parameters from least to most."""
    p = np.stack([point[0] for point in points])
    return (p.min(axis=0), np.min([point[1] for point in points], axis=0),
            np.max([point[2] for point in points], axis=0), p.max(axis=0))


def _region_text(posed, a: int, b: int, problem: tuple, outcome) -> str:
    """The proof in words, with the interval it holds for."""
    quantities = posed.formulation.quantities
    p_lo, p_hi = problem[0], problem[3]
    spans = [f"{q.name} {_shown(p_lo[i], q.unit)}-{_shown(p_hi[i], q.unit)}{_unit(q.unit)}"
             for i, q in enumerate(quantities) if p_lo[i] != p_hi[i] and not np.isnan(p_lo[i] + p_hi[i])]
    if not spans:  # (a run of the same values)
        return f"proven infeasible ({b - a} points at the same values, one proof): " + emptied(outcome)
    return (f"proven infeasible for {', '.join(spans)} ({b - a} points, one proof): "
            + emptied(outcome, "and the interval of " + ", ".join(s.split(" ")[0] for s in spans)))


def _apart(posed, broken: set[str], conflicting: Callable[[], bool]) -> bool:
    """A point whose constraints ``broken`` (by name) include a requirement no design variable enters, or two limits
    of one quantity that leave no room between (``conflicting()``, asked only then; ``Posed.conflicting``: they break
    one of their rows at every design): infeasible whatever the design, which its own verdict says, not a proof."""
    return bool(broken & {posed.row_names[i] for i in posed.fixed_rows}
                or broken & posed.paired and conflicting())


def _runs(apart: list[bool], first: int) -> list[tuple[int, int]]:
    """The runs (start, end) of the points from ``first`` on that are not ``apart``."""
    edges = np.flatnonzero(np.diff(np.concatenate([[True], apart, [True]]).astype(int))) + first
    return list(zip(edges[::2].tolist(), edges[1::2].tolist()))


def _moves(values: np.ndarray, first: float) -> bool:
    """A quantity's ``values`` over points are not all ``first`` (NaN, a value the case leaves out, the same as NaN:
    ``interval_proof._same``)."""
    return not np.all(_same(values, first))


def _span(values: np.ndarray, unit: str) -> str:
    """The least to the greatest of ``values`` (SI) in ``unit``; one value where they are all one."""
    low, high = _shown(values.min(), unit), _shown(values.max(), unit)
    return low if low == high else f"{low}-{high}"


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def _shown(value: float, unit: str) -> str:
    return f"{float(from_si(value, unit)):.6g}"


def _covered(problem, case, design: dict[str, float], text: str, seconds: float, spent: SolverInfo | None = None,
             figures: tuple | None = None, conflicting: bool | None = None,
             bounds: tuple[np.ndarray, np.ndarray] | None = None) -> Solution | None:
    """The verdict of a point a proof covers, showing ``design`` (the last point without one: its least relaxation;
    or the point's own failed solve, which ``spent`` its calls and seconds) with every constraint re-evaluated in
    float64 at this point's values (``figures``, if evaluated already: ``verdict.figures_at``) and the case's bounds
    (``bounds``, if read already: its search problem's); None where a requirement no design variable enters is
    broken or two limits of one quantity leave no room between (``Posed.conflicting``; ``conflicting``, if read
    already), or a start-up's drive proofs hold (its own verdict says so). ``case``: None where a static problem's
    figures, conflict and bounds are given (read from a batched sweep's arrays: :class:`SharedBox`)."""
    posed = problem.posed
    if problem.start_up is not None and start_up_proofs(case):
        return None
    figures = figures or figures_at(posed, [case], design)[0]
    if _apart(posed, {c.name for c in figures[0] if not c.feasible},
              lambda: posed.conflicting(case) if conflicting is None else conflicting):
        return None
    solves, time_s = (spent.solves, spent.time_s) if spent is not None else (0, 0.0)
    return infeasible_at(posed, case, design, text, SolverInfo("interval", "proven", 0, time_s + seconds, solves),
                         figures, bounds)
