"""Functions of one argument declared monotone, with a monotone slope: what interval evaluation may bound at the ends.

A formulation computes some coefficients by an algorithm (Hertz's n_a, n_b of a contact ellipse by a Newton step on
the elliptic integrals), whose interval replay operation by operation is far wider than the values (the argument
appears in every step). Where the function is known to be monotone in its argument, with a monotone slope, its
values over an interval of the argument lie between its values at the ends, and its slopes between its slopes at
the ends: :class:`MonotoneFunction` declares that. Within :func:`as_symbols` its symbolic calls return symbols in
place of their values, so that the interval proof (:mod:`clutchopt.optimise.interval_nodes`) can evaluate the node
at its argument's ends instead of replaying it.

A declaration is a claim its formulation must back with a test over the whole ``domain`` (values and slopes
monotone as declared, and within ``error`` of the exact function where the algorithm approximates one); outside the
domain the node is replayed as before. Called with floats or arrays it is the function itself.
"""

from __future__ import annotations

from contextlib import contextmanager
from typing import Callable, NamedTuple

import casadi as ca
import numpy as np

from clutchopt.backend import is_symbolic


class Node(NamedTuple):
    """One value of a declared function called on an SX argument, while nodes are collected (:func:`as_symbols`):
    ``symbol`` stands in the expression for ``value`` (the function's own expression of ``argument``)."""

    function: MonotoneFunction
    argument: ca.SX
    index: int
    value: ca.SX
    symbol: ca.SX


_collecting: list[list[Node]] = []


@contextmanager
def as_symbols():
    """Within, every declared function called on an SX argument returns fresh symbols in place of its values, and
    the list yielded collects them (:class:`Node`): the expressions built then use the nodes as inputs."""
    nodes: list[Node] = []
    _collecting.append(nodes)
    try:
        yield nodes
    finally:
        _collecting.pop()


class MonotoneFunction:
    """``function(x) -> tuple of values``, each value monotone in x over ``domain`` (``increasing``), its slope
    monotone too (``slope_increasing``: a convex value has a rising slope); ``error``: a relative bound on how far
    the values and slopes computed may lie from a function with exactly those properties."""

    def __init__(self, function: Callable, increasing: tuple[bool, ...], slope_increasing: tuple[bool, ...],
                 domain: tuple[float, float], error: float, source: str):
        self.function, self.increasing, self.slope_increasing = function, increasing, slope_increasing
        self.domain, self.error, self.source = domain, error, source
        self._float = None

    def __call__(self, argument):
        values = self.function(argument)
        if not (_collecting and is_symbolic(argument) and isinstance(argument, ca.SX)):
            return values
        nodes = [Node(self, argument, i, value, ca.SX.sym(f"{self.function.__name__}_{i}"))
                 for i, value in enumerate(values)]
        _collecting[-1].extend(nodes)
        return tuple(node.symbol for node in nodes)

    def on_floats(self) -> ca.Function:
        """The values and their slopes in x as a CasADi function of a float x (built once)."""
        if self._float is None:
            x = ca.SX.sym("x")
            values = ca.vertcat(*self.function(x))
            self._float = ca.Function("monotone", [x], [values, ca.jacobian(values, x)])
        return self._float

    def values_and_slopes(self, points: np.ndarray, mapped: Callable[[int], Callable] | None = None
                          ) -> tuple[np.ndarray, np.ndarray]:
        """The values and slopes (each of shape (len(increasing), points)) at float points, by the same algorithm:
        :meth:`on_floats` mapped over them, or ``mapped(size)``, the same function over ``size`` points as the
        interval proof calls it (``interval_nodes._mapped``: compiled, in place, built once a size; its enclosures
        evaluate it at every box's ends)."""
        count = points.size
        padded = np.full(_padded_size(count), self.domain[0])  # (the padding: a point of the domain, dropped)
        padded[:count] = points.reshape(-1)
        values, slopes = (mapped(padded.size) if mapped is not None else self.on_floats().map(padded.size))(padded)
        return np.asarray(values)[:, :count], np.asarray(slopes)[:, :count]

    def enclosure(self, lo: np.ndarray, hi: np.ndarray, mapped: Callable[[int], Callable] | None = None):
        """Bounds on every value and its slope (arrays of shape (values, intervals)) over each interval [lo, hi] of
        the argument within the domain (NaN elsewhere): the ends' values and slopes, ordered as declared, widened by
        ``error`` and a few ulps (``mapped``: as in :meth:`values_and_slopes`)."""
        inside = (lo >= self.domain[0]) & (hi <= self.domain[1]) & (lo <= hi)
        ends = np.concatenate([np.where(inside, lo, self.domain[0]), np.where(inside, hi, self.domain[0])])
        _, first, inverse = np.unique(ends.view(np.int64), return_index=True, return_inverse=True)
        values, slopes = self.values_and_slopes(ends[first], mapped)  # each end once (the same bits: the same
        # number; a search's boxes split in a variable the argument does not take share their ends: the ball's
        # searches evaluated a third of them)
        values, slopes = values[:, inverse], slopes[:, inverse]
        count = lo.size
        rising, slope_rising = np.array(self.increasing)[:, None], np.array(self.slope_increasing)[:, None]
        widen = self.error + 8 * np.finfo(float).eps
        value = (np.where(rising, values[:, :count], values[:, count:]),
                 np.where(rising, values[:, count:], values[:, :count]))
        slope = (np.where(slope_rising, slopes[:, :count], slopes[:, count:]),
                 np.where(slope_rising, slopes[:, count:], slopes[:, :count]))
        return _widened(*value, widen, inside), _widened(*slope, widen, inside)


def _padded_size(count: int) -> int:
    """The points a map is built for to evaluate ``count`` points: at least 16, rounded up to within a quarter (a
    search's enclosures evaluate a number of distinct ends that changes at every iteration; a few dozen maps serve a
    process, each evaluating at most a fifth more points than asked)."""
    step = max(16, 1 << max(count.bit_length() - 3, 0))
    return -(-max(count, 1) // step) * step


def _widened(low: np.ndarray, high: np.ndarray, relative: float, inside: np.ndarray):
    return (np.where(inside, low - np.abs(low) * relative, np.nan),
            np.where(inside, high + np.abs(high) * relative, np.nan))
