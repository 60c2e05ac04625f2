"""Rows' limits carried back through their expressions (clutchopt.optimise.interval_backward): every design a box
holds within a row's limit stays in it, the cuts are those the algebra gives, and the lever in design mode, whose
searches gave up at every point of 1x-10x its inertia without a design, is proven infeasible."""

from functools import lru_cache

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchopt.bench.reference import bench_cases
from clutchopt.cases import load_case
from clutchopt.optimise.interval import IntervalFunction
from clutchopt.optimise.interval_backward import Tape, contracted
from clutchopt.optimise.interval_proof import _search_problem, interval_functions, row_tape, search
from clutchopt.optimise.problem import case_problem
from conftest import CASES

LEVER = next(case for case in bench_cases() if case.coupling == "lever")
PROBLEMS = [("wedge_paper.toml", None), ("lever_centrifuge.toml", None), ("lever_centrifuge.toml", "design"),
            ("cable_conveyor.toml", None)]


@lru_cache(maxsize=None)
def _posed(path, mode):
    case = load_case(CASES / path)
    posed = case_problem(case, mode).posed
    p, lower, upper = _search_problem(posed, case)
    return posed, p, lower, upper


def _tape(rows: list, n: int) -> Tape:
    x, p = ca.SX.sym("x", n), ca.SX.sym("p", 1)
    function = ca.Function("rows", [x, p], [ca.vertcat(*rows(x, p))])
    return Tape(function, IntervalFunction(function).program)


@pytest.mark.parametrize("path, mode", PROBLEMS)
@settings(max_examples=15, deadline=None)
@given(st.lists(st.floats(0, 1), min_size=16, max_size=16), st.floats(-4, 0), st.floats(0.05, 0.95))
def test_every_point_within_a_row_s_limit_stays_in_the_contracted_box(path, mode, fractions, log_width, quantile):
    """Random boxes of the design box (a random centre, a relative width 10^-4 to 1): carrying one row back at a
    limit (a quantile of its values at 200 random points, so that some are within it and some beyond) keeps every
    point where the row is within the limit, and never empties such a box."""
    posed, p, lower, upper = _posed(path, mode)
    tape, n = row_tape(posed), len(lower)
    centre = lower + (upper - lower) * np.array(fractions[:n])
    half = (upper - lower) * 10 ** log_width * np.array(fractions[n:2 * n]) / 2 + 1e-300
    lo, hi = np.maximum(centre - half, lower), np.minimum(centre + half, upper)
    lo[posed.integer], hi[posed.integer] = np.round(lo[posed.integer]), np.round(lo[posed.integer])
    rng = np.random.default_rng(len(fractions) + int(1e6 * quantile))
    x = lo[:, None] + (hi - lo)[:, None] * rng.random((n, 200))
    g = np.array(interval_functions(posed)[0].function.map(200)(x, np.repeat(p[:, None], 200, axis=1)))
    for row in range(g.shape[0]):
        limit = float(np.quantile(g[row], quantile))
        uncertain = np.zeros((g.shape[0], 1), dtype=bool)
        uncertain[row] = True
        new_lo, new_hi, empty, cutters = contracted(tape, lo[:, None], hi[:, None], [(p[:, None], p[:, None])], limit,
                                                    uncertain)
        assert not cutters[np.arange(g.shape[0]) != row].any()  # (only the row carried back cuts)
        within = x[:, g[row] <= limit - 1e-12 * (1 + abs(limit))]
        if within.size:
            assert not empty[0]
            assert np.all(within >= new_lo) and np.all(within <= new_hi), (row, limit)


def test_a_product_s_limit_bounds_each_factor_by_the_other_s_ends():
    """x0 x1 >= 1 over [0.1, 1] x [0.1, 2]: x0 >= 1/2 (x1 at most 2), x1 >= 1 (x0 at most 1), the row named; the
    mean-value form cuts neither so far (its slopes span 0.1 to 2). sin(x0) <= 0.25 bounds x0 by asin(0.25), and
    x1^(1/3) >= 1.1 bounds x1 by 1.331; x1 <= 0.9 with the product's limit leaves nothing, both named."""
    tape = _tape(lambda x, p: [1 - x[0] * x[1] / p, ca.sin(x[0]) - 0.25, 1.1 - x[1] ** (1 / 3), x[1] - 0.9], 2)
    lo, hi, p = np.array([[0.1], [0.1]]), np.array([[1.0], [2.0]]), np.ones((1, 1))
    only = [np.array([[True], [False], [False], [False]]), np.array([[False], [True], [True], [False]])]
    new_lo, new_hi, empty, cutters = contracted(tape, lo, hi, [(p, p)], 0.0, only[0])
    assert not empty[0] and cutters[:, 0].tolist() == [True, False, False, False]
    assert new_lo[:, 0] == pytest.approx([0.5, 1.0], rel=1e-11) and np.all(new_lo[:, 0] <= [0.5, 1.0])
    assert new_hi[:, 0].tolist() == [1.0, 2.0]
    new_lo, new_hi, empty, cutters = contracted(tape, lo, hi, [(p, p)], 0.0, only[1])
    assert not empty[0] and cutters[:, 0].tolist() == [False, True, True, False]
    assert new_hi[0, 0] == pytest.approx(np.arcsin(0.25), rel=1e-11) and new_hi[0, 0] >= np.arcsin(0.25)
    assert new_lo[1, 0] == pytest.approx(1.331, rel=1e-11) and new_lo[1, 0] <= 1.331
    _, _, empty, cutters = contracted(tape, lo, hi, [(p, p)], 0.0, np.array([[True], [False], [False], [True]]))
    assert empty[0] and cutters[:, 0].tolist() == [True, False, False, True]


@pytest.mark.parametrize("factor", [5.0, 8.0])
def test_the_lever_in_design_mode_past_its_edge_is_proven_infeasible(factor):
    """The bench's lever case in design mode at 5x and 8x its inertia (its last design near 3.4x): the searches gave
    up (the boxes left growing by more than GROWTH past SURE_BOXES, 2,519 boxes) with the mean-value contraction
    alone; carried back, the torque (a product of m, z, R_0, d_cp over orders of magnitude) meets the weights' fit,
    the outer diameter and the linings' clearance, and the design box is proven empty."""
    posed = case_problem(LEVER, "design").posed
    emptiness = search(posed, *_search_problem(posed, LEVER.with_values(inertia=LEVER.values["inertia"] * factor)))
    assert emptiness.proven and emptiness.feasible is None
    assert {"torque", "outer_diameter", "lining_clears_flange"} <= set(emptiness.decisive)


def test_the_lever_in_design_mode_with_a_design_is_never_proven_empty():
    """At 2x its inertia the lever in design mode has a design (the solver's): its search must not prove."""
    posed = case_problem(LEVER, "design").posed
    emptiness = search(posed, *_search_problem(posed, LEVER.with_values(inertia=LEVER.values["inertia"] * 2)))
    assert not emptiness.proven


def test_the_compiled_forward_replay_gives_the_numpy_one_s_bounds():
    """Tape.forward by the compiled replay (each value in a work variable of its own) and by NumPy (without a
    library): the same bounds for every value a row depends on, over random boxes of the lever in design mode (to
    the last ulps libm's elementary functions may differ by from NumPy's, inside the replay's widening)."""
    posed, p, lower, upper = _posed("lever_centrifuge.toml", "design")
    compiled = row_tape(posed)
    assert compiled.compiled is not None
    numpy_tape = Tape(compiled.function, IntervalFunction(compiled.function).program)
    numpy_tape.compiled = None
    rng = np.random.default_rng(3)
    a, b = (lower[:, None] + (upper - lower)[:, None] * rng.random((len(lower), 20)) for _ in range(2))
    boxes = [(np.minimum(a, b), np.maximum(a, b)), (np.repeat(p[:, None], 20, axis=1),) * 2]
    rows = list(range(len(compiled.rows)))
    ours, theirs = compiled.forward(boxes, rows), numpy_tape.forward(boxes, rows)
    for k in sorted(set().union(*map(set, compiled.subgraphs))):
        for end in (0, 1):
            assert np.allclose(ours[k][end], theirs[k][end], rtol=1e-13, atol=0, equal_nan=True), k


@pytest.mark.parametrize("path, mode", PROBLEMS)
def test_the_compiled_backward_pass_gives_the_numpy_one_s_bounds(path, mode):
    """Tape.revised in C (the forward replay's values carried back by interval_revise) and Tape.backward in NumPy of
    the same values: the same bounds for each row carried back (a random subset of the rows, at a random quantile of
    their values as limit) and the same boxes emptied, over 300 random boxes of each problem, 10^-5 to 1 of the design
    box wide (to the last ulps libm's elementary functions may differ by from NumPy's, inside the rules' slack)."""
    posed, p, lower, upper = _posed(path, mode)
    tape, n, boxes = row_tape(posed), len(lower), 300
    assert tape.compiled is not None
    rng = np.random.default_rng(7)
    emptied = 0
    for _ in range(6):
        centre = lower[:, None] + (upper - lower)[:, None] * rng.random((n, boxes))
        half = (upper - lower)[:, None] * 10 ** rng.uniform(-5, 0, (n, boxes)) / 2
        lo, hi = np.maximum(centre - half, lower[:, None]), np.minimum(centre + half, upper[:, None])
        x = lo + (hi - lo) * rng.random((n, boxes))
        g = np.array(interval_functions(posed)[0].function.map(boxes)(x, np.repeat(p[:, None], boxes, axis=1)))
        limit = float(np.quantile(g, rng.uniform(0.05, 0.95)))
        rows = sorted(rng.choice(len(tape.rows), size=rng.integers(1, len(tape.rows) + 1), replace=False).tolist())
        inputs = [(lo, hi), (np.repeat(p[:, None], boxes, axis=1),) * 2]
        (c_lo, c_hi), c_empty = tape.revised(inputs, limit, n, rows)
        (n_lo, n_hi), n_empty = tape.backward(tape.forward(inputs, rows), limit, n, rows)
        assert np.array_equal(c_empty, n_empty)
        kept = ~n_empty.any(axis=0)
        for ours, theirs in ((c_lo, n_lo), (c_hi, n_hi)):
            assert np.allclose(ours[..., kept], theirs[..., kept], rtol=1e-13, atol=0, equal_nan=True)
        emptied += int(n_empty.any(axis=0).sum())
    assert mode == "design" or emptied  # (the rules' emptying compared too, not only their bounds)


def test_a_result_rounded_up_from_below_the_least_float_cuts_no_design():
    """exp(x0) x1 <= 1 and x0 <= -744.9 over x0 in [-745, -740], x1 in [1, 2]: x = (-745, 1.5) meets both, but the
    forward rules bound exp(-745) (2.1e-324) from the least subnormal, 5e-324, whose log carried back cut x0 >= -744.44
    and emptied the box (review 20c); every bound a backward rule reads is widened by FLOOR too."""
    x, p = ca.SX.sym("x", 2), ca.SX.sym("p", 1)
    rows = ca.Function("rows", [x, p], [ca.vertcat(ca.exp(x[0]) * x[1] - p[0], x[0] + 744.9)])
    tape = Tape(rows, IntervalFunction(rows).program)
    for compiled in (tape.compiled, None):  # (the forward replay in C, then in NumPy)
        tape.compiled = compiled
        lo, hi, empty, _ = contracted(tape, np.array([[-745.0], [1.0]]), np.array([[-740.0], [2.0]]),
                                      [(np.array([[1.0]]), np.array([[1.0]]))], 1e-6, np.ones((2, 1), dtype=bool))
        assert not empty.any() and lo[0, 0] <= -745.0 and lo[1, 0] <= 1.5 <= hi[1, 0]
