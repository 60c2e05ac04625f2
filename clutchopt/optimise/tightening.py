"""Whether a sweep's step only tightens the constraints, so that what no design met before none meets after.

Along a sweep of case quantities the design's bounds stay put and only the constraints move. Where every constraint
that the varied quantities enter does so through its limit alone, a function of case values only (the ball's torque
row: the torque the design carries, ``value``, against the rated torque k_s P / w, ``limit``: the power enters the
limit, no design variable does), the step from point j to point k moves each such limit by the same amount for every
design. If each moved limit is at least as tight at k (``at_least``: not lower; ``at_most``: not higher; its scale,
the row's normaliser, positive at both), the designs that meet every constraint at k are a subset of those at j:
an integer choice left without a design at j (IPOPT: ``Infeasible_Problem_Detected``; or its least violation,
``clutchopt.optimise.feasibility``) is left without one at k by the same verdict, and need not be solved again
(``clutchopt.optimise.batch``: the ball's row fewer, promised by the bound multiplier of its rows at every point
past 4.6x its power and infeasible at each). Where a varied quantity enters a constraint's value, or a limit or
scale that a design variable enters, the step's effect depends on the design and nothing is concluded
(:attr:`Tightening.known` is false).

A proof of infeasibility (``clutchopt.optimise.interval_proof``: over the whole design box some row breaks by more
than a tolerance of its scale, g = (value - limit) / scale > tol for ``<=``) holds after such a step too where each
moved row's scale is its limit (scale = limit > 0: value > (1 + tol) limit_j >= (1 + tol) limit_k) or is not moved
(a row :attr:`Tightening.sloped` is not): what a proof rules out at point j stays ruled out at every point the sweep has
only tightened since (``clutchopt.optimise.region_proof``).

Where a varied quantity enters a row's value (the cable's torque: the stress in its cables, clamp screws and fingers,
eqs. (18), (20), (22); a friction coefficient, a density, a ratio of the geometry), or its limit or scale holds a
design variable, a proof still holds where every row the step moves can only break more along it for every design of
the box (:class:`Slopes`): the interval bound of each normalised row's slope in each moved quantity, over the design
box and the hull of the two points' values, has the sign of that quantity's step (a row whose limit and scale hold no
design variable: its value's slope, its limit compared, ``Tightening.valued``). By the mean value theorem G(x, p_k) -
G(x, p_j) = dG/dp(x, xi) (p_k - p_j) for some xi between them, so G(x, p_k) >= G(x, p_j) > tol wherever the proof
broke a row at j; the rows are continuous (no jump a slope misses: a row with an operation outside :data:`CONTINUOUS`,
a comparison, a floor, a sign or atan2, concludes nothing).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from clutchopt.model import namespace
from clutchopt.optimise.interval import IntervalFunction

CONTINUOUS = frozenset(getattr(ca, f"OP_{name}") for name in (
    "INPUT", "OUTPUT", "CONST", "PARAMETER", "ASSIGN", "ADD", "SUB", "MUL", "DIV", "NEG", "INV", "TWICE", "SQ", "SQRT",
    "POW", "CONSTPOW", "EXP", "EXPM1", "LOG", "LOG1P", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "SINH", "COSH",
    "TANH", "ASINH", "ACOSH", "ATANH", "FABS", "FMIN", "FMAX", "HYPOT", "ERF"))  # operations continuous where they are
# defined (a pole within a hull leaves its slope unbounded): a row holding any other (a comparison, floor, sign,
# atan2 across its cut) may jump by more than its slope says


class Tightening:
    """For a posed problem's formulation and the varied quantities (``varied``, names): :meth:`tightened` says
    whether the step between two points' case values (all quantities, SI, in the formulation's order) only
    tightens the constraints the varied quantities enter. ``sloped``: the rows (of the normalised rows, flattened)
    whose step a proof needs the slopes of (:class:`Slopes`): a design variable in the limit or scale, or a scale the
    step moves apart from its limit; ``valued``: the rows a varied quantity moves through their value, their limit
    and scale free of the design and the scale their limit or not moved, whose value's slope a proof needs, their
    limits compared; the others' limits are compared (:meth:`held_from`)."""

    def __init__(self, posed, varied):
        f = posed.formulation
        x = namespace({v.name: ca.SX.sym(v.name) for v in f.variables})
        p_all = ca.SX.sym("p", len(f.quantities))
        p = namespace({q.name: p_all[j] for j, q in enumerate(f.quantities)})
        self.moved = np.array([j for j, q in enumerate(f.quantities) if q.name in set(varied)], dtype=int)
        moved = p_all[self.moved.tolist()]
        design = ca.vertcat(*vars(x).values())
        limits, scales, senses, self.sloped, self.valued, normalised, rising, row = [], [], [], [], [], [], [], 0
        self.varies = moved.numel() > 0
        unknown, self.moves = False, False  # (a row the step moves by what the design makes of it; a limit it moves)
        for c in f.constraints(x, p):
            value, limit = ca.SX(c.value), ca.SX(c.limit)
            scale = limit if c.scale is None else ca.SX(c.scale)
            normalised.append(ca.SX(c.normalised())), rising.append(_rising_value(value, c.sense, normalised[-1]))
            rows, row = list(range(row, row + normalised[-1].numel())), row + normalised[-1].numel()
            if not any(ca.depends_on(e, moved) for e in (value, limit, scale)):
                continue  # the step leaves it as it is
            apart = c.scale is not None and ca.depends_on(scale, moved)  # (its proof's tolerance moves apart from its
            # limit: a proof needs its slope)
            designed = ca.depends_on(limit, design) or ca.depends_on(scale, design)  # (a limit the design makes)
            if ca.depends_on(value, moved) or designed:
                unknown = True  # the step moves it by what the design makes of it
                if apart or designed:
                    self.sloped += rows
                    continue
                self.valued += rows  # (its value by its slope, its limit compared)
            elif apart:
                self.sloped += rows
            self.moves |= ca.depends_on(limit, moved) or ca.depends_on(scale, moved)
            limits.append(limit), scales.append(scale * ca.DM.ones(limit.shape))
            senses.append(np.full(limit.numel(), 1.0 if c.sense == ">=" else -1.0))
        self.known = self.varies and not unknown
        self.symbols = (design, p_all)  # (the rows' and values' symbols: :class:`Slopes`)
        self.normalised, self.rising = ca.vertcat(ca.SX(0, 1), *normalised), ca.vertcat(ca.SX(0, 1), *rising)
        self._senses = np.concatenate(senses) if senses else np.zeros(0)
        self._limits = ca.Function("tightening", [p_all], [ca.vertcat(ca.SX(0, 1), *limits),
                                                           ca.vertcat(ca.SX(0, 1), *scales)])

    def tightened(self, before: np.ndarray, after: np.ndarray) -> bool:
        """Every constraint the varied quantities enter is at least as tight with the case values ``after`` as
        with ``before`` (and the step moves no other)."""
        if not self.known:
            return False
        (limit_before, scale_before), (limit_after, scale_after) = (
            (np.asarray(v, dtype=float).ravel() for v in self._limits(values)) for values in (before, after))
        return self.holds(limit_before, scale_before, limit_after, scale_after)

    def holds(self, limit_before, scale_before, limit_after, scale_after) -> bool:
        """:meth:`tightened` on the limits and scales of the constraints the varied quantities enter, before and
        after the step (:meth:`limits`): :meth:`held_from` of the one step."""
        limits, scales = np.column_stack([limit_before, limit_after]), np.column_stack([scale_before, scale_after])
        return self.held_from(limits, scales, 0, 1) == 2

    def held_from(self, limits: np.ndarray, scales: np.ndarray, j: int, k: int) -> int:
        """The first point from k on (in :meth:`limits`' columns) whose step from point j does not only tighten
        the limits compared (each moved limit not looser for its sense, each scale positive at both; the rows
        ``sloped`` are not among them); the number of points where every one does."""
        before, scale = limits[:, j:j + 1], scales[:, j:j + 1]
        held = (np.all(scale > 0) & np.all(scales[:, k:] > 0, axis=0)
                & np.all(self._senses[:, None] * (limits[:, k:] - before) >= 0, axis=0))
        return k + (int(np.argmin(held)) if not held.all() else held.size)

    def limits(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The limits and scales of the constraints the varied quantities enter at each point (``points``: a row of
        case values each, as :meth:`tightened` takes them), by one mapped evaluation: a column per point each (the
        same numbers as :meth:`tightened` evaluates point by point)."""
        limits, scales = self._limits.map(len(points))(np.asarray(points, dtype=float).T)
        return np.asarray(limits, dtype=float), np.asarray(scales, dtype=float)


def tightening(posed, varied) -> Tightening:
    """The :class:`Tightening` of a posed problem along the quantities ``varied``, built once."""
    return posed.built("tightening", tuple(sorted(varied)), lambda _: Tightening(posed, varied))


class Slopes:
    """For a :class:`Tightening` ``t`` (a formulation and its varied quantities), the rows whose normalised form a
    proof needs the slope of (``t.sloped``) and the rows whose value it needs the slope of (``t.valued``; indices of
    the normalised rows, flattened): :meth:`held_from` says up to which point they keep a proof of infeasibility at
    point j: each normalised row ``g <= 0`` (the form a proof breaks, ``Constraint.normalised``) of ``t.sloped``
    rises along the step for every design of the box, each value of ``t.valued``
    does not fall (``<=``) or rise (``>=``): the interval bounds of its slope in each moved quantity, over the box and
    the hull of the two points' values, of that quantity's step's sign. With a limit no lower (``<=``: higher for
    ``>=``) and positive where it is its row's scale, or a scale not moved (``Tightening.held_from``), such a row
    breaks at k by as much as at j at least (``>=``, scaled by its limit: g = 1 - v / l, at k 1 or more where v <= 0,
    else v_k / l_k <= v_j / l_j), without the dependency of a quotient's interval bound (the ball's torque row over
    its power and friction coefficient: 1 - T(x, f) / T_req(P), whose slope in P spans zero)."""

    def __init__(self, t: Tightening):
        design, p_all = t.symbols
        self._moved = t.moved
        rows = ca.vertcat(ca.SX(0, 1), *(t.normalised[i] for i in t.sloped), *(t.rising[i] for i in t.valued))
        function = ca.Function("rows", [design, p_all], [rows])
        jumps = {function.instruction_id(k) for k in range(function.n_instructions())} - CONTINUOUS
        self._rows = rows.numel()
        self._slopes = None if jumps or not self._moved.size else IntervalFunction(ca.Function(
            "slopes", [design, p_all], [ca.densify(ca.jacobian(rows, p_all[self._moved.tolist()]))]))

    def held_from(self, values: np.ndarray, lower: np.ndarray, upper: np.ndarray, j: int, k: int, count: int) -> int:
        """The first point from k on (``values``: a row of case values a point, SI, in the formulation's order) whose
        step from point j may lower some row, or move some value away from breaking its row, for a design of the box
        [``lower``, ``upper``] (SI), looking ``count`` points ahead at most; k where no slope is bounded (a row that
        jumps, none moved)."""
        ahead = values[k:k + count]
        if self._slopes is None or not len(ahead):
            return k
        before, boxes = values[j], len(ahead)
        hull = (np.minimum(before, ahead).T, np.maximum(before, ahead).T)
        (low, high), = self._slopes.bounds([(np.repeat(lower[:, None], boxes, 1),
                                             np.repeat(upper[:, None], boxes, 1)), hull])
        shape = (self._moved.size, self._rows, boxes)  # (the Jacobian's nonzeros by column: a moved quantity each)
        low, high = low.reshape(shape).min(axis=1), high.reshape(shape).max(axis=1)
        step = (ahead - before)[:, self._moved].T
        held = np.all((step == 0) | (step > 0) & (low >= 0) | (step < 0) & (high <= 0), axis=0)
        return k + (int(np.argmin(held)) if not held.all() else held.size)


def _rising_value(value: ca.SX, sense: str, normalised: ca.SX) -> ca.SX:
    """A constraint's value, a row each of its ``normalised`` rows (a scalar value beside a vector limit repeated),
    signed to rise where the row breaks more: as it is for ``<=``, negated for ``>=``."""
    value = value if value.numel() == normalised.numel() else ca.repmat(value, normalised.numel(), 1)
    return value if sense == "<=" else -value


def slopes(posed, varied) -> Slopes:
    """The :class:`Slopes` of a posed problem's rows :func:`tightening` cannot compare along the quantities
    ``varied``, built once."""
    return posed.built("slopes", tuple(sorted(varied)), lambda _: Slopes(tightening(posed, varied)))


class ProofCarry:
    """Along a sweep's points (``values``: a row of case values a point, SI, in the formulation's order; the
    quantities ``varied``): up to which point a proof of infeasibility at point j holds (:meth:`held_from`), by the
    limits :class:`Tightening` compares and the slopes of the rows and values it cannot compare
    (``Tightening.sloped``, ``valued``: :class:`Slopes`), both worked out once a sweep."""

    def __init__(self, posed, varied, values: np.ndarray):
        self.tightening = tightening(posed, varied)
        self._values, self._limits = values, self.tightening.limits(values)
        t = self.tightening
        self.slopes = slopes(posed, varied) if t.sloped or t.valued else None

    def held_from(self, lower: np.ndarray, upper: np.ndarray, j: int, k: int, count: int) -> int:
        """The first point from k on at which point j's proof may not hold (the design box [``lower``, ``upper``],
        SI; the slopes looked at ``count`` points ahead at most); k where the sweep varies nothing."""
        if not self.tightening.varies:
            return k
        end = self.tightening.held_from(*self._limits, j, k)
        return end if self.slopes is None or end == k else min(
            end, self.slopes.held_from(self._values, lower, upper, j, k, count))

    @property
    def how(self) -> str:
        """Why the proof holds, in words: the limits compared, the values and the rows bounded by their slopes
        (review 22d: a split row's value is bounded, not its row)."""
        t, every = self.tightening, "for every design within the bounds"
        parts = (["every limit {} at least as tight at each"] if t.moves else []) + (
            [f"each value {{}} going no further within its limit {every}"] if t.valued else []) + (
            [f"each {'other ' if t.moves or t.valued else ''}row {{}} rising along it {every}"] if t.sloped else [])
        return ", and ".join(part.format("the sweep moves" if i == 0 else "it moves")
                             for i, part in enumerate(parts)) or "the sweep moves no limit"
