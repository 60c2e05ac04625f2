"""Interval evaluation (clutchopt.optimise.interval) bounds every value a function takes over a box, and the interval
proof (clutchopt.optimise.interval_proof) calls a case infeasible only where no design exists."""

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchopt.cases import load_case
from clutchopt.optimise.interval import IntervalFunction
from clutchopt.optimise.interval_proof import empty_design_space, interval_functions
from clutchopt.optimise.problem import case_problem
from clutchopt.start_up.drive import graded_part
from conftest import CASES

X = ca.SX.sym("x", 2)
EXPRESSIONS = {  # each op with a rule, and the compositions the formulations use
    "add-mul-div": X[0] * X[1] + X[0] / (X[1] + 3.5),
    "sub-neg": -(X[0] - 2 * X[1]),
    "sq-sqrt": ca.sqrt(X[0] ** 2 + 1) - X[1] ** 2,
    "powers": (X[0] ** 2 + 0.1) ** 1.5 + X[1] ** 3 - X[0] ** 4,
    "inverse-power": 1 / (X[0] ** 2 + 0.5),
    "exp-log": ca.exp(X[0]) * ca.log(X[1] ** 2 + 1),
    "sine": ca.sin(3 * X[0]) - X[1],
    "cosine": ca.cos(2 * X[1]) + X[0],
    "tangent": ca.tan(0.3 * X[0]) + ca.tan(X[1]),
    "no-rule": ca.erf(X[0]),  # unbounded, yet true
    "hyperbolic": ca.sinh(X[0]) + ca.cosh(X[1]) + ca.tanh(X[0] * X[1]) + ca.asinh(X[1]),
    "inverse-trig": ca.atan(X[0]) + ca.asin(X[1] / 3) + ca.acos(X[0] / 3),
    "min-max-abs": ca.fmax(X[0], X[1]) - ca.fmin(X[0], 2 * X[1]) + ca.fabs(X[0] - 1),
    "if-else": ca.if_else(X[0] < X[1], X[0] * X[1], -X[1]),
    "logic": ca.if_else(ca.logic_and(X[0] > 0, ca.logic_not(X[1] > 1)), 1.0, 2.0),
    "cbrt-of-product": (X[0] ** 2 * (X[1] ** 2 + 1)) ** (1 / 3),
}


@pytest.mark.parametrize("method", ["bounds", "replay"])  # compiled where it can be, and the NumPy reference
@pytest.mark.parametrize("name", EXPRESSIONS)
@settings(max_examples=40, deadline=None)
@given(st.floats(-3, 3), st.floats(-3, 3), st.floats(0, 2), st.floats(0, 2))
def test_bounds_contain_every_value_in_the_box(name, method, a, b, wa, wb):
    f = IntervalFunction(ca.Function("f", [X], [EXPRESSIONS[name]]))
    lo, hi = np.array([[a], [b]]), np.array([[a + wa], [b + wb]])
    (low, high), = getattr(f, method)([(lo, hi)])
    grid = np.stack(np.meshgrid(np.linspace(a, a + wa, 41), np.linspace(b, b + wb, 41))).reshape(2, -1)
    values = np.array(ca.Function("f", [X], [EXPRESSIONS[name]]).map(grid.shape[1])(grid)).ravel()
    finite = values[np.isfinite(values)]
    assert np.all(finite >= low[0, 0]) and np.all(finite <= high[0, 0]), (low, high, finite.min(), finite.max())
    if name not in ("no-rule", "tangent") and finite.size:  # (tan across a pole is unbounded)  # and not vacuously: as wide as the values, and a little
        assert high[0, 0] - low[0, 0] <= 10 * (np.ptp(finite) + 1)


@pytest.mark.parametrize("path", ["wedge_paper.toml", "lever_centrifuge.toml", "cable_conveyor.toml",
                                  "ball_crusher.toml", "wedge_motor_start.toml"])
def test_every_formulation_row_is_bounded_soundly(path):
    """The posed constraint rows of real models over boxes around the case's optimum: every sampled value inside."""
    case = load_case(CASES / path)
    problem = case_problem(case)
    posed = problem.posed
    design = problem.solve(case).design
    x = np.array([design[n] for n in posed.names])
    lower, upper, _ = posed.bounds_and_start(case, None)
    mesh = posed.start_up.initial_mesh(graded_part(case.start_up, case.values)) if posed.start_up else []
    p = np.concatenate([list(vars(posed.params(case)).values()), np.ones(len(x)), [1.0], mesh])
    rows, _ = interval_functions(posed)
    rng = np.random.default_rng(7)
    for relative in (0.3, 0.03, 0.003):
        half = (upper - lower) * relative / 2
        lo, hi = np.maximum(x - half, lower), np.minimum(x + half, upper)
        (low, high), = rows.bounds([(lo[:, None], hi[:, None]), (p[:, None], p[:, None])])
        samples = lo[:, None] + (hi - lo)[:, None] * rng.random((len(x), 300))
        g = np.array(rows.function.map(300)(samples, np.repeat(p[:, None], 300, axis=1)))
        assert np.all(g >= low - 1e-12) and np.all(g <= high + 1e-12)


@pytest.mark.parametrize("path, quantity, factor, decisive", [
    ("wedge_paper.toml", "resisting_torque", 1000, {"torque", "flank_pressure"}),
    ("cable_conveyor.toml", "torque", 10, set()),
    ("lever_centrifuge.toml", "resisting_torque", 10, set()),
    ("ball_crusher.toml", "power", 1000, {"torque"}),
])
def test_a_case_no_design_can_meet_is_proven_infeasible(path, quantity, factor, decisive):
    case = load_case(CASES / path)
    case = case.with_values(**{quantity: case.values[quantity] * factor})
    emptiness = empty_design_space(case_problem(case).posed, case)
    assert emptiness.proven and emptiness.feasible is None
    assert decisive <= set(emptiness.decisive)
    solution = case_problem(case).solve(case)
    assert solution.status == "infeasible" and "interval branch and bound" in solution.diagnosis


@pytest.mark.parametrize("path", ["wedge_paper.toml", "wedge_fan.toml", "lever_centrifuge.toml",
                                  "cable_pump.toml", "ball_conveyor.toml"])
def test_a_feasible_case_is_never_proven_empty(path):
    case = load_case(CASES / path)
    emptiness = empty_design_space(case_problem(case).posed, case)
    assert not emptiness.proven
    if emptiness.feasible is not None:  # a design it met meets every constraint, checked by the solver's own rows
        posed = case_problem(case).posed
        p = np.concatenate([list(vars(posed.params(case)).values()), np.ones(len(emptiness.feasible)), [1.0]])
        assert np.all(np.array(posed.constraint_values(emptiness.feasible, p)) <= 0)


def test_ball_motor_start_past_580_kw_is_proven_infeasible():
    """Issue 29: the crusher drive at 800 kW. Its design space is empty without the start-up: the static rows
    alone conflict (contact_stress, torque, width_ratio_max, ball_layers; no design from 40 random starts of the
    static NLP above 575 kW either). The proof needs Hertz's n_a, n_b bounded at the ends of B/A
    (clutchopt.monotone): replayed through the Newton step they are unbounded on 1 % boxes."""
    case = load_case(CASES / "ball_motor_start.toml")
    case = case.with_values(power=800e3)
    solution = case_problem(case).solve(case)
    assert solution.status == "infeasible"
    assert solution.diagnosis.startswith("proven infeasible") and "interval branch and bound" in solution.diagnosis
    assert "contact_stress" in solution.diagnosis.split("(")[0]


def test_integer_variables_are_whole_in_every_box():
    """The crusher drive at 565 kW: the continuous relaxation of its static design has designs (the solve's integer
    search says so, from the relaxed optimum), yet no whole number of ball rows does: the search proves it with
    each box's ball_rows rounded inwards to whole numbers, and keeps what is whole."""
    from clutchopt.optimise.interval_proof import _whole
    from clutchopt.optimise.problem import problem_for

    lo, hi = np.array([[0.1, 0.1, 0.1], [2.2, 2.0, 1.999999999999]]), np.array([[0.2, 0.2, 0.2], [2.8, 3.5, 2.0]])
    kept_lo, kept_hi, dropped = _whole(lo, hi, [1])
    assert kept_lo.tolist() == [[0.1, 0.1], [2.0, 2.0]] and kept_hi.tolist() == [[0.2, 0.2], [3.0, 2.0]]
    assert dropped == [1]  # [2.2, 2.8] holds no whole number
    case = load_case(CASES / "ball_motor_start.toml").with_values(power=565e3)
    problem = case_problem(case)
    relaxed = problem_for(problem.posed.base, "mass").refined(case)
    assert relaxed.status == "infeasible" and "the continuous relaxation is feasible" in relaxed.diagnosis
    emptiness = empty_design_space(problem.posed, case)
    assert emptiness.proven and "contact_stress" in emptiness.decisive
