"""Boxes contracted by the mean-value form of their rows: the part of a box that may hold a design, without bisecting.

Over a box X with centre c, each row satisfies g(x) = g(c) + J(xi) (x - c) with xi in X (the mean-value theorem), so
g(x) lies in g(c) + sum_i J_i(X) (x_i - c_i): the mean-value form (Hansen & Walster, "Global Optimization Using
Interval Analysis", 2nd ed., ch. 6 and 10: using inequality constraints to reduce a box; Moore, Kearfott & Cloud,
"Introduction to Interval Analysis", ch. 6). A design must have g(x) <= limit (the search's tolerance), so for each
variable j and each row, writing t = x_j - c_j, a in J_j(X) and S_j the least the other terms take over the box,

    a t <= R_j = limit - g(c)_lo - S_j   for some a in [a_lo, a_hi].

Where the row rises with x_j throughout (a_lo > 0) this bounds t above: t <= R_j / a_lo where R_j >= 0 (a t is least
at a_lo for t >= 0), t <= R_j / a_hi where R_j < 0 (then t < 0, least at a_hi). Where it falls throughout (a_hi < 0)
it bounds t below, the same rule mirrored. Where the slope spans zero nothing is taken (the points left would be two
intervals). Every row's bound on every variable is met with the box (all at once, then again on the contracted box:
``SWEEPS``); a box whose ends cross is empty. The rows that cut a box are named in the proof, as those that empty
one are: the proof rests on them (the lever's torque alone empties what its lining pressure cut). The slopes and the
centre's values are those over the box first evaluated: they hold over any box within it, so the contracted box needs
no new evaluation. Each bound is widened outwards by ``_SLACK`` of the magnitudes it was computed from (a sum of a few
terms in float64 errs by a few ulps of them), so a design is never cut away.

Near a constraint's limit, where the natural interval extension's overestimation (linear in the box's width) hides a
thin margin, this removes the slab of a box beyond each row's linearisation, whose error shrinks with the square of
the width; two rows in conflict cut a box from both sides until nothing is left.
"""

from __future__ import annotations

import numpy as np

from clutchopt.optimise.interval_contract_compiled import compiled_contracted, library

SWEEPS = 3  # contractions per evaluation: each on the box the last left (the slopes of the first box), fewer where
# one empties every box or moves none
_SLACK = 1e-12  # relative outward widening of each bound (float64 sums of a few terms err by a few ulps)
_CUT = 1e-9  # a row cut a box where it moved an end by more than this of the box's width (named in the proof)


def least_terms(d_lo: np.ndarray, d_hi: np.ndarray, step_lo: np.ndarray, step_hi: np.ndarray) -> np.ndarray:
    """The least of J_i(X) (x_i - c_i) over the box for each row and variable (rows x variables x boxes); a variable
    the box fixes at its centre (0 * inf) adds nothing."""
    with np.errstate(invalid="ignore"):
        corners = np.stack([d_lo * step_lo, d_lo * step_hi, d_hi * step_lo, d_hi * step_hi])
    return np.where(np.isnan(corners), 0.0, corners).min(axis=0)


def contracted(lo: np.ndarray, hi: np.ndarray, centre: np.ndarray, c_lo: np.ndarray, d_lo: np.ndarray,
               d_hi: np.ndarray, limit: float, compiled: bool = True
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The boxes [lo, hi] (variables x boxes) contracted to the points where every row may be at most ``limit``, from
    the rows' lower bounds at the ``centre`` (``c_lo``, rows x boxes) and their slopes' bounds over the boxes
    (``d_lo``, ``d_hi``, rows x variables x boxes); the new ends, which boxes are empty, and the rows that cut each
    box (rows x boxes: the proof rests on them as on the rows that empty a box, and names them). By the compiled
    rule where it can be had (``compiled``: :mod:`clutchopt.optimise.interval_contract_compiled`, the same numbers),
    else by NumPy below."""
    function = library() if compiled else None
    if function is not None:
        return compiled_contracted(function, lo, hi, centre, c_lo, d_lo, d_hi, limit, SWEEPS, _SLACK, _CUT)
    lo, hi = lo.copy(), hi.copy()
    m, n, count = d_lo.shape
    rising, falling = (d_lo > 0.0) & np.isfinite(d_lo), (d_hi < 0.0) & np.isfinite(d_hi)
    empty, cutters = np.zeros(count, dtype=bool), np.zeros((m, count), dtype=bool)
    if not (rising.any() or falling.any()):
        return lo, hi, empty, cutters
    c_lo = np.where(np.isnan(c_lo), -np.inf, c_lo)[:, None, :]
    for _ in range(SWEEPS):
        terms = least_terms(d_lo, d_hi, (lo - centre)[None], (hi - centre)[None])
        infinite = np.isinf(terms)
        finite = np.where(infinite, 0.0, terms)
        others = _sum_in_order(finite) - finite  # the least of the other variables' terms
        others = np.where(infinite.sum(axis=1, keepdims=True) - infinite > 0, -np.inf, others)
        magnitude = _sum_in_order(np.abs(finite)) + np.abs(c_lo) + abs(limit)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            room = limit - c_lo - others + _SLACK * magnitude  # R_j, rounded up
            room = np.where(np.isnan(room), np.inf, room)
            t_up = np.where(rising, np.where(room >= 0, room / d_lo, room / d_hi), np.inf)
            t_down = np.where(falling, np.where(room >= 0, room / d_hi, room / d_lo), -np.inf)
            t_up = np.where(np.isnan(t_up), np.inf, t_up)
            t_down = np.where(np.isnan(t_down), -np.inf, t_down)
            up = centre[None] + t_up + _SLACK * (np.abs(centre[None]) + np.abs(t_up))
            down = centre[None] + t_down - _SLACK * (np.abs(centre[None]) + np.abs(t_down))
        up, down = np.where(np.isnan(up), np.inf, up), np.where(np.isnan(down), -np.inf, down)
        new_hi, new_lo = np.minimum(hi, up.min(axis=0)), np.maximum(lo, down.max(axis=0))
        margin = _CUT * (hi - lo)
        cutters |= np.any((up < (hi - margin)[None]) | (down > (lo + margin)[None]), axis=1) & ~empty[None]
        empty |= np.any(new_lo > new_hi, axis=0)
        before = lo, hi
        lo, hi = np.where(empty, lo, new_lo), np.where(empty, hi, new_hi)
        if empty.all() or all(np.array_equal(a, b, equal_nan=True) for a, b in zip(before, (lo, hi))):
            break  # (every box empty, or none moved: a further sweep gives the same boxes and cutters)
    return lo, hi, empty, cutters


def _sum_in_order(terms: np.ndarray) -> np.ndarray:
    """The sum over the variables (axis 1, kept) added from the first on, as the compiled rule adds them (a running
    sum's last: an accumulation adds in order): NumPy's own sum adds pairwise along an innermost axis of 8 or more
    (one box), so a box's bits would depend on the boxes with it in the call."""
    return np.add.accumulate(terms, axis=1)[:, -1:]
