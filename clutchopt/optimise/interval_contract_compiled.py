"""The contraction of :mod:`clutchopt.optimise.interval_contract` as compiled code: all boxes in one call.

The NumPy contraction costs per operation, not per box: about 45 NumPy calls a sweep over arrays of rows x variables
x boxes (the ball's 6 x 5 x 30-60), 0.36 ms a call of three sweeps whatever the boxes, a quarter of an iteration of
the ball's interval searches. Here the same rule is written once in C, box by box (the boxes are contracted each on
its own: a box's sweeps stop where it is empty or did not move, which is where the NumPy sweeps over all boxes leave
it, since a further sweep of a box that did not move gives the same ends and cutters). Every operation is the NumPy
code's, in its order: the sums over the variables from the first term on (as the NumPy code adds them, for one box as
for many), the minima and maxima over the corners and the rows in turn, NaN replaced where NumPy replaces it; the
compiler is kept from contracting a * b + c into one rounding and from fast-math (the flags of
:mod:`clutchopt.optimise.interval_compiled`), so the ends are the NumPy code's to the bit (tested on random boxes with
infinite and zero slopes, tests/test_interval_contract.py). Built once per machine into the cache folder of
:mod:`clutchopt.optimise.compiled`; without a compiler or a cache folder the NumPy contraction is used.
"""

from __future__ import annotations

import ctypes
import os

import numpy as np

from clutchopt.optimise.compiled import CACHE_ENV, built_library
from clutchopt.optimise.interval_compiled import FLAGS, _address

_SOURCE = r"""
#include <math.h>

static double nmin(double a, double b) { return isnan(a) ? a : isnan(b) ? b : (a < b ? a : (b < a ? b : a)); }
static double nmax(double a, double b) { return isnan(a) ? a : isnan(b) ? b : (a > b ? a : (b > a ? b : a)); }
static double zero_nan(double x) { return isnan(x) ? 0.0 : x; }

/* Contract ``count`` boxes (column b of lo, hi, centre: variable j at [j * count + b]; c_lo row i at
   [i * count + b]; d_lo, d_hi at [(i * n + j) * count + b]) in place; ``empty`` and ``cutters`` (row i of box b at
   [i * count + b]) set, not cleared. ``work``: 3 m n doubles. */
void contract(long m, long n, long count, long sweeps, double limit, double slack, double cut, double *lo,
              double *hi, const double *centre, const double *c_lo_in, const double *d_lo, const double *d_hi,
              unsigned char *empty, unsigned char *cutters, double *work) {
    double *terms = work, *up = work + m * n, *down = work + 2 * m * n;
    for (long b = 0; b < count; ++b) {
        for (long sweep = 0; sweep < sweeps; ++sweep) {
            for (long i = 0; i < m; ++i)
                for (long j = 0; j < n; ++j) {
                    double a0 = d_lo[(i * n + j) * count + b], a1 = d_hi[(i * n + j) * count + b];
                    double s0 = lo[j * count + b] - centre[j * count + b];
                    double s1 = hi[j * count + b] - centre[j * count + b];
                    double t = zero_nan(a0 * s0);
                    t = nmin(t, zero_nan(a0 * s1));
                    t = nmin(t, zero_nan(a1 * s0));
                    terms[i * n + j] = nmin(t, zero_nan(a1 * s1));
                }
            for (long i = 0; i < m; ++i) {
                double c = c_lo_in[i * count + b];
                c = isnan(c) ? -INFINITY : c;
                double total = 0.0, size = 0.0;
                long infinite = 0;
                for (long j = 0; j < n; ++j) {
                    double t = terms[i * n + j], f = isinf(t) ? 0.0 : t;
                    total = j ? total + f : f;
                    size = j ? size + fabs(f) : fabs(f);
                    infinite += isinf(t) ? 1 : 0;
                }
                double magnitude = size + fabs(c) + fabs(limit);
                for (long j = 0; j < n; ++j) {
                    double t = terms[i * n + j], f = isinf(t) ? 0.0 : t;
                    double others = infinite - (isinf(t) ? 1 : 0) > 0 ? -INFINITY : total - f;
                    double room = limit - c - others + slack * magnitude;
                    room = isnan(room) ? INFINITY : room;
                    double a0 = d_lo[(i * n + j) * count + b], a1 = d_hi[(i * n + j) * count + b];
                    int rising = a0 > 0.0 && isfinite(a0), falling = a1 < 0.0 && isfinite(a1);
                    double t_up = rising ? (room >= 0 ? room / a0 : room / a1) : INFINITY;
                    double t_down = falling ? (room >= 0 ? room / a1 : room / a0) : -INFINITY;
                    t_up = isnan(t_up) ? INFINITY : t_up;
                    t_down = isnan(t_down) ? -INFINITY : t_down;
                    double x = centre[j * count + b];
                    double u = x + t_up + slack * (fabs(x) + fabs(t_up));
                    double d = x + t_down - slack * (fabs(x) + fabs(t_down));
                    up[i * n + j] = isnan(u) ? INFINITY : u;
                    down[i * n + j] = isnan(d) ? -INFINITY : d;
                }
            }
            int crossed = 0, moved = 0;
            for (long j = 0; j < n; ++j) {
                double l = lo[j * count + b], h = hi[j * count + b], margin = cut * (h - l);
                double least = up[j], most = down[j];
                for (long i = 1; i < m; ++i) {
                    least = nmin(least, up[i * n + j]);
                    most = nmax(most, down[i * n + j]);
                }
                for (long i = 0; i < m; ++i)
                    if (!empty[b] && (up[i * n + j] < h - margin || down[i * n + j] > l + margin))
                        cutters[i * count + b] = 1;
                double new_hi = nmin(h, least), new_lo = nmax(l, most);
                crossed |= new_lo > new_hi;
                terms[j] = new_lo;  /* (terms reused: the new ends, set below unless the box is empty) */
                up[j] = new_hi;
            }
            if (crossed) { empty[b] = 1; break; }
            for (long j = 0; j < n; ++j) {
                double l = lo[j * count + b], h = hi[j * count + b];
                moved |= !((l == terms[j] || (isnan(l) && isnan(terms[j])))
                           && (h == up[j] || (isnan(h) && isnan(up[j]))));
                lo[j * count + b] = terms[j];
                hi[j * count + b] = up[j];
            }
            if (!moved) break;
        }
    }
}
"""

_FOUND: dict[str | None, object] = {}  # the cache folder's setting -> the function found for it (looked up once: a
# library's check reads and hashes its bytes)


def library():
    """The compiled ``contract`` (built or taken from the cache), or None where no library can be had."""
    setting = os.environ.get(CACHE_ENV)
    if setting not in _FOUND:
        _FOUND[setting] = _loaded(built_library(_SOURCE.encode(), prefix="contract", flags=FLAGS))
    return _FOUND[setting]


def _loaded(path: str | None):
    if path is None:
        return None
    try:
        loaded = ctypes.CDLL(path)
        loaded.contract.restype = None
    except (OSError, AttributeError):  # a library that does not load, or without the function (damaged cache)
        return None
    loaded.contract.argtypes = [ctypes.c_long] * 4 + [ctypes.c_double] * 3 + [ctypes.c_void_p] * 9
    return loaded.contract


def compiled_contracted(function, lo: np.ndarray, hi: np.ndarray, centre: np.ndarray, c_lo: np.ndarray, d_lo: np.ndarray,
               d_hi: np.ndarray, limit: float, sweeps: int, slack: float, cut: float):
    """``interval_contract.contracted`` by the compiled ``function`` (:func:`library`): the same arguments and
    results."""
    m, n, count = d_lo.shape
    lo, hi = np.array(lo, dtype=float, order="C"), np.array(hi, dtype=float, order="C")
    arrays = [np.ascontiguousarray(a, dtype=float) for a in (centre, c_lo, d_lo, d_hi)]
    empty, cutters = np.zeros(count, dtype=np.uint8), np.zeros((m, count), dtype=np.uint8)
    work = np.empty(3 * m * n)
    function(m, n, count, sweeps, float(limit), slack, cut,
             *(_address(a) for a in (lo, hi, *arrays, empty, cutters, work)))
    return lo, hi, empty.astype(bool), cutters.astype(bool)
