"""A start-up sweep's point solved from the optimum of the point before (issue 26 item 2).

``Problem.solve`` starts a start-up design cold: the papers' sizing at the point (a static solve), a simulation of that
design for the collocation's states (the start guess), IPOPT from there on the first mesh, then the accuracy loop (mesh
adapted to the simulated start, defect corrections), each solve checked by the independent simulator. Along a sweep the
point before gives a start as good and cheaper: its design, scales, multipliers and collocation states, on the mesh its
loop ended on (adapted to a start next to this one's), and the limits its defect correction moved, as shares of its
case's (:mod:`clutchopt.optimise.start_up_shift`): the first solve then needs no adaptation nor correction where the
point before's did (wedge_motor_start over driven_inertia: 1.65 solves and simulated starts a point before, 1.0 now).
Where the two points before ended on the same mesh and this point lies on the line through theirs, the moved limits are
carried on along that line (:func:`predicted_shift`, a secant): where the temperature rise binds, the correction moves
by some 1e-5 a point, which the carried share misses by more than the loop accepts, the secant's by the second
difference only (a correction a point saved on a dense sweep; an elastic link's limits, which its loop never centres,
are carried as they are). The loop still decides on this point's own simulated start, so the design is ``solve``'s
within the accuracy contract (docs/start_up.md: each is the simulator's optimum to a quarter of the tolerance on the
objective). A limit its loop left at the case's is moved only where the correction would move it (:func:`held_limits`),
a point whose error the secant puts beyond the tolerance starts on the adapted mesh (:func:`first_mesh`), and an integer
choice the papers' sizing finds infeasible at the point is not solved where the sizing's rows are all the start-up
problem's (:func:`sized_out`): the corrections, adaptations and integer attempts the loop would solve only to land where
it would have. The sizing and the start guess's simulation are saved; every solve is still checked by the simulator. A
point this does not bring to an optimum is solved cold, as ``solve`` solves it (its verdict is ``solve``'s), and so is
one its loop brings to a design a row of the collocation holds (:func:`solved_alone_where_held`). A point the
drive's proofs cover (:mod:`clutchopt.optimise.proofs`) is not started: ``solve`` gives its verdict without a solve.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.failed_starts import case_numbers, on_ray
from clutchopt.optimise.integers import INFEASIBLE
from clutchopt.optimise.proofs import start_up_proofs
from clutchopt.optimise.solution import Solution
from clutchopt.optimise.start_up_compiled import compiled_when_ready
from clutchopt.optimise.start_up_check import CENTRE, limit_gaps, objective_error

FURTHEST = 1.5  # the longest step ahead, in steps of the two points before, the secant is carried over


@dataclass(frozen=True)
class Along:
    """A sweep point's limits as its accuracy loop ended: the point's case values (numbers), its ``limit_shift``, the
    mesh its last solve was on, and the point before's (``before``; its own ``before`` dropped)."""

    values: dict[str, float]
    shift: dict[str, float]
    mesh: np.ndarray
    before: "Along | None" = None
    error: float = 0.0  # the collocation's error of its last solve (its start time against the simulated one)
    held: dict[str, float] = field(default_factory=dict)  # the active limits its loop never moved: the objective's
    # error from each (:func:`held_limits`)


def solved_along(problem, case: Case, previous: Solution | None) -> Solution | None:
    """The start-up design at ``case`` from ``previous`` (the optimum of the point before, of this problem): its
    solve, which the caller keeps where it ends optimal (else its solver calls are counted with the point's cold
    solve); None where there is none to start from (nothing solved)."""
    compiled_when_ready(problem.posed, previous)  # (its NLP's functions compiled once built: the same numbers)
    solution = started_warm(problem, case, previous)  # (where it fails, solve's own cold start and diagnosis follow)
    if solution is None or solution.status != "optimal":
        return solution
    sized = solution.sized
    solution = (solved_alone_where_held(problem, case, solution, sized)
                or as_solve_would(problem, case, solution, sized))
    solution.sized = sized
    if problem.posed.start_up.s.elastic:  # its loop moves a limit only where the simulated start misses it, never
        return solution  # centres one: the NLP is another model than the simulated dynamics, not a mesh off them (the
        # share is kept)
    before = previous.along
    solution.along = Along(_numbers(case), centred_shift(solution, case), solution.mesh[0],
                           replace(before, before=None) if before is not None else None,
                           solution.start_up["discretisation_error"]["start_time"], held_limits(solution))
    return solution


def started_warm(problem, case: Case, previous: object) -> Solution | None:
    """The start-up design at ``case`` solved warm from ``previous`` (:func:`warm_from`; the papers' sizing at
    ``case``, :func:`sized_out`, kept as its ``sized``): a sweep's point from the point before's optimum
    (:func:`solved_along`), a continuation's step from the step before's (``clutchopt.optimise.sweep.continued``).
    None where ``previous`` does not start one (:func:`of_this_problem`), where the drive's proofs cover ``case`` (no
    design to start: ``Problem.refined`` gives the proof without a solve) or where its first simulation failed."""
    if start_up_proofs(case) or not of_this_problem(problem, previous):
        return None
    try:
        sized = sized_out(problem, case, previous.sized)
        solution = warm_from(problem, case, previous, sized)
    except InputError:  # its first simulation failed from this start
        return None
    solution.sized = sized
    return solution


def of_this_problem(problem, previous: object) -> bool:
    """Whether ``previous`` (a point's or a continuation step's verdict, or a stored design) starts a warm solve of the
    start-up ``problem`` (:func:`warm_from`): an optimum of it, its collocation states as many as the problem's (not
    its loop's doubled problem's, whose intervals it doubled, nor a stored design's, which has none)."""
    return isinstance(previous, Solution) and previous.status == "optimal" and previous.internal is not None \
        and len(previous.internal) == problem.posed.start_up.size


def warm_from(problem, case: Case, previous: Solution, sized: "SizedOut") -> Solution:
    """The start-up design at ``case`` solved warm from ``previous``, an optimum of this problem at a point nearby
    (:func:`of_this_problem`): its design, scales, multipliers and collocation states, on the mesh its loop ended on
    (or adapted ahead: :func:`first_mesh`), its moved limits carried (:func:`predicted_shift`), the integer choices and
    the design of the papers' sizing at ``case`` (``sized``: :func:`sized_out`) completing each warm solve's search;
    a warm start that fails ends it (``not_found``, undiagnosed: ``Problem.refined``'s ``cold=False``). A sweep's point
    (:func:`solved_along`) and each step of its continuation (``clutchopt.optimise.sweep.continued``) start so.
    InputError: its first simulation failed from this start."""
    block = problem.posed.start_up
    numbers, tolerance = _numbers(case), block.s.spec.tolerance
    step = secant_step(previous.along, numbers)
    mesh, shift = first_mesh(previous, step, tolerance), predicted_shift(previous, step, tolerance)
    looped = SizedOut(sized.key) if block.s.elastic else sized  # (an elastic link's loop takes neither: its NLP is
    # another model than its simulation)
    return problem.refined(case, warm=previous, mesh=mesh, shift=shift, diagnosed=False, cold=False,
                           infeasible=looped.choices, sizing=looped.design)


def solved_alone_where_held(problem, case: Case, solution: Solution, sized: "SizedOut") -> Solution | None:
    """A point whose warm loop ended on a design a row of the collocation holds, not a limit
    (``clutchopt.optimise.problem.held_by_the_mesh``: no start-up limit's multiplier, the objective elastic to the
    drive; the loop's own remedy, the papers' sizing, missed a limit): also solved as ``solve`` solves it alone
    (``Problem.solve``: its starts, retries and the sampled design), whose design is kept unless it has none verified or
    is heavier beyond the tolerance (the held design kept has its integers probed as :func:`as_solve_would` probes them,
    and says what ``solve`` alone ended with: ``Solution.beside_alone``); every solve counted. None where ``solution``
    is not held. A held design is the fold of the discretised start on the mesh the point before handed on, not the
    physics' optimum: its lighter neighbours along the torque's need meet every simulated limit (ball_motor_start in
    paper mode at 1.5 GPa, 507.9 then 650 kW: held at 696.98 kg, the torque alone active, where ``solve`` reaches 687.92
    kg, the start time active too; on NumPy's SSE4 loops with OpenBLAS on Sandybridge kernels, 507.9 then 605.7 kW:
    558.28 kg against 554.69 kg: tests/test_start_up_sweep_held.py). A held point costs one ``solve`` of it more (for
    the same design where ``solve``'s own loop ends held too); no point of the bench's driven-inertia sweeps ends held."""
    if not problem._held(solution):
        return None
    alone = problem.solve(case)
    tolerance = problem.posed.start_up.s.spec.tolerance
    if alone.status == "optimal" and not alone.objective > solution.objective * (1 + tolerance):
        return alone.counted(solution)
    probed = as_solve_would(problem, case, solution, sized, alone)  # (its solves counted with ``solution``'s)
    return replace(probed, solver=probed.solver.summed([probed.solver, alone.solver])).beside_alone(alone)  # (said
    # once: the probe's ``solve`` alone is this one)


def as_solve_would(problem, case: Case, solution: Solution, sized: "SizedOut",
                   alone: Solution | None = None) -> Solution:
    """A point whose integers are not those of the papers' sizing at the point: also solved as ``solve`` solves it alone
    (``Problem.solve``: from the sizing, its relaxation rounded, its search, its retries), the lighter of the two kept,
    each verified by its own simulated start; the warm design kept where ``solve``'s is heavier beyond the tolerance or
    not verified says so (``Solution.beside_alone``: the record's ``solve_alone``). The fixed-integer start-up NLPs have
    several local optima, and a warm search decides the integers from the point before's optimum and its own loop's
    meshes, not from the sizing: kept, it tries their downhill neighbours from the kept optimum only (ball_motor_start
    over its motor inertia, 14.65 then 12.26 kg m^2, kept 25 rows, 1002.07 kg, where ``solve`` relaxes from the sizing's
    23 rows to 24.x and ends at 24 rows, 998.53 kg: tests/test_hostile_agree.py); moved, its loop may have left a count
    on a local verdict (ball_motor_start over driven_inertia, 100 then 375 kg m^2, on NumPy's AVX2 loops: 25 rows found
    infeasible on the adapted mesh from their first-mesh optimum, 26 rows kept at 1029.52 kg, where ``solve`` ends at 25
    rows, 1026.07 kg: tests/test_start_up_sweep.py). Where the integers are the sizing's, ``solve`` starts from them too
    (its search then completed by them, ``integers.from_the_start``): not solved again. Nor where an elastic link's
    every lighter count is settled at the point already (``Problem.lighter_settled``: refuted by the link's least
    stress at the case's limits, solved through its own accuracy loop there, the loop ``solve`` runs on it, or its
    design of the NLP at the case's limits simulated there, unverified: evidence ``solve``'s path goes no further
    with, not a proof), which kept no lighter verified design: cable_motor_start over driven_inertia 0.6x-1.4x, 8 cables
    kept from the third point on, the sizing's 6 refuted, 7 looped at 14 points (at the others refuted), where the
    probe solved the relaxation and 7 cables again (2 solver calls a point) to end on them ``unverified`` (or on the 8
    kept). It assumes, as ``Problem._one_up_first`` does, that no count above the kept one is lighter at the case's
    limits. ``alone``: ``solve`` of the point alone where the caller has it (:func:`solved_alone_where_held`; its
    solves counted by the caller)."""
    names = problem.integer_names
    if not names:
        return solution
    sizing = problem.sized_design(case) if sized.design is None else sized.design
    if sizing is None or all(round(sizing[name]) == round(solution.design[name]) for name in names):
        return solution
    if problem.lighter_settled(case, solution):
        return solution
    probe = problem._solve(case, warm=solution, diagnosed=False, cold=False, redecide=True)
    tried = [probe]
    if probe.status == "optimal" and any(probe.design[name] != solution.design[name] for name in names):
        tried.append(alone or problem.solve(case))
    spent = [s.solver for s in (solution, *tried) if s is not alone]  # (a caller's ``alone``: counted by it)
    last, tolerance = tried[-1], problem.posed.start_up.s.spec.tolerance
    solved = len(tried) > 1 and last.status == "optimal"
    kept = last if solved and last.objective < solution.objective * (1 - tolerance) else solution
    counted = replace(kept, solver=kept.solver.summed(spent))  # (every solve counted, its iterations and seconds too)
    if len(tried) > 1 and not (solved and last.objective <= solution.objective * (1 + tolerance)):
        return counted.beside_alone(last)  # (``solve``'s heavier beyond the tolerance, or none verified)
    return counted


@dataclass(frozen=True)
class SizedOut:
    """The papers' sizing's problem at a sweep's point (``key``: its case values, as its posed problem reads them)
    and the integer choices its search found infeasible there (``choices``: the start-up problem's integer
    variables' values -> why; None: not solved for), and its design there (``design``; None: not solved for, or not
    optimal), whose integers complete each warm solve's search at the point (``Problem._sized``)."""

    key: str
    choices: dict[tuple, str] | None = None
    design: dict[str, float] | None = None


def sized_out(problem, case: Case, before: SizedOut | None) -> SizedOut:
    """The integer choices a start-up sweep's point need not solve: those the papers' sizing (the same formulation
    without the start-up, ``Problem.static_problem``) finds infeasible at the point (IPOPT:
    ``Infeasible_Problem_Detected``), where the start-up problem keeps every row of it (no constant-acceleration row
    left to the start-up model, as the wedge's and lever's torque rows are): its designs are then a subset of the
    sizing's, and a choice without a design there has none here, as the batch's ``tightening`` reads a step that only
    tightens. The sizing is solved at a point whose sizing problem is not the point before's (the first solved along a
    sweep, or each point of a sweep that moves it), where :func:`as_solve_would` solved it anyway, and carried while
    the problem stays the same (a sweep of start-up quantities alone: the driven inertia). ball_motor_start over
    driven_inertia: 22 rows, the sizing's row fewer, infeasible by the same least violation 2.72e-3 at every point from
    225 to 336 kg m^2, were solved at each (26-33 IPOPT iterations); ``solve`` of such a point alone rules them out
    from its own sizing (``Problem._refined``, :func:`sized_choices`): the same verdict. The first point solved along
    solved them until its sizing was solved before its loop (35 IPOPT iterations; ball_motor_start's 20-point sweeps
    over driven_inertia, max_start_time 0.8x-1.2x and power a solver call fewer each, every design the same to the
    bit). An elastic link (the cable) keeps every row too, but its loop takes
    neither the choices nor the design (:func:`solved_along`; it rules nothing out, ``Problem._refined``: no
    ``RuledOut``, its NLP is another model than its simulation): the design is carried for :func:`as_solve_would`
    alone, which had solved the sizing again at every point (cable_motor_start over driven_inertia: 3 static IPOPT
    runs, 41 iterations, about 9 ms CPU a point; the same problem, the same design). ``before``: the point
    before's (``Solution.sized``)."""
    static = problem.static_problem
    key = repr(tuple(vars(static.posed.params(case)).values()))
    if before is not None and before.key == key and before.choices is not None:
        return before
    if not keeps_the_sizing(problem):  # a row left to the start-up model
        return SizedOut(key, {})
    sizing = static.solve(case)
    return SizedOut(key, sized_choices(problem, sizing), sizing.design if sizing.status == "optimal" else None)


def keeps_the_sizing(problem) -> bool:
    """Whether the start-up problem keeps every row of the papers' sizing (``Problem.static_problem``): no
    constant-acceleration row left to the start-up model, as the wedge's and lever's torque rows are."""
    return set(problem.static_problem.posed.row_names) <= set(problem.posed.row_names)


def sized_choices(problem, sizing: Solution) -> dict[tuple, str]:
    """The integer choices (the start-up problem's integer variables' values -> why) the papers' sizing's search
    (``sizing``, its solution at the point) found infeasible, where the start-up problem keeps every row of it
    (:func:`keeps_the_sizing`; else none): a start-up solve need not solve them (:func:`sized_out`; ``Problem``'s
    first solve from the sizing, ``Problem._refined``)."""
    if not keeps_the_sizing(problem):
        return {}
    names = problem.integer_names
    return {tuple(float(entry[name]) for name in names if name in entry):
            f"infeasible in the papers' sizing at this point ({entry['status']}), whose every row the start-up "
            "problem keeps" for entry in sizing.integer_search if entry["status"] == INFEASIBLE}


def first_mesh(previous: Solution, step: float | None, tolerance: float) -> np.ndarray:
    """The mesh a point's first solve is on: the one the point before's loop ended on, or where the secant through the
    collocation errors of the two points before on that mesh (their start time against the simulated one) puts this
    point's error beyond ``tolerance`` (:func:`error_ahead`, ``step`` steps on: :func:`secant_step`), the mesh the point
    before's simulated start suggests (adapted to it, ``Solution.mesh[1]``): the loop would solve on the old mesh only
    to adapt it (wedge_motor_start over driven_inertia at 0.658 kg m^2: errors -5.9e-7 and -9.0e-7 at the two points
    before, -1.24e-6 there). The secant is taken as :func:`predicted_shift` takes it (the same mesh, on the line, at
    most FURTHEST steps on), and only after a mesh that resolved the point before's start (its error within
    ``tolerance``): a loop that kept a coarse mesh for another reason (no start-up limit shapes the design,
    ``shapes_nothing``: ball_motor_start at 0.6-0.9 times its driven inertia, errors 1e-3 to 1e-2) keeps it (adapted
    ahead, the ball's integer search went down another path at 272 and 288 kg m^2, to designs 0.4 and 0.7 % heavier than
    ``solve``'s). Nor where the point before binds at a limit its loop left uncorrected (:func:`held_limits`): its
    design then carries the collocation's error at that limit, so the mesh decides it within the contract, and a mesh
    adapted to the start of the point before instead of this point's own moves it and every later point on it
    (lever_motor_start from 9.22 kg m^2 on, ten points by up to 3.6e-8 off main's, 1.0e-7 off ``solve``'s; where the
    correction centres every binding limit, as on the wedge at 0.658 kg m^2, the designs after it are main's to
    5e-11)."""
    ahead, last = error_ahead(previous.along, step), previous.along
    if ahead is None or not abs(ahead) > tolerance or not abs(last.error) <= tolerance or last.held:  # (a loop that
        return previous.mesh[0]  # kept a coarse mesh for another reason; a binding limit left uncorrected)
    return previous.mesh[1]


def secant_step(last: Along | None, numbers: dict[str, float]) -> float | None:
    """How many steps of the two points before (``last``, the point before, and its ``before``) the point whose
    case's values are ``numbers`` (:func:`_numbers`) lies on from ``last``: where both ended on the same mesh (a
    mesh adaptation moves the collocation's figures, hence the corrections, by a step of its own), the point lies on
    the line through their values, at most FURTHEST steps on; None where not (no secant)."""
    if last is None or last.before is None or not np.array_equal(last.mesh, last.before.mesh):
        return None
    return _step(last.before.values, last.values, numbers)


def error_ahead(last: Along | None, step: float | None) -> float | None:
    """The collocation error (start time against the simulated one) the secant through the two points before
    (``last`` and its ``before``) puts ``step`` steps on from ``last`` (:func:`secant_step`); None without a secant."""
    return None if step is None else _ahead(last.error, last.before.error, step)


def predicted_shift(previous: Solution, step: float | None, tolerance: float) -> dict[str, float]:
    """The limits a point starts with, as shares of its case's: the point before's, centred (:func:`centred_shift`),
    each moved on by the secant through the two points before over ``step`` of their steps (:func:`secant_step`; none:
    carried as they are); the point before's ``limit_shift`` where it was not solved along the sweep. An active limit
    the point before's loop left at the case's (:func:`held_limits`) is moved only where the objective's error from it,
    carried on the same way, passes what the defect correction accepts (CENTRE of ``tolerance``): the correction this
    point would solve is then not solved (wedge_motor_start over driven_inertia at 0.595 kg m^2, where the start time's
    passes it: 2.1e-7 and 2.5e-7 at the two points before, 2.9e-7 there; centred from then on), and a point it would not
    correct is solved at the case's limit, as the point alone is. Where the secant puts the point's collocation error
    beyond ``tolerance`` (:func:`error_ahead`), an adaptation (ahead, :func:`first_mesh`, or the loop's) moves the
    collocation's figures by a step of its own: only the limits the point before's loop moved are carried into it, as
    the loop carries them, not those moved ahead on the old mesh's figures (every held limit and every slack one
    centred, :func:`centred_shift`, dropped)."""
    last = previous.along
    if last is None:
        return previous.limit_shift
    before = last.before or Along({}, {}, last.mesh)
    shares = {name: _ahead(share, before.shift.get(name), step) for name, share in last.shift.items()}
    if not abs(error_ahead(last, step) or 0.0) <= tolerance:  # adapting: the limits the loop moved, as it carries them
        return {name: share for name, share in shares.items() if name in previous.limit_shift}
    for name, error in last.held.items():
        if not _ahead(error, before.held.get(name), step) > CENTRE * tolerance:
            shares.pop(name, None)
    return shares


def held_limits(solution: Solution) -> dict[str, float]:
    """Each start-up limit ``solution``'s design binds at (the simulated check active) that its loop left at the
    case's (not in its ``limit_shift``): the objective's relative error from the simulated figure off the limit
    (:func:`~clutchopt.optimise.start_up_check.objective_error`), what the defect correction compares with CENTRE of
    the tolerance (:func:`~clutchopt.optimise.start_up_check.corrected_case`)."""
    return {name: objective_error(check, gap) for check, name, gap in limit_gaps(solution)
            if check.active and name not in solution.limit_shift}


def _ahead(value: float, before: float | None, step: float | None) -> float:
    """``value`` moved on by the secant from ``before`` over ``step`` steps (as it is without either)."""
    return value if step is None or before is None else value + step * (value - before)


def centred_shift(solution: Solution, case: Case) -> dict[str, float]:
    """``solution``'s ``limit_shift`` with each limit its design binds at (the simulated check active) moved to where
    the simulated figure meets the case's limit: the NLP's limit L_k less the simulated gap S - L. That is the defect
    correction's L - (S - C) (:func:`~clutchopt.optimise.start_up_check.corrected_case`) where the NLP binds the limit
    (its own figure C = L_k); where the NLP leaves it slack (C < L_k) the correction also takes that slack in
    (docs/start_up.md, "The defect correction's fixed point"), the share here does not (the former step, kept: the
    sweeps' designs and solver calls stay as they were). A limit its loop never moved from the case's
    has share 1 (:func:`predicted_shift` carries it only where the correction would move it). The shares a
    point ends with are those of the limits its last solve saw, off that by up to what the loop accepts; the secant
    is taken through the centred ones, not through its own predictions. A limit the design does not bind at is
    centred on what the simulator adds to the NLP's own figure there, L - (S - C), where that figure is known: the
    point where it first binds then meets it with its first solve, where the case's limit was missed and corrected
    (wedge_motor_start over driven_inertia at 0.637 kg m^2, where the temperature rise first binds: 3 solves to 2;
    its design 1.8e-8 off ``solve``'s, within the contract: docs/start_up.md, "Fewer solver calls a start-up sweep's
    point"). Without that figure it is left as it is."""
    shares, collocated = dict(solution.limit_shift), getattr(solution, "collocated", None) or {}
    for check, name, gap in limit_gaps(solution):
        if check.active:
            shares[name] = shares.get(name, 1.0) - gap / case.values[name]
        elif math.isfinite(figure := collocated.get(check.name, math.nan)):  # L - (S - C), the NLP's own figure C
            shares[name] = 1.0 - (check.value - figure) / case.values[name]
    return shares


def _step(first: dict[str, float], second: dict[str, float], third: dict[str, float]) -> float | None:
    """t where ``third`` = ``second`` + t (``second`` - ``first``) in every value (to ON_RAY of each step:
    ``failed_starts.on_ray`` from ``second`` towards ``first``, t its negative), 0 < t <= FURTHEST; None where the
    three points are not so placed."""
    back = on_ray(second, first, third)
    return -back if back is not None and 0.0 < -back <= FURTHEST else None


def _numbers(case: Case) -> dict[str, float]:
    return {name: value for name, value in case_numbers(case).items() if math.isfinite(value)}
