"""An SX function replayed by NumPy over columns (clutchopt.optimise.sx_columns) against CasADi's virtual machine."""

import casadi as ca
import numpy as np
import pytest

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.optimise.in_place import InPlace
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.sensitivity import _case_gradient, _window_gradient
from clutchopt.optimise.sx_columns import SXColumns, replayable


def _on_machine(function: ca.Function, *args: np.ndarray) -> np.ndarray:
    return InPlace(function.map(args[0].shape[1]))(*args)[0]


def test_the_basic_operations_give_the_machines_numbers_bit_for_bit():
    # hand values at x = 3, y = 4: x^2 + y^2 = 25 and its root 5; (x - y) / y = -0.25; 1 / (2x) = 1/6; 3x - y = 5;
    # min(x, y) = 3, max = 4, |x - y| = 1, x < y: 1, x <= y: 1, x == y: 0, x != y: 1
    x, y = ca.SX.sym("x"), ca.SX.sym("y")
    rows = [x**2 + y**2, ca.sqrt(x**2 + y**2), (x - y) / y, 1 / (2 * x), 3 * x - y, ca.fmin(x, y), ca.fmax(x, y),
            ca.fabs(x - y), x < y, x <= y, x == y, x != y, -x * y]
    function = ca.Function("basic", [ca.vertcat(x, y)], [ca.vertcat(*rows)])
    assert replayable(function)
    ops = {function.instruction_id(k) for k in range(function.n_instructions())}
    assert {ca.OP_SQ, ca.OP_SQRT, ca.OP_DIV, ca.OP_INV, ca.OP_TWICE, ca.OP_FMIN, ca.OP_FMAX, ca.OP_FABS,
            ca.OP_LT, ca.OP_LE, ca.OP_EQ, ca.OP_NE, ca.OP_NEG, ca.OP_CONST} <= ops
    rng = np.random.default_rng(7)
    points = np.column_stack([[3.0, 4.0], [0.0, 0.0], [np.nan, 1.0], [np.inf, -np.inf], [-2.0, 0.0],
                              *rng.normal(0, 10, (200, 2))])
    got = SXColumns(function)(points)[0]
    assert got[:, 0].tolist() == [25.0, 5.0, -0.25, 1 / 6, 5.0, 3.0, 4.0, 1.0, 1.0, 1.0, 0.0, 1.0, -12.0]
    assert np.array_equal(got, _on_machine(function, points), equal_nan=True)


def test_a_subexpression_the_algorithm_holds_twice_is_replayed_once():
    # sqrt(x) and x * y each built twice (two nodes: two instructions each in CasADi's algorithm), replayed once each
    # (casadi.cse), the machine's numbers bit for bit; at x = 4, y = 3: 2 + 2 * 3 = 8 and 12 - 12^2 = -132
    x, y = ca.SX.sym("x"), ca.SX.sym("y")
    function = ca.Function("twice", [ca.vertcat(x, y)],
                           [ca.vertcat(ca.sqrt(x) + ca.sqrt(x) * y, x * y - (x * y) * (x * y))])
    held = [function.instruction_id(k) for k in range(function.n_instructions())]
    assert held.count(ca.OP_SQRT) == 2 and held.count(ca.OP_MUL) == 3  # (x * y twice, sqrt(x) * y)
    replay = SXColumns(function)
    ops = [op for op, _ in replay.program]
    assert ops.count(np.sqrt) == 1 and ops.count(np.multiply) == 2
    points = np.column_stack([[4.0, 3.0], [0.0, -1.0], [np.inf, 0.0], [-1.0, 2.0],
                              *np.random.default_rng(5).uniform(0.0, 50.0, (300, 2))])
    got = replay(points)[0]
    assert got[:, 0].tolist() == [8.0, -132.0]
    assert got.tobytes() == _on_machine(function, points).tobytes()


def test_a_function_without_outputs_replays_to_none():
    # (found in review) casadi.cse of no outputs is an empty SX, not a list: no merge where there are no outputs
    x = ca.SX.sym("x")
    assert SXColumns(ca.Function("none", [x], []))(np.ones((1, 3))) == ()


def test_the_transcendental_functions_agree_with_the_machine_to_the_last_bits():
    # at (pi/6, 2): sin = 0.5, e^2 = 7.38905609893065, ln 2 = 0.6931471805599453, 2^0.5 = 1.4142135623730951;
    # at (pi/4, 1): tan = 1, atan(1) = pi/4 = 0.7853981633974483 (to within rounding)
    x = ca.SX.sym("x", 2)
    rows = [ca.sin(x[0]), ca.cos(x[0]), ca.tan(x[0]), ca.atan(x[1]), ca.exp(x[1]), ca.log(x[1]), x[1] ** 0.5,
            x[1] ** x[0], x[0] ** 3.5]
    function = ca.Function("transcendental", [x], [ca.vertcat(*rows)])
    assert replayable(function)
    points = np.column_stack([[np.pi / 6, 2.0], [np.pi / 4, 1.0],
                              *np.random.default_rng(3).uniform(0.1, 3.0, (500, 2))])
    got, want = SXColumns(function)(points)[0], _on_machine(function, points)
    assert got[[0, 4, 5, 6], 0] == pytest.approx([0.5, 7.38905609893065, 0.6931471805599453, 1.4142135623730951],
                                                 rel=1e-15)
    assert got[[2, 3], 1] == pytest.approx([1.0, 0.7853981633974483], rel=1e-15)
    assert np.max(np.abs(got - want) / np.spacing(np.abs(want))) <= 4  # a few units in the last place at most


def test_a_function_with_an_operation_numpy_lacks_is_not_replayed():
    x = ca.SX.sym("x")
    function = ca.Function("erf", [x], [ca.erf(x) + x])
    assert not replayable(function)
    with pytest.raises(ValueError, match="cannot be replayed"):
        SXColumns(function)
    assert not replayable(ca.Function("mx", [ca.MX.sym("y")], [ca.MX.sym("y") * 0]))


@pytest.mark.parametrize("case", bench_cases(), ids=lambda case: case.coupling)
def test_each_couplings_case_gradient_replayed_is_the_machines(case):
    # the case gradient of the Lagrangian at 300 primal-dual points about the case's (what a window's sensitivities
    # read), replayed by NumPy: the machine's numbers to within rounding (measured: the wedge's bit for bit, the
    # others' within 4e-14 of their largest term, where a last bit of tan, atan, exp, log or pow differs)
    posed = case_problem(case, reference_mode(case.coupling), "mass").posed
    function = _case_gradient(posed, False)
    rng = np.random.default_rng(11)
    args = [rng.uniform(0.5, 1.5, (function.nnz_in(i), 300)) for i in range(3)]
    got, want = SXColumns(function)(*args)[0], _on_machine(function, *args)
    assert got.shape == want.shape == (function.nnz_out(0), 300)
    assert np.array_equal(np.isfinite(got), np.isfinite(want))
    finite = np.isfinite(want)
    scale = np.max(np.abs(np.where(finite, want, 0)), axis=1, keepdims=True)
    assert np.all(np.abs(got - want)[finite] <= (1e-12 * scale + 1e-300).repeat(300, axis=1)[finite])


def test_a_window_of_the_wedge_reads_its_gradient_replayed():
    # a stored sweep's largest cost was this gradient on CasADi's machine (0.65-1.0 ms a 1000 wedge points)
    case = next(case for case in bench_cases() if case.coupling == "wedge")
    posed = case_problem(case, reference_mode("wedge"), "mass").posed
    assert isinstance(_window_gradient(posed), SXColumns)
