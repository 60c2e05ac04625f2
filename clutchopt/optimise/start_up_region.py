"""A start-up sweep's point deeper into a run without designs, tested against its neighbour's reason first (issue 26,
"infeasible regions found cheaply").

A start-up point without a design costs ``solve``'s whole verdict: its cold start from the papers' sizing and the
elastic diagnosis, the least relaxation's retry and a second diagnosis, the interval search's design (which bounds the
static rows only, so it always meets one), the 16 sampled designs projected and simulated and the walk from the least
violated (lever_motor_start at 15.8-16.8 kg m^2: 4 solves, 340-420 IPOPT iterations, 0.5-0.7 s a point; a design
there about 20 ms). A start-up has no interval proof, so no point is decided by its neighbour: where the point before
ended ``not_found`` for a named reason (its least relaxation converged, violating the constraints it names,
``Diagnosis.violated``) and this point lies beyond it, on the ray from the run's last feasible point, this point is
solved once from the point before's least relaxation, with its own elastic diagnosis (:func:`region_test`). Where
that finds a design, or its least relaxation names other constraints (or a feasible point, or none converged), the
point gets its full verdict as before, this solve counted with it (a design it found kept where the verdict has
none). Where its own least relaxation violates the same constraints, the point is ``not_found`` on that solve
(:func:`region_verdict`), its diagnosis its own least relaxation, saying that ``solve``'s starts were not tried. A
point so decided between the run's last design and a later one is retried from the later design and, where that
finds none, given ``solve``'s verdict after all (``clutchopt.optimise.sweep.solve_points``): only a run that ends
without a design keeps such verdicts. A resumed run's first point has no neighbour: it gets the full verdict.
"""

from __future__ import annotations

from dataclasses import replace

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.failed_starts import on_ray
from clutchopt.optimise.solution import Solution
from clutchopt.optimise.verdict import verdict_from

REGION = "the neighbouring point's least relaxation"  # the one start of a point tested against its neighbour's reason


def region_test(problem, case: Case, values: dict[str, float], last_feasible: dict[str, float] | None,
                without: Solution | None, without_values: dict[str, float] | None) -> Solution | None:
    """Point ``case`` (its varied ``values``) solved once from the least relaxation of the point before (``without``,
    its verdict without a design, at ``without_values``), with its own elastic diagnosis, where that point ended
    ``not_found`` for a named reason and this one lies beyond it on the ray from the run's last feasible point
    (``last_feasible``, its values; t > 1); else None (not tested: its full verdict follows). None too where the
    start's simulation fails."""
    if without is None or last_feasible is None or without.status != "not_found":
        return None
    reason = without.diagnosed
    if reason is None or not reason.violated or reason.nearest is None:  # (an elastic problem stopped unconverged
        return None  # names no reason)
    t = on_ray(last_feasible, without_values, values)
    if t is None or not t > 1.0:
        return None
    try:
        return problem.refined(case, reason.nearest, diagnosed=True)
    except InputError:  # (its start not simulated from that design)
        return None


def region_verdict(tested: Solution, without: Solution) -> Solution | None:
    """The verdict of a point :func:`region_test` solved (``tested``): ``not_found`` where it ended without a design
    and its own least relaxation (converged) violates the constraints the point before's (``without``) did, its diagnosis its own saying so; a proof (a drive's: no solve) as it is; else None
    (the point's full verdict follows: ``tested`` found a design, a feasible point, or another reason)."""
    own = tested.diagnosed
    if own is not None and own.proven:
        return tested
    if own is None or own.status != "infeasible" or set(own.violated) != set(without.diagnosed.violated):
        return None
    verdict = verdict_from([(REGION, tested)], [])
    note = ("; solved from the least relaxation of the point before, which violates the same constraints, as its "
            "only start: the starts solve of this point alone tries were not tried")
    return replace(verdict, diagnosis=verdict.diagnosis + note)


def in_a_region(solution: Solution) -> bool:
    """Whether ``solution`` is a point's verdict :func:`region_verdict` gave (its one start the point before's least
    relaxation): no ``solve`` of the point alone is behind it."""
    return solution.starts == (REGION,)
