"""A start-up sweep's point solved from the optimum of the point before (issue 26 item 2).

``Problem.solve`` starts a start-up design cold: the papers' sizing at the point (a static solve), a simulation of
that design for the collocation's states (the start guess), IPOPT from there on the first mesh, then the accuracy
loop (mesh adapted to the simulated start, defect corrections), each solve checked by the independent simulator.
Along a sweep the point before gives a start as good and cheaper: its design, scales, multipliers and collocation
states, on the mesh its loop ended on (adapted to a start next to this one's), and the limits its defect correction
moved, as shares of its case's (:mod:`clutchopt.optimise.start_up_shift`): the first solve then needs no
adaptation nor correction where the point before's did (wedge_motor_start over driven_inertia: 1.65 solves and
simulated starts a point before, 1.0 now). Where the two points before ended on the same mesh and this point lies on
the line through theirs, the moved limits are carried on along that line (:func:`predicted_shift`, a secant): where
the temperature rise binds, the correction moves by some 1e-5 a point, which the carried share misses by more than
the loop accepts, the secant's by the second difference only (a correction a point saved on a dense sweep; an
elastic link's limits, which its loop never centres, are carried as they are). The loop
still decides on this point's own simulated start, so the design is ``solve``'s within the accuracy contract
(docs/start_up.md: each is the simulator's optimum to a quarter of the tolerance on the objective). The sizing and
the start guess's simulation are saved; every solve is still checked by the simulator. A point this does not bring
to an optimum is solved cold, as ``solve`` solves it (its verdict is ``solve``'s). A point the drive's proofs cover
(:mod:`clutchopt.optimise.proofs`) is not started: ``solve`` gives its verdict without a solve.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.failed_starts import case_numbers, on_ray
from clutchopt.optimise.proofs import start_up_proofs
from clutchopt.optimise.solution import Solution
from clutchopt.optimise.start_up_check import limit_gaps

FURTHEST = 1.5  # the longest step ahead, in steps of the two points before, the secant is carried over


@dataclass(frozen=True)
class Along:
    """A sweep point's limits as its accuracy loop ended: the point's case values (numbers), its ``limit_shift``, the
    mesh its last solve was on, and the point before's (``before``; its own ``before`` dropped)."""

    values: dict[str, float]
    shift: dict[str, float]
    mesh: np.ndarray
    before: "Along | None" = None


def solved_along(problem, case: Case, previous: Solution | None) -> Solution | None:
    """The start-up design at ``case`` from ``previous`` (the optimum of the point before, of this problem), or
    None where there is none to start from or it does not end optimal."""
    block = problem.posed.start_up
    if start_up_proofs(case):  # no design to start: ``Problem.solve`` gives the proof without a solve
        return None
    if previous is None or previous.status != "optimal" or previous.internal is None \
            or len(previous.internal) != block.size:  # none, or of another problem (its intervals doubled)
        return None
    try:
        numbers = _numbers(case)
        solution = problem.refined(case, warm=previous, mesh=previous.mesh[0], shift=predicted_shift(previous, numbers),
                                   diagnosed=False, cold=False)  # solve's own cold start and diagnosis follow
    except InputError:  # its first simulation failed from this start
        return None
    if solution.status != "optimal":
        return None
    if block.s.elastic:  # its loop moves a limit only where the simulated start misses it, never centres one: the
        return solution  # NLP is another model than the simulated dynamics, not a mesh off them (the share is kept)
    before = previous.along
    solution.along = Along(numbers, centred_shift(solution, case), solution.mesh[0],
                           replace(before, before=None) if before is not None else None)
    return solution


def predicted_shift(previous: Solution, numbers: dict[str, float]) -> dict[str, float]:
    """The limits the point whose case's values are ``numbers`` (:func:`_numbers`) starts with, as shares of its
    case's: the point before's, centred
    (:func:`centred_shift`), each moved on by the secant through the two points before where both ended on the same
    mesh (a mesh adaptation moves the collocation's figures, hence the corrections, by a step of its own) and
    ``case`` lies on the line through their values, at most FURTHEST steps on; the point before's ``limit_shift``
    where it was not solved along the sweep."""
    last = previous.along
    if last is None:
        return previous.limit_shift
    if last.before is None or not np.array_equal(last.mesh, last.before.mesh):
        return last.shift
    step = _step(last.before.values, last.values, numbers)
    if step is None:
        return last.shift
    return {name: share + step * (share - last.before.shift[name]) if name in last.before.shift else share
            for name, share in last.shift.items()}


def centred_shift(solution: Solution, case: Case) -> dict[str, float]:
    """``solution``'s ``limit_shift`` with each limit its design binds at (the simulated check active) moved to where
    the simulated figure meets the case's limit: the NLP's limit less the simulated gap, what the defect correction
    would move it to (:func:`~clutchopt.optimise.start_up_check.corrected_case`). The shares a point ends with are
    those of the limits its last solve saw, off that by up to what the loop accepts; the secant is taken through
    the centred ones, not through its own predictions."""
    shares = dict(solution.limit_shift)
    for check, name, gap in limit_gaps(solution):
        if name in shares and check.active:
            shares[name] -= gap / case.values[name]
    return shares


def _step(first: dict[str, float], second: dict[str, float], third: dict[str, float]) -> float | None:
    """t where ``third`` = ``second`` + t (``second`` - ``first``) in every value (to ON_RAY of each step:
    ``failed_starts.on_ray`` from ``second`` towards ``first``, t its negative), 0 < t <= FURTHEST; None where the
    three points are not so placed."""
    back = on_ray(second, first, third)
    return -back if back is not None and 0.0 < -back <= FURTHEST else None


def _numbers(case: Case) -> dict[str, float]:
    return {name: value for name, value in case_numbers(case).items() if math.isfinite(value)}
