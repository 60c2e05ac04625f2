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
with its elastic diagnosis) and, where it ends without a design, tested against that reason (:func:`region_tested`):
where its own least relaxation (converged) violates a constraint the point before's did, the point is ``not_found`` on
that one solve (lever_motor_start from 15.79 kg m^2 on). Where its elastic problem stops unconverged and names no
reason, the point is solved once more from the point before's least relaxation, then from its own least relaxation's
design (``solve``'s own second start), each with its elastic diagnosis, until one's least relaxation violates such a
constraint (ball_motor_start at 477 and 509 kg m^2 the first of them, at 446 the second): ``not_found`` on the starts
tried (:func:`region_verdict`), its diagnosis the least relaxation of them. Either verdict says that ``solve``'s other
starts were not tried, nor the sweep's. Else (a design, a feasible point, another reason, no converged one) the point
gets ``solve``'s verdict from that first solve on, and the sweep's own starts, the tests' solves counted and named
among them (a design one found kept where the verdict has none; ``solve``'s second start, where solved, is solved by
``solve`` again). A point so decided before a later design in the run is given ``solve``'s verdict after all and,
where that has no design, retried from the later design (``clutchopt.optimise.sweep.alone_after_all``: ``solve``'s
verdict first, that start only where it has none): only a run that ends without a design keeps such verdicts (a pool
chunk's points are a run of their own). A resumed run's first point, and a pool chunk's, has no point before: it gets
the full verdict. This is a heuristic where it decides: a design ``solve``'s other starts (the interval search's, the
sampled one) reach at such a point is not looked for.
"""

from __future__ import annotations

from dataclasses import replace

from clutchopt.cases import Case
from clutchopt.optimise.failed_starts import on_ray
from clutchopt.optimise.solution import Solution
from clutchopt.optimise.verdict import LEAST, SIZING, retried, verdict_from
from clutchopt.records import DESIGN_STATUSES

REGION = "the neighbouring point's least relaxation"  # the start a point tested against its neighbour's reason adds
TESTS = (SIZING, REGION, LEAST)  # a point's starts in the order its test tries them (:func:`region_tested`); a point
# it decides names the first and those of the others it solved (a start whose simulation failed is not named)


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


def region_tested(problem, case: Case, first: Solution, without: Solution) -> tuple[Solution | None, list]:
    """The verdict :func:`region_verdict` gives ``case`` from its first solve (``first``: ``Problem.solve``'s, from the
    papers' sizing, with its elastic diagnosis, without a design) and the point before's verdict (``without``), with the
    solves it made beyond ``first`` (each its label and solve): none where ``first``'s own least relaxation decides;
    else the point solved from the point before's least relaxation (REGION), then from ``first``'s least relaxation's
    design (LEAST), each diagnosed, until one decides or reaches a design. None (no verdict): the point's full verdict
    follows."""
    made: list[tuple[str, Solution]] = []
    decided = region_verdict(first, without)
    for label, start in zip(TESTS[1:], (without.diagnosed.nearest, first.diagnosed.nearest)):
        if decided is not None or any(s.status in DESIGN_STATUSES for _, s in made):
            break
        solved = retried(problem, case, start, diagnosed=True) if start is not None else None  # (None: no such
        # start, or its start not simulated from that design)
        if solved is not None:
            made.append((label, solved))
            decided = region_verdict(first, without, made)
    return decided, made


def region_verdict(first: Solution, without: Solution, made: list | tuple = ()) -> Solution | None:
    """The verdict of a point from its own first solve (``first``), without a design, the point before's verdict
    (``without``) and the solves :func:`region_tested` made since (``made``: each its label and solve, none with a
    design): ``not_found`` on those starts where the least relaxation of the last (``first``'s where none was made)
    converged and violates a constraint the point before's did (lever_motor_start from 15.79 kg m^2 on: lining_pressure
    and temperature_rise; ball_motor_start: contact_stress, with start_time over its limit at some points, binding at
    others), its diagnosis the least relaxation of them all, saying that ``solve``'s other starts were not tried, nor
    the sweep's; else None (the point's full verdict follows: a design found, a feasible point, another reason or
    none)."""
    label, deciding = made[-1] if made else (SIZING, first)
    own = deciding.diagnosed
    shared = sorted(set(own.violated) & set(without.diagnosed.violated)) if own is not None else []
    if not shared or first.diagnosed is None or first.diagnosed.proven or own.status != "infeasible":
        return None
    tried = [(SIZING, first), *made]
    verdict = verdict_from(tried, [])
    if verdict.status != "not_found":  # (the first solve's elastic check met a feasible point: solve's verdict)
        return None
    note = (f"; the least relaxation from {label} violates what the point before's did ({', '.join(shared)}): solve's "
            "other starts of this point alone were not tried, nor the sweep's (the neighbour's design, the "
            "continuation)")
    verdict.solver = verdict.solver.summed([s.solver for _, s in tried])
    return replace(verdict, diagnosis=verdict.diagnosis + note, region_decided=True)


def in_a_region(solution: Solution) -> bool:
    """Whether ``solution`` is a point's verdict :func:`region_verdict` gave (``Solution.region_decided``, not read
    off its starts: a start whose simulation failed is not among them, and another verdict's starts can begin as the
    test's do): no ``solve`` of the point alone is behind it."""
    return solution.region_decided
