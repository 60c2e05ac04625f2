"""A function of a few numbers written with :mod:`clutchopt.backend` (an equation of a formulation, generic over
floats, arrays and CasADi symbols) made cheap to call on floats: traced once with CasADi SX symbols, its algorithm
written out as Python source on floats (``math``), every subexpression of the other arguments folded to a number.

A start-up check calls its right-hand side some 2,000-4,500 times; through the generic equations (each call
dispatching every operation on its arguments' type and recomputing the design's constants) the cable's link torque
and stress alone were two thirds of its check. The traced function is the same equation, evaluated in the same IEEE
operations, and it is compared with the equation at probe points when built: where it differs by more than
PROBE_TOLERANCE, or the trace meets an operation not written out here, the equation itself is used. Python's
``math`` and ``**`` are not IEEE's where the equation's backend is (``sqrt(-1)``, ``log(0)``, ``sin(inf)`` and
``x / 0`` raise, ``exp(1000)`` overflows with an error, a negative number to a fractional power is complex): a call
that raises or gives other than a float is answered by the equation on NumPy floats (NaN or infinite as IEEE says),
only as slow.

A whole right-hand side (:func:`family`) is traced the same way once per *structure*: its arguments may be vectors
(a solver's state, read as floats), it may give several numbers, and the constants of a design are parameters, so
that the source is written once and each design only binds its numbers (the subexpressions of the parameters alone
computed then, once; :func:`trusted` checks the bound function against the equations at probes).
"""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace
from typing import Callable

import casadi as ca
import numpy as np

PROBE_TOLERANCE = 1e-13  # relative: the traced function against the equation at the probes
KEPT = 64  # written-out families kept, by their callers' keys (one a structure of a right-hand side)
FAILS = (ArithmeticError, ValueError, TypeError)  # what Python's math raises where IEEE gives NaN or an infinity
TRACE_FAILS = (NotImplementedError, RuntimeError, TypeError, ValueError, KeyError, ArithmeticError)

_UNARY = {ca.OP_NEG: "(-{0})", ca.OP_SQ: "({0} * {0})", ca.OP_TWICE: "(2.0 * {0})", ca.OP_INV: "(1.0 / {0})",
          ca.OP_SQRT: "sqrt({0})", ca.OP_SIN: "sin({0})", ca.OP_COS: "cos({0})", ca.OP_TAN: "tan({0})",
          ca.OP_ATAN: "atan({0})", ca.OP_EXP: "exp({0})", ca.OP_LOG: "log({0})", ca.OP_FABS: "abs({0})",
          ca.OP_ASSIGN: "{0}", ca.OP_NOT: "(not {0})"}
_BINARY = {ca.OP_ADD: "({0} + {1})", ca.OP_SUB: "({0} - {1})", ca.OP_MUL: "({0} * {1})", ca.OP_DIV: "({0} / {1})",
           ca.OP_FMAX: "({0} if {0} != {0} or {0} >= {1} else {1})",  # as numpy.maximum and minimum on numbers
           ca.OP_FMIN: "({0} if {0} != {0} or {0} <= {1} else {1})",  # (NaN propagates); written in place, not
           ca.OP_POW: "({0} ** {1})", ca.OP_CONSTPOW: "({0} ** {1})",  # called: 30 ns, not 75 (operands are names)
           ca.OP_LT: "({0} < {1})", ca.OP_LE: "({0} <= {1})",
           ca.OP_EQ: "({0} == {1})", ca.OP_NE: "({0} != {1})", ca.OP_AND: "({0} != 0 and {1} != 0)",
           ca.OP_OR: "({0} != 0 or {1} != 0)", ca.OP_IF_ELSE_ZERO: "({1} if {0} else 0.0)"}
_NOT_FLOAT = (ca.OP_NOT, ca.OP_LT, ca.OP_LE, ca.OP_EQ, ca.OP_NE, ca.OP_AND, ca.OP_OR)  # give bools (C: 1.0 or 0.0)
_NAMESPACE = {"sqrt": math.sqrt, "sin": math.sin, "cos": math.cos, "tan": math.tan, "atan": math.atan,
              "exp": math.exp, "log": math.log, "inf": math.inf, "_ndarray": np.ndarray, "_FAILS": FAILS,
              "_empty": np.empty}
_FAMILIES: dict = {}


def bound(equations_of: Callable, shapes: tuple[int, ...], objects, key, reference: Callable, probes: list,
          fallback: Callable | None = None) -> Callable:
    """``equations_of(*objects)`` (a function of arguments of ``shapes``, see :func:`family`) written out on floats
    once per structure of the objects (``objects``: :func:`parametrised` of them, their numbers the parameters; the
    maker kept under ``key`` and that structure, unless ``key`` is None), bound to their numbers and compared with
    ``reference`` (the same equations, as they are) at ``probes``; ``reference`` itself where it cannot be traced or
    the probes differ. ``fallback`` answers a call Python's math cannot (default: ``reference``)."""
    values, rebuild, structure = objects
    count = len(shapes)

    def traced(*arguments):
        return equations_of(*rebuild(arguments[count:]))(*arguments[:count])

    try:
        make = family(traced, shapes, len(values), key=None if key is None else (*key, structure))
        return trusted(make(fallback or reference, *values), reference, probes)
    except TRACE_FAILS:
        return reference


def family(function: Callable, shapes: tuple[int, ...], parameters: int = 0, key=None) -> Callable:
    """``function(*arguments, *parameters)`` written out on floats: a maker ``make(fallback, *parameter_values)``
    of the function of the arguments alone. ``shapes``: per argument 0 (a number) or n (a vector of n numbers, a
    NumPy array read with ``tolist`` or a sequence); ``function`` gives a number or a list of numbers (then the
    function made also has ``into``: the same numbers written into one array of its own, for LSODA). A call
    that raises as Python's math does where IEEE does not, or gives other than floats, is answered by
    ``fallback`` (the equations). Raises one of TRACE_FAILS where the function cannot be traced (an operation not
    written out, a branch on a symbol); ``key``: the maker kept under it, traced once."""
    if key is not None and key in _FAMILIES:
        made = _FAMILIES[key]
        if made is None:
            raise NotImplementedError("not traceable (kept)")
        return made
    try:
        made = _made(function, shapes, parameters)
    except TRACE_FAILS:
        if key is not None:
            _keep(key, None)
        raise
    if key is not None:
        _keep(key, made)
    return made


def _keep(key, made) -> None:
    while len(_FAMILIES) >= KEPT:
        del _FAMILIES[next(iter(_FAMILIES))]  # the oldest
    _FAMILIES[key] = made


def trusted(fast: Callable, equations: Callable, probes: list) -> Callable:
    """``fast`` where it gives what ``equations`` gives at every probe (tuples of arguments; to PROBE_TOLERANCE
    relative, NaN where they give NaN), and so does its ``into`` where it has one, else ``equations``."""
    into = getattr(fast, "into", None)
    for point in probes:
        exact = equations(*point)
        for value in (fast(*point), *(() if into is None else (list(into(*point)),))):
            if not _gives(exact, value):
                return equations
    return fast


def _gives(exact, value) -> bool:
    exact, value = (exact, value) if isinstance(exact, (list, tuple)) else ([exact], [value])
    return len(exact) == len(value) and all(_agrees(float(e), float(v)) for e, v in zip(exact, value))


def _agrees(exact: float, value: float) -> bool:
    return abs(value - exact) <= PROBE_TOLERANCE * abs(exact) or (math.isnan(exact) and math.isnan(value))


def parametrised(*objects):
    """The numbers in ``objects`` (a number itself; a dataclass or a namespace its fields, in turn): (their values,
    ``rebuild(numbers)`` giving the objects with those numbers (symbols) in their places, the objects' structure
    and everything in them that is not a number, as a key)."""
    values: list[float] = []

    def taken(thing):
        """(key, rebuild from an iterator of numbers) of one thing; its numbers appended to ``values``."""
        if isinstance(thing, float):
            values.append(float(thing))
            return "number", next
        if isinstance(thing, SimpleNamespace) or (dataclasses.is_dataclass(thing) and not isinstance(thing, type)):
            names = vars(thing) if isinstance(thing, SimpleNamespace) else [f.name for f in dataclasses.fields(thing)]
            parts = {name: taken(getattr(thing, name)) for name in names}
            key = (type(thing).__qualname__, tuple((name, part[0]) for name, part in parts.items()))
            if isinstance(thing, SimpleNamespace):
                return key, lambda numbers: SimpleNamespace(**{n: part[1](numbers) for n, part in parts.items()})
            return key, lambda numbers: dataclasses.replace(thing, **{n: part[1](numbers)
                                                                      for n, part in parts.items()})
        try:
            hash(thing)
        except TypeError:
            return repr(thing), lambda numbers: thing
        return thing, lambda numbers: thing

    shapes = [taken(thing) for thing in objects]

    def rebuild(numbers):
        numbers = iter(numbers)
        return [part[1](numbers) for part in shapes]

    return values, rebuild, tuple(part[0] for part in shapes)


def on_numpy(function: Callable, arguments: tuple):
    """``function`` at ``arguments`` as NumPy floats: IEEE's NaN and infinities where Python's math raises (a
    number, or a list of them)."""
    with np.errstate(all="ignore"):
        value = function(*(np.float64(a) for a in arguments))
    if isinstance(value, (list, tuple)):
        return [float(np.real_if_close(v)) for v in value]
    return float(np.real_if_close(value))


def _made(function: Callable, shapes: tuple[int, ...], parameters: int) -> Callable:
    """Trace ``function`` (see :func:`family`) and compile its written-out source: the maker."""
    arguments = [ca.SX.sym(f"a{i}", max(n, 1)) for i, n in enumerate(shapes)]
    numbers = [ca.SX.sym(f"p{j}") for j in range(parameters)]
    given = [a if n == 0 else [a[j] for j in range(n)] for a, n in zip(arguments, shapes)]
    result = function(*given, *numbers)
    several = isinstance(result, (list, tuple))
    outputs = [ca.densify(ca.SX(value)) for value in (result if several else [result])]
    traced = ca.Function("traced", arguments + numbers, outputs)
    source = _source(traced, shapes, parameters, several)
    namespace = dict(_NAMESPACE)
    exec(compile(source, "<traced>", "exec"), namespace)  # noqa: S102 - source written above from opcodes only
    return namespace["make"]


def _source(traced: ca.Function, shapes: tuple[int, ...], parameters: int, several: bool) -> str:
    """The SX function's instructions as the source of ``make(_fallback, p0, ...)``, which computes what depends
    on the parameters alone and returns ``traced(a0, ...)`` of the rest."""
    inputs = [[f"a{i}"] if n == 0 else [f"a{i}_{j}" for j in range(n)] for i, n in enumerate(shapes)]
    inputs += [[f"p{j}"] for j in range(parameters)]
    names: dict[int, str] = {}  # work slot -> the name of the value it holds now
    fixed: dict[int, bool] = {}  # work slot -> whether its value depends on the parameters alone
    constants: dict[int, float] = {}
    outer, inner, outputs, unsure = [], [], ["0.0"] * traced.n_out(), [False] * traced.n_out()
    odd: dict[int, bool] = {}  # work slot -> whether its value may be other than a float (a comparison's bool, a
    # fractional power's complex number, what they make)
    for k in range(traced.n_instructions()):
        op, args, out = traced.instruction_id(k), traced.instruction_input(k), traced.instruction_output(k)
        if op == ca.OP_INPUT:
            names[out[0]], fixed[out[0]], odd[out[0]] = inputs[args[0]][args[1]], args[0] >= len(shapes), False
            constants.pop(out[0], None)
            continue
        if op == ca.OP_OUTPUT:
            outputs[out[0]], unsure[out[0]] = names[args[0]], odd.get(args[0], False)
            continue
        name = f"v{k}"
        if op == ca.OP_CONST:
            value = float(traced.instruction_constant(k))
            if math.isnan(value):  # what a symbol converted to a float gives (math.isnan(x) of a table): no trace
                raise NotImplementedError("a NaN constant")
            line, constant = f"{name} = {value!r}", True
            constants[out[0]], odd[out[0]] = value, False
        elif op in _UNARY or op in _BINARY:
            form = _UNARY.get(op) or _BINARY[op]
            line, constant = f"{name} = " + form.format(*(names[a] for a in args)), all(fixed[a] for a in args)
            exponent = constants.get(args[1]) if op in (ca.OP_POW, ca.OP_CONSTPOW) else 0.0
            values = args[1:] if op == ca.OP_IF_ELSE_ZERO else args  # (its condition only chooses)
            odd[out[0]] = (op in _NOT_FLOAT or exponent is None or not float(exponent).is_integer()
                           or any(odd.get(a, False) for a in values))
        else:
            raise NotImplementedError(f"CasADi operation {op}")
        (outer if constant else inner).append(line)
        names[out[0]], fixed[out[0]] = name, constant
        if op != ca.OP_CONST:
            constants.pop(out[0], None)
    call = ", ".join(name[0] if n == 0 else f"a{i}" for i, (name, n) in enumerate(zip(inputs, shapes)))
    unpack = [f"{', '.join(inputs[i])}, = a{i}.tolist() if a{i}.__class__ is _ndarray else a{i}"
              for i, n in enumerate(shapes) if n > 0]
    answer = f"[{', '.join(outputs)}]" if several else outputs[0]
    unsure = [output for output, maybe in zip(outputs, unsure) if maybe]
    check = [f"if not ({' and '.join(f'{o}.__class__ is float' for o in unsure)}):",
             f"    return _fallback({call})"] if unsure else []
    body = unpack + ["try:"] + [f"    {line}" for line in inner or ["pass"]] + ["except _FAILS:",
                                                                                f"    return _fallback({call})"]
    lines = [f"def make(_fallback{''.join(f', p{j}' for j in range(parameters))}):"]
    lines += [f"    {line}" for line in outer]
    lines += [f"    def traced({call}):"] + [f"        {line}" for line in body + check + [f"return {answer}"]]
    if several:  # the same, its numbers written into one array of its own (a solver's right-hand side: odeint takes
        # an array as it is, a list it converts: 0.1-0.2 us a call)
        filled = [f"_out[{k}] = {output}" for k, output in enumerate(outputs)] + ["return _out"]
        lines += [f"    _out = _empty({len(outputs)})", f"    def into({call}):"]
        lines += [f"        {line}" for line in body + check + filled]
        lines += ["    traced.into = into"]
    lines += ["    return traced"]
    return "\n".join(lines) + "\n"
