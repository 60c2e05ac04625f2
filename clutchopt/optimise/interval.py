"""Interval evaluation of a CasADi SX function: bounds on every output over boxes of its inputs, many boxes at once.

The function's own algorithm (``Function.instruction_*``) is replayed with interval arithmetic on NumPy arrays, one
interval ``[lo, hi]`` per box and work variable. Every operation's result is widened outwards by a few units in the
last place (NumPy's elementary functions are faithful, not correctly rounded), so a bound computed here holds for
every point of the box in exact arithmetic. An operation without an interval rule here gives the whole real line: a
bound that is true, if useless. Used to prove a design space empty (:mod:`clutchopt.optimise.interval_proof`).

This replay is the reference; :meth:`IntervalFunction.bounds` runs the same rules compiled, all boxes in one call
(:mod:`clutchopt.optimise.interval_compiled`), where a C compiler and a cache folder allow it.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from clutchopt.optimise.interval_compiled import CompiledReplay, replay_library

_WIDEN = 8 * np.finfo(float).eps  # relative outward widening of every result

Bounds = tuple[np.ndarray, np.ndarray]


def _outward(lo, hi, by: float = _WIDEN) -> Bounds:
    """[lo, hi] widened outwards by ``by`` of their magnitudes; NaN (an operation outside its domain on part of a box)
    becomes unbounded (fmax and fmin return the other argument for a NaN). A result that underflowed to zero stays
    zero: an error below 1e-300, which no verdict's tolerance can see."""
    return np.fmax(lo - np.abs(lo) * by, -np.inf), np.fmin(hi + np.abs(hi) * by, np.inf)


def _products(a: Bounds, b: Bounds) -> Bounds:
    """[a] * [b]: the extremes of the four corner products (0 * inf, a NaN, left out by fmin/fmax: the product of a
    zero end is zero, and another corner is as low or as high). Both non-negative in every box (the usual case): the
    products of the ends, which are those extremes unless one is 0 * inf; so a box's bounds never depend on the
    other boxes evaluated with it (a sweep's points are searched together: ``interval_proof.searches``)."""
    if a[0].min(initial=0.0) >= 0 and b[0].min(initial=0.0) >= 0:
        low, high = a[0] * b[0], a[1] * b[1]
        if not (np.isnan(low).any() or np.isnan(high).any()):
            return low, high
    p, q, r, s = a[0] * b[0], a[0] * b[1], a[1] * b[0], a[1] * b[1]
    return np.fmin(np.fmin(p, q), np.fmin(r, s)), np.fmax(np.fmax(p, q), np.fmax(r, s))


def _inverse(a: Bounds) -> Bounds:
    lo, hi = a
    spans_zero = (lo <= 0) & (hi >= 0)
    return np.where(spans_zero, -np.inf, 1.0 / hi), np.where(spans_zero, np.inf, 1.0 / lo)


def _monotone(function, increasing: bool = True, domain: tuple[float, float] = (-np.inf, np.inf)):
    """The rule of a monotone function on ``domain`` (the box clipped to it: points outside give NaN, no design)."""
    def rule(a: Bounds) -> Bounds:
        lo, hi = np.clip(a[0], *domain), np.clip(a[1], *domain)
        f_lo, f_hi = function(lo), function(hi)
        return (f_lo, f_hi) if increasing else (f_hi, f_lo)
    return rule


def _even(function, minimum: float = 0.0):
    """The rule of a function falling to ``minimum`` at 0 and rising symmetrically (x^2, |x|, cosh)."""
    def rule(a: Bounds) -> Bounds:
        lo, hi = a
        f_lo, f_hi = function(lo), function(hi)
        spans_zero = (lo <= 0) & (hi >= 0)
        return np.where(spans_zero, minimum, np.minimum(f_lo, f_hi)), np.maximum(f_lo, f_hi)
    return rule


def _truth(certain, impossible) -> Bounds:
    """A comparison's value over a box: 1 where it holds throughout, 0 where nowhere, else [0, 1]."""
    return np.where(certain, 1.0, 0.0), np.where(impossible, 0.0, 1.0)


def _wave(function, peak: float):
    """sin or cos over [lo, hi]: the ends' values, 1 where a peak (``peak`` + 2 k pi) lies within, -1 where a
    trough."""
    def rule(a: Bounds) -> Bounds:
        lo, hi = a
        f_lo, f_hi = function(lo), function(hi)
        top = np.floor((hi - peak) / (2 * np.pi)) * 2 * np.pi + peak >= lo
        bottom = np.floor((hi - peak - np.pi) / (2 * np.pi)) * 2 * np.pi + peak + np.pi >= lo
        unbounded = ~(np.isfinite(lo) & np.isfinite(hi))
        return (np.where(bottom | unbounded, -1.0, np.minimum(f_lo, f_hi)),
                np.where(top | unbounded, 1.0, np.maximum(f_lo, f_hi)))
    return rule


def _tangent(a: Bounds) -> Bounds:
    """tan over [lo, hi]: rising between its poles (pi/2 + k pi); unbounded where a pole lies within."""
    lo, hi = a
    pole = np.floor((hi - np.pi / 2) / np.pi) * np.pi + np.pi / 2 >= lo
    pole |= ~(np.isfinite(lo) & np.isfinite(hi))
    return np.where(pole, -np.inf, np.tan(lo)), np.where(pole, np.inf, np.tan(hi))


def _hypot(a: Bounds, b: Bounds) -> Bounds:
    """hypot(|a|, |b|) (rising in each): at the least and the most magnitudes (not through the squares, which
    underflow below 1e-154: hypot(0, 1e-200) is 1e-200, the root of the squares' sum 0)."""
    return np.hypot(a[0], b[0]), np.hypot(a[1], b[1])


def _zero(a: Bounds) -> np.ndarray:
    return (a[0] == 0) & (a[1] == 0)


def _nonzero(a: Bounds) -> np.ndarray:
    return (a[0] > 0) | (a[1] < 0)


def _power(a: Bounds, exponent: Bounds) -> Bounds:
    """a^b: an integer constant exponent for any base; otherwise over the base's non-negative part, where a^b is
    monotone in each argument, so its extremes are at the corners."""
    b_lo, b_hi = exponent
    lo, hi = a
    integer = (b_lo == b_hi) & (np.round(b_lo) == b_lo) & (np.abs(b_lo) <= 64)
    base = (np.maximum(lo, 0.0), np.maximum(hi, 0.0))
    corners = np.stack([np.power(x, y) for x in base for y in exponent])
    n = np.where(integer, b_lo, 1.0)
    p_lo, p_hi = lo**n, hi**n
    spans_zero = (lo <= 0) & (hi >= 0)
    even = np.mod(n, 2) == 0
    low = np.where(even & (n > 0) & spans_zero, 0.0, np.minimum(p_lo, p_hi))
    high = np.maximum(p_lo, p_hi)
    negative_spans = (n < 0) & spans_zero  # 1/x^k across zero
    low, high = np.where(negative_spans, -np.inf, low), np.where(negative_spans, np.inf, high)
    return (np.where(integer, low, np.nanmin(corners, axis=0)), np.where(integer, high, np.nanmax(corners, axis=0)))


_exp = _monotone(np.exp)
_log = _monotone(np.log, domain=(0.0, np.inf))
_UNARY = {
    ca.OP_ASSIGN: lambda a: a,
    ca.OP_NEG: lambda a: (-a[1], -a[0]),
    ca.OP_TWICE: lambda a: (2 * a[0], 2 * a[1]),
    ca.OP_INV: _inverse,
    ca.OP_EXP: _exp,
    ca.OP_LOG: _log,
    ca.OP_SQRT: _monotone(np.sqrt, domain=(0.0, np.inf)),
    ca.OP_SQ: _even(np.square),
    ca.OP_FABS: _even(np.abs),
    ca.OP_COSH: _even(np.cosh, 1.0),
    ca.OP_SINH: _monotone(np.sinh),
    ca.OP_TANH: _monotone(np.tanh),
    ca.OP_ASINH: _monotone(np.arcsinh),
    ca.OP_ACOSH: _monotone(np.arccosh, domain=(1.0, np.inf)),
    ca.OP_ATANH: _monotone(np.arctanh, domain=(-1.0, 1.0)),
    ca.OP_ATAN: _monotone(np.arctan),
    ca.OP_ASIN: _monotone(np.arcsin, domain=(-1.0, 1.0)),
    ca.OP_ACOS: _monotone(np.arccos, increasing=False, domain=(-1.0, 1.0)),
    ca.OP_LOG1P: _monotone(np.log1p, domain=(-1.0, np.inf)),
    ca.OP_EXPM1: _monotone(np.expm1),
    ca.OP_FLOOR: _monotone(np.floor),
    ca.OP_CEIL: _monotone(np.ceil),
    ca.OP_SIGN: _monotone(np.sign),
    ca.OP_SIN: _wave(np.sin, np.pi / 2),
    ca.OP_COS: _wave(np.cos, 0.0),
    ca.OP_TAN: _tangent,
}
_BINARY = {
    ca.OP_ADD: lambda a, b: (a[0] + b[0], a[1] + b[1]),
    ca.OP_SUB: lambda a, b: (a[0] - b[1], a[1] - b[0]),
    ca.OP_MUL: _products,
    ca.OP_DIV: lambda a, b: _products(a, _inverse(b)),
    ca.OP_FMIN: lambda a, b: (np.minimum(a[0], b[0]), np.minimum(a[1], b[1])),
    ca.OP_FMAX: lambda a, b: (np.maximum(a[0], b[0]), np.maximum(a[1], b[1])),
    ca.OP_POW: _power,
    ca.OP_CONSTPOW: _power,
    ca.OP_HYPOT: lambda a, b: _hypot(_even(np.abs)(a), _even(np.abs)(b)),
    ca.OP_IF_ELSE_ZERO: lambda c, a: (  # c ? a : 0 (c true where nonzero)
        np.where(_nonzero(c), a[0], np.where(_zero(c), 0.0, np.minimum(a[0], 0.0))),
        np.where(_nonzero(c), a[1], np.where(_zero(c), 0.0, np.maximum(a[1], 0.0)))),
}
_LOGICAL = {  # exact results (0 or 1), not widened
    ca.OP_LT: lambda a, b: _truth(a[1] < b[0], a[0] >= b[1]),
    ca.OP_LE: lambda a, b: _truth(a[1] <= b[0], a[0] > b[1]),
    ca.OP_AND: lambda a, b: _truth(_nonzero(a) & _nonzero(b), _zero(a) | _zero(b)),
    ca.OP_OR: lambda a, b: _truth(_nonzero(a) | _nonzero(b), _zero(a) & _zero(b)),
}
_NOT = lambda a: _truth(_zero(a), _nonzero(a))  # noqa: E731


class IntervalFunction:
    """A CasADi SX function (or an MX one that can be expanded) evaluated over boxes: :meth:`bounds`."""

    def __init__(self, function: ca.Function, compiled: bool = True):
        f = function.expand() if function.is_a("MXFunction") else function
        self.function = f
        self.program = [(f.instruction_id(k), f.instruction_input(k), f.instruction_output(k),
                         f.instruction_constant(k)) for k in range(f.n_instructions())]
        self.work = f.sz_w()
        library = replay_library(_WIDEN) if compiled else None
        try:
            self.compiled = None if library is None else CompiledReplay(f, self.program, self.work, library)
        except ValueError:  # an instruction the interpreter cannot address: replayed
            self.compiled = None

    def bounds(self, inputs: list[Bounds]) -> list[Bounds]:
        """Bounds on each output's nonzeros (arrays of shape (nnz, boxes)) for boxes given per input as (lo, hi)
        arrays of shape (nnz, boxes): compiled where it could be built, else :meth:`replay` (the same rules)."""
        return self.compiled.bounds(inputs) if self.compiled is not None else self.replay(inputs)

    @np.errstate(all="ignore")  # inf - inf, 0 * inf: NaN, which the rules make unbounded
    def replay(self, inputs: list[Bounds]) -> list[Bounds]:
        """:meth:`bounds` by NumPy, one operation at a time over all boxes (the reference implementation)."""
        boxes = inputs[0][0].shape[1]
        work: list[Bounds | None] = [None] * self.work
        outputs = [(np.full((self.function.nnz_out(i), boxes), -np.inf), np.full((self.function.nnz_out(i), boxes),
                                                                                 np.inf))
                   for i in range(self.function.n_out())]
        for op, args, result, constant in self.program:
            if op == ca.OP_INPUT:
                work[result[0]] = (inputs[args[0]][0][args[1]], inputs[args[0]][1][args[1]])
            elif op == ca.OP_OUTPUT:
                lo, hi = work[args[0]]
                outputs[result[0]][0][result[1]], outputs[result[0]][1][result[1]] = lo, hi
            elif op == ca.OP_CONST:
                work[result[0]] = (np.full(boxes, constant), np.full(boxes, constant))
            elif op in _UNARY:
                work[result[0]] = _outward(*_UNARY[op](work[args[0]]))
            elif op == ca.OP_NOT:
                work[result[0]] = _NOT(work[args[0]])
            elif op in _LOGICAL:
                work[result[0]] = _LOGICAL[op](work[args[0]], work[args[1]])
            elif op in _BINARY:
                work[result[0]] = _outward(*_BINARY[op](work[args[0]], work[args[1]]))
            else:  # no rule: the whole real line is a true bound
                work[result[0]] = (np.full(boxes, -np.inf), np.full(boxes, np.inf))
        return outputs
