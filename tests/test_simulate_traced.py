"""Right-hand sides traced once per structure and written out on floats (clutchopt/simulate/on_floats.py ``family``,
``parametrised``; the engine's phases, clutchopt/simulate/engine.py ``_flat``): the same numbers as the equations,
the design's numbers bound without tracing again, the equations where Python's math is not IEEE's or the equations
cannot be traced."""

import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np
import pytest

from clutchopt.backend import fmax, fmin, sqrt, where
from clutchopt.simulate.engine import Model, _Run
from clutchopt.simulate.laws import CentrifugalFriction, InductionMotor, Load, PaperFriction, positive_part
from clutchopt.simulate.on_floats import family, parametrised


def test_a_family_takes_vectors_gives_several_numbers_and_binds_a_design_s_numbers():
    # f(t, y; k, c) = [k t y0, sqrt(c) y1 where y1 > 0 else 0, 0]; at t = 2, y = (3, 4), k = 5, c = 9: [30, 12, 0]
    def rates(t, y, k, c):
        return [k * t * y[0], where(y[1] > 0.0, sqrt(c) * y[1], 0.0), 0.0]

    make = family(rates, (0, 2), 2)
    fast = make(lambda t, y: "equations", 5.0, 9.0)
    assert fast(2.0, np.array([3.0, 4.0])) == [30.0, 12.0, 0.0]
    assert fast(2.0, [3.0, -4.0]) == [30.0, 0.0, 0.0]  # a sequence as well as an array
    assert make(None, 1.0, 4.0)(2.0, np.array([3.0, 4.0])) == [6.0, 8.0, 0.0]  # another design, the same source


def test_a_family_answers_with_its_equations_where_python_s_math_raises_or_goes_complex():
    # x / p at p = 0 raises ZeroDivisionError in Python (IEEE: inf); (-8) ** (1/3) is complex in Python (IEEE: NaN)
    calls = []

    def fallback(*arguments):
        calls.append(arguments)
        return "equations"

    assert family(lambda x, p: x / p, (0,), 1)(fallback, 0.0)(1.0) == "equations"
    assert family(lambda x, y: x ** y, (0, 0))(fallback)(-8.0, 1.0 / 3.0) == "equations"
    assert family(lambda x, y: x ** y, (0, 0))(fallback)(8.0, 1.0 / 3.0) == pytest.approx(2.0, rel=1e-15)
    assert calls == [(1.0,), (-8.0, 1.0 / 3.0)]


def test_a_family_kept_under_its_key_is_traced_once():
    traced = []

    def equation(x, p):
        traced.append(x)
        return p * x * x

    first = family(equation, (0,), 1, key=("test", "square"))
    again = family(equation, (0,), 1, key=("test", "square"))
    assert again is first and len(traced) == 1
    assert again(None, 3.0)(2.0) == 12.0  # p x^2 = 3 * 4


def test_a_number_converted_from_a_symbol_is_no_trace():
    # float() of a CasADi symbol gives NaN silently (math.isnan(x) in table_segment): refused, not written out
    with pytest.raises(NotImplementedError):
        family(lambda x: x + float(x), (0,))


@dataclass(frozen=True)
class _Part:
    stiffness: float
    name: str


def test_parametrised_takes_every_number_and_keys_the_rest():
    values, rebuild, key = parametrised(_Part(2.0, "spring"), SimpleNamespace(mass=3.0, count=4), 5.0, None)
    assert values == [2.0, 3.0, 5.0]  # the int 4 is structure, as the name
    part, namespace, number, nothing = rebuild(["a", "b", "c"])
    assert (part, namespace.mass, namespace.count, number, nothing) == (_Part("a", "spring"), "b", 4, "c", None)
    assert parametrised(_Part(7.0, "spring"), SimpleNamespace(mass=1.0, count=4), 6.0, None)[2] == key
    assert parametrised(_Part(2.0, "lever"), SimpleNamespace(mass=3.0, count=4), 5.0, None)[2] != key


def test_a_load_table_is_no_trace_and_its_right_hand_side_the_equations():
    # table_segment at a symbol: math.isnan(x) reads a symbol as NaN (silently): refused, the equations used; a
    # 1000-point table traced segment by segment would be some 8,000 operations a call (bisection: a few)
    load = Load(over="speed", points=(0.0, 50.0, 100.0), values=(2.5, 7.5, 20.0))
    with pytest.raises(NotImplementedError):
        family(lambda t, w: load(t, w), (0, 0))
    run = _Run(Model(CentrifugalFriction(0.01, 900.0), 0.5, load, ("slip_friction", "lockup"), driver_speed=100.0))
    assert run.flat["slip"].__self__ is run
    assert run.flat["slip"](0.0, np.array([100.0, 25.0, 0.0, 0.0, 0.0]))[1] == pytest.approx(
        -(0.01 * (100.0**2 - 900.0) - (7.5 + 0.25 * 25.0)) / 0.5, rel=1e-15)  # driven at 75 rad/s: 13.75 N m


def test_a_load_on_floats_is_its_table_looked_up():
    # over speed: (2.5, 7.5, 20) at (0, 50, 100) rad/s, held beyond both ends: at 75 rad/s 7.5 + 12.5 / 2 = 13.75 N m;
    # over time the same table read at t; constant: the torque whatever t and speed
    table = {"points": (0.0, 50.0, 100.0), "values": (2.5, 7.5, 20.0)}
    by_speed, by_time = Load(over="speed", **table).on_floats(), Load(over="time", **table).on_floats()
    assert by_speed(1e9, 75.0) == 13.75 and by_time(75.0, 1e9) == 13.75
    assert by_speed(0.0, -5.0) == 2.5 and by_speed(0.0, 500.0) == 20.0
    assert math.isnan(by_speed(0.0, math.nan))
    assert Load(4.0).on_floats()(3.0, 7.0) == 4.0


def test_the_positive_part_is_one_function_at_numbers_samples_and_symbols():
    # (x)^+ of the centrifugal torque K (w_a^2 - w_e^2)^+ and of the elastic link's net torque at rest: 3 -> 3,
    # -2 -> 0, NaN -> NaN at a number as numpy.maximum gives it at samples; a symbol: CasADi's fmax
    import casadi as ca

    assert positive_part(3.0) == 3.0 and positive_part(-2.0) == 0.0 and math.isnan(positive_part(math.nan))
    samples = positive_part(np.array([3.0, -2.0, math.nan]))
    assert samples[:2].tolist() == [3.0, 0.0] and math.isnan(samples[2])
    x = ca.SX.sym("x")
    assert float(ca.Function("f", [x], [positive_part(x)])(-2.0)) == 0.0


def _wedge_on_its_motor(law) -> _Run:
    motor = InductionMotor(104.72, 37.0, 0.2, 0.012)
    return _Run(Model(law, 0.5, Load(5.0), ("slip_friction", "motor_curve", "lockup", "friction_heat"),
                      motor=motor, heat_capacity=1400.0, conductance=4.0))


def test_the_engine_s_slip_phase_is_one_traced_function_of_the_equations_numbers():
    # K = 0.01 N m s^2, w_e = 30 rad/s, at w_a = 80 rad/s, w_r = 30 rad/s, 2 K: T = K (80^2 - 30^2) = 55 N m;
    # Kloss at s = 1 - 80 / 104.72: T_m = 2 T_k s s_k / (s^2 + s_k^2); dw_a = (T_m - T) / J_m, the machine's
    # (T - T_c) / J = (55 - 5) / 0.5 = 100 1/s^2, P = T w_r = 1650 W, T w_a = 4400 W, dT/dt = (P - G 2) / C
    run = _wedge_on_its_motor(CentrifugalFriction(0.01, 900.0))
    s = 1.0 - 80.0 / 104.72
    drive = 2.0 * 37.0 * s * 0.2 / (s * s + 0.2 * 0.2)
    dwa = (drive - 55.0) / 0.012
    expected = [dwa, dwa - 100.0, 1650.0, 4400.0, (1650.0 - 4.0 * 2.0) / 1400.0]
    flat = run.flat["slip"]
    assert flat.__name__ == "traced"  # written out, not the equations
    assert flat(0.0, np.array([80.0, 30.0, 0.0, 0.0, 2.0])) == pytest.approx(expected, rel=1e-14)
    for state in ([80.0, 30.0, 1.0, 2.0, 2.0], [20.0, 20.0, 0.0, 0.0, 0.0], [104.0, 1e-9, 3.0, 4.0, 0.5]):
        y = np.array(state)  # below the engagement speed too (no torque): the equations' own numbers
        for kind in ("rest", "slip", "stick"):
            assert run.flat[kind](1.0, y) == pytest.approx(getattr(run, kind)(1.0, y), rel=1e-15, abs=1e-300)


def test_lsoda_is_handed_the_rates_written_into_one_array_of_their_own(monkeypatch):
    # odeint takes an array as it is and converts a list: the written-out rates' ``into`` gives the same numbers as
    # they do, in one array per binding (the same object at every call, another design's another array); the
    # traced rates themselves (the events', whose last value is kept) still give a new list a call
    from clutchopt.simulate import engine

    run = _wedge_on_its_motor(CentrifugalFriction(0.01, 900.0))
    y = np.array([80.0, 30.0, 0.0, 0.0, 2.0])
    into = run.flat["slip"].into
    first = into(0.0, y)
    assert type(first) is np.ndarray and first.tolist() == run.flat["slip"](0.0, y)
    assert into(1.0, np.array([20.0, 20.0, 0.0, 0.0, 0.0])) is first
    assert first.tolist() == run.flat["slip"](1.0, np.array([20.0, 20.0, 0.0, 0.0, 0.0]))
    heavier = _wedge_on_its_motor(CentrifugalFriction(0.02, 900.0)).flat["slip"]  # T = 110 N m at (80, 30)
    other = heavier.into(0.0, y)
    assert other is not first and other.tolist() == heavier(0.0, y)
    assert other[2] == pytest.approx(3300.0, rel=1e-15) and other[0] - other[1] == pytest.approx(210.0, rel=1e-14)
    assert first.tolist() == run.flat["slip"](1.0, np.array([20.0, 20.0, 0.0, 0.0, 0.0]))  # (its own array kept)
    assert type(run.flat["slip"](0.0, y)) is list
    handed = []
    real = engine.integrate_spans
    monkeypatch.setattr(engine, "integrate_spans", lambda fun, *rest, **named: handed.append(fun) or real(fun, *rest,
                                                                                                           **named))
    engine.simulate(run.m)
    assert handed and all(getattr(fun, "__name__", "") == "into" for fun in handed)


def test_an_equation_that_cannot_be_traced_is_the_solver_s_right_hand_side_itself():
    run = _wedge_on_its_motor(PaperFriction(25.0, 0.02))  # min(a w_r, 300) and math.exp: no trace
    assert all(run.flat[kind].__self__ is run for kind in ("rest", "slip", "stick"))
    assert run.flat["slip"](0.0, np.array([80.0, 30.0, 0.0, 0.0, 0.0]))[2] == pytest.approx(
        25.0 * (1.0 + math.exp(0.02 * 30.0)) * 30.0, rel=1e-15)


def test_a_branch_written_with_fmax_is_traced_and_equal_to_the_number_s_branch():
    # the centrifugal torque K (w^2 - w_e^2)^+ at numbers (a branch) and traced (fmax) below and above w_e
    law = CentrifugalFriction(0.01, 900.0)
    fast = family(lambda w: law.kinetic(w, 0.0), (0,))(None)
    assert [fast(w) for w in (0.0, 29.0, 30.0, 31.0)] == [0.0, 0.0, 0.0, 0.01 * (961.0 - 900.0)]
    assert [fast(w) for w in (29.0, 31.0)] == [law.kinetic(w, 0.0) for w in (29.0, 31.0)]


def test_fmax_and_fmin_written_out_give_numpy_s_maximum_and_minimum_nan_included():
    # written in place in the source (not a call): the larger / smaller operand, a NaN on either side propagated,
    # as numpy.maximum and numpy.minimum (and CasADi's fmax and fmin) give them
    both = family(lambda a, b: [fmax(a, b), fmin(a, b)], (0, 0))(None)
    for a, b in ((1.0, 2.0), (2.0, 1.0), (-0.0, 0.0), (math.nan, 1.0), (1.0, math.nan), (-math.inf, 3.0)):
        expected = [float(np.maximum(a, b)), float(np.minimum(a, b))]
        assert all(v == e or (math.isnan(v) and math.isnan(e)) for v, e in zip(both(a, b), expected)), (a, b)


@pytest.mark.parametrize("kind", ["rest", "slip", "stick"])
def test_each_phase_s_jacobian_is_its_rates_differentiated(kind):
    # the wedge on its motor with heat, the load a table over the driven speed (slope 0.25 N m s at 75 rad/s);
    # the hand-written Jacobian (LSODA's) against central differences of the phase's rates, step 1e-6 of each state:
    # d(dw_a/dt)/dw_a = (dT_m/dw_a - 2 K w_a) / J_m and the rest, each entry to 1e-6 of the largest in its row
    motor = InductionMotor(104.72, 37.0, 0.2, 0.012)
    load = Load(over="speed", points=(0.0, 50.0, 100.0), values=(2.5, 7.5, 20.0))
    run = _Run(Model(CentrifugalFriction(0.01, 900.0), 0.5, load,
                     ("slip_friction", "motor_curve", "lockup", "friction_heat"), motor=motor, heat_capacity=1400.0,
                     conductance=4.0))
    y = np.array([100.0, 25.0, 10.0, 20.0, 3.0])
    rates, jacobian = getattr(run, kind), getattr(run, f"{kind}_jacobian")(0.0, y)
    for j in range(5):
        h = 1e-6 * max(abs(y[j]), 1.0)
        up, down = y.copy(), y.copy()
        up[j] += h
        down[j] -= h
        column = (np.array(rates(0.0, up)) - np.array(rates(0.0, down))) / (2.0 * h)
        scale = np.maximum(np.abs(jacobian).max(axis=1), 1e-300)
        assert np.all(np.abs(jacobian[:, j] - column) <= 1e-6 * scale), (kind, j, jacobian[:, j], column)


def test_written_out_rates_whose_array_disagrees_are_not_trusted():
    # the probes that decide whether the written-out rates stand for the equations read ``into`` too (the function
    # LSODA is handed): one that writes another number is refused, the equations answer
    from clutchopt.simulate.on_floats import trusted

    def equations(t, y):
        return [y[0] + t, 2.0 * y[1]]

    def fast(t, y):
        return [y[0] + t, 2.0 * y[1]]

    fast.into = lambda t, y: np.array([y[0] + t, 2.0 * y[1]])
    probes = [(0.5, [1.0, 3.0]), (1.0, [2.0, -1.0])]
    assert trusted(fast, equations, probes) is fast
    fast.into = lambda t, y: np.array([y[0] + t, 2.0 * y[1] * (1.0 + 1e-6)])
    assert trusted(fast, equations, probes) is equations
