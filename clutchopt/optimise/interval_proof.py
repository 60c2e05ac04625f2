"""A design space shown empty by interval branch and bound: no design within the bounds meets the constraints.

The posed problem's own constraint rows (``g <= 0``, normalised) are bounded over boxes of the design variables by
interval evaluation (:mod:`clutchopt.optimise.interval`). A box is empty of feasible designs when one row's lower
bound exceeds the tolerance over all of it. A box whose uncertain rows (those not met throughout it) all fall, or all
rise, with one variable holds a feasible design only if its face at that variable's upper (lower) bound does: the
box shrinks to the face (the monotonicity test of interval global optimisation). Other boxes are bisected across
their widest variable, relative to the design box. Each box's integer variables are rounded inwards to whole
numbers, and a box without one is dropped. When no box is left the design space is empty: a proof, for the integers
(ball_motor_start at 565 kW: its continuous relaxation has designs, no whole number of ball rows does). A box whose
centre meets every row is a feasible design (of the relaxation), and the search stops there: the case is not
infeasible.

Work is bounded: at most ``MAX_BOXES`` boxes are evaluated, after which the search gives up without a verdict; beyond
the first ``SURE_BOXES`` it also gives up as soon as the boxes left grow by more than ``GROWTH`` in an iteration. A
search that will prove closes in: the boxes left grow by at most 1.25 an iteration and then fall (ball_motor_start
at 580-800 kW: 300 to 1,200 boxes left at each of about 30 iterations, 15,000-34,000 boxes in all), while one whose
bounds are too loose to prove doubles them every iteration (wedge_motor_start in geometry mode in a 100 mm
housing: 32, 110, 204, 392, 752, ...) and stops where it did with a budget of 2,500 boxes.

Declared monotone nodes (Hertz's n_a, n_b of the ball's contact, :mod:`clutchopt.monotone`) are bounded at their
argument's ends (:mod:`clutchopt.optimise.interval_nodes`): replayed through their Newton step on the elliptic
integrals, their bounds are unbounded on boxes 1 % wide, and no conflict through the contact stress was provable.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from clutchopt.optimise.interval_nodes import enclosed_rows

MAX_BOXES = 40_000  # about 1.5 s of CPU; ball_motor_start's static conflict at 580-800 kW takes 15,000-34,000
SURE_BOXES = 2_500  # evaluated in any case; beyond, only while the search closes in (GROWTH)
GROWTH = 1.5  # the most the boxes left may grow from one iteration to the next beyond SURE_BOXES
BATCH = 128  # boxes an iteration evaluates at least (bisecting as often as it takes)
TOLERANCE = 1e-6  # a row must be broken by more than this (relative) over a whole box for the box to be empty


class Emptiness(NamedTuple):
    """The outcome of a search: ``proven`` empty, or a ``feasible`` design of the relaxation found, or neither."""

    proven: bool
    boxes: int  # evaluated
    decisive: dict[str, int]  # constraint name -> boxes it emptied
    feasible: np.ndarray | None = None  # a design meeting every row (SI), if one was met


def interval_functions(posed):
    """The formulation's own constraint rows (a start-up's left out: its states are not searched) and their
    Jacobian in the design variables, as interval functions of (design, p) with the declared monotone nodes
    enclosed at their arguments' ends (:mod:`clutchopt.optimise.interval_nodes`), built once per problem."""
    return posed.built("interval", True, lambda _: enclosed_rows(posed))


def search(posed, p: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> Emptiness | None:
    """Interval branch and bound over the box [lower, upper] of a posed problem's design whose variable scales in
    ``p`` are 1 (x in SI); None where it cannot start (an unbounded variable)."""
    if not (np.all(np.isfinite(lower)) and np.all(np.isfinite(upper))):
        return None
    functions = interval_functions(posed)
    if not functions[0].nodes.agree(lower, upper, p):  # the declared nodes do not stand for the NLP's rows here
        functions = posed.built("interval", False, lambda _: enclosed_rows(posed, declared=False))
    names = posed.row_names
    decisive: dict[str, int] = {}
    lo, hi = lower[:, None].copy(), upper[:, None].copy()
    width0 = np.where(upper > lower, upper - lower, 1.0)[:, None]
    evaluated, left = 0, np.inf
    while lo.shape[1]:
        lo, hi, dropped = _whole(lo, hi, posed.integer)
        for i, count in zip(posed.integer, dropped):
            if count:
                decisive[f"a whole {posed.names[i]}"] = decisive.get(f"a whole {posed.names[i]}", 0) + count
        if not lo.shape[1]:
            break
        if evaluated + lo.shape[1] > MAX_BOXES:
            return Emptiness(False, evaluated, decisive)
        evaluated += lo.shape[1]
        (g_lo, g_hi), (d_lo, d_hi), centre, (c_lo, c_hi) = _bounds(functions, lo, hi, p)
        met = np.all(c_hi <= 0.0, axis=0)
        if met.any():
            return Emptiness(False, evaluated, decisive, centre[:, int(np.argmax(met))])
        empty = g_lo > TOLERANCE
        for row in np.flatnonzero(empty.any(axis=1)):
            decisive[names[row]] = decisive.get(names[row], 0) + int(empty[row].sum())
        alive = ~empty.any(axis=0)
        lo, hi, uncertain = lo[:, alive], hi[:, alive], g_hi[:, alive] > 0.0
        if not lo.shape[1]:
            break
        if evaluated > SURE_BOXES and lo.shape[1] > GROWTH * left:  # spreading, not closing in: give up
            return Emptiness(False, evaluated, decisive)
        left = lo.shape[1]
        d_lo, d_hi = d_lo[:, :, alive], d_hi[:, :, alive]
        lo, hi = _faces(lo, hi, d_lo, d_hi, uncertain)
        for _ in range(max(1, int(np.ceil(np.log2(BATCH / lo.shape[1]))))):  # few large batches: an evaluation
            lo, hi, parents = _bisected(lo, hi, d_lo, d_hi, uncertain, width0)  # costs per operation, not per box
            d_lo, d_hi, uncertain = d_lo[..., parents], d_hi[..., parents], uncertain[:, parents]
    return Emptiness(True, evaluated, decisive)


def _whole(lo: np.ndarray, hi: np.ndarray, integer: list[int]) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """The boxes with their integer variables' ranges rounded inwards to whole numbers (1e-9 of slack), those left
    without a whole number dropped (an integer design lies in what is left); how many each integer variable
    dropped."""
    if not integer:
        return lo, hi, []
    lo, hi = lo.copy(), hi.copy()
    lo[integer], hi[integer] = np.ceil(lo[integer] - 1e-9), np.floor(hi[integer] + 1e-9)
    none = lo[integer] > hi[integer]
    kept = ~none.any(axis=0)
    return lo[:, kept], hi[:, kept], [int(row.sum()) for row in none]


def _bounds(functions, lo: np.ndarray, hi: np.ndarray, p: np.ndarray):
    """Over each box: the rows' bounds (the natural interval extension met with the mean-value form
    g(c) + J(X) (X - c), which is tight on small boxes), the Jacobian's bounds (rows x variables x boxes), the centre
    and the rows' bounds there."""
    rows, jacobian = functions
    count, n = lo.shape[1], lo.shape[0]
    params = (np.repeat(p[:, None], count, axis=1),) * 2
    centre = 0.5 * (lo + hi)
    (g_lo, g_hi), = rows.bounds([(lo, hi), params])
    (c_lo, c_hi), = rows.bounds([(centre, centre), params])
    (d_lo, d_hi), = jacobian.bounds([(lo, hi), params])
    m = g_lo.shape[0]
    d_lo, d_hi = d_lo.reshape(n, m, count).transpose(1, 0, 2), d_hi.reshape(n, m, count).transpose(1, 0, 2)
    step_lo, step_hi = (lo - centre)[None], (hi - centre)[None]
    with np.errstate(invalid="ignore"):
        corners = np.stack([d_lo * step_lo, d_lo * step_hi, d_hi * step_lo, d_hi * step_hi])
    corners = np.where(np.isnan(corners), 0.0, corners)  # 0 * inf: a variable the box fixes adds nothing
    mv_lo, mv_hi = c_lo + corners.min(axis=0).sum(axis=1), c_hi + corners.max(axis=0).sum(axis=1)
    mv_lo, mv_hi = np.where(np.isnan(mv_lo), -np.inf, mv_lo), np.where(np.isnan(mv_hi), np.inf, mv_hi)
    return (np.maximum(g_lo, mv_lo), np.minimum(g_hi, mv_hi)), (d_lo, d_hi), centre, (c_lo, c_hi)


def _faces(lo: np.ndarray, hi: np.ndarray, d_lo: np.ndarray, d_hi: np.ndarray,
           uncertain: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each box shrunk to its face where every uncertain row is monotone in a variable (the side it may favour)."""
    relevant = uncertain[:, None, :]  # rows x 1 x boxes
    falling = np.all(~relevant | (d_hi <= 0.0), axis=0)  # variables x boxes: no uncertain row rises with it
    rising = np.all(~relevant | (d_lo >= 0.0), axis=0)
    return np.where(falling & ~rising, hi, lo), np.where(rising, lo, hi)


def _bisected(lo: np.ndarray, hi: np.ndarray, d_lo: np.ndarray, d_hi: np.ndarray, uncertain: np.ndarray,
              width0: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each box split in two across the variable that spreads its uncertain rows most (largest |dg/dx| width; a
    variable whose slope is unbounded first, the widest of them relative to the design box), at its middle (a
    positive range over a factor 4: its geometric middle); the halves and the box each came from."""
    slope = np.where(uncertain[:, None, :], np.maximum(np.abs(d_lo), np.abs(d_hi)), 0.0).max(axis=0)
    with np.errstate(invalid="ignore"):  # an unbounded slope times a zero width: the where's other branch
        smear = np.where(np.isfinite(slope), slope * (hi - lo), 1e300 * (hi - lo) / width0)
    smear = np.where(hi > lo, smear, -1.0)
    widest = np.argmax(smear, axis=0)
    columns = np.arange(lo.shape[1])
    a, b = lo[widest, columns], hi[widest, columns]
    middle = np.where((a > 0) & (b > 4 * a), np.sqrt(a * b), 0.5 * (a + b))  # wide positive ranges: by ratio
    left_hi, right_lo = hi.copy(), lo.copy()
    left_hi[widest, columns], right_lo[widest, columns] = middle, middle
    split = hi[widest, columns] > lo[widest, columns]
    return (np.concatenate([lo, right_lo[:, split]], axis=1),
            np.concatenate([np.where(split, left_hi, hi), hi[:, split]], axis=1),
            np.concatenate([columns, columns[split]]))


def empty_design_space(posed, case) -> Emptiness | None:
    """:func:`search` over the design box of ``case`` in ``posed`` (with a start-up: its formulation's own
    constraints, without the start-up's: a design space empty without them is empty with them)."""
    lower, upper, _ = posed.bounds_and_start(case, None)
    mesh = posed.start_up.initial_mesh() if posed.start_up is not None else []
    p = np.concatenate([list(vars(posed.params(case)).values()), np.ones(len(lower)), [1.0], mesh])
    return search(posed, p, lower, upper)
