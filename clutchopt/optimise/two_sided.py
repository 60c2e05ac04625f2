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
    """Pairs of row indices ``(upper, lower)``: a ``<=`` constraint and a ``>=`` constraint on the same value
    expression, one row each, their limits and scales free of the design ``x_hat``; each row in one pair at most."""
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
        lbg_posed[at] = lower
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
        lbg, posed_ubg = self.bounds_of(p)
        if isinstance(p, (ca.MX, ca.SX)):
            return lbg, posed_ubg
        lbg, posed_ubg = lbg.full().ravel(), posed_ubg.full().ravel()
        ubg = np.broadcast_to(np.asarray(ubg, dtype=float), self.lbg.shape)
        lbg[[a for a, f in zip(self.at, self.freed) if np.isinf(ubg[f])]] = -np.inf
        return lbg, np.maximum(posed_ubg, ubg[self.rows])

    def posed(self, lam_g, p):
        """Named rows' multipliers (each >= 0 on its own row) as the solvers' (a two-sided row's signed)."""
        return self._mapped("posed_of", lam_g, p)

    def named(self, lam_g, p):
        """The solvers' multipliers as the named rows' (split by sign onto the side that is active)."""
        return self._mapped("named_of", lam_g, p)

    def values(self, g, p):
        """The solvers' row values as the named rows' (a left-out row's from its kept one)."""
        return self._mapped("values_of", g, p)

    def _mapped(self, function: str, lam_g, p):
        if not self.pairs:
            return lam_g
        out = getattr(self, function)(lam_g, p)
        return out if isinstance(out, (ca.MX, ca.SX)) else out.full().ravel()
