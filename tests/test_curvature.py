"""A warm re-solve's KKT point is kept only where no direction its holding rows and bounds leave free curves down
(``chain.curvature``): an SQP along a sweep had kept a maximum along such a direction (review 24)."""

from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise.chain import CURVATURE_TOL, curved_up, first_order_optimal, no_descent_curvature
from clutchopt.optimise.problem import case_problem, solve_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import Vary

CASES = Path(__file__).resolve().parents[1] / "cases"
SPEEDS, FRICTIONS = np.geomspace(0.6, 1.6, 8), np.geomspace(0.5, 2.0, 8)  # factors on the case's values
# The batched sweep's point 12 (speed x 0.6875, friction x 1.1006) had ended at this design, 0.73045804 kg: every row
# that holds it is met with equality along one direction, on which the mass peaks at radius_ratio 1.13337 (1.1, its
# lower bound, 0.73044093 kg; 1.14, 0.7304568 kg)
SADDLE = {"flank_inner_radius": 0.12793750620275307, "radius_ratio": 1.1333658463697267,
          "weight_height": 0.018083242402269585, "sector_angle": 0.19026167760419385,
          "weight_width": 0.03633492325967773, "finger_diameter": 0.012055494934846388,
          "flank_angle": 0.19903031407663652, "weight_count": 3.0}


def _case():
    case = load_case(CASES / "wedge_centrifuge.toml")
    return case, case.with_values(speed=SPEEDS[1] * case.values["speed"],
                                  friction_coefficient=FRICTIONS[4] * case.values["friction_coefficient"])


def _primal_dual(posed, case, design):
    """The scaled point of ``design`` (its weight count fixed) with the multipliers of the rows and bounds that hold
    it, by least squares on the stationarity of the Lagrangian."""
    data = posed.scaled_data(case, design)
    x, p, nlp = data.x0, data.p, posed.nlp
    g, jac, grad = (np.array(ca.Function("f", [nlp["x"], nlp["p"]], [expr])(x, p)) for expr in (
        nlp["g"], ca.jacobian(nlp["g"], nlp["x"]), ca.gradient(nlp["f"], nlp["x"])))
    lbx, ubx = data.lbx.copy(), data.ubx.copy()
    count = posed.names.index("weight_count")
    lbx[count] = ubx[count] = x[count]
    rows = np.flatnonzero(g.ravel() > -1e-8)
    bounds = np.flatnonzero((x - lbx < 1e-12) | (ubx - x < 1e-12))
    mu = np.linalg.lstsq(np.vstack([jac[rows], np.eye(len(x))[bounds]]).T, -grad.ravel(), rcond=None)[0]
    lam_g, lam_x = np.zeros(g.shape[0]), np.zeros(len(x))
    lam_g[rows], lam_x[bounds] = mu[:len(rows)], mu[len(rows):]
    return x, p, lam_x, lam_g, lbx, ubx


def test_a_kkt_point_that_is_a_maximum_along_a_free_direction_is_refused_and_the_minimum_kept():
    _, case = _case()
    posed = case_problem(case, "geometry", "mass").posed
    at_saddle = _primal_dual(posed, case, SADDLE)
    assert first_order_optimal(posed, *at_saddle)[0]  # a KKT point to the verdict's tolerance
    assert not no_descent_curvature(posed, *at_saddle)[0]
    alone = solve_case(case, "geometry", "mass")
    assert alone.objective == pytest.approx(0.7304409336169, rel=1e-9)  # (the saddle's 0.73045804 kg)
    at_minimum = _primal_dual(posed, case, alone.design)
    assert first_order_optimal(posed, *at_minimum)[0] and no_descent_curvature(posed, *at_minimum)[0]


def test_the_sweep_grid_keeps_the_minimum_solve_finds_at_that_point():
    base, case = _case()
    quantities = {q.name: q for q in base.quantities}
    result = Sweep(base, [Vary(quantities["speed"], tuple(SPEEDS * base.values["speed"])),
                          Vary(quantities["friction_coefficient"],
                               tuple(FRICTIONS * base.values["friction_coefficient"]))],
                   mode="geometry").run(progress=False)
    point = result.solutions[12]
    assert point["status"] == "optimal"
    assert point["objective"]["value"] == pytest.approx(0.7304409336169, rel=1e-9)
    assert point["design"]["radius_ratio"] == pytest.approx(1.1, rel=1e-12)


def _values(hessian, held) -> np.ndarray:
    """:func:`curved_up`'s column for a point: H then P, each column by column."""
    return np.concatenate([np.asarray(hessian, dtype=float).ravel(order="F"),
                           np.asarray(held, dtype=float).ravel(order="F")])[:, None]


def test_the_matrix_test_reads_negative_curvature_along_free_directions_only():
    held = np.diag([0.0, 0.0, 1.0])  # (the third direction held by a row, the first two free)
    columns = [
        _values(np.diag([-1e-3, 2.0, 1.0]), held),  # a free direction curving down: refused
        _values(np.diag([-0.1 * CURVATURE_TOL, 2.0, 1.0]), held),  # flat to within the tolerance: kept
        _values(np.diag([1.0, 2.0, -5.0]), held),  # curving down only where a row holds it: kept
        _values(np.diag([-1.0, 1.0, 1.0]), np.diag([1e-8, 1.0, 1.0])),  # barely held (the penalty lifts it by 0.01,
        # the exact test finds no free direction): kept
        _values(np.diag([-1.0, 1.0, 1.0]), np.diag([1e-12, 1.0, 1.0])),  # held by nothing to within 1e-10: refused
        np.full((18, 1), np.nan),
    ]
    assert list(curved_up(np.hstack(columns))) == [False, True, True, True, False, False]
