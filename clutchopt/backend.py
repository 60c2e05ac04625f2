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
    def apply(*args):  # is_symbolic written out: the simulator calls these ~10^5 times a start (the cable's link)
        for arg in args:
            if isinstance(arg, _SYMBOLIC):
                return casadi_fn(*args)
        return numpy_fn(*args)

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
where = _either(np.where, ca.if_else)  # where(condition, a, b): a where the condition holds, else b


def cbrt(x):
    """Real cube root of numbers; a power of anything symbolic (CasADi, or cvxpy in ``optimise/gp.py``)."""
    return np.cbrt(x) if isinstance(x, (int, float, np.ndarray, np.generic)) else x ** (1.0 / 3.0)


sinh = _either(np.sinh, ca.sinh)
arcsinh = _either(np.arcsinh, ca.asinh)


def ellipke(m, iterations: int = 7):
    """Complete elliptic integrals K(m), E(m) (parameter m = k^2, as scipy.special.ellipk/ellipe) by the
    arithmetic-geometric mean: a fixed number of steps, so CasADi can differentiate it. Converges
    quadratically; 7 steps give float64 accuracy for 0 <= m <= 1 - 1e-12 (within 4e-16 of SciPy's K, 3e-15 of
    its E, as 10 steps; 6 steps miss by 4e-9 at m = 1 - 1e-12). Each step more grows the ball clutch's Hessian.

    K = pi / (2 AGM(1, sqrt(1 - m))),  E = K (1 - sum_n 2^(n-1) c_n^2),  c_0^2 = m, c_(n+1) = (a_n - b_n) / 2.
    """
    a, b = 1.0, sqrt(1.0 - m)
    deficit = 0.5 * m
    for n in range(1, iterations + 1):
        c = (a - b) / 2.0
        a, b = (a + b) / 2.0, sqrt(a * b)
        deficit = deficit + 2.0 ** (n - 1) * c * c
    k = np.pi / (2.0 * a)
    return k, k * (1.0 - deficit)
