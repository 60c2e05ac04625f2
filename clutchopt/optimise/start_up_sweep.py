"""A start-up sweep's point solved from the optimum of the point before (issue 26 item 2).

``Problem.solve`` starts a start-up design cold: the papers' sizing at the point (a static solve), a simulation of
that design for the collocation's states (the start guess), IPOPT from there on the first mesh, then the accuracy
loop (mesh adapted to the simulated start, defect corrections), each solve checked by the independent simulator.
Along a sweep the point before gives a start as good and cheaper: its design, scales, multipliers and collocation
states, on the mesh its loop ended on (adapted to a start next to this one's), and the limits its defect correction
moved, as shares of its case's (:mod:`clutchopt.optimise.start_up_shift`): the first solve then needs no
adaptation nor correction where the point before's did (wedge_motor_start over driven_inertia: 1.65 solves and
simulated starts a point before, 1.0 now). The loop still decides on this point's own simulated start, so the design
is ``solve``'s within the accuracy contract (docs/start_up.md: each is the simulator's optimum to a quarter of the
tolerance on the objective). The sizing and the start guess's simulation are saved; every solve is still checked by
the simulator. A point this does not bring to an optimum is solved cold, as ``solve`` solves it (its verdict is
``solve``'s). A point the drive's proofs cover (:mod:`clutchopt.optimise.proofs`) is not started: ``solve`` gives
its verdict without a solve.
"""

from __future__ import annotations

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.proofs import start_up_proofs
from clutchopt.optimise.solution import Solution


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
        solution = problem.refined(case, warm=previous, mesh=previous.mesh[0], shift=previous.limit_shift,
                                   diagnosed=False, cold=False)  # solve's own cold start and diagnosis follow
    except InputError:  # its first simulation failed from this start
        return None
    return solution if solution.status == "optimal" else None
