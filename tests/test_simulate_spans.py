"""LSODA in spans of odeint (clutchopt/simulate/spans.py) against closed-form solutions: a terminal event's time and
state, sampled maxima located on the span's own samples and (a motion too fast for them) on an interval
integrated again; the step budget; the traced functions of clutchopt/simulate/on_floats.py."""

import math

import numpy as np
import pytest

import clutchopt.simulate.spans as spans
from clutchopt.backend import exp, fmax, sqrt
from clutchopt.simulate.on_floats import bound, on_numpy, parametrised
from clutchopt.simulate.spans import integrate_spans
from clutchopt.simulate.stepping import Budget


def _event(function, terminal, direction):
    function.terminal, function.direction = terminal, direction
    return function


def test_a_terminal_event_of_a_decay_is_found_at_its_closed_form():
    # y' = -k y, y(0) = 1: y = e^{-k t} reaches 0.3 at t = ln(1 / 0.3) / k; work' = y: work = (1 - e^{-k t}) / k
    k = 2.0
    falls = _event(lambda t, y: y[0] - 0.3, True, -1)
    out = integrate_spans(lambda t, y: [-k * y[0], y[0]], lambda t, y: np.array([[-k, 0.0], [1.0, 0.0]]), 0.0,
                          np.array([1.0, 0.0]), 100.0, [falls], 1e-12, np.array([1e-12, 1e-12]), Budget(20_000),
                          1e-3)
    assert out.status == "event" and out.event == 0
    assert out.t[-1] == pytest.approx(math.log(1 / 0.3) / k, rel=1e-10)
    assert out.y[0, -1] == pytest.approx(0.3, rel=1e-10)
    assert out.y[1, -1] == pytest.approx(0.7 / k, rel=1e-10)
    assert np.all(np.diff(out.t) >= 0) and out.t[0] == 0.0


def test_a_maximum_where_the_samples_interpolate_as_accurately_as_integrated_is_not_integrated_again(monkeypatch):
    # x'' = -w^2 x, x(0) = 0, x'(0) = w, w = 2 rad/s: the maximum x = 1 at t = pi / (2 w) = 0.785 s, where the samples
    # are 1.6 % of the time apart (0.0126 s: w h = 0.025, two interpolants of six agree to ~(w h)^6 / 720 ~ 3e-13 of
    # the amplitude, below rtol): its state is the interpolant's, no odeint run from a sample to it (a restart of
    # LSODA); the terminal event at t = pi / w is integrated to, as ever (runs of two times, from its last sample)
    omega, end = 2.0, math.pi / 2.0
    runs, odeint = [], spans.odeint
    monkeypatch.setattr(spans, "odeint", lambda *args, **kwargs: runs.append(args[2]) or odeint(*args, **kwargs))
    peak = _event(lambda t, y: y[1], False, -1)
    ends = _event(lambda t, y: t - end, True, 1)
    out = integrate_spans(lambda t, y: [y[1], -omega**2 * y[0]],
                          lambda t, y: np.array([[0.0, 1.0], [-omega**2, 0.0]]), 0.0, np.array([0.0, omega]),
                          1e9, [peak, ends], 1e-11, np.array([1e-11, 1e-11 * omega]), Budget(50_000), 1e-3,
                          extremes_interpolated=True)
    assert out.status == "event" and out.t[-1] == pytest.approx(end, rel=1e-12)
    at = int(np.argmax(out.y[0]))
    assert out.t[at] == pytest.approx(math.pi / (2 * omega), rel=1e-6) and out.y[0, at] == pytest.approx(1.0, abs=1e-9)
    roots = [grid for grid in runs if len(grid) == 2]
    assert roots and all(grid[0] > 0.9 * end for grid in roots)  # the terminal event's only (its last sample)


@pytest.mark.parametrize("omega, periods, zoomed", [(2.0, 2, False), (400.0, 20, True)])  # samples spaced 1.6 % of
# the time since the start: at 2 rad/s some 30 a period to the end (roots on them), at 400 rad/s a few (on zooms)
def test_the_maxima_of_an_oscillation_are_sampled_where_they_are(omega, periods, zoomed, monkeypatch):
    # x'' = -w^2 x, x(0) = 0, x'(0) = w: x = sin(w t), maxima 1 at t = (pi/2 + 2 pi n) / w (v = x' from + to -);
    # LSODA's own error over 20 periods at rtol 1e-11: 1.5e-9 in the amplitude (stepped through solve_ivp: 1.5e-9)
    zooms = []
    monkeypatch.setattr(spans, "_zoom", lambda *args, _zoom=spans._zoom: zooms.append(1) or _zoom(*args))
    peak = _event(lambda t, y: y[1], False, -1)
    ends = _event(lambda t, y: t - periods * 2 * math.pi / omega, True, 1)
    out = integrate_spans(lambda t, y: [y[1], -omega**2 * y[0]],
                          lambda t, y: np.array([[0.0, 1.0], [-omega**2, 0.0]]), 0.0, np.array([0.0, omega]),
                          1e9, [peak, ends], 1e-11, np.array([1e-11, 1e-11 * omega]), Budget(50_000), 1e-3)
    assert out.status == "event" and out.event == 1
    assert out.t[-1] == pytest.approx(periods * 2 * math.pi / omega, rel=1e-12)
    assert out.y[0].max() == pytest.approx(1.0, abs=3e-9)
    assert bool(zooms) == zoomed
    maxima = out.t[np.isclose(out.y[0], 1.0, rtol=0, atol=3e-9)]
    assert len(maxima) == periods
    assert maxima == pytest.approx((math.pi / 2 + 2 * math.pi * np.arange(periods)) / omega, rel=1e-6)


@pytest.mark.parametrize("second, located", [(0.9, 1), (0.995, 2)])
def test_an_extreme_that_cannot_be_the_largest_of_its_figure_is_not_located(second, located):
    # x'' = -2a x' - (w^2 + a^2) x, x(0) = 0, x'(0) = w: x = e^{-a t} sin(w t), each maximum e^{-2 pi a / w} times the
    # one before (``second``); two periods. With the event's figure x, a maximum whose samples are more than
    # PEAK_MARGIN (1e-2) below the largest sample so far is not located: at 0.9 the second is not, at 0.995 it is (its
    # samples within the margin); the largest x is the same to the bit as where every maximum is located
    omega = 2.0
    a = -math.log(second) * omega / (2 * math.pi)

    def run(figure):
        peak = _event(lambda t, y: y[1], False, -1)
        if figure:
            peak.figure = lambda y: y[0]
        ends = _event(lambda t, y: t - 2 * 2 * math.pi / omega, True, 1)
        jacobian = np.array([[0.0, 1.0], [-(omega**2 + a**2), -2 * a]])
        return integrate_spans(lambda t, y: [y[1], -2 * a * y[1] - (omega**2 + a**2) * y[0]], lambda t, y: jacobian,
                               0.0, np.array([0.0, omega]), 1e9, [peak, ends], 1e-11, np.array([1e-11, 1e-11 * omega]),
                               Budget(50_000), 1e-3, extremes_interpolated=True)

    every, largest = run(False), run(True)
    maxima = largest.t[np.abs(largest.y[1]) < 1e-9 * omega]  # located: the rate zero there
    assert len(every.t[np.abs(every.y[1]) < 1e-9 * omega]) == 2 and len(maxima) == located
    assert len(largest.t) == len(every.t) - (2 - located)
    assert largest.y[0].max() == every.y[0].max()
    assert maxima[0] == pytest.approx(math.atan(omega / a) / omega, rel=1e-6)  # x' = 0: tan(w t) = w / a


def test_a_run_past_its_budget_stops_with_that_status():
    budget = Budget(50)
    out = integrate_spans(lambda t, y: [y[1], -1e4 * y[0]], None, 0.0, np.array([0.0, 1.0]), 1e3, [], 1e-12,
                          np.array([1e-12, 1e-12]), budget, 1e-3)
    assert out.status == "budget" and budget.spent and out.t[-1] < 1e3


def _traced(equation, probes):
    """``equation`` of two numbers written out on floats as clutchopt/simulate/elastic.py binds its equations: no
    parameters, untraceable or differing at ``probes`` the equation itself, a call Python's math cannot answer
    answered by it on NumPy floats."""
    return bound(lambda: equation, (0, 0), parametrised(), None, equation, probes,
                 fallback=lambda *point: on_numpy(equation, point))


def test_a_traced_function_is_the_equation_on_floats():
    def equation(x, y):  # written with clutchopt.backend, as a formulation's
        return sqrt(1.0 + x * x) / (2.0 + y) + fmax(x - 1.0, 0.0)

    traced = _traced(equation, [(0.0, 0.0), (3.0, 1.0)])
    assert traced is not equation
    for x, y in [(0.5, 0.25), (3.0, 1.0), (-2.0, 7.0)]:
        assert traced(x, y) == pytest.approx(math.sqrt(1 + x * x) / (2 + y) + max(x - 1, 0), rel=1e-15)


def test_a_traced_function_is_the_equation_where_python_s_math_is_not_ieee_s():
    def equation(x, y):  # on NumPy floats NaN for x < 0 and y fractional, inf at x = 0; Python's math raises or
        # goes complex
        return x ** y + sqrt(x) + 1.0 / x + exp(y)

    traced = _traced(equation, [(1.0, 2.0), (4.0, 0.5)])
    assert traced is not equation and traced(4.0, 0.5) == pytest.approx(2.0 + 2.0 + 0.25 + math.exp(0.5), rel=1e-15)
    with np.errstate(all="ignore"):
        f = np.float64
        assert math.isnan(traced(-8.0, 1.0 / 3.0)) and math.isnan(equation(f(-8.0), f(1.0 / 3.0)))
        assert traced(0.0, 1.0) == math.inf == equation(f(0.0), f(1.0))
        assert traced(1.0, 1000.0) == math.inf == equation(f(1.0), f(1000.0))


def test_an_equation_that_cannot_be_traced_is_used_itself():
    def branching(x, y):
        return x if x > y else y

    assert _traced(branching, [(1.0, 2.0)]) is branching


def test_samples_that_cannot_advance_end_the_phase_instead_of_looping():
    # at t0 = 1e20 s a first span of 1e-10 s spaces its samples far below the time's resolution (ulp 1.6e4 s):
    # t0 + offsets == t0, so no span would advance (and odeint takes no step, so the budget never runs out)
    out = integrate_spans(lambda t, y: [-y[0]], None, 1e20, np.array([1.0]), 2e20, [], 1e-9, np.array([1e-12]),
                          Budget(1_000), 1e-10)
    assert out.status == "failed" and out.t[-1] == 1e20


def test_a_state_gone_infinite_fails_its_phase_without_printing_numpy_s_warnings():
    """A right-hand side that turns infinite at t = 0.5 (a start far in a scatter's tail): DOP853's steps printed
    "invalid value encountered in dot" 308 times (1e308: "overflow", 203 times) before the step size fell below its
    least; the phase still ends failed, saying so, and nothing is printed."""
    import warnings

    from clutchopt.simulate.stepping import integrate

    for bad in (np.inf, 1e308):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            out = integrate(lambda t, y, bad=bad: np.array([bad if t > 0.5 else 1.0]), None, 0.0, np.array([1.0]),
                            10.0, [], "DOP853", 1e-8, np.array([1e-8]), Budget(1000))
        assert out.status == "failed" and out.message == "the step size fell below its least" and caught == []
