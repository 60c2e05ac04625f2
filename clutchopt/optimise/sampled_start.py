"""A start-up case's last retry before ``not_found``: from the sampled design its NLP's rows miss least.

``solve`` starts a start-up from the papers' sizing, and before it says ``not_found`` retries from the starts that can
reach a design (``clutchopt.optimise.verdict``): the sizing, the least relaxation's design, a design the interval search
met. All of them lie by the sizing. A sweep reaches designs those starts do not: warm from the point before, it follows
a design that moves off the sizing as the case moves (ball_motor_start in paper mode at a service factor of 1.49, from
1.389: 595.66 kg; at 605.7 kW from 507.9 kW: 554.69 kg), where ``solve`` of the point alone found none
(tests/test_hostile_agree.py, tests/test_hostile_agree2.py). There the designs that meet every check form a thin band
along the torque's need, away from the sizing, whose start locks up early and misses a row no case quantity limits
(stays_locked); from the sizing every cold IPOPT ends at the same least relaxation, and no homotopy from the sizing
measured reached the band (docs/start_up.md, "A cold start a sweep's continuation reaches").

The start then comes from the whole design box: SAMPLES designs of a Sobol sequence over the variables the case leaves
free (integers rounded), each moved first onto the rows the design alone enters (:func:`projected`: the nearest design
that meets the torque and the case's limits on the geometry; a sample breaks them by as much as the box is wide),
then its start simulated as any start's states are (``Posed.scaled_data``), and the one whose largest normalised row
of the NLP is least (:func:`~clutchopt.optimise.integers.least_violation`) is solved from, in steps
(:func:`walked`): each step within a box of +-STEP around the design before, through the accuracy loop as any retry,
warm from the step before, until a step's design lies inside its box; that design, no side of its box holding it,
or the case solved from it without the box where that is lighter (a step's optimum is its own NLP's, posed from the
step's start), is the case's own optimum from that start. A collocation's mesh is drawn for the start it is solved from: one solve
from a far design took the sizing's start, on that mesh, for feasible (its start time 35 % short of its simulated
one) and was lost there. The sequence is not scrambled: the same case gives the same samples, the same start and the
same answer. Its design is checked as every design is (float64, the simulated start); its failure keeps the verdict
``not_found`` and names the start among those tried. ``solve`` of a point from its own start gets it
(``Problem.solve``: no start, warm solution or neighbour given), and so does every start-up sweep point without a
design, solved as alone before the starts a sweep adds (its neighbour's design, its continuation, which reach the
local optimum nearest the points before: ``clutchopt.optimise.sweep``),
wherever the point lies in its run and wherever the run started (a resumed one, a pool's chunk): a point's verdict
rests on at least the starts ``solve`` of it alone tries (ball_motor_start in paper mode listed over 507.9, 900 and
605.7 kW: the third point, deeper than the first past a design, was ``not_found`` where ``solve`` finds 554.69 kg;
tests/test_start_up_sweep_deeper.py). The one exception, a sweep's: a point beyond a point without a design, on the
ray from the run's last design, whose one solve from that point's least relaxation fails for the same constraints
(``clutchopt.optimise.start_up_region``; its verdict says so, and a later design in the run brings ``solve``'s after
all). A retry from a given design is the caller's. ``solve`` walks the same way from a
start-up optimum a row of the collocation holds, not a limit (:func:`from_the_held_design`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import casadi as ca
import numpy as np

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.integers import least_violation
from clutchopt.optimise.solution import Solution
from clutchopt.optimise.verdict import one_more_start
from clutchopt.records import DESIGN_STATUSES

SAMPLES = 16  # designs sampled over the box (a power of two: a Sobol sequence's balanced size). Each start simulated
# costs what the coupling's start costs: 16 take 0.2 s on the ball, 4 s on the lever (0.1-0.5 s each; a simulation's
# tolerance hardly changes it), their projections 0.2 s on the ball. ball_motor_start (paper, 1.5 GPa) at 605.7 kW:
# the 16th sample (r = 0.172 m, b = 1.876 m) moved onto l / R_a = 3 (r = 0.233 m) meets every row with its start
# simulated, and is walked to the sweep's design; at a service factor of 1.8 no sample's start meets every row, and no
# walk finds a design: a sampled start is a start, not a search
STEP = 0.1  # how far a step of the walk from the sample (:func:`walked`) may move each variable, relative
STEPS = 30  # steps at most (ball_motor_start in paper mode: 13 from its sample to 554.69 kg at 605.7 kW, 12 at 1.49)
EDGE = 1e-6  # a step's design this near (relative) a side of its box is on it: the walk goes on
SAMPLED = f"the least violated of {SAMPLES} sampled designs"


def least_violated(posed, case: Case) -> dict[str, float] | None:
    """The design among SAMPLES of a Sobol sequence over ``case``'s box (the variables its bounds leave free, each
    between its finite bounds; integers rounded), each moved first onto the rows the design alone enters
    (:func:`projected`), whose NLP rows, with its start simulated, are missed least; None where no variable is free
    or no sample's start can be simulated."""
    lower, upper, start = (np.asarray(a, dtype=float) for a in posed.bounds_and_start(case, None))
    free = [i for i, (lo, hi) in enumerate(zip(lower, upper)) if hi > lo and math.isfinite(lo) and math.isfinite(hi)]
    if not free:
        return None
    from scipy.stats import qmc  # (here: scipy.stats costs a second to import, and only a not_found retry needs it)

    best, least = None, math.inf
    for unit in qmc.Sobol(len(free), scramble=False).random(SAMPLES):
        x = start.copy()
        x[free] = lower[free] + unit * (upper[free] - lower[free])
        x[posed.integer] = np.clip(np.round(x[posed.integer]), lower[posed.integer], upper[posed.integer])
        design = projected(posed, case, dict(zip(posed.names, map(float, x))))
        try:
            data = posed.scaled_data(case, design)
        except (InputError, ValueError, ArithmeticError):  # its start cannot be simulated or seeded: outside the
            continue  # simulator's ranges, or a corner of the box where the weights never engage (the wedge in
            # geometry mode: its engagement speed squared below 0)
        violation = least_violation(posed, np.array(posed.constraint_values(data.x0, data.p)).ravel())
        if violation < least:
            best, least = design, violation
    return best


def projected(posed, case: Case, design: dict[str, float]) -> dict[str, float]:
    """The design nearest ``design`` (each free continuous variable relative to its scale; integers kept) that meets
    the rows the design alone enters (the torque, the case's limits on the geometry, the start-up's rows of the
    design alone: its overload torque, ...), by IPOPT; ``design`` itself where IPOPT ends without one. A sample
    breaks those rows by as much as the box is wide (ball_motor_start in paper mode: l / R_a = 10.9 against its
    limit 3, the clutch's torque 1,000 times its overload limit), where no start-up row says anything of it."""
    data = posed.scaled_data(case, design, internal=np.zeros(posed.start_up.size))  # (no start simulated)
    kept = data.lower == data.upper
    kept[posed.integer] = True
    rows, solver = posed.built("projection", None, lambda _: _projection(posed))
    start = data.start / data.scale
    found = solver(x0=start, p=np.concatenate([data.p, start, ~kept]), lbx=np.where(kept, start, data.lower /
                   data.scale), ubx=np.where(kept, start, data.upper / data.scale), lbg=posed.lbg[rows], ubg=0.0)
    if not solver.stats()["success"]:
        return design
    return posed.design(np.asarray(found["x"]).ravel(), data.scale)


def _projection(posed) -> tuple[np.ndarray, ca.Function]:
    """The rows the design alone enters, and IPOPT on the scaled design nearest a target (the sum of squares of the
    weighted differences) that meets them; its parameters the NLP's, the target and the weights."""
    n = len(posed.names)
    rows, values = posed.fixed_only(np.ones(n, dtype=bool))
    x, p = ca.SX.sym("x", n), ca.SX.sym("p", posed.nlp["p"].shape[0])
    target, weight = ca.SX.sym("target", n), ca.SX.sym("weight", n)
    g = values(ca.vertcat(x, ca.SX.zeros(posed.nlp["x"].shape[0] - n)), p)
    nlp = {"x": x, "p": ca.vertcat(p, target, weight), "f": ca.sumsqr(weight * (x - target)), "g": g}
    return rows, ca.nlpsol("projection", "ipopt", nlp, posed.options.ipopt())


def walked(problem, case: Case, design: dict[str, float]) -> Solution | None:
    """``case`` solved from ``design`` in steps: each within +-STEP of the design before in every free continuous
    variable (the case's bounds narrowed), warm from the step before, while each step's design ends on its box's
    edge. A step's design inside its box (no side of it holds it) is returned with the case's bounds, or the case
    solved from it where that is lighter (:func:`_confirmed`); where a step ends without an optimum, or STEPS are spent, ``case`` is solved without the box, warm
    from the last optimal step; every step's solver calls summed. None where the first step's start cannot be
    simulated. A start-up's collocation mesh is drawn for the start it is solved from and adapted around the
    design the solve moves to: a solve that moves the design far sees that design's start on a mesh drawn for
    another's (ball_motor_start in paper mode at 605.7 kW: from a design whose start meets every row, IPOPT's first
    solve moved to the papers' sizing, its start-time 35 % short of its simulated start's, which locks up early, and
    the loop lost the designs that meet every check), so a step moves the design by STEP at most."""
    names = [v.name for v in problem.formulation.variables if not v.integer]
    step = last = None  # (the last step that ended optimal)
    spent = []
    for _ in range(STEPS):
        box = _box(problem.posed, case, design, names)
        try:
            step = problem.refined(replace(case, bounds={**case.bounds, **box}), None if last else design, last,
                                   diagnosed=False)
        except InputError:  # (a start-up whose first simulation fails from this start)
            if last is None:
                return None
            break
        spent.append(step.solver)
        if step.status != "optimal":
            break
        last, design = step, step.design
        if not _on_edge(design, box, case, problem.posed):
            return _confirmed(problem, case, last, spent)
    if last is None and step.status not in DESIGN_STATUSES:
        return step
    found = problem.refined(case, warm=last or step, diagnosed=False)
    found.solver = found.solver.summed(spent + [found.solver])
    return found


def _confirmed(problem, case: Case, last: Solution, spent: list) -> Solution:
    """The walk's end ``last`` (a step's optimum inside its box) or, where lighter, the case solved from its design
    without the box, its mesh drawn for that design's own start: a step's optimum is one of the NLP posed from the
    step's start, within its box, not always the case's (ball_motor_start in paper mode at 605.7 kW with NumPy's
    OpenBLAS on its SkylakeX kernels: the walk ended at 577.36 kg, the torque alone active, from where the case
    solved reaches 554.69 kg, the walk's end on this machine's kernels); every solver call summed."""
    lower, upper, _ = problem.posed.bounds_and_start(case, last.design)
    last.bounds = problem.posed.named_bounds(lower, upper)
    try:
        again = problem.refined(case, last.design, diagnosed=False)
    except InputError:  # (its start not simulated from this design: the step's optimum stands)
        last.solver = last.solver.summed(spent)
        return last
    kept = again if again.status == "optimal" and again.objective < last.objective else last
    kept.solver = kept.solver.summed(spent + [again.solver])
    return kept


def _box(posed, case: Case, design: dict[str, float], names: list[str]) -> dict[str, tuple[float, float]]:
    """The bounds of a step from ``design``: +-STEP of each free continuous variable (of its bounds' width where it
    is 0), within the case's bounds."""
    lower, upper, _ = posed.bounds_and_start(case, design)
    box = {}
    for name, lo, hi in zip(posed.names, lower, upper):
        if name in names and lo < hi:
            reach = STEP * (abs(design[name]) or hi - lo)
            box[name] = (max(lo, design[name] - reach), min(hi, design[name] + reach))
    return box


def _on_edge(design: dict[str, float], box: dict[str, tuple[float, float]], case: Case, posed) -> bool:
    """Whether ``design`` lies on a side of ``box`` that is not one of the case's own bounds."""
    lower, upper, _ = posed.bounds_and_start(case, design)
    own = {name: (lo, hi) for name, lo, hi in zip(posed.names, lower, upper)}
    return any(math.isclose(design[name], side, rel_tol=EDGE) and side not in own[name]
               for name, sides in box.items() for side in sides)


def from_the_held_design(problem, case: Case, held: Solution) -> Solution:
    """``held`` (a start-up optimum a row of the collocation holds, not a limit:
    ``clutchopt.optimise.problem.held_by_the_mesh``; the loop's remedy, the papers' sizing, missed a limit) or,
    where lighter and ``optimal``, the design the walk from it reaches (:func:`walked`: each step on a mesh drawn for
    its own start, so no step sees the fold); every solver call summed. Where the walk finds none lighter, ``held``
    is kept, its diagnosis saying so. ball_motor_start in paper mode at 1.5 GPa, 650 kW warm from 507.9 kW (NumPy's
    AVX-512 loops): held at 696.98 kg, the walk reaches 687.92 kg, ``solve``'s alone (docs/start_up.md, "A design
    the mesh holds, walked")."""
    try:
        walk = walked(problem, case, held.design)  # (None: its first simulation failed)
    except InputError:  # (the walk's last solve not simulated from its start)
        walk = None
    spent = [held.solver] + ([walk.solver] if walk is not None else [])
    if walk is not None and walk.status == "optimal" and walk.objective < held.objective:
        walk.solver = walk.solver.summed(spent)
        return walk
    note = "a walk from it reached no lighter design"
    return replace(held, solver=held.solver.summed(spent),
                   diagnosis=f"{held.diagnosis}; {note}" if held.diagnosis else note)


def from_a_sampled_design(problem, case: Case, verdict: Solution) -> Solution:
    """``verdict`` (a start-up solve's ``not_found``) retried from the least violated sampled design
    (:func:`least_violated`): its design where the retry reaches one, else ``verdict`` with that start named among
    those tried; the solver calls of both summed. The samples and the walk are a function of the case alone: a walk
    that ended without a design is kept (``Problem.failed_starts``, as a retry from a given design is) and not walked
    again at the case (a sweep's point retried from the next feasible point's design, ``solve``'s sampled retry of
    it already spent)."""
    if verdict.status != "not_found":
        return verdict
    key = problem.failed_starts.key(case, {SAMPLED: 0.0})
    retry = problem.failed_starts.known(key)
    if retry is None:
        design = least_violated(problem.posed, case)
        retry = None if design is None else walked(problem, case, design)  # (None: its first simulation failed)
        if retry is not None and retry.status not in DESIGN_STATUSES:
            problem.failed_starts.keep(key, retry)
    kept = one_more_start(verdict, retry, SAMPLED)
    if kept is retry:  # (its design found from the starts tried before it, named as the verdict names them)
        kept.starts = verdict.starts + (SAMPLED,)
    return kept
