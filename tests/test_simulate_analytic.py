"""Closed forms of the start-up (Simionescu & Oproescu) against independent evaluations and the simulation."""

import itertools
import math

import pytest
from scipy.integrate import quad

from clutchopt.simulate.analytic import PaperTransient
from clutchopt.simulate.engine import Model, simulate
from clutchopt.simulate.laws import Load, PaperFriction
from clutchopt.simulate.paper import paper_start_up

pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning", "error::scipy.integrate.IntegrationWarning")

J, K, W0 = 2.0, 50.0, 157.07963267948966  # kg m^2, N m, rad/s (1500 rpm): the paper scene's values


def simulated(a, m_r, effects=("slip_friction",), **kw):
    return simulate(Model(PaperFriction(K, a), J, Load(m_r), effects, driver_speed=W0, **kw)).headline


def by_quadrature(a, m_r, weight):
    """J int_0^w0 weight(w_r) / (M_fr - M_r) dw_r, eqs. (5), (11), (14), directly (moderate a w0 only)."""
    value, _ = quad(lambda x: weight(x) / (K * (1 + math.exp(a * x)) - m_r), 0.0, W0, epsabs=0, epsrel=1e-13, limit=200)
    return J * value


def test_start_time_by_hand_and_printed_eq9():
    a, m_r = -0.01, 20.0
    c = K - m_r
    hand = J / (a * c) * (a * W0 + math.log((2 * K - m_r) / (K * math.exp(a * W0) + c)))  # (9) corrected
    p = PaperTransient(J, K, a, m_r, W0)
    assert hand == pytest.approx(5.916336179, rel=1e-9)
    assert p.start_time() == pytest.approx(hand, rel=1e-13)
    printed = J / (a * c) * (a * W0 + math.log((2 * K - m_r) / (K * math.exp(a * W0) + K * m_r)))
    assert p.start_time_printed() == pytest.approx(printed, rel=1e-13)
    assert printed == pytest.approx(27.3791, rel=1e-5)  # the printed "k M_r" (errata T1): 4.6 times too long


@pytest.mark.parametrize("a", [-0.01, 0.003])
def test_friction_and_source_work_and_time_to_slip_against_quadrature(a):
    m_r = 20.0
    p = PaperTransient(J, K, a, m_r, W0)
    friction = lambda x: K * (1 + math.exp(a * x))  # noqa: E731
    assert p.start_time() == pytest.approx(by_quadrature(a, m_r, lambda x: 1.0), rel=1e-11)
    assert p.friction_work() == pytest.approx(by_quadrature(a, m_r, lambda x: friction(x) * x), rel=1e-11)
    assert p.source_work() == pytest.approx(by_quadrature(a, m_r, lambda x: friction(x) * W0), rel=1e-11)
    half = J * quad(lambda x: 1 / (friction(x) - m_r), W0 / 2, W0, epsrel=1e-13)[0]
    assert p.time_to_slip(W0 / 2) == pytest.approx(half, rel=1e-11)  # eq. (8)
    h = simulated(a, m_r, rtol=1e-12)
    for key in ("start_time", "friction_work", "source_work"):
        assert h[key] == pytest.approx(getattr(p, key)(), rel=1e-9)


def test_simulated_slip_at_the_time_of_eq8():
    a, m_r = -0.01, 20.0
    t = PaperTransient(J, K, a, m_r, W0).time_to_slip(0.3 * W0)
    h = simulated(a, m_r, end_time=t)
    assert h["final_driver_speed"] - h["final_driven_speed"] == pytest.approx(0.3 * W0, rel=1e-9)


@pytest.mark.parametrize("a", [-0.02, 0.0, 1e-9, 0.02])
def test_without_resisting_torque_energy_identities_hold_exactly(a):
    p = PaperTransient(J, K, a, 0.0, W0)
    assert p.friction_work() == J * W0**2 / 2  # (12)
    assert p.source_work() == J * W0**2  # (15)
    h = simulated(a, 0.0)
    assert h["friction_work"] == pytest.approx(J * W0**2 / 2, rel=1e-10)
    assert h["source_work"] == pytest.approx(J * W0**2, rel=1e-10)


@pytest.mark.parametrize("m_r", [30.0, 2 * K * (1 - 1e-8)])
@pytest.mark.parametrize("a", [0.0, 1e-12, -1e-12, 1e-8])
def test_limit_a_to_zero(a, m_r):
    limit = J * W0 / (2 * K - m_r)  # slower by 1e8 when M_r is 1e-8 below 2k: a -> 0 and M_r -> 2k together
    p = PaperTransient(J, K, a, m_r, W0)
    assert p.start_time() == pytest.approx(limit, rel=max(abs(a * W0) * limit / (J * W0 / K), 1e-13))
    assert p.friction_work() > 0 and math.isfinite(p.friction_work())


@pytest.mark.parametrize("aw0", [300.0, 1000.0, -300.0, -1000.0])
def test_large_a_w0_without_overflow(aw0):
    a = aw0 / W0
    p = PaperTransient(J, K, a, 0.0, W0)
    # M_r = 0: t_c = J/(k a) [a w0 + ln 2 - ln(1 + e^{a w0})], by hand in each sign's safe form
    hand = J / (K * a) * (math.log(2) - math.log1p(math.exp(-aw0))) if a > 0 else J / (K * a) * (
        aw0 + math.log(2) - math.log1p(math.exp(aw0)))
    assert p.start_time() == pytest.approx(hand, rel=1e-13)
    assert simulated(a, 0.0)["start_time"] == pytest.approx(hand, rel=1e-8)


def test_resisting_torque_close_to_the_friction_torque():
    a, m_r = 30.0 / W0, 2 * K * (1 - 1e-6)
    t = PaperTransient(J, K, a, m_r, W0).start_time()
    assert t == pytest.approx(by_quadrature(a, m_r, lambda x: 1.0), rel=1e-8)
    assert simulated(a, m_r)["start_time"] == pytest.approx(t, rel=1e-6)


@pytest.mark.parametrize("a, m_r, words", [
    (0.01, 2 * K * 1.001, "M_fr(0) = 2k"),  # steady slip where k (1 + e^{a w_r}) = M_r
    (-0.01, 2 * K * 0.9, "does not start"),  # M_fr(w0) = 60.4 N m < M_r
])
def test_no_lockup_is_reported(a, m_r, words):
    summary = PaperTransient(J, K, a, m_r, W0).summary()
    assert not summary["locks_up"] and summary["reason"].startswith("no lock-up") and words in summary["reason"]
    assert math.isinf(summary["start_time"])
    h = simulated(a, m_r, effects=("slip_friction", "lockup"), end_time=1e9)
    assert not h["locks_up"] and h["reason"].startswith("no lock-up") and math.isinf(h["start_time"])


TORTURE = list(itertools.product([0.0, 1e-6, 1.0, 30.0, 300.0, 1000.0], [1, -1], [0.0, 0.5, 0.999, 1.001]))


@pytest.mark.parametrize("aw0, sign, ratio", TORTURE)
def test_torture_grid_agrees_or_says_no_lockup(aw0, sign, ratio):
    both = paper_start_up(J, K, sign * aw0 / W0, ratio * 2 * K, W0)
    analytic, simulated_ = both["analytic"], both["simulated"]
    assert simulated_["locks_up"] == analytic["locks_up"]
    if analytic["locks_up"]:
        for key in ("start_time", "friction_work", "source_work"):
            assert simulated_[key] == pytest.approx(analytic[key], rel=1e-9)
    else:
        assert simulated_["reason"].startswith("no lock-up") and analytic["reason"].startswith("no lock-up")
        assert math.isinf(simulated_["start_time"]) and math.isinf(analytic["start_time"])
