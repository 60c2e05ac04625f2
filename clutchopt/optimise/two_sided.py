"""A quantity held from both sides at one value, posed once: one two-sided row ``lbg <= g <= 0`` of the scaled NLP.

A formulation names its constraints one-sided, ``value <= limit`` or ``value >= limit``, each normalised by its own
scale into a row ``g <= 0`` (``Constraint.normalised``). Where two constraints hold the same quantity (the same
``value`` expression) from above and from below - the ball's K5 = l / R_a: in paper mode at least the paper's K5
(``width_ratio``) and at most the case's ``width_ratio_max``, in design mode between width_ratio_min and _max - their
rows are g_k = s_k (L_k - v) / S_k and g_f = s_f (v - L_f) / S_f (s = +-1 by sense): g_f <= 0 is
g_k >= s_f (L_k - L_f) / S_k. Where the two limits leave room between them (design mode; paper mode below the
case's width_ratio_max) the rows are posed as they are, two one-sided rows. Where they are one value (the ball
compressor in paper mode: 0.8 and 0.8; or closer than ROOM, one value to the float64 check), the two opposite rows
g and -g left IPOPT no interior (multipliers 4.8e9, 30 iterations instead of 8; docs/tradeoffs.md): the solvers see
the kept row with both limits and the other row free (-inf <= g_f <= inf), an equality IPOPT solves as such.
Posed so in every case (a pair with room between as one row too), the ball's design-mode sweeps' chained SQP took
5 times as long a call (its speed sweep 3,545 -> 1,046 points/s), so only the limits decide, at each parameter
vector, and the NLP itself (its rows, derivatives, compiled code) is one. Where the limits cross (the lower above
the upper) the solvers see the kept row where the two rows cross (:func:`_crossed`: a well-posed NLP, each row
violated alike, within the float64 check's tolerance where they cross by less than it allows on both rows), and
beyond that the verdict is given before any solve (:meth:`TwoSided.conflicts`).

Everything apart from the solvers (the float64 re-check, the KKT verdict, the diagnosis, the proofs) sees the named
rows, one-sided, each with its own multiplier: a two-sided row's multiplier lam splits by sign onto the side that
is active, lam_k = max(lam, 0) and lam_f = max(-lam, 0) S_f / S_k (the Lagrangian's lam_k g_k + lam_f g_f is
(lam_k - lam_f S_k / S_f) g_k + const). A pair is posed so only where both limits and scales are free of the design
(else the lower limit of g_k would move with it).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

DEPTH = 100  # how deep two value expressions are compared (``ca.is_equal``): a formulation's quantities are a few
#              operations deep (K5 = l / R_a: one)
ROOM = 1e-8  # limits closer than this (in the kept row's scale) are one value: the pair posed as one row. Two rows
# g and -g closer than the float64 check tells apart (ball_compressor paper, width_ratio_max 2e-12 to 3e-10 above the
# paper's K5 0.8) left IPOPT 26-29 iterations and an unpolished optimum 7.8e-9 heavier; one row: 8, polished


def _scale(constraint):
    return constraint.limit if constraint.scale is None else constraint.scale


def held_from_both_sides(constraints, x_hat, rows: np.ndarray) -> list[tuple[int, int]]:
    """Pairs of row indices ``(kept, other)``: a ``>=`` constraint's row, which the solvers keep, and a ``<=``
    constraint's on the same value expression, one row each, their limits and scales free of the design ``x_hat``;
    each row in one pair at most. ``rows``: each constraint's first row (and the rows' count at the end)."""
    single = [i for i, c in enumerate(constraints) if rows[i + 1] - rows[i] == 1 and not any(
        ca.depends_on(ca.SX(e), x_hat) for e in (c.limit, _scale(c)))]
    pairs, used = [], set()
    for i in (i for i in single if constraints[i].sense == "<="):
        for j in (j for j in single if constraints[j].sense == ">=" and j not in used):
            if ca.is_equal(ca.SX(constraints[i].value), ca.SX(constraints[j].value), DEPTH):
                pairs.append((int(rows[j]), int(rows[i])))
                used.add(j)
                break
    return pairs


class TwoSided:
    """The rows of a posed NLP held from both sides (:func:`held_from_both_sides`), and the maps between the named
    rows' bounds and multipliers and the solvers': a pair whose limits are one value (or conflict) posed as its kept
    row with both limits and its other row free; every other row, and every pair with room between its limits, as
    it is (the same arrays: nothing changes for the formulations without a pair)."""

    def __init__(self, constraints, x_hat, p: ca.SX, lbg: np.ndarray):
        rows = np.cumsum([0] + [ca.SX(c.normalised()).shape[0] for c in constraints])  # each constraint's first row
        self.pairs = held_from_both_sides(constraints, x_hat, rows)
        self.lbg = lbg  # the named rows' (-inf for g <= 0, 0 for equalities)
        if not self.pairs:
            return
        by_row = dict(zip(rows.tolist(), constraints))
        self.kept, self.freed = (np.array([pair[side] for pair in self.pairs]) for side in (0, 1))
        k_c, f_c = [by_row[k] for k in self.kept], [by_row[f] for f in self.freed]
        ratio = ca.vertcat(*[ca.SX(_scale(b)) / ca.SX(_scale(a)) for a, b in zip(k_c, f_c)])  # S_f / S_k
        lower = ca.vertcat(*[(1 if b.sense == "<=" else -1) * (ca.SX(a.limit) - ca.SX(b.limit)) / ca.SX(_scale(a))
                             for a, b in zip(k_c, f_c)])  # g_f <= 0: g_k >= s_f (L_k - L_f) / S_k
        self.coefficients = ca.Function("two_sided_coefficients", [p], [lower, ratio])
        self._last = (None, None)  # the coefficients at the last NumPy p (a solve's runs share their p)
        n, kept, freed = len(lbg), self.kept.tolist(), self.freed.tolist()
        one, crossed = lower >= -ROOM, _crossed(ca.fmax(lower, 0), ratio)
        lbg_s, ubg_s = ca.SX(ca.DM(lbg)), ca.SX.zeros(n)
        lbg_s[kept] = ca.if_else(one, ca.fmin(lower, 0) + crossed, -ca.inf)
        ubg_s[kept] = ca.if_else(one, crossed, 0)
        ubg_s[freed] = ca.if_else(one, ca.inf, 0)
        lam = ca.SX.sym("lam", n)
        merged, split = ca.SX(lam), ca.SX(lam)
        merged[kept] = ca.if_else(one, lam[kept] - lam[freed] / ratio, lam[kept])
        merged[freed] = ca.if_else(one, 0, lam[freed])
        split[kept] = ca.if_else(one, ca.fmax(lam[kept], 0), lam[kept])
        split[freed] = ca.if_else(one, ca.fmax(-lam[kept], 0) * ratio, lam[freed])
        self.bounds_of = ca.Function("two_sided_bounds", [p], [lbg_s, ubg_s])
        self.posed_of = ca.Function("two_sided_posed", [lam, p], [merged])
        self.named_of = ca.Function("two_sided_named", [lam, p], [split])

    def bounds(self, p, ubg=0.0):
        """The solvers' ``(lbg, ubg)`` at the NLP parameters ``p`` (NumPy, or CasADi symbols); ``ubg`` the named
        rows' (0, or +inf where a row is left out of a solve: the polish; a pair's other side left out, its limit
        too)."""
        if not self.pairs:
            return self.lbg, ubg
        if _symbolic(p):
            return self.bounds_of(p)
        one, lower, ratio = self._at(p)
        if not one.any():
            return self.lbg, ubg
        kept, freed, lower = self.kept[one], self.freed[one], lower[one]
        lbg, ubg = self.lbg.copy(), np.broadcast_to(np.asarray(ubg, dtype=float), self.lbg.shape).copy()
        out_kept, out_freed = np.isinf(ubg[kept]), np.isinf(ubg[freed])
        crossed = np.where(out_kept | out_freed, 0.0, _crossed(np.maximum(lower, 0.0), ratio[one]))  # (where both
        # sides are posed: one left out, the other at its own limit)
        lbg[kept] = np.where(out_freed, -np.inf, np.where(out_kept, lower, np.minimum(lower, 0.0) + crossed))
        ubg[kept] = np.where(out_kept, np.inf, crossed)
        ubg[freed] = np.inf
        return lbg, ubg

    def conflicts(self, p: np.ndarray, tolerance: float) -> list[tuple[int, int, float]]:
        """The pairs whose limits leave no room between them at ``p`` (the lower one above the upper by more than
        ``tolerance``, the float64 re-check's, allows on both rows: no design meets both): ``(kept row, other row, how
        far apart, relative to the kept row's scale)``. The solvers see the kept row where the two rows cross there
        (a well-posed NLP, lbg <= ubg), the float64 re-check one row broken; the verdict is given without a solve
        (``diagnosis.whatever_the_design``). Limits apart by less (ball_compressor's paper K5 0.8 and a
        width_ratio_max 1.5e-8 below: each row 7.5e-9 short at the crossing) are met, within the check's tolerance."""
        if not self.pairs:
            return []
        _, lower, ratio = self._at(np.asarray(p, dtype=float))
        return [(int(k), int(f), float(gap)) for k, f, gap, r in zip(self.kept, self.freed, lower, ratio)
                if _apart(gap, r, tolerance)]

    def conflicting(self, p: np.ndarray, tolerance: float) -> np.ndarray:
        """Whether any pair's limits leave no room between them (as :meth:`conflicts`) at each column of ``p`` (the
        parameter vectors of a run of a sweep's points), the coefficients evaluated in one call over all columns (the
        same function column by column: the same bits; a call a point had cost 40 us, 4 of the ball's 35 ms over
        9.3x-18.7x its power)."""
        if not self.pairs:
            return np.zeros(p.shape[1], dtype=bool)
        lower, ratio = (v.full() for v in self.coefficients(p))
        return np.any(_apart(lower, ratio, tolerance), axis=0)

    def posed(self, lam_g, p):
        """Named rows' multipliers (each >= 0 on its own row) as the solvers' (a two-sided row's signed)."""
        return self._mapped(lam_g, p, "posed_of", lambda lam, kept, freed, ratio: (lam[kept] - lam[freed] / ratio,
                                                                                    0.0))

    def named(self, lam_g, p):
        """The solvers' multipliers as the named rows' (a two-sided row's split by sign onto the side it presses)."""
        return self._mapped(lam_g, p, "named_of", lambda lam, kept, freed, ratio: (
            np.maximum(lam[kept], 0.0), np.maximum(-lam[kept], 0.0) * ratio))

    def _mapped(self, lam_g, p, symbolic: str, pair):
        """``lam_g`` mapped at ``p``: by the CasADi map named ``symbolic`` (built where there are pairs; the chained
        SQP's expressions), else in NumPy, each pair whose limits are one value given ``pair(lam_g, kept rows, other
        rows, S_f / S_k)``'s values on its kept and other row (3-8 us a solver call; the CasADi map's call cost about
        50); the identity where no pair is one row."""
        if not self.pairs:
            return lam_g
        if _symbolic(p):
            return getattr(self, symbolic)(lam_g, p)
        one, _, ratio = self._at(p)
        if not one.any():
            return lam_g
        kept, freed = self.kept[one], self.freed[one]
        mapped = np.array(lam_g, dtype=float)
        mapped[kept], mapped[freed] = pair(lam_g, kept, freed, ratio[one])
        return mapped

    def _at(self, p: np.ndarray) -> tuple[np.ndarray, ...]:
        """(whether the pair's limits are one value, the kept row's lower limit, S_f / S_k) of each pair at ``p``,
        evaluated once per p."""
        key = np.asarray(p, dtype=float).tobytes()
        if self._last[0] != key:
            lower, ratio = (v.full().ravel() for v in self.coefficients(p))
            self._last = (key, (lower >= -ROOM, lower, ratio))
        return self._last[1]


def _apart(lower, ratio, tolerance: float):
    """Limits that leave no room between them: the kept row's lower limit ``lower`` (in its scale) above 0 by more
    than ``tolerance`` allows on both rows (``ratio``: S_f / S_k); floats or arrays."""
    return lower > tolerance * (1.0 + ratio)


def _crossed(apart, ratio):
    """Where limits ``apart`` (>= 0: the other row's limit above the kept row's, in its scale) pose the kept row: the
    value of g_k at which both rows are violated alike (g_k = g_f = apart / (1 + S_f / S_k)); 0 where they leave room
    (apart 0)."""
    return apart / (1.0 + ratio)


def _symbolic(p) -> bool:
    return isinstance(p, (ca.MX, ca.SX))
