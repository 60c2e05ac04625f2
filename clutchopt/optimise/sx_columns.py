"""A CasADi SX function evaluated on NumPy columns, one NumPy operation per instruction over all the points at once.

CasADi's virtual machine runs an SX function's instructions point by point, a few ns an instruction and point (the
wedge's case gradient, 244 instructions: 0.65-1.0 ms for 1024 points). Replaying its algorithm instruction by
instruction with NumPy ufuncs over rows of a work array (a row per work slot, a column per point) does the same
operations in the same order on whole rows: 0.2-0.3 ms for the wedge's 1000 points. Its common subexpressions are
merged first (``casadi.cse``: an operation on the same operands, which CasADi's algorithm can hold several times, done
once: the same numbers from fewer instructions; the lever's case gradient 546 of 700, 45 of its sines and cosines 4,
0.25 ms for 767 points where it took 0.55; the wedge's 398 of 443, 0.21 ms where 0.29; about 1 ms once a problem,
a merge that grows with the instructions: 50-85 ms more for a start-up's 18-23 thousand, which no window replays).
Addition, subtraction, multiplication, division, negation, squares, square roots and reciprocals are IEEE's
correctly rounded operations in both, so those give the same numbers bit for bit; the transcendental functions (sin,
cos, tan, atan, exp, log, pow) are NumPy's, which on some processors (SIMD code for AVX-512) may round the last bit
otherwise than the C library CasADi calls. A function with an instruction outside :data:`UFUNCS` is not replayed
(``replayable``).
"""

from __future__ import annotations

import threading

import casadi as ca
import numpy as np

UFUNCS = {  # CasADi's operation -> the NumPy ufunc that computes it (one or two work rows in, one out)
    ca.OP_ADD: np.add, ca.OP_SUB: np.subtract, ca.OP_MUL: np.multiply, ca.OP_DIV: np.divide,
    ca.OP_NEG: np.negative, ca.OP_SQ: np.square, ca.OP_SQRT: np.sqrt, ca.OP_INV: np.reciprocal,
    ca.OP_FABS: np.fabs, ca.OP_FMIN: np.fmin, ca.OP_FMAX: np.fmax,
    ca.OP_LT: np.less, ca.OP_LE: np.less_equal, ca.OP_EQ: np.equal, ca.OP_NE: np.not_equal,
    ca.OP_SIN: np.sin, ca.OP_COS: np.cos, ca.OP_TAN: np.tan, ca.OP_ATAN: np.arctan,
    ca.OP_EXP: np.exp, ca.OP_LOG: np.log, ca.OP_POW: np.power, ca.OP_CONSTPOW: np.power,
}
TWICE = ca.OP_TWICE  # x + x
MOVES = (ca.OP_INPUT, ca.OP_OUTPUT, ca.OP_CONST, ca.OP_ASSIGN)  # no arithmetic: data moved into and out of the rows


def replayable(function: ca.Function) -> bool:
    """Whether ``function`` is an SX function of dense inputs and outputs whose every instruction has a NumPy
    counterpart."""
    if not function.is_a("SXFunction"):
        return False
    dense = all(function.nnz_in(i) == function.numel_in(i) for i in range(function.n_in())) and all(
        function.nnz_out(i) == function.numel_out(i) for i in range(function.n_out()))
    return dense and all(function.instruction_id(k) in UFUNCS or function.instruction_id(k) in (TWICE, *MOVES)
                         for k in range(function.n_instructions()))


class SXColumns:
    """``function`` (see :func:`replayable`) called on NumPy arrays of any number of columns (a point each, every
    input with the same number): ``f(*args)`` returns each output as an array of its rows by the points."""

    def __init__(self, function: ca.Function):
        if not replayable(function):
            raise ValueError(f"{function.name()} cannot be replayed by NumPy")
        if function.n_out():  # its common subexpressions merged, where the merged function replays too
            inputs = function.sx_in()
            merged = ca.Function(function.name(), inputs, ca.cse(function.call(inputs)))
            function = merged if replayable(merged) else function
        self.name, self.slots = function.name(), function.sz_w()
        self._local = threading.local()  # each thread's work array (see _rows)
        self.outputs = [function.nnz_out(i) for i in range(function.n_out())]
        self.program = []  # (ufunc or a move, its operands: work slots, or an input's or output's (index, row))
        for k in range(function.n_instructions()):
            op, out, given = function.instruction_id(k), function.instruction_output(k), function.instruction_input(k)
            if op in UFUNCS:
                self.program.append((UFUNCS[op], (*given, out[0])))  # the ufunc's inputs, then its out
            elif op == TWICE:
                self.program.append((np.add, (given[0], given[0], out[0])))
            elif op == ca.OP_CONST:
                self.program.append((ca.OP_CONST, (out[0], function.instruction_constant(k))))
            else:  # OP_INPUT: (input, row) -> slot; OP_OUTPUT: slot -> (output, row); OP_ASSIGN: slot -> slot
                self.program.append((op, (*given, *out)))

    def _rows(self, count: int) -> list[np.ndarray]:
        """A view of each work slot's row, for ``count`` points: the thread's work array of the last call, where it
        is as wide (a window's 1000 points: 400 kB on the wedge, warm in the cache and its pages mapped)."""
        rows = getattr(self._local, "rows", None)
        if rows is None or (rows and len(rows[0]) != count):
            rows = self._local.rows = list(np.empty((self.slots, count)))
        return rows

    def __call__(self, *args) -> tuple[np.ndarray, ...]:
        count = np.shape(args[0])[1]
        rows = self._rows(count)
        outputs = [np.empty((size, count)) for size in self.outputs]
        with np.errstate(all="ignore"):  # NaN and infinities as CasADi gives them, without NumPy's warnings
            for op, operands in self.program:
                if len(operands) == 3 and callable(op):  # a binary ufunc: in, in, out
                    op(rows[operands[0]], rows[operands[1]], rows[operands[2]])
                elif callable(op):  # a unary one: in, out
                    op(rows[operands[0]], rows[operands[1]])
                elif op == ca.OP_INPUT:
                    rows[operands[2]][:] = args[operands[0]][operands[1]]
                elif op == ca.OP_OUTPUT:
                    outputs[operands[1]][operands[2]] = rows[operands[0]]
                elif op == ca.OP_CONST:
                    rows[operands[0]].fill(operands[1])
                else:  # OP_ASSIGN
                    rows[operands[1]][:] = rows[operands[0]]
        return tuple(outputs)
