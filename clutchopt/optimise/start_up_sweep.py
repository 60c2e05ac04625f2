"""A start-up sweep's point solved from the optimum of the point before (issue 26 item 2).

``Problem.solve`` starts a start-up design cold: the papers' sizing at the point (a static solve), a simulation of
that design for the collocation's states (the start guess), IPOPT from there on the first mesh, then the accuracy
loop (mesh adapted to the simulated start, defect corrections), each solve checked by the independent simulator.
Along a sweep the point before gives a start as good and cheaper: its design, scales, multipliers and collocation
states, on the first mesh, the mesh a cold solve starts on (not the point before's adapted mesh: the loop then takes
the same steps as from cold, so the design is ``solve``'s to the solver's tolerance whatever the points before it).
The sizing and the start guess's simulation are saved; every solve is still checked by the simulator. A point this
does not bring to an optimum is solved cold, as ``solve`` solves it (its verdict is ``solve``'s).
"""

from __future__ import annotations

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.solution import Solution


def solved_along(problem, case: Case, previous: Solution | None) -> Solution | None:
    """The start-up design at ``case`` from ``previous`` (the optimum of the point before, of this problem), or
    None where there is none to start from or it does not end optimal."""
    block = problem.posed.start_up
    if previous is None or previous.status != "optimal" or previous.internal is None \
            or len(previous.internal) != block.size:  # none, or of another problem (its intervals doubled)
        return None
    try:
        solution = problem.refined(case, warm=previous, mesh=block.initial_mesh())
    except InputError:  # its first simulation failed from this start
        return None
    return solution if solution.status == "optimal" else None
