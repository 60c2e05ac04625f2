"""A start-up sweep's point deeper into a run without designs, tested against its neighbour's reason (issue 26:
"infeasible regions found cheaply ... the full diagnosis runs once per region, not once per point").

A start-up point without a design costs ``solve``'s whole verdict: its first solve from the papers' sizing with its
elastic diagnosis, the least relaxation's retry with a second diagnosis, the interval search's design (which bounds the
static rows only, so it always meets one), 16 sampled designs projected and simulated and the walk from the least
violated: lever_motor_start at 15.8-16.8 kg m^2 4 solves, 344-420 IPOPT iterations, 0.66-0.84 s a point, where a point
with a design takes about 0.02 s; ball_motor_start at 414-525 kg m^2 0.49-1.41 s (docs/start_up.md, "A point beyond one
without a design, tested against its reason"). A start-up has no interval proof, so no point is decided by its
neighbour. Where the point before ended ``not_found`` for a named reason (its least relaxation converged, naming the
constraints it violates: ``Diagnosis.violated``) and this point lies beyond it, on the ray from the run's last feasible
point (:func:`beyond`), ``solve``'s first solve of the point is made (``Problem.refined``, from the papers' sizing,
with its elastic diagnosis) and, where it ends without a design, tested against that reason (:func:`region_verdict`):
where its own least relaxation (converged) violates a constraint the point before's did, the point is ``not_found`` on
that one solve (lever_motor_start from 15.79 kg m^2 on); where its elastic problem stops unconverged and names no
reason, the point is solved once more, from the point before's least relaxation, with its own elastic diagnosis
(:func:`region_test`), and is ``not_found`` on those two starts where that least relaxation violates such a constraint
(ball_motor_start at 477 and 509 kg m^2), its diagnosis the less of the two. Either verdict says that ``solve``'s
other starts were not tried, nor the sweep's. Else (a design, a feasible point, another reason, no converged one) the
point gets ``solve``'s verdict from that first solve on, and the sweep's own starts, the test counted and named among
them where it was solved (a design it found kept where the verdict has none). A point so decided before a later
design in the run is retried from that design and, where that finds none, given ``solve``'s verdict after all
(``clutchopt.optimise.sweep.solve_points``): only a run that ends without a design keeps such verdicts. A resumed
run's first point, and a pool chunk's, has no point before: it gets the full verdict. This is a heuristic where it
decides: a design ``solve``'s other starts (the interval search's, the sampled one) reach at such a point is not looked
for.
"""

from __future__ import annotations

from dataclasses import replace

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.failed_starts import on_ray
from clutchopt.optimise.solution import Solution
from clutchopt.optimise.verdict import SIZING, verdict_from

REGION = "the neighbouring point's least relaxation"  # the start a point tested against its neighbour's reason adds
OWN_REASON = (SIZING,)  # the starts of a point its first solve's own least relaxation decided (:func:`region_verdict`)
DECIDED = (SIZING, REGION)  # the starts of a point decided by its solve from the point before's least relaxation


def beyond(values: dict[str, float], last_feasible: dict[str, float] | None, without: Solution,
           without_values: dict[str, float]) -> bool:
    """Whether a sweep's point (its varied ``values``) is tested against the reason of the point before (``without``,
    at ``without_values``, its verdict without a design): that point ended ``not_found`` for a named reason (its least
    relaxation converged, naming the constraints it violates) and this one lies beyond it on the ray from the run's
    last feasible point (``last_feasible``, its values; t > 1)."""
    reason = without.diagnosed
    if last_feasible is None or without.status != "not_found" or reason is None or not reason.violated \
            or reason.nearest is None:  # (an elastic problem stopped unconverged names no reason)
        return False
    t = on_ray(last_feasible, without_values, values)
    return t is not None and t > 1.0


def region_test(problem, case: Case, without: Solution) -> Solution | None:
    """``case`` solved once from the least relaxation of the point before (``without``), with its own elastic
    diagnosis; None where the start's simulation fails."""
    try:
        return problem.refined(case, without.diagnosed.nearest, diagnosed=True)
    except InputError:  # (its start not simulated from that design)
        return None


def region_verdict(first: Solution, without: Solution, tested: Solution | None = None) -> Solution | None:
    """The verdict of a point from its own first solve (``first``: ``Problem.solve``'s, from the papers' sizing, with
    its elastic diagnosis), without a design, and the point before's verdict (``without``): ``not_found`` on that solve
    alone where its own least relaxation (converged) violates a constraint the point before's did (lever_motor_start
    from 15.79 kg m^2 on: lining_pressure and temperature_rise); with ``tested`` (:func:`region_test`, its solve from
    the point before's least relaxation, without a design), ``not_found`` on the least relaxation of the two where
    ``tested``'s own violates such a constraint (ball_motor_start at 477 and 509 kg m^2, where the first solve's
    elastic problem stops unconverged and names none); either saying that ``solve``'s other starts were not tried, nor
    the sweep's; else None (the point's full verdict follows: a design found, a feasible point, another reason or
    none)."""
    deciding = first if tested is None else tested
    own = deciding.diagnosed
    shared = sorted(set(own.violated) & set(without.diagnosed.violated)) if own is not None else []
    if not shared or first.diagnosed is None or first.diagnosed.proven or own.status != "infeasible":
        return None
    tried = [(SIZING, first)] + ([(REGION, tested)] if tested is not None else [])
    verdict = verdict_from(tried, [])
    if verdict.status != "not_found":  # (the first solve's elastic check met a feasible point: solve's verdict)
        return None
    how = ("its least relaxation violates what the point before's did" if tested is None else
           "its second start the least relaxation of the point before, whose reason its own shares")
    note = (f"; {how} ({', '.join(shared)}): solve's other starts of this point alone were not tried, nor the sweep's "
            "(the neighbour's design, the continuation)")
    verdict.solver = verdict.solver.summed([s.solver for _, s in tried])
    return replace(verdict, diagnosis=verdict.diagnosis + note)


def in_a_region(solution: Solution) -> bool:
    """Whether ``solution`` is a point's verdict :func:`region_verdict` gave: no ``solve`` of the point alone is
    behind it (a sweep's start-up point without a design that ``solve`` gave its verdict ends with the sampled start,
    ``Problem.solve``: never on the papers' sizing alone)."""
    return solution.starts in (OWN_REASON, DECIDED)
