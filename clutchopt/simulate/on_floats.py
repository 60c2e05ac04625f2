"""A function of a few numbers written with :mod:`clutchopt.backend` (an equation of a formulation, generic over
floats, arrays and CasADi symbols) made cheap to call on floats: traced once with CasADi SX symbols, its algorithm
written out as Python source on floats (``math``), every subexpression of the other arguments folded to a number.

The cable's link torque and stress are called some 10,000 times a start-up check; through the generic equations
(each call dispatching every operation on its arguments' type and recomputing the design's constants) they were two
thirds of the check. The traced function is the same equation, evaluated in the same IEEE operations, and it is
compared with the equation at probe points when built: where it differs by more than PROBE_TOLERANCE, or the trace
meets an operation not written out here, the equation itself is used. Python's ``math`` and ``**`` are not IEEE's
where the equation's backend is (``sqrt(-1)``, ``log(0)``, ``sin(inf)`` and ``x / 0`` raise, ``exp(1000)`` overflows
with an error, a negative number to a fractional power is complex): a call that raises or gives other than a float
is answered by the equation on NumPy floats (NaN or infinite as IEEE says), only as slow.
"""

from __future__ import annotations

import math
from typing import Callable

import casadi as ca
import numpy as np

PROBE_TOLERANCE = 1e-13  # relative: the traced function against the equation at the probes

_UNARY = {ca.OP_NEG: "(-{0})", ca.OP_SQ: "({0} * {0})", ca.OP_TWICE: "(2.0 * {0})", ca.OP_INV: "(1.0 / {0})",
          ca.OP_SQRT: "sqrt({0})", ca.OP_SIN: "sin({0})", ca.OP_COS: "cos({0})", ca.OP_TAN: "tan({0})",
          ca.OP_ATAN: "atan({0})", ca.OP_EXP: "exp({0})", ca.OP_LOG: "log({0})", ca.OP_FABS: "abs({0})",
          ca.OP_ASSIGN: "{0}"}
_BINARY = {ca.OP_ADD: "({0} + {1})", ca.OP_SUB: "({0} - {1})", ca.OP_MUL: "({0} * {1})", ca.OP_DIV: "({0} / {1})",
           ca.OP_FMAX: "_fmax({0}, {1})", ca.OP_FMIN: "_fmin({0}, {1})", ca.OP_POW: "({0} ** {1})",
           ca.OP_CONSTPOW: "({0} ** {1})"}


def _fmax(a: float, b: float) -> float:
    """As numpy.maximum on numbers (NaN propagates)."""
    return a if a != a or a >= b else b


def _fmin(a: float, b: float) -> float:
    return a if a != a or a <= b else b


def on_floats(function: Callable, arguments: int, probes: list[tuple[float, ...]]) -> Callable:
    """``function`` of ``arguments`` numbers as a Python function of floats (see the module), or ``function``
    itself where it cannot be traced or its trace does not match it at ``probes`` (points of its arguments)."""
    try:
        symbols = [ca.SX.sym(f"x{i}") for i in range(arguments)]
        traced = ca.Function("traced", symbols, [ca.SX(function(*symbols))])
        fast = _written_out(traced)
    except (NotImplementedError, RuntimeError, TypeError, ValueError, KeyError):
        return function
    def on_numbers(*arguments: float) -> float:
        try:
            value = fast(*arguments)
        except (ArithmeticError, ValueError, TypeError):
            return _on_numpy(function, arguments)
        return value if value.__class__ is float else _on_numpy(function, arguments)

    for point in probes:
        exact, value = float(function(*point)), on_numbers(*point)
        if not (abs(value - exact) <= PROBE_TOLERANCE * abs(exact) or (math.isnan(exact) and math.isnan(value))):
            return function
    return on_numbers


def _on_numpy(function: Callable, arguments: tuple) -> float:
    """``function`` at ``arguments`` as NumPy floats: IEEE's NaN and infinities where Python's math raises."""
    with np.errstate(all="ignore"):
        return float(np.real_if_close(function(*(np.float64(a) for a in arguments))))


def _written_out(traced: ca.Function) -> Callable:
    """The SX function's instructions as Python source, compiled."""
    arguments = [f"x{i}" for i in range(traced.n_in())]
    lines, output = [], None
    for k in range(traced.n_instructions()):
        op, inputs, outputs = traced.instruction_id(k), traced.instruction_input(k), traced.instruction_output(k)
        target = f"w{outputs[0]}" if outputs else ""
        if op == ca.OP_INPUT:
            lines.append(f"{target} = {arguments[inputs[0]]}")
        elif op == ca.OP_CONST:
            lines.append(f"{target} = {float(traced.instruction_constant(k))!r}")
        elif op == ca.OP_OUTPUT:
            output = f"w{inputs[0]}"
        elif op in _UNARY:
            lines.append(f"{target} = " + _UNARY[op].format(f"w{inputs[0]}"))
        elif op in _BINARY:
            lines.append(f"{target} = " + _BINARY[op].format(f"w{inputs[0]}", f"w{inputs[1]}"))
        else:
            raise NotImplementedError(f"CasADi operation {op}")
    if output is None:
        raise ValueError("no output")
    source = f"def traced({', '.join(arguments)}):\n" + "".join(f"    {line}\n" for line in lines) + \
        f"    return {output}\n"
    namespace = {"sqrt": math.sqrt, "sin": math.sin, "cos": math.cos, "tan": math.tan, "atan": math.atan,
                 "exp": math.exp, "log": math.log, "_fmax": _fmax, "_fmin": _fmin}
    exec(compile(source, "<traced>", "exec"), namespace)  # noqa: S102 - source written above from opcodes only
    return namespace["traced"]
