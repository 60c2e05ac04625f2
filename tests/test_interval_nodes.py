"""Declared monotone nodes (clutchopt.monotone): the declaration holds over its domain, and the interval rows that
use it bound every value the NLP's own rows take."""

import casadi as ca
import numpy as np

from clutchopt.formulations.ball.contact import HERTZ_ERROR, hertz_area_coefficient, hertz_coefficients, \
    hertz_coefficients_exact
from clutchopt.monotone import as_symbols


def test_hertz_coefficients_are_monotone_with_monotone_slopes_over_the_domain():
    """n_a rises, n_b falls with B/A (Timoshenko & Goodier's table: n_a = n_b = 1 at B/A = 1); n_a concave, n_b
    convex: the declaration the interval proof bounds them by, at 200,001 points of 1.01 <= B/A <= 1e5."""
    ratios = np.geomspace(*hertz_coefficients.domain, 200_001)
    values, slopes = hertz_coefficients.values_and_slopes(ratios)
    for k, (rising, slope_rising) in enumerate(zip(hertz_coefficients.increasing, hertz_coefficients.slope_increasing)):
        assert np.all(np.diff(values[k]) > 0) == rising and np.all(np.diff(values[k]) < 0) == (not rising)
        assert np.all(np.diff(slopes[k]) > 0) == slope_rising and np.all(np.diff(slopes[k]) < 0) == (not slope_rising)
    exact = np.array([hertz_coefficients_exact(r) for r in ratios[::1000]]).T
    assert np.max(np.abs(values[:, ::1000] / exact - 1)) < HERTZ_ERROR / 10


def test_the_contact_area_coefficient_is_monotone_with_a_monotone_slope_over_its_domain():
    """n_a n_b (what the peak pressure takes: p_0 = 1.5 / (pi n_a n_b) (...)^(1/3)) rises with B/A from 1 at
    B/A = 1; its slope rises up to B/A = 2.55 and falls beyond, so it is declared concave over 2.6 <= B/A <= 1e5
    (200,001 points), its values within 3 HERTZ_ERROR of the exact product."""
    ratios = np.geomspace(*hertz_area_coefficient.domain, 200_001)
    (values,), (slopes,) = hertz_area_coefficient.values_and_slopes(ratios)
    assert hertz_area_coefficient.increasing == (True,) and hertz_area_coefficient.slope_increasing == (False,)
    assert np.all(np.diff(values) > 0) and np.all(np.diff(slopes) < 0)
    below, = hertz_area_coefficient.values_and_slopes(np.geomspace(1.01, 2.5, 1001))[1]
    assert not np.all(np.diff(below) < 0)  # the inflection the domain leaves out
    exact = np.prod([hertz_coefficients_exact(r) for r in ratios[::1000]], axis=1)
    assert np.max(np.abs(values[::1000] / exact - 1)) < hertz_area_coefficient.error / 10


def test_enclosure_holds_every_value_between_the_ends():
    """Over [20, 30] of B/A the enclosure of n_a is [n_a(20), n_a(30)], of n_b [n_b(30), n_b(20)], a little wider;
    every value and slope inside, and no wider than the ends' span."""
    (v_lo, v_hi), (s_lo, s_hi) = hertz_coefficients.enclosure(np.array([20.0]), np.array([30.0]))
    values, slopes = hertz_coefficients.values_and_slopes(np.linspace(20.0, 30.0, 1001))
    for k in (0, 1):
        assert v_lo[k, 0] <= values[k].min() and values[k].max() <= v_hi[k, 0]
        assert s_lo[k, 0] <= slopes[k].min() and slopes[k].max() <= s_hi[k, 0]
        assert v_hi[k, 0] - v_lo[k, 0] < 1.0001 * np.ptp(values[k]) + 1e-8
    (n_lo, _), _ = hertz_coefficients.enclosure(np.array([0.5]), np.array([30.0]))
    assert np.isnan(n_lo).all()  # outside the domain: no claim


def test_as_symbols_stands_symbols_for_the_values_and_collects_them():
    r = ca.SX.sym("r")
    with as_symbols() as nodes:
        n_a, n_b = hertz_coefficients(r * 2)
    assert [node.index for node in nodes] == [0, 1] and n_a.is_symbolic() and n_b.is_symbolic()
    assert ca.depends_on(nodes[0].argument, r) and ca.depends_on(nodes[1].value, r)
    n_a, _ = hertz_coefficients(r)  # outside: the expression itself
    assert not n_a.is_symbolic()


def test_declared_nodes_stand_for_the_nlp_rows_or_are_not_used():
    """The ball's rows with n_a, n_b as symbols agree with the NLP's own at the design box's points; a formulation
    that differentiates its own rows through the node (here: d contact_stress / d ball_radius taken inside the
    constraint, as a chance constraint takes its slope in a scattered quantity) does not, and the search replays
    the node instead."""
    from dataclasses import replace

    from clutchopt.cases import load_case
    from clutchopt.model import at_most
    from clutchopt.optimise.interval_proof import interval_functions
    from clutchopt.optimise.problem import case_problem, problem_for
    from conftest import CASES

    case = load_case(CASES / "ball_crusher.toml")
    posed = case_problem(case).posed
    lower, upper, _ = posed.bounds_and_start(case, None)
    p = np.concatenate([list(vars(posed.params(case)).values()), np.ones(len(lower)), [1.0]])
    rows, _ = interval_functions(posed)
    assert rows.nodes.nodes and rows.nodes.agree(lower, upper, p)

    base = posed.formulation

    def constraints(x, q):
        own = base.constraints(x, q)
        stress = [c for c in own if c.name == "contact_stress"][0]
        if not isinstance(stress.value, ca.SX):
            return own
        scaled_radius = [v for v in ca.symvar(x.ball_radius) if v.name().startswith("x_hat")][0]
        slope = ca.jacobian(ca.SX(stress.value), scaled_radius)  # d p_0 / d r_c, r_c in its start's units
        return own + [at_most("stress_slope", slope, 1e13, equation="-")]

    bent = problem_for(replace(base, constraints=constraints, variant="slope"), "mass").posed
    rows, _ = interval_functions(bent)
    assert rows.nodes.nodes and not rows.nodes.agree(lower, upper, p)
