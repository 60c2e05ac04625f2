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
free (integers rounded), each with its start simulated as any start's states are (``Posed.scaled_data``), and the one
whose largest normalised row of the NLP is least (:func:`~clutchopt.optimise.integers.least_violation`) is solved as a
retry is, through the accuracy loop. The sequence is not scrambled: the same case gives the same samples, the same
start and the same answer. Its design is checked as every design is (float64, the simulated start); its failure keeps
the verdict ``not_found`` and names the start among those tried. Only ``solve`` of a point from its own start gets it
(``Problem.solve``: no start, warm solution or neighbour given): a sweep's point with a feasible neighbour follows
that neighbour's design instead (its continuation), and a retry from a given design is the caller's. Along a run of
points without a design, a sampled start that failed at the last point of the same case (but its values) for the
same violated constraints is not sampled or solved again (``FailedStarts.skips``, as for the design the interval
search meets).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.integers import least_violation
from clutchopt.optimise.solution import Solution
from clutchopt.optimise.verdict import retried
from clutchopt.optimise.verify import DESIGN_STATUSES

SAMPLES = 16  # designs sampled over the box (a power of two: a Sobol sequence's balanced size). Each start simulated
# costs what the coupling's start costs: 16 take 0.2 s on the ball, 4 s on the lever (0.1-0.5 s each; a simulation's
# tolerance hardly changes it). ball_motor_start (paper) at a service factor of 1.49 and at 605.7 kW: the least
# violated of 16, 32 or 64 is the same design (r = 0.172 m, b = 1.876 m, largest row 0.22 and 0.20), which solves to
# the sweep's design; at 641.7, 661.3 and 672.2 kW 16 and 32 alike find a design; at a service factor of 1.6 the
# least violated of 16 reaches 757.93 kg, of 32 none: a sampled start is a start, not a search
SAMPLED = f"the least violated of {SAMPLES} sampled designs"
_SAMPLED_KEY = {"sampled_designs": float(SAMPLES)}  # the sampled start as ``FailedStarts`` keeps it: by what it is,
# not by the design it lands on at each point


def least_violated(posed, case: Case) -> dict[str, float] | None:
    """The design among SAMPLES of a Sobol sequence over ``case``'s box (the variables its bounds leave free, each
    between its finite bounds; integers rounded) whose NLP rows, with its start simulated, are missed least; None
    where no variable is free or no sample's start can be simulated."""
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
        design = dict(zip(posed.names, map(float, x)))
        try:
            data = posed.scaled_data(case, design)
        except (InputError, ValueError, ArithmeticError):  # its start cannot be simulated or seeded: outside the
            continue  # simulator's ranges, or a corner of the box where the weights never engage (the wedge in
            # geometry mode: its engagement speed squared below 0)
        violation = least_violation(posed, np.array(posed.constraint_values(data.x0, data.p)).ravel())
        if violation < least:
            best, least = design, violation
    return best


def from_a_sampled_design(problem, case: Case, verdict: Solution) -> Solution:
    """``verdict`` (a start-up solve's ``not_found``) retried from the least violated sampled design
    (:func:`least_violated`): its design where the retry reaches one, else ``verdict`` with that start named among
    those tried; the solver calls of both summed."""
    failed = problem.failed_starts
    if verdict.status != "not_found" or failed.skips(case, _SAMPLED_KEY, verdict.diagnosed):
        return verdict
    design = least_violated(problem.posed, case)
    retry = None if design is None else retried(problem, case, design)  # (None: its first simulation failed)
    if retry is not None and retry.status in DESIGN_STATUSES:
        retry.solver = retry.solver.summed([verdict.solver, retry.solver])
        retry.starts = verdict.starts + (SAMPLED,)
        return retry
    kept = replace(verdict, starts=verdict.starts + (SAMPLED,),
                   solver=verdict.solver.summed([verdict.solver] + ([retry.solver] if retry is not None else [])))
    failed.keep(failed.key(case, _SAMPLED_KEY), kept)
    return kept
