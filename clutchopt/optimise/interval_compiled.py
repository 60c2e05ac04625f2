"""The interval replay of :mod:`clutchopt.optimise.interval` as compiled code: one call for all boxes of a function.

The NumPy replay costs per operation, not per box: about ten NumPy calls an instruction (the rule and ``_outward``),
2.6 ms a call on the lever's 193-instruction rows whatever the number of boxes. Here the same rules are written once
in C, as an interpreter of a function's instruction list (``Function.instruction_*``): for each instruction, a loop
over the boxes. The C source is fixed (no code is generated per function), so one library serves every function; it
is built once per machine into the cache folder of :mod:`clutchopt.optimise.compiled` (``$CLUTCHOPT_CACHE``) and
loaded with ctypes. Without a compiler or a cache folder the NumPy replay is used.

The rules are those of :mod:`clutchopt.optimise.interval` (their docstrings are the specification), operation for
operation, with NumPy's NaN semantics: ``fmin``/``fmax`` leave a NaN out (C99's fmin and fmax), ``minimum``/
``maximum``/``clip`` pass it on (``nmin``/``nmax`` here); every result is widened outwards as there. The arithmetic
(+, -, *, /, sqrt) is IEEE in both and rounded the same way, so the bounds are the NumPy replay's to the bit; the other
elementary functions (C's libm against NumPy's own loops) may differ by an ulp or two, inside the widening of
8 eps both allow for them. The compiler is kept from contracting a * b + c into one rounding (``-ffp-contract=off``)
and from fast-math, so each operation rounds as written. An operation without a rule gives the whole real line, as
in the replay. The product's rule takes its fast path box by box (the replay's takes it where every box allows it:
the same numbers, as its docstring says).

The backward rules of :mod:`clutchopt.optimise.interval_backward` (HC4-revise) are written here too, in the same
library (``interval_revise``, :class:`CompiledRevise`): each row's limit carried back through the values the replay
kept, rule for rule and bound for bound as ``Tape.backward`` (the reference) carries them, to the bit where the
arithmetic is IEEE.
"""

from __future__ import annotations

import ctypes

import casadi as ca
import numpy as np

from clutchopt.optimise.compiled import FLAGS as NLP_FLAGS, built_library

FLAGS = ("-O2", *NLP_FLAGS[1:])  # the compiled NLP's flags (IEEE, operation by operation), optimised further

UNARY = ("ASSIGN", "NEG", "TWICE", "INV", "EXP", "LOG", "SQRT", "SQ", "FABS", "COSH", "SINH", "TANH", "ASINH",
         "ACOSH", "ATANH", "ATAN", "ASIN", "ACOS", "LOG1P", "EXPM1", "FLOOR", "CEIL", "SIGN", "SIN", "COS", "TAN",
         "NOT")
BINARY = ("ADD", "SUB", "MUL", "DIV", "FMIN", "FMAX", "POW", "CONSTPOW", "HYPOT", "IF_ELSE_ZERO", "LT", "LE", "AND",
          "OR")
RULED = frozenset(getattr(ca, "OP_" + name) for name in (*UNARY, *BINARY))  # the operations with a rule here

_RULES = r"""
#include <math.h>
#include <float.h>

static double nmin(double a, double b) { return isnan(a) ? a : isnan(b) ? b : (a < b ? a : b); }  /* np.minimum */
static double nmax(double a, double b) { return isnan(a) ? a : isnan(b) ? b : (a > b ? a : b); }  /* np.maximum */
static double fmin_(double a, double b) { return isnan(a) ? b : isnan(b) ? a : (a < b ? a : b); }  /* C99 fmin */
static double fmax_(double a, double b) { return isnan(a) ? b : isnan(b) ? a : (a > b ? a : b); }  /* C99 fmax */
static double clip(double x, double lo, double hi) { return nmin(nmax(x, lo), hi); }  /* np.clip */
static double square(double x) { return x * x; }
static double sign(double x) { return x > 0 ? 1.0 : x < 0 ? -1.0 : x; }  /* np.sign: 0 and NaN as they are */
static int same(double a, double b) { return a == b && signbit(a) == signbit(b); }  /* the same number, as bits */
/* f at both ends, once where they are the same number (a parameter the box fixes: the same result, half the cost) */
static void ends(double (*f)(double), double lo, double hi, double *f_lo, double *f_hi) {
    *f_lo = f(lo);
    *f_hi = same(lo, hi) ? *f_lo : f(hi);
}
static int spans_zero(double lo, double hi) { return lo <= 0 && hi >= 0; }
static int zero(double lo, double hi) { return lo == 0 && hi == 0; }
static int nonzero(double lo, double hi) { return lo > 0 || hi < 0; }

static void products(double alo, double ahi, double blo, double bhi, double *lo, double *hi) {
    if (alo >= 0 && blo >= 0) {  /* both non-negative: the ends' products, unless one is 0 * inf */
        double l = alo * blo, h = ahi * bhi;
        if (!isnan(l) && !isnan(h)) { *lo = l; *hi = h; return; }
    }
    double p = alo * blo, q = alo * bhi, r = ahi * blo, s = ahi * bhi;
    *lo = fmin_(fmin_(p, q), fmin_(r, s));
    *hi = fmax_(fmax_(p, q), fmax_(r, s));
}

static void inverse(double alo, double ahi, double *lo, double *hi) {
    int z = spans_zero(alo, ahi);
    *lo = z ? -INFINITY : 1.0 / ahi;
    *hi = z ? INFINITY : 1.0 / alo;
}

static void even(double (*f)(double), double minimum, double alo, double ahi, double *lo, double *hi) {
    double f_lo, f_hi;
    ends(f, alo, ahi, &f_lo, &f_hi);
    *lo = spans_zero(alo, ahi) ? minimum : nmin(f_lo, f_hi);
    *hi = nmax(f_lo, f_hi);
}

static void monotone(double (*f)(double), int increasing, double d0, double d1, double alo, double ahi, double *lo,
                     double *hi) {
    double f_lo, f_hi;
    ends(f, clip(alo, d0, d1), clip(ahi, d0, d1), &f_lo, &f_hi);
    *lo = increasing ? f_lo : f_hi;
    *hi = increasing ? f_hi : f_lo;
}

static void wave(double (*f)(double), double peak, double alo, double ahi, double *lo, double *hi) {
    double f_lo, f_hi;
    ends(f, alo, ahi, &f_lo, &f_hi);
    int top = floor((ahi - peak) / (2 * M_PI)) * 2 * M_PI + peak >= alo;
    int bottom = floor((ahi - peak - M_PI) / (2 * M_PI)) * 2 * M_PI + peak + M_PI >= alo;
    int unbounded = !(isfinite(alo) && isfinite(ahi));
    *lo = (bottom || unbounded) ? -1.0 : nmin(f_lo, f_hi);
    *hi = (top || unbounded) ? 1.0 : nmax(f_lo, f_hi);
}

static void tangent(double alo, double ahi, double *lo, double *hi) {
    int pole = floor((ahi - M_PI / 2) / M_PI) * M_PI + M_PI / 2 >= alo;
    pole = pole || !(isfinite(alo) && isfinite(ahi));
    double t_lo, t_hi;
    ends(tan, alo, ahi, &t_lo, &t_hi);
    *lo = pole ? -INFINITY : t_lo;
    *hi = pole ? INFINITY : t_hi;
}

static void power(double alo, double ahi, double blo, double bhi, double *lo, double *hi) {
    int integer = blo == bhi && floor(blo) == blo && fabs(blo) <= 64;
    if (!integer) {  /* the base's non-negative part: the corners (NaN left out, all NaN: NaN) */
        double x0 = nmax(alo, 0.0), x1 = nmax(ahi, 0.0);
        double p = pow(x0, blo), q = pow(x0, bhi), r = pow(x1, blo), s = pow(x1, bhi);
        *lo = fmin_(fmin_(fmin_(p, q), r), s);
        *hi = fmax_(fmax_(fmax_(p, q), r), s);
        return;
    }
    double n = blo, p_lo = pow(alo, n), p_hi = pow(ahi, n);
    int z = spans_zero(alo, ahi);
    *lo = (fmod(n, 2) == 0 && n > 0 && z) ? 0.0 : nmin(p_lo, p_hi);
    *hi = nmax(p_lo, p_hi);
    if (n < 0 && z) { *lo = -INFINITY; *hi = INFINITY; }  /* 1/x^k across zero */
}

static void truth(int certain, int impossible, double *lo, double *hi) {
    *lo = certain ? 1.0 : 0.0;
    *hi = impossible ? 0.0 : 1.0;
}

static void outward_by(double *lo, double *hi, double by) {  /* interval._outward */
    *lo = fmax_(*lo - fabs(*lo) * by, -INFINITY);
    *hi = fmin_(*hi + fabs(*hi) * by, INFINITY);
}

static void outward(double *lo, double *hi) { outward_by(lo, hi, WIDEN); }

/* One rule over every box: the arguments' ends a0, a1 (b0, b1) in, the result's lo, hi out, widened outwards. */
#define UNARY_RULE(body) for (long b = 0; b < boxes; ++b) { \
    double a0 = alo[b], a1 = ahi[b], lo, hi; body; outward(&lo, &hi); rlo[b] = lo; rhi[b] = hi; } break
#define BINARY_RULE(body) for (long b = 0; b < boxes; ++b) { \
    double a0 = alo[b], a1 = ahi[b], b0 = blo[b], b1 = bhi[b], lo, hi, t0, t1, u0, u1; (void)t0; (void)t1; \
    (void)u0; (void)u1; body; outward(&lo, &hi); rlo[b] = lo; rhi[b] = hi; } break
#define LOGICAL_RULE(certain, impossible) for (long b = 0; b < boxes; ++b) { \
    double a0 = alo[b], a1 = ahi[b], b0 = blo[b], b1 = bhi[b]; (void)b0; (void)b1; \
    int c = certain, i = impossible; rlo[b] = c ? 1.0 : 0.0; rhi[b] = i ? 0.0 : 1.0; } break  /* exact: not widened */

/* Replay ``count`` instructions over ``boxes`` boxes. Work variable k of box b at [k * boxes + b]; an input's row
   ``arg0`` (its inputs' nonzeros stacked) at in_*[arg0 * boxes + b], an output's row ``result`` likewise. */
void interval_replay(long count, const int *op, const int *arg0, const int *arg1, const int *result,
                     const double *constant, long boxes, const double *in_lo, const double *in_hi, double *w_lo,
                     double *w_hi, double *out_lo, double *out_hi) {
    for (long k = 0; k < count; ++k) {
        const double *alo = w_lo + (long)arg0[k] * boxes, *ahi = w_hi + (long)arg0[k] * boxes;
        const double *blo = w_lo + (long)(arg1[k] < 0 ? 0 : arg1[k]) * boxes;
        const double *bhi = w_hi + (long)(arg1[k] < 0 ? 0 : arg1[k]) * boxes;
        double *rlo = w_lo + (long)result[k] * boxes, *rhi = w_hi + (long)result[k] * boxes;
        switch (op[k]) {
        case OP_INPUT:
            alo = in_lo + (long)arg0[k] * boxes; ahi = in_hi + (long)arg0[k] * boxes;
            for (long b = 0; b < boxes; ++b) { rlo[b] = alo[b]; rhi[b] = ahi[b]; } break;
        case OP_OUTPUT:
            rlo = out_lo + (long)result[k] * boxes; rhi = out_hi + (long)result[k] * boxes;
            for (long b = 0; b < boxes; ++b) { rlo[b] = alo[b]; rhi[b] = ahi[b]; } break;
        case OP_CONST: for (long b = 0; b < boxes; ++b) rlo[b] = rhi[b] = constant[k]; break;  /* not widened */
        case OP_ASSIGN: UNARY_RULE(lo = a0; hi = a1);
        case OP_NEG: UNARY_RULE(lo = -a1; hi = -a0);
        case OP_TWICE: UNARY_RULE(lo = 2 * a0; hi = 2 * a1);
        case OP_INV: UNARY_RULE(inverse(a0, a1, &lo, &hi));
        case OP_EXP: UNARY_RULE(monotone(exp, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_LOG: UNARY_RULE(monotone(log, 1, 0.0, INFINITY, a0, a1, &lo, &hi));
        case OP_SQRT: UNARY_RULE(monotone(sqrt, 1, 0.0, INFINITY, a0, a1, &lo, &hi));
        case OP_SQ: UNARY_RULE(even(square, 0.0, a0, a1, &lo, &hi));
        case OP_FABS: UNARY_RULE(even(fabs, 0.0, a0, a1, &lo, &hi));
        case OP_COSH: UNARY_RULE(even(cosh, 1.0, a0, a1, &lo, &hi));
        case OP_SINH: UNARY_RULE(monotone(sinh, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_TANH: UNARY_RULE(monotone(tanh, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_ASINH: UNARY_RULE(monotone(asinh, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_ACOSH: UNARY_RULE(monotone(acosh, 1, 1.0, INFINITY, a0, a1, &lo, &hi));
        case OP_ATANH: UNARY_RULE(monotone(atanh, 1, -1.0, 1.0, a0, a1, &lo, &hi));
        case OP_ATAN: UNARY_RULE(monotone(atan, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_ASIN: UNARY_RULE(monotone(asin, 1, -1.0, 1.0, a0, a1, &lo, &hi));
        case OP_ACOS: UNARY_RULE(monotone(acos, 0, -1.0, 1.0, a0, a1, &lo, &hi));
        case OP_LOG1P: UNARY_RULE(monotone(log1p, 1, -1.0, INFINITY, a0, a1, &lo, &hi));
        case OP_EXPM1: UNARY_RULE(monotone(expm1, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_FLOOR: UNARY_RULE(monotone(floor, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_CEIL: UNARY_RULE(monotone(ceil, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_SIGN: UNARY_RULE(monotone(sign, 1, -INFINITY, INFINITY, a0, a1, &lo, &hi));
        case OP_SIN: UNARY_RULE(wave(sin, M_PI / 2, a0, a1, &lo, &hi));
        case OP_COS: UNARY_RULE(wave(cos, 0.0, a0, a1, &lo, &hi));
        case OP_TAN: UNARY_RULE(tangent(a0, a1, &lo, &hi));
        case OP_ADD: BINARY_RULE(lo = a0 + b0; hi = a1 + b1);
        case OP_SUB: BINARY_RULE(lo = a0 - b1; hi = a1 - b0);
        case OP_MUL: BINARY_RULE(products(a0, a1, b0, b1, &lo, &hi));
        case OP_DIV: BINARY_RULE(inverse(b0, b1, &t0, &t1); products(a0, a1, t0, t1, &lo, &hi));
        case OP_FMIN: BINARY_RULE(lo = nmin(a0, b0); hi = nmin(a1, b1));
        case OP_FMAX: BINARY_RULE(lo = nmax(a0, b0); hi = nmax(a1, b1));
        case OP_POW: case OP_CONSTPOW: BINARY_RULE(power(a0, a1, b0, b1, &lo, &hi));
        case OP_HYPOT: BINARY_RULE(even(fabs, 0.0, a0, a1, &t0, &t1); even(fabs, 0.0, b0, b1, &u0, &u1);
                                   lo = hypot(t0, u0); hi = hypot(t1, u1));
        case OP_IF_ELSE_ZERO: BINARY_RULE(  /* c ? a : 0, the condition c first */
            lo = nonzero(a0, a1) ? b0 : zero(a0, a1) ? 0.0 : nmin(b0, 0.0);
            hi = nonzero(a0, a1) ? b1 : zero(a0, a1) ? 0.0 : nmax(b1, 0.0));
        case OP_LT: LOGICAL_RULE(a1 < b0, a0 >= b1);
        case OP_LE: LOGICAL_RULE(a1 <= b0, a0 > b1);
        case OP_AND: LOGICAL_RULE(nonzero(a0, a1) && nonzero(b0, b1), zero(a0, a1) || zero(b0, b1));
        case OP_OR: LOGICAL_RULE(nonzero(a0, a1) || nonzero(b0, b1), zero(a0, a1) && zero(b0, b1));
        case OP_NOT: LOGICAL_RULE(zero(a0, a1), nonzero(a0, a1));
        default: for (long b = 0; b < boxes; ++b) { rlo[b] = -INFINITY; rhi[b] = INFINITY; } break;  /* no rule */
        }
    }
}

/* The backward rules of interval_backward (_back_unary, _back_binary: their docstrings are the specification), one
   box: where x (and y) may lie given z = op(x[, y]) in [z0, z1]; 0 where the operation has no rule. */
static int back_unary(int op, double z0, double z1, double x0, double x1, double *l, double *h) {
    int inside;
    switch (op) {
    case OP_ASSIGN: *l = z0; *h = z1; return 1;
    case OP_NEG: *l = -z1; *h = -z0; return 1;
    case OP_TWICE: *l = 0.5 * z0; *h = 0.5 * z1; return 1;
    case OP_INV: inverse(z0, z1, l, h); return 1;
    case OP_SQRT: *l = square(nmax(z0, 0.0)); *h = z1 >= 0 ? square(z1) : -INFINITY; return 1;
    case OP_SQ: *l = x0 >= 0 ? sqrt(nmax(z0, 0.0)) : -sqrt(nmax(z1, 0.0));
                *h = x1 <= 0 ? -sqrt(nmax(z0, 0.0)) : sqrt(nmax(z1, 0.0)); return 1;
    case OP_EXP: *l = log(nmax(z0, 0.0)); *h = log(nmax(z1, 0.0)); return 1;
    case OP_LOG: *l = exp(z0); *h = exp(z1); return 1;
    case OP_SIN: inside = x0 >= -(0.5 * M_PI) && x1 <= 0.5 * M_PI;  /* the rising branch */
                 *l = inside ? asin(clip(z0, -1.0, 1.0)) : -INFINITY;
                 *h = inside ? asin(clip(z1, -1.0, 1.0)) : INFINITY;
                 return 1;
    case OP_COS: inside = x0 >= 0.0 && x1 <= M_PI;  /* the falling branch */
                 *l = inside ? acos(clip(z1, -1.0, 1.0)) : -INFINITY;
                 *h = inside ? acos(clip(z0, -1.0, 1.0)) : INFINITY;
                 return 1;
    case OP_TAN: inside = x0 >= -(0.5 * M_PI) && x1 <= 0.5 * M_PI;
                 *l = inside ? atan(z0) : -INFINITY; *h = inside ? atan(z1) : INFINITY; return 1;
    default: return 0;
    }
}

static int back_binary(int op, double z0, double z1, double x0, double x1, double y0, double y1, double *xl,
                       double *xh, double *yl, double *yh) {
    double t0, t1;
    switch (op) {
    case OP_ADD: *xl = z0 - y1; *xh = z1 - y0; *yl = z0 - x1; *yh = z1 - x0; return 1;
    case OP_SUB: *xl = z0 + y0; *xh = z1 + y1; *yl = x0 - z1; *yh = x1 - z0; return 1;
    case OP_MUL: inverse(y0, y1, &t0, &t1); products(z0, z1, t0, t1, xl, xh);
                 inverse(x0, x1, &t0, &t1); products(z0, z1, t0, t1, yl, yh); return 1;
    case OP_DIV: products(z0, z1, y0, y1, xl, xh); inverse(z0, z1, &t0, &t1); products(x0, x1, t0, t1, yl, yh);
                 return 1;
    case OP_POW: case OP_CONSTPOW: {  /* a constant positive exponent, not a whole number: x >= 0, rising */
        int fits = y0 == y1 && y0 > 0 && nearbyint(y0) != y0;
        *xl = fits ? pow(nmax(z0, 0.0), 1.0 / y0) : -INFINITY;
        *xh = fits ? (z1 >= 0 ? pow(nmax(z1, 0.0), 1.0 / y0) : -INFINITY) : INFINITY;
        *yl = -INFINITY; *yh = INFINITY; return 1; }
    default: return 0;
    }
}

static int has_rule(int op, int arguments) {
    double l, h, yl, yh;
    return arguments == 1 ? back_unary(op, 0, 0, 0, 0, &l, &h) :
           arguments == 2 && back_binary(op, 0, 0, 0, 0, 0, 0, &l, &h, &yl, &yh);
}

/* interval_backward.Tape.backward (its docstring is the specification), every box in one call: each of the rows
   ``row_list`` carried back alone through its own values (``order[start[r]:start[r + 1]]``, each value after those
   it is computed from), from the forward replay's w_* (value k of box b at [k * boxes + b]); the value k's bound as
   carried back so far in back_* (taken from w_* where first reached: ``reached``); each bound a rule reads widened by
   ``floor_``, each it gives outwards by ``slack``. Out: x_* (rows x variables x boxes; the design variable
   ``variable[k]`` of each input value k, -1 for none) and ``empty`` (rows x boxes). */
void interval_revise(long count, const int *row_list, const int *row_value, const long *start, const int *order,
                     const int *op, const int *arguments, const int *arg0, const int *arg1, const int *variable,
                     const unsigned char *free_, long boxes, long variables, const double *w_lo, const double *w_hi,
                     double limit, double slack, double floor_, double *back_lo, double *back_hi,
                     unsigned char *reached, double *x_lo, double *x_hi, unsigned char *empty) {
    for (long i = 0; i < count; ++i) {
        long r = row_list[i], row = row_value[r];
        for (long j = start[r]; j < start[r + 1]; ++j) reached[order[j]] = 0;
        reached[row] = 1;
        for (long b = 0; b < boxes; ++b) {
            back_lo[row * boxes + b] = w_lo[row * boxes + b];
            back_hi[row * boxes + b] = nmin(w_hi[row * boxes + b], limit);
        }
        unsigned char *none = empty + r * boxes;
        for (long j = start[r]; j < start[r + 1]; ++j) {
            long k = order[j];
            if (!reached[k]) continue;  /* a value this row's bound did not reach, or not of the design */
            const double *z_lo = back_lo + k * boxes, *z_hi = back_hi + k * boxes;
            for (long b = 0; b < boxes; ++b) none[b] |= z_lo[b] > z_hi[b];
            if (op[k] == OP_INPUT) {
                if (variable[k] >= 0) {  /* (a variable read twice: both bounds hold) */
                    double *lo = x_lo + (r * variables + variable[k]) * boxes, *hi = x_hi + (r * variables
                                                                                            + variable[k]) * boxes;
                    for (long b = 0; b < boxes; ++b) { lo[b] = nmax(lo[b], z_lo[b]); hi[b] = nmin(hi[b], z_hi[b]); }
                }
                continue;
            }
            int n = arguments[k];
            if (!has_rule(op[k], n)) continue;
            long a[2] = {arg0[k], n > 1 ? arg1[k] : arg0[k]};
            for (int m = 0; m < n; ++m) if (free_[a[m]] && !reached[a[m]]) {  /* first reached: its forward bound */
                for (long b = 0; b < boxes; ++b) {
                    back_lo[a[m] * boxes + b] = w_lo[a[m] * boxes + b];
                    back_hi[a[m] * boxes + b] = w_hi[a[m] * boxes + b];
                }
                reached[a[m]] = 1;
            }
            const double *c_lo[2], *c_hi[2];  /* the arguments' bounds as the rule reads them */
            for (int m = 0; m < n; ++m) {
                c_lo[m] = (reached[a[m]] ? back_lo : w_lo) + a[m] * boxes;
                c_hi[m] = (reached[a[m]] ? back_hi : w_hi) + a[m] * boxes;
            }
            for (long b = 0; b < boxes; ++b) {
                double found[2][2], x0 = c_lo[0][b] - floor_, x1 = c_hi[0][b] + floor_;
                double z0 = z_lo[b] - floor_, z1 = z_hi[b] + floor_;
                if (n == 1) back_unary(op[k], z0, z1, x0, x1, &found[0][0], &found[0][1]);
                else back_binary(op[k], z0, z1, x0, x1, c_lo[1][b] - floor_, c_hi[1][b] + floor_, &found[0][0],
                                 &found[0][1], &found[1][0], &found[1][1]);
                for (int m = 0; m < n; ++m) {
                    if (!free_[a[m]]) continue;
                    double lo = found[m][0], hi = found[m][1];
                    outward_by(&lo, &hi, slack);
                    double *old_lo = back_lo + a[m] * boxes + b, *old_hi = back_hi + a[m] * boxes + b;
                    *old_lo = fmax_(*old_lo, lo);
                    *old_hi = fmin_(*old_hi, hi);
                }
            }
        }
    }
}
"""


def source(widen: float) -> bytes:
    """The C source: CasADi's operation codes and the replay's widening defined, then the rules."""
    codes = "".join(f"#define OP_{name} {getattr(ca, 'OP_' + name)}\n"
                    for name in ("INPUT", "OUTPUT", "CONST", *UNARY, *BINARY))
    return (codes + f"#define WIDEN {float(widen)!r}\n" + _RULES).encode()


_LOADED: dict[str, ctypes.CDLL] = {}


def _address(array: np.ndarray) -> int:
    """Where a C-contiguous array's data starts (cheaper than ``array.ctypes``, which builds an object per call)."""
    return array.__array_interface__["data"][0]


def replay_library(widen: float):
    """The compiled ``interval_replay`` (built or taken from the cache), or None where no library can be had."""
    library = _library(widen)
    return None if library is None else library.interval_replay


def revise_library(widen: float):
    """The compiled ``interval_revise`` (:class:`CompiledRevise`) from the same library, or None."""
    library = _library(widen)
    return None if library is None else library.interval_revise


def _library(widen: float) -> ctypes.CDLL | None:
    path = built_library(source(widen), prefix="interval", flags=FLAGS)
    if path is None:
        return None
    if path not in _LOADED:
        try:
            library = ctypes.CDLL(path)
            library.interval_replay.restype = library.interval_revise.restype = None
        except (OSError, AttributeError):  # a library that does not load, or without the replay (damaged cache)
            return None
        library.interval_replay.argtypes = [ctypes.c_long, *[ctypes.c_void_p] * 5, ctypes.c_long,
                                            *[ctypes.c_void_p] * 6]
        library.interval_revise.argtypes = [ctypes.c_long, *[ctypes.c_void_p] * 10, ctypes.c_long, ctypes.c_long,
                                            ctypes.c_void_p, ctypes.c_void_p, *[ctypes.c_double] * 3,
                                            *[ctypes.c_void_p] * 6]
        _LOADED[path] = library
    return _LOADED[path]


class CompiledReplay:
    """A function's instruction list (:class:`clutchopt.optimise.interval.IntervalFunction`'s ``program``) as arrays
    for ``interval_replay``; :meth:`bounds` as ``IntervalFunction.bounds``."""

    def __init__(self, function: ca.Function, program: list, work: int, replay):
        in_rows = np.cumsum([0] + [function.nnz_in(i) for i in range(function.n_in())])
        out_rows = np.cumsum([0] + [function.nnz_out(i) for i in range(function.n_out())])
        op, arg0, arg1, result, constant = [], [], [], [], []
        for code, args, res, value in program:
            op.append(code)
            constant.append(value if code == ca.OP_CONST else 0.0)
            if code == ca.OP_INPUT:  # the stacked inputs' row
                arg0.append(in_rows[args[0]] + args[1]), arg1.append(-1), result.append(res[0])
            elif code == ca.OP_OUTPUT:  # the stacked outputs' row
                arg0.append(args[0]), arg1.append(-1), result.append(out_rows[res[0]] + res[1])
            else:
                arg0.append(args[0] if len(args) and args[0] >= 0 else 0)
                arg1.append(args[1] if len(args) > 1 and args[1] >= 0 else -1)
                result.append(res[0])
        inner = np.array([k for k, code in enumerate(op) if code not in (ca.OP_INPUT, ca.OP_OUTPUT)], dtype=int)
        for index, bound in ((arg0, work), (arg1, work), (result, work)):  # the C reads and writes only these
            if inner.size and not np.all((np.take(index, inner) >= -1) & (np.take(index, inner) < bound)):
                raise ValueError("an instruction outside the work vector")
        self.arrays = [np.ascontiguousarray(a, dtype=np.intc) for a in (op, arg0, arg1, result)]
        self.constant = np.ascontiguousarray(constant, dtype=float)
        self.program = [len(constant), *(_address(a) for a in (*self.arrays, self.constant))]  # (kept alive above)
        self.in_rows, self.out_rows, self.work, self.replay = in_rows, out_rows, max(work, 1), replay
        self.in_sizes = np.diff(in_rows).tolist()

    def bounds(self, inputs: list) -> list:
        _, out_lo, out_hi = self.replayed(inputs)
        return [(out_lo[a:b], out_hi[a:b]) for a, b in zip(self.out_rows[:-1], self.out_rows[1:])]

    def replayed(self, inputs: list) -> tuple[tuple[np.ndarray, np.ndarray], np.ndarray, np.ndarray]:
        """The work variables' bounds after the replay (work x boxes: a program that writes each value once keeps
        them all, ``interval_backward.Tape``) and the outputs' stacked."""
        boxes = inputs[0][0].shape[1]
        if len(inputs) != len(self.in_sizes) or any(
                np.shape(lo) != (n, boxes) or np.shape(hi) != (n, boxes)
                for (lo, hi), n in zip(inputs, self.in_sizes)):  # (the C trusts the shapes)
            raise ValueError(f"inputs of shapes {[np.shape(lo) for lo, _ in inputs]}, not the function's nonzeros "
                             f"{self.in_sizes} by {boxes} boxes")
        in_lo = np.ascontiguousarray(np.vstack([lo for lo, _ in inputs]) if len(inputs) > 1 else inputs[0][0],
                                     dtype=float)
        in_hi = np.ascontiguousarray(np.vstack([hi for _, hi in inputs]) if len(inputs) > 1 else inputs[0][1],
                                     dtype=float)
        rows = int(self.out_rows[-1])
        out_lo, out_hi = np.full((rows, boxes), -np.inf), np.full((rows, boxes), np.inf)
        w_lo, w_hi = np.empty((self.work, boxes)), np.empty((self.work, boxes))
        self.replay(*self.program, boxes, *(_address(a) for a in (in_lo, in_hi, w_lo, w_hi, out_lo, out_hi)))
        return (w_lo, w_hi), out_lo, out_hi


class CompiledRevise:
    """A :class:`clutchopt.optimise.interval_backward.Tape` (its ``steps``, ``rows``, ``subgraphs``, ``free``) as
    arrays for ``interval_revise``; :meth:`backward` as ``Tape.backward`` from the compiled replay's work variables
    (each value in its own, as the tape's program writes them)."""

    def __init__(self, steps: list, rows: dict[int, int], subgraphs: list[list[int]], free: list[bool], revise):
        op, arguments, arg0, arg1, variable = [], [], [], [], []
        for code, args, _, read in steps:
            op.append(code), arguments.append(len(args)), arg0.append(args[0] if args else 0)
            arg1.append(args[1] if len(args) > 1 else 0)
            variable.append(read[1] if code == ca.OP_INPUT and read[0] == 0 else -1)
        order = [k for graph in subgraphs for k in graph]
        row_value = [rows[r] for r in range(len(rows))]
        if any(not 0 <= k < len(steps) for k in (*order, *row_value, *arg0, *arg1)):  # (the C trusts them)
            raise ValueError("a value outside the tape")
        self.arrays = [np.ascontiguousarray(a, dtype=np.intc) for a in (row_value, order, op, arguments, arg0, arg1,
                                                                         variable)]
        self.start = np.ascontiguousarray(np.cumsum([0] + [len(g) for g in subgraphs]), dtype=ctypes.c_long)
        self.free = np.ascontiguousarray(free, dtype=np.uint8)
        row_value, order, *tape = (_address(a) for a in self.arrays)
        self.program = [row_value, _address(self.start), order, *tape, _address(self.free)]  # (kept alive above)
        self.values, self.variables, self.revise = len(steps), max(variable, default=-1) + 1, revise

    def backward(self, w_lo: np.ndarray, w_hi: np.ndarray, limit: float, variables: int, rows: list[int],
                 slack: float, floor: float) -> tuple[tuple[np.ndarray, np.ndarray], np.ndarray]:
        """``Tape.backward`` of the values ``w_lo``, ``w_hi`` (values x boxes, C-contiguous: the replay's)."""
        boxes, m = w_lo.shape[1], len(self.arrays[0])
        if w_lo.shape != (self.values, boxes) or w_hi.shape != w_lo.shape or variables < self.variables \
                or not all(0 <= r < m for r in rows) or not (w_lo.flags.c_contiguous and w_hi.flags.c_contiguous) \
                or not w_lo.dtype == w_hi.dtype == np.float64:
            raise ValueError(f"values of shape {w_lo.shape} or rows {rows} not the tape's")
        x_lo, x_hi = np.full((m, variables, boxes), -np.inf), np.full((m, variables, boxes), np.inf)
        empty = np.zeros((m, boxes), dtype=np.uint8)
        back_lo, back_hi, reached = np.empty_like(w_lo), np.empty_like(w_hi), np.zeros(self.values, dtype=np.uint8)
        row_list = np.ascontiguousarray(rows, dtype=np.intc)
        self.revise(len(rows), _address(row_list), *self.program, boxes, variables, _address(w_lo), _address(w_hi),
                    limit, slack, floor, *(_address(a) for a in (back_lo, back_hi, reached, x_lo, x_hi, empty)))
        return (x_lo, x_hi), empty.view(bool)
