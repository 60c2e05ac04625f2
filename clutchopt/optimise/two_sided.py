"""A quantity held from both sides, posed once: one two-sided row ``lbg <= g <= 0`` of the scaled NLP.

A formulation names its constraints one-sided, ``value <= limit`` or ``value >= limit``, each normalised by its own
scale into a row ``g <= 0`` (``Constraint.normalised``). Where two constraints hold the same quantity (the same
``value`` expression) from above and from below - the ball's paper mode, K5 = l / R_a at least the paper's K5
(``width_ratio``) and at most the case's ``width_ratio_max`` - their rows are g_u = (v - L_u) / S_u and
g_l = (L_l - v) / S_l = (L_l - L_u - S_u g_u) / S_l: g_l <= 0 is g_u >= (L_l - L_u) / S_u. The solvers see the
upper row with that lower limit and the lower row free (-inf <= g_l <= inf), so IPOPT has an interior wherever
L_l < L_u and, where the two limits are one value (the ball compressor: 0.8 and 0.8), an equality row instead of two
opposite rows g and -g that left it none (multipliers 4.8e9, 30 iterations instead of 8; docs/tradeoffs.md).

The NLP itself (its rows, derivatives, compiled code) is the same: only its row bounds and multipliers are posed
so. Everything apart from the solvers (the float64 re-check, the KKT verdict, the diagnosis, the proofs) sees the
named rows, one-sided, each with its own multiplier: the two-sided row's multiplier lam splits by sign onto the
side that is active, lam_u = max(lam, 0) and lam_l = max(-lam, 0) S_l / S_u (the Lagrangian's lam_u g_u + lam_l g_l
is (lam_u - lam_l S_u / S_l) g_u + const). A pair is posed so only where both limits and scales are free of the
design (else the lower limit of g_u would move with it).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

DEPTH = 100  # how deep two value expressions are compared (``ca.is_equal``): a formulation's quantities are a few
#              operations deep (K5 = l / R_a: one)


def _scale(constraint):
    return constraint.limit if constraint.scale is None else constraint.scale


def held_from_both_sides(constraints, x_hat) -> list[tuple[int, int]]:
    """Pairs of row indices ``(kept, other)``: a ``>=`` constraint's row, which the solvers keep, and a ``<=``
    constraint's on the same value expression, one row each, their limits and scales free of the design ``x_hat``;
    each row in one pair at most."""
    rows = np.cumsum([0] + [ca.SX(c.normalised()).shape[0] for c in constraints])
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
    rows (their values, bounds and multipliers) and the rows the solvers see: each pair's kept row with both limits,
    its other row left out. Without such a pair every map is the identity (the same arrays: nothing changes for the
    formulations without one)."""

    def __init__(self, constraints, x_hat, p: ca.SX, lbg: np.ndarray):
        self.pairs = held_from_both_sides(constraints, x_hat)
        self.lbg = lbg  # the named rows' (-inf for g <= 0, 0 for equalities)
        if not self.pairs:
            return
        n = len(lbg)
        by_row = dict(zip(np.cumsum([0] + [ca.SX(c.normalised()).shape[0] for c in constraints]).tolist(),
                          constraints))
        kept, freed = ([int(pair[side]) for pair in self.pairs] for side in (0, 1))
        self.rows = [i for i in range(n) if i not in freed]  # the solvers' rows, in their order
        at = [self.rows.index(k) for k in kept]  # each kept row's place among them
        k_c, f_c = [by_row[k] for k in kept], [by_row[f] for f in freed]
        # g_f = s_f (v - L_f) / S_f with v = L_k + s_k S_k g_k: g_f = s_f (L_k - L_f) / S_f - g_k / ratio
        ratio = ca.vertcat(*[ca.SX(_scale(b)) / ca.SX(_scale(a)) for a, b in zip(k_c, f_c)])  # S_f / S_k
        offset = ca.vertcat(*[(1 if b.sense == "<=" else -1) * (ca.SX(a.limit) - ca.SX(b.limit)) / ca.SX(_scale(b))
                              for a, b in zip(k_c, f_c)])
        lower = offset * ratio  # g_f <= 0: g_k >= s_f (L_k - L_f) / S_k
        lbg_posed, ubg_posed = ca.SX(ca.DM(lbg[self.rows])), ca.SX.zeros(len(self.rows))
        lbg_posed[at] = ca.fmin(lower, 0)  # (limits with no room between: the kept row's limit, :meth:`conflicts`)
        lam, posed = ca.SX.sym("named", n), ca.SX.sym("posed", len(self.rows))  # (multipliers or values)
        merged = lam[self.rows]
        merged[at] = lam[kept] - lam[freed] / ratio
        split, g_full = ca.SX.zeros(n), ca.SX.zeros(n)
        split[self.rows] = posed
        split[kept] = ca.fmax(posed[at], 0)
        split[freed] = ca.fmax(-posed[at], 0) * ratio
        g_full[self.rows] = posed
        g_full[freed] = offset - posed[at] / ratio
        self.at, self.kept, self.freed = at, kept, freed
        self.coefficients = ca.Function("two_sided_coefficients", [p], [lower, ratio, offset])
        self._last = (None, None)  # the coefficients at the last NumPy p (a solve's runs share their p)
        self.bounds_of = ca.Function("two_sided_bounds", [p], [lbg_posed, ubg_posed])
        self.posed_of = ca.Function("two_sided_posed", [lam, p], [merged])
        self.named_of = ca.Function("two_sided_named", [posed, p], [split])
        self.values_of = ca.Function("two_sided_values", [posed, p], [g_full])

    def nlp(self, nlp: dict) -> dict:
        """The NLP the solvers see: ``nlp`` with each pair's other row left out."""
        return {**nlp, "g": nlp["g"][self.rows]} if self.pairs else nlp

    def bounds(self, p, ubg=0.0):
        """The solvers' ``(lbg, ubg)`` at the NLP parameters ``p`` (NumPy, or CasADi symbols); ``ubg`` the named
        rows' (0, or +inf where a row is left out of a solve: a side of a two-sided row left out, its limit too)."""
        if not self.pairs:
            return self.lbg, ubg
        if _symbolic(p):
            return self.bounds_of(p)[:2]
        lower = self._at(p)[0]
        lbg = self.lbg[self.rows].copy()
        lbg[self.at] = np.minimum(lower, 0.0)  # (limits with no room between: :meth:`conflicts`)
        ubg = np.broadcast_to(np.asarray(ubg, dtype=float), self.lbg.shape)
        lbg[[a for a, f in zip(self.at, self.freed) if np.isinf(ubg[f])]] = -np.inf
        return lbg, np.maximum(0.0, ubg[self.rows])

    def conflicts(self, p: np.ndarray, tolerance: float) -> list[tuple[int, int, float]]:
        """The pairs whose limits leave no room between them at ``p`` (the lower one above the upper: no design meets
        both): ``(kept row, other row, how far apart, relative to the kept row's scale)``. The solvers see the kept
        row at its own limit there (a well-posed NLP, lbg <= ubg), the float64 re-check the other row broken; the
        verdict is given without a solve (``diagnosis.whatever_the_design``)."""
        if not self.pairs:
            return []
        lower = self._at(np.asarray(p, dtype=float))[0]
        return [(k, f, float(gap)) for k, f, gap in zip(self.kept, self.freed, lower) if gap > tolerance]

    def posed(self, lam_g, p):
        """Named rows' multipliers (each >= 0 on its own row) as the solvers' (a two-sided row's signed)."""
        if not self.pairs or _symbolic(p):
            return self.posed_of(lam_g, p) if self.pairs else lam_g
        merged = lam_g[self.rows].copy()
        merged[self.at] = lam_g[self.kept] - lam_g[self.freed] / self._at(p)[1]
        return merged

    def named(self, lam_g, p):
        """The solvers' multipliers as the named rows' (split by sign onto the side that is active)."""
        if not self.pairs or _symbolic(p):
            return self.named_of(lam_g, p) if self.pairs else lam_g
        split = self._full(lam_g)
        split[self.kept] = np.maximum(lam_g[self.at], 0.0)
        split[self.freed] = np.maximum(-lam_g[self.at], 0.0) * self._at(p)[1]
        return split

    def values(self, g, p):
        """The solvers' row values as the named rows' (a left-out row's from its kept one)."""
        if not self.pairs:
            return g
        _, ratio, offset = self._at(p)
        full = self._full(g)
        full[self.freed] = offset - g[self.at] / ratio
        return full

    def _full(self, posed: np.ndarray) -> np.ndarray:
        full = np.zeros(len(self.lbg))
        full[self.rows] = posed
        return full

    def _at(self, p: np.ndarray) -> tuple[np.ndarray, ...]:
        """(lower, ratio, offset) of each pair at ``p``, evaluated once per p."""
        key = np.asarray(p, dtype=float).tobytes()
        if self._last[0] != key:
            self._last = (key, tuple(v.full().ravel() for v in self.coefficients(p)))
        return self._last[1]


def _symbolic(p) -> bool:
    return isinstance(p, (ca.MX, ca.SX))
