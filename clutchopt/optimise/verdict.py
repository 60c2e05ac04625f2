"""An infeasible verdict that is true (issue: "the same case, two answers").

A solve that ends without a design has shown nothing yet: IPOPT's restoration may have stalled from a poor start,
and the elastic relaxation that names the conflict is a local minimum from that start. Before a case is reported
without a design it is solved again from the starts that can reach one: the case's own (for a start-up, the
papers' sizing at that point), the least relaxation's design, a feasible neighbour's (a sweep's point before; a
sweep also follows the design from its last feasible point by continuation and re-solves from the next feasible
point: ``clutchopt.optimise.sweep.solve_points``). The first that reaches a design is the answer. Otherwise the
verdict says how sure it is:

- ``infeasible``: proven. A requirement no design variable enters is broken (the diagnosis's "whatever the
  design"), or the drive cannot do what the start-up asks of any coupling (:mod:`clutchopt.optimise.proofs`, given
  by ``Problem.proven`` before any solve), or
  interval branch and bound shows that no design within the bounds meets the formulation's constraints
  (:mod:`clutchopt.optimise.interval_proof`; should it meet a design of the relaxation instead, the solve is
  retried from there);
- ``not_found``: no feasible design found from the starts it names (``Solution.starts``), with the least
  relaxation found from the first two, and whether they agree (the others are not diagnosed again: a sweep's
  stretch without designs costs a solve a start, not a diagnosis each): a strong hint, not a proof;
- ``solver_failed``: a feasible point exists (the elastic check found one), yet no start reached an optimum.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.model import Output, namespace
from clutchopt.optimise.interval_proof import SURE_BOXES, empty_design_space
from clutchopt.optimise.solution import Solution, SolverInfo
from clutchopt.records import DESIGN_STATUSES
from clutchopt.optimise.verify import (ConstraintCheck, check_design, column_checks, column_figures,
                                       column_outputs, evaluate_objective, evaluate_outputs)


NEIGHBOUR = "the neighbouring point's design"  # a start a sweep adds: the last feasible point's design
NEXT = "the next feasible point's design"  # a start a sweep adds: a point without a design retried from the design of
# the next point that has one (``sweep.solve_points``)
GIVEN = "the start given"  # a solve's first start where its caller gives one (a design or a warm solution)
SIZING = "the papers' sizing"  # a start-up solve's own first start
CASE = "the case's own start"  # a static solve's own first start
LEAST = "the least relaxation's design"  # a retry's start: the design of the first solve's least relaxation
OWN = "the case's own starts (solve alone)"  # every start ``solve`` of the case alone tries, where a start-up from a
# start or a warm solution given ends without a verified design (``problem.verified_alone``)


def shown(problem, case: Case, first: Solution, started: bool, neighbour: dict[str, float] | None) -> Solution:
    """``first`` (a solve without a design) retried from the starts that can reach one; the first design found, or
    the verdict on all of them."""
    own = SIZING if problem.start_up is not None else CASE  # the solve's own first start
    first_label = GIVEN if started else own
    tried = [(first_label, first)]
    proofs: list[str] = []  # (a drive that starts no coupling as asked is proven before any solve: Problem.proven)
    searched = _Searched(problem.posed, case)  # (its seconds the verdict's: a sweep takes the runs' it searched along)
    early = searched(SURE_BOXES) if _relaxed_apart(problem, first) else None
    # (before the retries, the boxes every search evaluates: proven, no start reaches a design, and none is tried;
    # where a retry finds one, a search that cannot prove has cost these, not up to MAX_BOXES; where none does, the
    # search without a budget goes on from where this one stood)
    if early is not None and early.proven:
        proofs = [emptied(early)]
    if not (first.diagnosed and first.diagnosed.proven) and not proofs:
        starts = [(own, None)] if started else []
        if first.diagnosed and first.diagnosed.nearest:
            starts.append((LEAST, first.diagnosed.nearest))
        if neighbour is not None and not problem.failed_starts.lost_beyond(case, neighbour):  # (its path lost
            # nearer: clutchopt.optimise.failed_starts)
            starts.append((NEIGHBOUR, neighbour))
        for label, start in starts:  # the first retry diagnosed too: a least relaxation seen from two starts
            retry = retried(problem, case, start, diagnosed=len(tried) == 1)
            if retry is None:
                continue
            tried.append((label, retry))
            if retry.status in DESIGN_STATUSES:
                return _spent(retry, tried, searched.seconds)
    if first.diagnosed and first.diagnosed.proven:
        return _spent(first, tried, searched.seconds)
    if not proofs:
        settled = early is not None and early.feasible is not None  # (a design met: the search's outcome whatever
        # its budget; else the search without one, as before the retries)
        emptiness = early if settled else searched(resume=early)
        if emptiness is not None and emptiness.feasible is not None:  # a design of the relaxation: solve from it
            retry = retried(problem, case, dict(zip(problem.posed.names, emptiness.feasible)))
            if retry is not None:
                tried.append(("a design the interval search met", retry))
                if retry.status in DESIGN_STATUSES:
                    return _spent(retry, tried, searched.seconds)
        elif emptiness is not None and emptiness.proven:
            proofs = [emptied(emptiness)]
    return _spent(verdict_from(tried, proofs), tried, searched.seconds)


def _relaxed_apart(problem, first: Solution) -> bool:
    """The interval search goes before the retries: a static problem whose first solve's elastic relaxation found
    the constraints apart (a least total relaxation above zero, not a feasible point IPOPT missed). Such a solve
    is most often right, and where the search proves it, the retries from the other starts (each a solve, the
    first with its own elastic diagnosis: 30-50 ms on the lever and the cable where the proof takes 1-2 ms) cannot
    reach a design. It evaluates SURE_BOXES at most (the boxes every search evaluates; the ball near its
    contact-stress limit is proven in 900-1,400): where it does not prove, the retries follow, then its outcome where
    it met a design of the relaxation, else the search without that budget, which goes on from where the budget
    stopped it (``interval_proof.Emptiness.paused``: its outcome the same, its first boxes not evaluated again)."""
    diagnosed = first.diagnosed
    return (problem.start_up is None and diagnosed is not None and not diagnosed.proven
            and diagnosed.status == "infeasible" and diagnosed.least > 0)


def emptied(emptiness, over: str = "") -> str:
    """The interval proof in words: the constraints that emptied the boxes, most boxes first (``over``: what the
    boxes spanned beyond the design space, e.g. a sweep's interval of a quantity)."""
    names = sorted(emptiness.decisive, key=emptiness.decisive.get, reverse=True)
    return (f"no design within the bounds meets {', '.join(names)} together (interval branch and bound over "
            f"{emptiness.boxes} boxes of the design space{' ' + over if over else ''})")


def retried(problem, case: Case, start: dict[str, float] | None, diagnosed: bool = False) -> Solution | None:
    """``problem`` solved again at ``case`` from ``start`` (undiagnosed unless ``diagnosed``); None where a
    start-up's first simulation fails from that start."""
    try:
        return problem.refined(case, start, diagnosed=diagnosed)
    except InputError:  # a start-up whose first simulation fails from this start
        return None


def verdict_from(tried: list[tuple[str, Solution]], proofs: list[str]) -> Solution:
    """The verdict on the starts ``tried`` (each its label and solve, none with a design; the first the point's
    own) and the interval ``proofs`` found: ``infeasible`` with a proof, ``solver_failed`` where an elastic check met
    a feasible point, else ``not_found`` with the least relaxation the diagnosed starts found."""
    first = tried[0][1]
    diagnosed = [(label, s) for label, s in tried if s.diagnosed is not None]
    starts = tuple(label for label, _ in tried)
    if not diagnosed:  # the integer search's verdict: no integer near the feasible relaxation
        least, text = first, first.diagnosis or ""
    else:
        _, least = min(diagnosed, key=lambda item: item[1].diagnosed.least)
        text = "the least relaxation found " + least.diagnosed.text.removeprefix("infeasible: ") + _confirmed(diagnosed)
    if proofs:  # with the integer search's verdict, which it explains; a local least relaxation beside it would
        # name constraints the proof does not need
        return replace(least, status="infeasible", starts=starts, diagnosis="proven infeasible: " + "; ".join(proofs)
                       + ("" if diagnosed or not text else f" ({text})"))
    if any(s.diagnosed.status == "solver_failed" for _, s in diagnosed):
        return replace(least, status="solver_failed", starts=starts,
                       diagnosis="a feasible point exists (elastic check), yet no start reached an optimum")
    return replace(least, status="not_found", starts=starts,
                   diagnosis=f"no feasible design found (not proven infeasible): {text}")


def _confirmed(diagnosed: list[tuple[str, Solution]]) -> str:
    """Whether the elastic relaxations from the starts diagnosed agree on the least violation."""
    leasts = [s.diagnosed.least for _, s in diagnosed]
    if len(leasts) < 2:
        return ""
    if max(leasts) - min(leasts) <= 1e-6 * max(1.0, min(leasts)):
        return f" (the same from {len(leasts)} starts)"
    return f" (the least of {len(leasts)} starts' relaxations: {', '.join(f'{v:.3g}' for v in leasts)})"


def one_more_start(verdict: Solution, retry: Solution | None, label: str) -> Solution:
    """``verdict`` (a solve without a design) after one more start, ``label`` (``retry``: its solve, None where its
    first simulation failed): the retry where it reaches a design, else ``verdict`` with ``label`` named among the
    starts tried where it was solved (a start that could not be simulated is not one tried, as the region test
    leaves it out: ``start_up_region``); the solver calls of both summed."""
    if retry is None:
        return verdict
    if retry.status in DESIGN_STATUSES:
        retry.solver = retry.solver.summed([verdict.solver, retry.solver])
        return retry
    return replace(verdict, starts=verdict.starts + (label,), solver=verdict.solver.summed([verdict.solver,
                                                                                             retry.solver]))


class _Searched:
    """The interval searches of a verdict (:func:`empty_design_space` of ``case``; a ``budget`` or none), their
    seconds summed: the verdict's own (a sweep's region proofs take from them the share of the runs a search proved
    along with it: ``region_proof.Regions._took``; uncounted, that share had made a point's seconds negative, 58 of
    the lever's 180 in design mode over inertia and friction coefficient: review 20)."""

    def __init__(self, posed, case: Case):
        self.posed, self.case, self.seconds = posed, case, 0.0

    def __call__(self, budget: int | None = None, resume=None):
        began = time.perf_counter()
        try:
            return empty_design_space(self.posed, self.case, budget, resume)
        finally:
            self.seconds += time.perf_counter() - began


def _spent(solution: Solution, tried: list[tuple[str, Solution]], searched: float = 0.0) -> Solution:
    """``solution`` with the solver calls of every start tried summed, and ``searched`` seconds more (its interval
    searches')."""
    solver = solution.solver.summed(s.solver for _, s in tried)
    solution.solver = replace(solver, time_s=solver.time_s + searched)
    return solution


def infeasible_at(posed, case: Case, design: dict[str, float], diagnosis: str, solver: SolverInfo,
                  figures: tuple | None = None, bounds: tuple[np.ndarray, np.ndarray] | None = None) -> Solution:
    """A proven ``infeasible`` verdict at ``case`` that shows ``design`` (a start-up the drive makes impossible: the
    papers' sizing, ``Problem.proven``; a sweep's point a proof covers: the design of the point before,
    ``region_proof``), every constraint, the objective and the outputs re-evaluated in float64 at the case's values
    (``figures``: evaluated already, :func:`figures_at`), the bounds the case's (``bounds``: lower and upper, SI,
    read already from ``posed.bounds_and_start``)."""
    f = posed.formulation
    checks, objective, outputs = figures or figures_at(posed, [case], design)[0]
    lower, upper = bounds or posed.bounds_and_start(case, None)[:2]
    return Solution(f.coupling, f.mode, posed.objective.name, posed.objective.unit, "infeasible", objective, design,
                    outputs, checks, solver, diagnosis,
                    bounds=posed.named_bounds(lower, upper),
                    design_units={v.name: v.unit for v in f.variables})


def figures_at(posed, cases: list[Case], design: dict[str, float]
               ) -> list[tuple[list[ConstraintCheck], float, dict[str, Output]]]:
    """The float64 figures of ``design`` at each of ``cases``: its constraint checks, objective and outputs, by the
    formulation's own equations; for several cases of a static problem evaluated once over arrays of their values (a
    column each, as ``batch_window.Checked`` checks batched points; the same arithmetic, the same bits: a run of
    points a region proof covers shares one design), else by ``verify`` point by point (a start-up's constraints are
    arrays over its path already)."""
    f, count = posed.formulation, len(cases)
    if count == 1 or posed.start_up is not None:
        return [(check_design(f, design, params), evaluate_objective(f, posed.objective.name, design, params),
                 evaluate_outputs(f, design, params)) for params in map(posed.params, cases)]
    return figures_over(posed, posed.params_of(cases), count, design)


def figures_over(posed, p, count: int, design: dict[str, float]
                 ) -> list[tuple[list[ConstraintCheck], float, dict[str, Output]]]:
    """:func:`figures_at` of a static problem at ``count`` (more than one) points whose values ``p`` holds, an array
    over them by name (``Posed.params_of``; a batched sweep's points, read from its arrays:
    ``region_proof.SharedBox``)."""
    f = posed.formulation
    x = namespace({name: float(value) for name, value in design.items()})
    constraints, table, objective = column_figures(f, posed.objective, x, p, count)
    outputs = column_outputs(f, x, p, count)
    names, declared = list(outputs), [out for _, out in outputs.values()]
    points = zip(*(values.tolist() for values, _ in outputs.values()))  # (each point's outputs as floats)
    return [(checks, value, dict(zip(names, [Output(v, out.unit, out.description) for v, out in zip(at, declared)])))
            for checks, value, at in zip(column_checks(constraints, table), objective.tolist(), points)]
