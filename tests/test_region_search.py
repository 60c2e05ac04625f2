"""Infeasible regions of a sweep searched together (issue 26 item 3): the interval searches of the points ahead of a
point without a design run in one array (interval_proof.searches), and every point keeps the verdict its own solve
gives (issue 29: "infeasible" only when shown, whatever the order of the points)."""

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import interval_proof, sweep
from clutchopt.optimise.interval import IntervalFunction
from clutchopt.optimise.interval_proof import search, searches
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from tests.conftest import CASES

WEDGE = load_case(CASES / "wedge_paper.toml")


def test_a_box_is_bounded_alike_whatever_boxes_are_evaluated_with_it():
    import casadi as ca

    x, y = ca.SX.sym("x"), ca.SX.sym("y")
    product = IntervalFunction(ca.Function("xy", [x, y], [x * y]))
    # box 0: x in [0, 0], y in [1, inf]: x y = 0 throughout (the corners 0 * 1 = 0; 0 * inf left out); box 1 has a
    # negative x, which once sent every box to the four-corner rule
    x_lo, x_hi, y_lo, y_hi = np.array([[0.0, -1.0]]), np.array([[0.0, 1.0]]), np.array([[1.0, 1.0]]), \
        np.array([[np.inf, 2.0]])
    (alone_lo, alone_hi), = product.bounds([(x_lo[:, :1], x_hi[:, :1]), (y_lo[:, :1], y_hi[:, :1])])
    (both_lo, both_hi), = product.bounds([(x_lo, x_hi), (y_lo, y_hi)])
    assert alone_hi[0, 0] == both_hi[0, 0] == 0.0 and alone_lo[0, 0] == both_lo[0, 0] == 0.0
    assert both_lo[0, 1] <= -2.0 and both_hi[0, 1] >= 2.0  # [-1, 1] x [1, 2] = [-2, 2], widened outwards


def test_searches_together_give_each_point_its_own_search():
    # the wedge paper case at resisting torques from 20 to 400 N m: a design met at the low ones (the search stops
    # there), emptiness proven at the high ones over 129 or 257 boxes (torque and flank pressure)
    posed = case_problem(WEDGE).posed
    problems = [interval_proof._search_problem(posed, WEDGE.with_values(resisting_torque=torque))
                for torque in (20.0, 140.0, 60.0, 400.0, 160.0)]
    together = searches(posed, problems)
    alone = [search(posed, *problem) for problem in problems]
    assert [e.proven for e in alone] == [False, True, False, True, True]
    assert [e.feasible is not None for e in alone] == [True, False, True, False, False]
    for a, b in zip(alone, together):
        assert (a.proven, a.boxes, list(a.decisive.items())) == (b.proven, b.boxes, list(b.decisive.items()))
        assert (a.feasible is None and b.feasible is None) or np.array_equal(a.feasible, b.feasible)


@pytest.mark.parametrize("batched", [True, False])  # in batches, or point by point (start-ups, varied variables)
def test_a_sweep_into_an_infeasible_region_gives_each_point_its_solve_s_verdict(monkeypatch, batched):
    ahead = []
    real = interval_proof.search_ahead
    monkeypatch.setattr(interval_proof, "search_ahead",
                        lambda posed, cases: ahead.append(len(cases)) or real(posed, cases))
    if not batched:
        monkeypatch.setattr(sweep, "batchable", lambda problem, names: False)
    vary = parse_vary("resisting_torque=20:400:12", "wedge", WEDGE.quantities)
    frame = Sweep(WEDGE, [vary]).run(progress=False).frame
    # 20, 54.5, 89.1 N m designed; from 123.6 N m on proven infeasible: the first such point searched alone, the
    # next 8 (up to 400 N m) together
    assert list(frame["status"]) == ["optimal"] * 3 + ["infeasible"] * 9
    assert ahead == [8]
    problem = case_problem(WEDGE)
    for point in (2, 3, 4, 11):  # both edges of the region and its far end
        solution = problem.solve(WEDGE.with_values(resisting_torque=vary.values[point]))
        assert (frame["status"][point], frame["diagnosis"][point]) == (solution.status, solution.diagnosis or "")


@pytest.mark.parametrize("order", [slice(None), slice(None, None, -1)])
def test_the_verdicts_do_not_depend_on_the_order_of_the_points(order):
    values = np.linspace(20.0, 400.0, 12)[order]
    vary = parse_vary("resisting_torque=" + ",".join(f"{v:.17g}" for v in values), "wedge", WEDGE.quantities)
    frame = Sweep(WEDGE, [vary]).run(progress=False).frame
    statuses = list(frame["status"])[order]
    assert statuses == ["optimal"] * 3 + ["infeasible"] * 9
