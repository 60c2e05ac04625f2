"""Interval functions of (design, p) whose declared monotone nodes (:class:`clutchopt.monotone.MonotoneFunction`)
are bounded at their argument's ends instead of being replayed operation by operation.

The formulation's rows are built again with a symbol ``y`` in place of each declared value
(:func:`clutchopt.monotone.as_symbols`): ``G(design, p, y)``, and their Jacobian by the chain rule,
``dG/dx + dG/dy diag(s) dr/dx``, with ``s`` the values' slopes in their arguments ``r``. Over a box, ``r`` is bounded
by interval replay (:mod:`clutchopt.optimise.interval`), then ``y`` and ``s`` by the declared monotony (values and
slopes at the ends of ``r``, widened by the declaration's error), met with the node's own replay: bounds as true
as the declaration, and as tight as the argument's. Where every box evaluated together lies within the
declarations' domains the replay is left out (it is far wider there, and it was 45 % of an evaluation of the ball's
rows: the searches of ``ball_crusher`` at 575-800 kW took 0.10 s of CPU instead of 0.17, over the same boxes).
Where ``r`` leaves the declared domain, ``y`` is the node's own replay and ``s`` unbounded, as without a
declaration. Before a search, the rows with the nodes' own values for ``y``
are compared with the NLP's at points of the box (:meth:`DeclaredNodes.agree`); should a formulation differentiate
its own expressions through a node (a chance constraint's slope), the symbols would cut that path, and the search
replays the nodes instead.
"""

from __future__ import annotations

from functools import cached_property, lru_cache, partial

import casadi as ca
import numpy as np

from clutchopt.model import namespace
from clutchopt.monotone import MonotoneFunction, Node, as_symbols
from clutchopt.optimise.compiled import compiled_function
from clutchopt.optimise.in_place import InPlace
from clutchopt.optimise.interval import Bounds, IntervalFunction


@lru_cache(maxsize=None)
def _compiled(function: MonotoneFunction) -> ca.Function:
    """A declared function's values and slopes compiled where a library can be had, once a process (the enclosures
    evaluate it at every box's ends: 60 % of a search's evaluation of the ball's rows on CasADi's virtual
    machine)."""
    return compiled_function(function.on_floats())


@lru_cache(maxsize=None)
def _mapped(function: MonotoneFunction, size: int) -> InPlace:
    """A declared function's compiled values and slopes (:func:`_compiled`) mapped over ``size`` points and called on
    NumPy arrays in place, built once a size and process (a search's enclosures had mapped it afresh and converted
    its DM arguments at every evaluation: 0.2 ms of fixed cost each, more than the values of 100 points cost)."""
    return InPlace(_compiled(function).map(size))


def _column(expressions: list) -> ca.SX:
    return ca.vertcat(*expressions) if expressions else ca.SX(0, 1)


class DeclaredNodes:
    """The declared values a set of rows uses: their arguments' and their own replays, and their enclosures."""

    def __init__(self, nodes: list[Node], design: ca.SX, p: ca.SX):
        self.nodes = nodes
        self.y = _column([node.symbol for node in nodes])
        self.s = ca.SX.sym("s", len(nodes))
        self.arguments = _column([node.argument for node in nodes])
        self._arguments = IntervalFunction(ca.Function("arguments", [design, p], [self.arguments]))
        self._replayed = IntervalFunction(ca.Function("declared", [design, p], [_column([n.value for n in nodes])]))
        calls: dict[int, list[int]] = {}
        for k, node in enumerate(nodes):
            calls.setdefault(id(node.argument), []).append(k)
        self._calls = list(calls.values())

    def agree(self, lower: np.ndarray, upper: np.ndarray, p: np.ndarray, points: int = 8) -> bool:
        """Whether the rows with the nodes' own values for ``y`` are the NLP's rows (to 1e-9) at the box's centre
        and random points of it: not so where a formulation differentiates its own expressions (a chance
        constraint's slope in a scattered quantity), a path the symbols ``y`` would cut."""
        return self.agree_all([(p, lower, upper)], points)[0]

    def agree_all(self, problems: list[tuple[np.ndarray, ...]], points: int = 8) -> list[bool]:
        """:meth:`agree` for each ``(p, lower, upper, ...)`` of a call of searches, their points in one evaluation
        (the same points and numbers: one mapped call where each search's had cost one, about 0.25 ms)."""
        if not self.nodes or not problems:
            return [True] * len(problems)
        n = len(problems[0][1])
        rng = np.random.default_rng(0)
        fractions = np.column_stack([np.full(n, 0.5), rng.random((n, points - 1))])
        samples = np.hstack([lower[:, None] + (upper - lower)[:, None] * fractions for _, lower, upper, *_ in problems])
        p = np.hstack([np.repeat(problem[0][:, None], points, axis=1) for problem in problems])
        difference = np.array(self.check.map(points * len(problems))(samples, p))
        close = np.isnan(difference) | (np.abs(difference) <= 1e-9)
        return [bool(np.all(close[:, k * points:(k + 1) * points])) for k in range(len(problems))]

    def bounds(self, inputs: list[Bounds]) -> tuple[Bounds, Bounds]:
        """Bounds on the values ``y`` and slopes ``s`` over boxes given as (design, p) bounds."""
        boxes = inputs[0][0].shape[1]
        if not self.nodes:
            return (np.zeros((0, boxes)),) * 2, (np.zeros((0, boxes)),) * 2
        (r_lo, r_hi), = self._arguments.bounds(inputs)
        within = all(np.all(r_lo[k] >= node.function.domain[0]) and np.all(r_hi[k] <= node.function.domain[1])
                     for k, node in enumerate(self.nodes))
        if within:  # every box within the declarations: their bounds alone (the replay is far wider there)
            y_lo, y_hi = np.full_like(r_lo, -np.inf), np.full_like(r_hi, np.inf)
        else:
            (y_lo, y_hi), = self._replayed.bounds(inputs)
        y_lo, y_hi, s_lo, s_hi = y_lo.copy(), y_hi.copy(), np.full_like(y_lo, -np.inf), np.full_like(y_hi, np.inf)
        for rows in self._calls:  # the values of one call share its argument: evaluated once at its ends
            node = self.nodes[rows[0]]
            (v_lo, v_hi), (d_lo, d_hi) = node.function.enclosure(r_lo[rows[0]], r_hi[rows[0]],
                                                                  partial(_mapped, node.function))
            for k in rows:
                index = self.nodes[k].index
                inside = ~np.isnan(v_lo[index])
                y_lo[k] = np.where(inside, np.maximum(y_lo[k], v_lo[index]), y_lo[k])  # both hold: intersected
                y_hi[k] = np.where(inside, np.minimum(y_hi[k], v_hi[index]), y_hi[k])
                s_lo[k], s_hi[k] = np.where(inside, d_lo[index], -np.inf), np.where(inside, d_hi[index], np.inf)
        return (y_lo, y_hi), (s_lo, s_hi)


class EnclosedFunction:
    """Outputs of (design, p, y, s) evaluated over boxes of (design, p) (:meth:`bounds`, as
    :meth:`IntervalFunction.bounds`); ``function``: the first output as the NLP computes it, of (design, p). Both
    built at their first use (the interval function's program and compiled replay cost 1-2 ms a problem and variant:
    the rows' own function serves the tests alone, a search takes the rows from the Jacobian's)."""

    def __init__(self, nodes: DeclaredNodes, inputs: list[ca.SX], outputs: list[ca.SX], plain: ca.SX, name: str):
        self.nodes = nodes
        self._inputs, self._outputs, self._plain, self._name = inputs, outputs, plain, name

    @cached_property
    def interval(self) -> IntervalFunction:
        return IntervalFunction(ca.Function(self._name, [*self._inputs, self.nodes.y, self.nodes.s], self._outputs))

    @cached_property
    def function(self) -> ca.Function:
        return ca.Function(self._name, self._inputs, [self._plain])

    def bounds(self, inputs: list[Bounds]) -> list[Bounds]:
        y, s = self.nodes.bounds(inputs)
        return self.interval.bounds([*inputs, y, s])


def split_bounds(first: EnclosedFunction, second: EnclosedFunction, inputs: list[Bounds], count: int
                 ) -> tuple[list[Bounds], list[Bounds]]:
    """``first``'s outputs over the first ``count`` columns of ``inputs`` and ``second``'s over the others, the
    declared nodes (the same for both) enclosed once over all of them: a search's Jacobian over its boxes and its
    rows alone at their centres and ends (``interval_proof._bounds``). Each output's bounds are those of its
    function's own :meth:`EnclosedFunction.bounds` to the bit: a node's enclosure is a column's own, and the rows
    are the same expression nodes in both functions, replayed by the same rules (the ball's Jacobian has 359
    instructions, its rows 153: the centres and ends, half or more of the columns, had replayed all 359)."""
    assert first.nodes is second.nodes, "the functions enclose different nodes"
    y, s = first.nodes.bounds(inputs)
    extra = [*inputs, y, s]
    head = [(lo[:, :count], hi[:, :count]) for lo, hi in extra]
    tail = [(lo[:, count:], hi[:, count:]) for lo, hi in extra]
    return first.interval.bounds(head), second.interval.bounds(tail)


def enclosed_rows(posed, declared: bool = True) -> tuple[EnclosedFunction, EnclosedFunction]:
    """A posed problem's own constraint rows (``g <= 0``, normalised, as the NLP's first rows; a start-up's left
    out) and their Jacobian in the design (dense, rows x variables) as interval functions of (design, p), the
    declared monotone nodes among them enclosed at their arguments' ends (``declared``; else all replayed). The
    Jacobian's function gives the rows too, as its second output: a search replays it over its boxes, for both, and
    the rows' own function alone over the boxes' centres and ends, the nodes enclosed once over all of them
    (:func:`split_bounds`, called by ``interval_proof._bounds``: the same bits as the Jacobian's function over every
    column, the ball's rows 153 instructions where its Jacobian takes 359)."""
    f, n = posed.formulation, len(posed.names)
    design, p = posed.nlp["x"][:n], posed.nlp["p"]
    plain = posed.nlp["g"][: sum(posed.constraint_rows[: posed.n_checked])]
    if declared:
        x_scale = p[posed.p_case.shape[0]: posed.p_case.shape[0] + n]
        x = namespace({v.name: design[i] * x_scale[i] for i, v in enumerate(f.variables)})
        q = namespace({quantity.name: posed.p_case[j] for j, quantity in enumerate(f.quantities)})
        with as_symbols() as collected:
            rows = ca.vertcat(*[ca.SX(c.normalised()) for c in f.constraints(x, q)])
        assert rows.shape == plain.shape, "the formulation's rows built again differ from the NLP's"
    else:
        rows, collected = plain, []
    used = [node for node in collected if ca.depends_on(rows, node.symbol)]
    nodes = DeclaredNodes(used, design, p)
    nodes.check = ca.Function("declared_check", [design, p], [
        ca.substitute(rows, nodes.y, _column([node.value for node in used])) - plain])
    chain = ca.jacobian(rows, nodes.y) @ ca.diag(nodes.s) @ ca.jacobian(nodes.arguments, design) if used else 0
    return (EnclosedFunction(nodes, [design, p], [rows], plain, "g_interval"),
            EnclosedFunction(nodes, [design, p], [ca.densify(ca.jacobian(rows, design) + chain), rows],
                             ca.densify(ca.jacobian(plain, design)), "dg_interval"))
