"""The compiled interval replay (clutchopt.optimise.interval_compiled) gives the NumPy replay's bounds
(clutchopt.optimise.interval, the reference): to the bit where only IEEE arithmetic is involved (+, -, *, /, sqrt),
within the widening of 8 eps both allow where an elementary function of C's libm stands for NumPy's, on every rule,
on boxes with zero, negative, infinite and NaN ends, and on the rows of all four couplings; and those bounds hold
every value the function takes in the box."""

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import clutchopt.optimise.compiled as compiled
from clutchopt.bench.reference import bench_cases
from clutchopt.optimise import interval, interval_compiled
from clutchopt.optimise.interval import IntervalFunction
from clutchopt.optimise.interval_proof import interval_functions
from clutchopt.optimise.problem import case_problem

pytestmark = pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler here (the NumPy replay is used)")

X, Y = ca.SX.sym("x"), ca.SX.sym("y")
NAMES = {getattr(ca, name): name for name in dir(ca) if name.startswith("OP_")}
OPERATIONS = {  # one expression per operation with a rule, the operation it must compile to
    ca.OP_NEG: -X, ca.OP_TWICE: 2 * X, ca.OP_INV: 1 / X, ca.OP_EXP: ca.exp(X), ca.OP_LOG: ca.log(X),
    ca.OP_SQRT: ca.sqrt(X), ca.OP_SQ: X * X, ca.OP_FABS: ca.fabs(X), ca.OP_COSH: ca.cosh(X), ca.OP_SINH: ca.sinh(X),
    ca.OP_TANH: ca.tanh(X), ca.OP_ASINH: ca.asinh(X), ca.OP_ACOSH: ca.acosh(X), ca.OP_ATANH: ca.atanh(X),
    ca.OP_ATAN: ca.atan(X), ca.OP_ASIN: ca.asin(X), ca.OP_ACOS: ca.acos(X), ca.OP_LOG1P: ca.log1p(X),
    ca.OP_EXPM1: ca.expm1(X), ca.OP_FLOOR: ca.floor(X), ca.OP_CEIL: ca.ceil(X), ca.OP_SIGN: ca.sign(X),
    ca.OP_SIN: ca.sin(X), ca.OP_COS: ca.cos(X), ca.OP_TAN: ca.tan(X), ca.OP_NOT: ca.logic_not(X),
    ca.OP_ADD: X + Y, ca.OP_SUB: X - Y, ca.OP_MUL: X * Y, ca.OP_DIV: X / Y, ca.OP_FMIN: ca.fmin(X, Y),
    ca.OP_FMAX: ca.fmax(X, Y), ca.OP_POW: X ** Y, ca.OP_CONSTPOW: ca.vertcat(X ** 2.5, X ** 3, X ** -2, X ** 0.5),
    ca.OP_HYPOT: ca.hypot(X, Y), ca.OP_IF_ELSE_ZERO: ca.if_else(X, Y, 0), ca.OP_LT: X < Y, ca.OP_LE: X <= Y,
    ca.OP_AND: ca.logic_and(X, Y), ca.OP_OR: ca.logic_or(X, Y),
}
IEEE = {ca.OP_NEG, ca.OP_TWICE, ca.OP_INV, ca.OP_SQRT, ca.OP_SQ, ca.OP_FABS, ca.OP_FLOOR, ca.OP_CEIL, ca.OP_SIGN,
        ca.OP_NOT, ca.OP_ADD, ca.OP_SUB, ca.OP_MUL, ca.OP_DIV, ca.OP_FMIN, ca.OP_FMAX, ca.OP_IF_ELSE_ZERO, ca.OP_LT,
        ca.OP_LE, ca.OP_AND, ca.OP_OR}  # correctly rounded in both (or exact): the same bits
ENDS = np.array([-np.inf, -1e300, -100.0, -3.0, -1.0, -0.5, -1e-300, 0.0, 1e-300, 0.25, 1.0, 1.5, 2.0, 3.0,
                 100.0, 1e300, np.inf])


def _special_boxes() -> tuple[np.ndarray, np.ndarray]:
    """Every interval [a, b] of the ends above with a <= b, and intervals with a NaN end (an operation outside its
    domain upstream)."""
    lo, hi = np.meshgrid(ENDS, ENDS, indexing="ij")
    proper = lo <= hi
    lo, hi = lo[proper], hi[proper]
    return np.concatenate([lo, [np.nan, 0.0, np.nan]]), np.concatenate([hi, [1.0, np.nan, np.nan]])


def _agree(compiled_bounds, replayed_bounds, exact: bool, composite: bool = False) -> None:
    """The compiled bounds are the replay's: the same bits (NaN where it has NaN), or within 8 eps of them (one
    operation), or, where an elementary function's last bit went through later sums (``composite``: the ball's
    Jacobian, 260 eps of a bound seen), within 1e-12 of it and 1e-9 of the replay's width."""
    for (c_lo, c_hi), (r_lo, r_hi) in zip(compiled_bounds, replayed_bounds):
        for c, r in ((c_lo, r_lo), (c_hi, r_hi)):
            same = (c == r) | (np.isnan(c) & np.isnan(r))
            if exact:
                assert same.all(), (c[~same], r[~same])
                continue
            with np.errstate(invalid="ignore"):
                allowed = 8 * np.finfo(float).eps * np.abs(r)
                if composite:
                    allowed = 1e-12 * np.abs(r) + 1e-9 * np.where(np.isfinite(r_hi - r_lo), r_hi - r_lo, 0.0)
                close = np.abs(c - r) <= allowed
            assert (same | close).all(), (c[~(same | close)], r[~(same | close)])


def test_every_operation_with_a_rule_is_compiled():
    """The C source knows exactly the operations interval.py has a rule for (a rule added there must be added here)."""
    ruled = set(interval._UNARY) | set(interval._BINARY) | set(interval._LOGICAL) | {ca.OP_NOT}
    assert interval_compiled.RULED == ruled
    assert set(OPERATIONS) == ruled - {ca.OP_ASSIGN}  # (a copy CasADi does not emit for an expression)


@pytest.mark.filterwarnings("ignore:All-NaN slice")  # the replay's a^b where no corner is defined
@pytest.mark.parametrize("op", OPERATIONS, ids=lambda op: NAMES[op])
def test_each_rule_gives_the_replays_bounds_on_special_boxes(op):
    """Each rule over every pair of boxes with ends in -inf, -1e300, ..., 0, ..., inf and NaN: the replay's bounds."""
    function = ca.Function("f", [X, Y], [OPERATIONS[op]])
    f = IntervalFunction(function)
    assert f.compiled is not None and op in [code for code, *_ in f.program]
    lo, hi = _special_boxes()
    x_lo, y_lo = (a.ravel()[None] for a in np.meshgrid(lo, lo, indexing="ij"))
    x_hi, y_hi = (a.ravel()[None] for a in np.meshgrid(hi, hi, indexing="ij"))
    inputs = [(x_lo, x_hi), (y_lo, y_hi)]
    _agree(f.bounds(inputs), f.replay(inputs), exact=op in IEEE)


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(sorted(OPERATIONS)), st.floats(-4, 4), st.floats(-4, 4), st.floats(0, 3), st.floats(0, 3))
def test_compiled_bounds_hold_every_value_in_the_box(op, a, b, wa, wb):
    """The values at a grid of points of a random box lie within the compiled bounds."""
    function = ca.Function("f", [X, Y], [OPERATIONS[op]])
    (low, high), = IntervalFunction(function).bounds([(np.array([[a]]), np.array([[a + wa]])),
                                                      (np.array([[b]]), np.array([[b + wb]]))])
    grid = np.stack(np.meshgrid(np.linspace(a, a + wa, 21), np.linspace(b, b + wb, 21))).reshape(2, -1)
    values = np.array(function.map(grid.shape[1])(grid[:1], grid[1:]))
    for k in range(values.shape[0]):
        finite = values[k][np.isfinite(values[k])]
        assert np.all(finite >= low[k, 0]) and np.all(finite <= high[k, 0]), (low[k], high[k], finite.min())


@pytest.mark.parametrize("case", bench_cases(), ids=lambda case: case.coupling)
def test_the_rows_of_every_coupling_compiled_are_the_replays(case):
    """The constraint rows and their Jacobian (declared nodes enclosed) over boxes of the design space, random and
    with zero, negative, infinite and NaN ends: the replay's bounds (the wedge's and the cable's to the bit: their
    rows are IEEE arithmetic and CasADi's sin, cos, tan, atan, pow of constants), and every sampled value within."""
    posed = case_problem(case).posed
    lower, upper, _ = posed.bounds_and_start(case, None)
    n = len(lower)
    p = np.concatenate([list(vars(posed.params(case)).values()), np.ones(n), [1.0]])
    rows, jacobian = interval_functions(posed)
    rng = np.random.default_rng(3)
    lo = lower[:, None] + (upper - lower)[:, None] * rng.random((n, 200))
    hi = lo + (upper[:, None] - lo) * rng.random((n, 200)) ** 3
    special = np.array([[0.0, 0.0], [-1.0, 0.0], [-np.inf, 1.0], [0.0, np.inf], [np.nan, 1.0], [-2.0, -1.0]])
    for k in range(len(special)):  # one variable at a time at the special interval, the others at random boxes
        lo = np.hstack([lo, lo[:, :n]])
        hi = np.hstack([hi, hi[:, :n]])
        lo[np.arange(n), -n + np.arange(n)], hi[np.arange(n), -n + np.arange(n)] = special[k]
    params = (np.repeat(p[:, None], lo.shape[1], axis=1),) * 2
    for function in (rows, jacobian):
        y, s = function.nodes.bounds([(lo, hi), params])
        inputs = [(lo, hi), params, y, s]
        compiled_bounds = function.interval.bounds(inputs)
        _agree(compiled_bounds, function.interval.replay(inputs), exact=case.coupling in ("wedge", "cable"),
               composite=True)
    (g_lo, g_hi), = rows.bounds([(lo[:, :200], hi[:, :200]), (params[0][:, :200],) * 2])
    for box in range(0, 200, 20):
        samples = lo[:, box, None] + (hi - lo)[:, box, None] * rng.random((n, 50))
        g = np.array(rows.function.map(50)(samples, np.repeat(p[:, None], 50, axis=1)))
        assert np.all(g >= g_lo[:, box, None] - 1e-12) and np.all(g <= g_hi[:, box, None] + 1e-12)


def test_without_a_compiler_or_cache_the_replay_is_used(monkeypatch):
    monkeypatch.setenv(compiled.CACHE_ENV, "")  # no cache folder: no compiled code
    f = IntervalFunction(ca.Function("f", [X, Y], [X * Y + ca.sin(X)]))
    assert f.compiled is None
    (low, high), = f.bounds([(np.array([[1.0]]), np.array([[2.0]])), (np.array([[-1.0]]), np.array([[3.0]]))])
    # [1, 2] [-1, 3] = [-2, 6]; sin over [1, 2] (its peak pi/2 within): [sin 1, 1]; the sum [-2 + sin 1, 7]
    assert low[0, 0] <= -2 + np.sin(1.0) and np.isclose(low[0, 0], -2 + np.sin(1.0), rtol=1e-14, atol=0)
    assert high[0, 0] >= 7.0 and np.isclose(high[0, 0], 7.0, rtol=1e-14, atol=0)


@pytest.mark.parametrize("method", ["bounds", "replay"])
def test_hypot_of_tiny_values_is_not_lost_to_underflow(method):
    """hypot(0, 1e-200) = 1e-200 (CasADi's value too); through the squares' sum, 1e-400, it would be bounded by 0."""
    function = ca.Function("f", [X, Y], [ca.hypot(X, Y)])
    (low, high), = getattr(IntervalFunction(function), method)([(np.zeros((1, 1)),) * 2, (np.full((1, 1), 1e-200),) * 2])
    assert float(function(0.0, 1e-200)) == 1e-200
    assert low[0, 0] <= 1e-200 <= high[0, 0] and high[0, 0] <= 1e-200 * (1 + 1e-14)


def test_inputs_of_the_wrong_shape_are_refused_not_read_past():
    """The C reads the rows the function declares: an input with fewer rows (or boxes) is an error, not a read past
    its end."""
    f = IntervalFunction(ca.Function("f", [X, Y], [X * Y]))
    with pytest.raises(ValueError, match="nonzeros"):
        f.bounds([(np.zeros((1, 4)), np.ones((1, 4))), (np.zeros((0, 4)), np.ones((0, 4)))])
    with pytest.raises(ValueError, match="nonzeros"):
        f.bounds([(np.zeros((1, 4)), np.ones((1, 4)))])
