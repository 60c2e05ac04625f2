"""Math that works on floats, NumPy arrays and CasADi symbols alike.

Each equation of a formulation is written once with these functions; called with floats it gives the
float64 check value, called with CasADi SX symbols it builds the NLP expression.
"""

from __future__ import annotations

import casadi as ca
import numpy as np

_SYMBOLIC = (ca.SX, ca.MX)


def is_symbolic(*values: object) -> bool:
    return any(isinstance(v, _SYMBOLIC) for v in values)


def _either(numpy_fn, casadi_fn):
    def apply(*args):
        return casadi_fn(*args) if is_symbolic(*args) else numpy_fn(*args)

    apply.__name__ = numpy_fn.__name__
    return apply


sin = _either(np.sin, ca.sin)
cos = _either(np.cos, ca.cos)
tan = _either(np.tan, ca.tan)
arctan = _either(np.arctan, ca.atan)
sqrt = _either(np.sqrt, ca.sqrt)
exp = _either(np.exp, ca.exp)
log = _either(np.log, ca.log)
fmax = _either(np.maximum, ca.fmax)
fmin = _either(np.minimum, ca.fmin)


def cbrt(x):
    return x ** (1.0 / 3.0) if is_symbolic(x) else np.cbrt(x)
