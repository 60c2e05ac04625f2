"""Boxes contracted by propagating each row's limit back through its own expression (HC4-revise).

The rows' function is replayed forward over a box (:mod:`clutchopt.optimise.interval`'s rules, each operation's
result kept), then each row's bound ``g <= limit`` is carried back through the operations to their arguments: where
z = x * y holds and z, y are bounded, x lies in z / y; where z = sin(x) with x within [-pi/2, pi/2], x lies in
asin(z); and so on (Benhamou, Goualard, Granvilliers & Puget, "Revising hull and box consistency", ICLP 1999). Every
design variable ends bounded by what each row allows, one row at a time (the rows that cut or empty a box are named
in the proof, as :mod:`clutchopt.optimise.interval_contract`'s are). Each bound is
widened outwards by ``_SLACK`` of its magnitude (NumPy's inverse functions and powers are faithful, not correctly
rounded), so a design is never cut away; an operation without a rule here cuts nothing. Where the forward replay is
compiled, the backward pass is too (:meth:`Tape.revised`; :class:`clutchopt.optimise.interval_compiled.CompiledRevise`,
the same rules in C); :meth:`Tape.backward` is the reference.

Where a row is a product of variables over wide ranges (the lever's torque, m z w^2 R_0 d_cp / (4 tan gamma_0),
against its weights' fit z (m / rho)^(1/3) <= k 2 pi R_0), the mean-value form's slopes span orders of magnitude and
cut little; propagated back, each row bounds the weight's mass by the others' ends at once (m <= rho (k 2 pi R_0 /
z)^3 from the fit, m >= ... from the torque), and a conflict between them empties the box without bisecting it.
"""

from __future__ import annotations

from functools import cached_property

import casadi as ca
import numpy as np

from clutchopt.optimise.interval import _BINARY, _LOGICAL, _NOT, _UNARY, _WIDEN, Bounds, _inverse, _outward, _products
from clutchopt.optimise.interval_compiled import CompiledReplay, CompiledRevise, replay_library, revise_library
from clutchopt.optimise.interval_contract import _CUT, _SLACK

_HALF_PI = 0.5 * np.pi


FLOOR = 1e-300  # the least any bound a rule reads is widened by (absolute): the forward rules round a result that
# underflows (exp(-745) = 2.1e-324 bounded from 5e-324) within a tiny absolute error but not within a relative one,
# and carried back through a log or a division such an error becomes a cut of the design (review 20c: exp(x0) x1 <= 1
# with x0 in [-745, -740] had emptied a box that x0 = -745 meets)


def _floored(bound: Bounds) -> Bounds:
    """``bound`` widened outwards by FLOOR: a value a backward rule reads (its result's bound and its other
    operand's)."""
    return bound[0] - FLOOR, bound[1] + FLOOR


def _within(a: Bounds, low: float, high: float) -> np.ndarray:
    return (a[0] >= low) & (a[1] <= high)


def _nothing(shape) -> Bounds:
    return np.full(shape, -np.inf), np.full(shape, np.inf)


def _back_unary(op: int, z: Bounds, x: Bounds) -> Bounds | None:
    """Where x may lie given z = op(x) in z (and x in x: the side of a function's branch); None: no rule."""
    if op == ca.OP_ASSIGN:
        return z
    if op == ca.OP_NEG:
        return -z[1], -z[0]
    if op == ca.OP_TWICE:
        return 0.5 * z[0], 0.5 * z[1]
    if op == ca.OP_INV:
        return _inverse(z)
    if op == ca.OP_SQRT:  # x >= 0 (the rule's domain)
        return np.square(np.maximum(z[0], 0.0)), np.where(z[1] >= 0, np.square(z[1]), -np.inf)
    if op == ca.OP_SQ:
        root = np.sqrt(np.maximum(z[1], 0.0))
        least = np.sqrt(np.maximum(z[0], 0.0))
        positive, negative = x[0] >= 0, x[1] <= 0
        return (np.where(positive, least, -root), np.where(negative, -least, root))
    if op == ca.OP_EXP:
        return np.log(np.maximum(z[0], 0.0)), np.log(np.maximum(z[1], 0.0))
    if op == ca.OP_LOG:
        return np.exp(z[0]), np.exp(z[1])
    if op == ca.OP_SIN:  # on the rising branch
        inside = _within(x, -_HALF_PI, _HALF_PI)
        return (np.where(inside, np.arcsin(np.clip(z[0], -1.0, 1.0)), -np.inf),
                np.where(inside, np.arcsin(np.clip(z[1], -1.0, 1.0)), np.inf))
    if op == ca.OP_COS:  # on the falling branch
        inside = _within(x, 0.0, np.pi)
        return (np.where(inside, np.arccos(np.clip(z[1], -1.0, 1.0)), -np.inf),
                np.where(inside, np.arccos(np.clip(z[0], -1.0, 1.0)), np.inf))
    if op == ca.OP_TAN:
        inside = _within(x, -_HALF_PI, _HALF_PI)
        return np.where(inside, np.arctan(z[0]), -np.inf), np.where(inside, np.arctan(z[1]), np.inf)
    return None


def _back_binary(op: int, z: Bounds, x: Bounds, y: Bounds) -> tuple[Bounds, Bounds] | None:
    """Where x and y may lie given z = op(x, y) in z; None: no rule."""
    if op == ca.OP_ADD:
        return (z[0] - y[1], z[1] - y[0]), (z[0] - x[1], z[1] - x[0])
    if op == ca.OP_SUB:
        return (z[0] + y[0], z[1] + y[1]), (x[0] - z[1], x[1] - z[0])
    if op == ca.OP_MUL:
        return _products(z, _inverse(y)), _products(z, _inverse(x))
    if op == ca.OP_DIV:
        return _products(z, y), _products(x, _inverse(z))
    if op in (ca.OP_POW, ca.OP_CONSTPOW):  # a constant positive exponent b, not a whole number: x >= 0, rising
        b = y[0]
        fits = (y[0] == y[1]) & (b > 0) & (np.round(b) != b)
        inverse = np.where(fits, 1.0 / np.where(fits, b, 1.0), 1.0)
        with np.errstate(invalid="ignore"):
            low = np.where(fits, np.power(np.maximum(z[0], 0.0), inverse), -np.inf)
            high = np.where(fits, np.where(z[1] >= 0, np.power(np.maximum(z[1], 0.0), inverse), -np.inf), np.inf)
        return (low, high), _nothing(np.shape(b))
    return None


def _compiled(function: ca.Function, steps: list) -> CompiledReplay | None:
    """The steps replayed forward by :mod:`clutchopt.optimise.interval_compiled` (the same rules in C), each
    writing a work variable of its own, all kept; None where no library can be had (NumPy, :meth:`Tape.forward`)."""
    library = replay_library(_WIDEN)
    program = [(op, read if op == ca.OP_INPUT else args, [k], constant)
               for k, (op, args, constant, read) in enumerate(steps)]
    return None if library is None else CompiledReplay(function, program, len(steps), library)


class Tape:
    """The rows' function as operations on values each kept (the function's work variables are reused): each
    operation's code, its arguments' positions on the tape, and the rows' positions."""

    def __init__(self, function: ca.Function, program: list):
        self.function = function
        writer: dict[int, int] = {}
        self.steps: list[tuple[int, tuple[int, ...], float, tuple[int, int] | None]] = []
        self.rows: dict[int, int] = {}
        for op, args, result, constant in program:
            if op == ca.OP_OUTPUT:
                if result[0] == 0:
                    self.rows[result[1]] = writer[args[0]]
                continue
            arguments = () if op in (ca.OP_INPUT, ca.OP_CONST) else tuple(writer[a] for a in args if a >= 0)
            read = (args[0], args[1]) if op == ca.OP_INPUT else None
            writer[result[0]] = len(self.steps)
            self.steps.append((op, arguments, constant, read))
        self.compiled = _compiled(function, self.steps)
        self.free = []  # which values depend on the design (the others, of parameters and constants, are not carried
        # back into: nothing of the design's bounds would follow)
        for op, arguments, _, read in self.steps:
            self.free.append(read[0] == 0 if op == ca.OP_INPUT else any(self.free[a] for a in arguments))

    @cached_property
    def subgraphs(self) -> list[list[int]]:
        """Each row's values (the row's own first, every value after those it is computed from: the order to carry
        the row back in)."""
        graphs = []
        for r in range(len(self.rows)):
            seen, stack = set(), [self.rows[r]]
            while stack:
                k = stack.pop()
                if k not in seen:
                    seen.add(k)
                    stack.extend(self.steps[k][1])
            graphs.append(sorted(seen, reverse=True))
        return graphs

    def revised(self, inputs: list[Bounds], limit: float, variables: int, rows: list[int]
                ) -> tuple[Bounds, np.ndarray]:
        """:meth:`backward` of :meth:`forward`'s values; both compiled where the forward replay is (the same
        rules in C: :class:`clutchopt.optimise.interval_compiled.CompiledRevise`), NumPy's otherwise."""
        if self.compiled is None:
            return self.backward(self.forward(inputs, rows), limit, variables, rows)
        (w_lo, w_hi), _, _ = self.compiled.replayed(self._all(inputs))
        return self._compiled_revise.backward(w_lo, w_hi, limit, variables, rows, _SLACK, FLOOR)

    @cached_property
    def _compiled_revise(self) -> CompiledRevise:
        return CompiledRevise(self.steps, self.rows, self.subgraphs, self.free, revise_library(_WIDEN))

    def _all(self, inputs: list[Bounds]) -> list[Bounds]:
        """``inputs`` and the function's others (none of the rows' own) as the compiled replay takes them."""
        empty = (np.zeros((0, inputs[0][0].shape[-1])),) * 2
        return [*inputs, *[empty] * (self.function.n_in() - len(inputs))]

    @np.errstate(all="ignore")
    def forward(self, inputs: list[Bounds], rows: list[int]) -> list[Bounds | None]:
        """The bounds over the boxes of each operation the ``rows`` depend on (``inputs`` as
        :meth:`IntervalFunction.bounds` takes them; None for the others)."""
        if self.compiled is not None:
            (w_lo, w_hi), _, _ = self.compiled.replayed(self._all(inputs))
            return list(zip(w_lo, w_hi))
        boxes = inputs[0][0].shape[-1]
        values: list[Bounds | None] = [None] * len(self.steps)
        used = sorted(set().union(*(self.subgraphs[r] for r in rows)))
        for k in used:
            op, args, constant, read = self.steps[k]
            if op == ca.OP_INPUT:
                values[k] = (inputs[read[0]][0][..., read[1], :], inputs[read[0]][1][..., read[1], :])
            elif op == ca.OP_CONST:
                values[k] = (np.full(boxes, constant), np.full(boxes, constant))
            elif op in _UNARY:
                values[k] = _outward(*_UNARY[op](values[args[0]]))
            elif op == ca.OP_NOT:
                values[k] = _NOT(values[args[0]])
            elif op in _LOGICAL:
                values[k] = _LOGICAL[op](values[args[0]], values[args[1]])
            elif op in _BINARY:
                values[k] = _outward(*_BINARY[op](values[args[0]], values[args[1]]))
            else:
                values[k] = _nothing(boxes)
        return values

    @np.errstate(all="ignore")
    def backward(self, values: list[Bounds | None], limit: float, variables: int, rows: list[int]
                 ) -> tuple[Bounds, np.ndarray]:
        """Each of the ``rows``' limit carried back alone through its own values (:meth:`forward`'s): the bounds
        each row allows the design variables (input 0; rows x variables x boxes, unbounded for the rows not
        carried back) and which rows leave a box no value of some operation (rows x boxes)."""
        m, boxes = len(self.rows), values[self.rows[rows[0]]][0].shape[-1]
        empty = np.zeros((m, boxes), dtype=bool)
        x_lo, x_hi = np.full((m, variables, boxes), -np.inf), np.full((m, variables, boxes), np.inf)
        for r in rows:
            row, nodes = self.rows[r], self.subgraphs[r]
            back: dict[int, Bounds] = {row: (values[row][0], np.minimum(values[row][1], limit))}
            for k in nodes:
                z = back.pop(k, None)
                if z is None:  # (a value this row's bound did not reach, or not of the design)
                    continue
                empty[r] |= z[0] > z[1]
                op, args, _, read = self.steps[k]
                if op == ca.OP_INPUT:
                    if read[0] == 0:  # (a variable read twice: both bounds hold)
                        x_lo[r, read[1]] = np.maximum(x_lo[r, read[1]], z[0])
                        x_hi[r, read[1]] = np.minimum(x_hi[r, read[1]], z[1])
                    continue
                current = [_floored(back.get(a, values[a])) for a in args]
                if len(args) == 1:
                    found = _back_unary(op, _floored(z), current[0])
                    found = None if found is None else (found,)
                else:
                    found = _back_binary(op, _floored(z), *current) if len(args) == 2 and op in _BINARY else None
                for a, bound in zip(args, found or ()):
                    if not self.free[a]:
                        continue
                    lo, hi = _outward(*bound, _SLACK)  # (NaN, no bound carried back: unbounded)
                    old = back.get(a, values[a])
                    back[a] = (np.fmax(old[0], lo), np.fmin(old[1], hi))
        return (x_lo, x_hi), empty


def contracted(tape: Tape, lo: np.ndarray, hi: np.ndarray, others: list[Bounds], limit: float,
               uncertain: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The boxes [lo, hi] (variables x boxes; ``others``: the function's further inputs' bounds, a column a box)
    contracted to the points where every row may be at most ``limit``, by each row's limit carried back
    (:class:`Tape`); the new ends, which boxes are empty, and the rows that cut or emptied each box (rows x boxes),
    as :func:`clutchopt.optimise.interval_contract.contracted` gives them. Only the rows ``uncertain`` in some box
    (rows x boxes: not met throughout it) are carried back: a row met throughout a box cuts none of it."""
    rows = np.flatnonzero(uncertain.any(axis=1)).tolist()
    if not rows:
        return lo, hi, np.zeros(lo.shape[1], dtype=bool), np.zeros(uncertain.shape, dtype=bool)
    (x_lo, x_hi), void = tape.revised([(lo, hi), *others], limit, lo.shape[0], rows)
    margin = _CUT * (hi - lo)
    cutters = void | np.any((x_hi < (hi - margin)[None]) | (x_lo > (lo + margin)[None]), axis=1)
    new_lo, new_hi = np.maximum(lo, x_lo.max(axis=0)), np.minimum(hi, x_hi.min(axis=0))
    empty = void.any(axis=0) | np.any(new_lo > new_hi, axis=0)
    return np.where(empty, lo, new_lo), np.where(empty, hi, new_hi), empty, cutters
