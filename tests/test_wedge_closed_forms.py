"""Wedge coupling: closed forms and equations against hand calculation (numbers worked out here, not by the code)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

from clutchopt.cases import load_case
from clutchopt.formulations.duty import required_torque
from clutchopt.formulations.wedge.closed_forms import closed_form_finger_diameter, closed_form_weight_mass
from clutchopt.formulations.wedge.equations import flank_pressure, self_locking_angle, weight_base_width, weight_body
from clutchopt.formulations.wedge.paper import paper_eq27_first_form, paper_eq27_second_form, paper_eq28
from tests.conftest import CASES

# The paper's worked example, by hand.
W = 1000 * 2 * math.pi / 60  # 104.7197551 rad/s, eq. (1)
T_MAX = 0.5 * W / 10 + 5  # 10.2359878 N m, eqs. (5), (17)
R1, R2, H_R, Z, F = 0.05, 0.06, 0.02, 4, 0.15
ALPHA, GAMMA = math.radians(15), 0.785
R_C = R2 - 2 / 3 * H_R  # 0.0466667 m, eq. (11)
# Torque T = z * (f m w^2 r_c / sin(alpha)) * (r1 + r2)/2  =>  m = 2 T sin(alpha) / (z f w^2 r_c (r1 + r2))
M_R = 2 * T_MAX * math.sin(ALPHA) / (Z * F * W**2 * R_C * (R1 + R2))


@pytest.fixture(scope="module")
def p():
    return load_case(CASES / "wedge_paper.toml").params()


def test_hand_values_are_what_the_notes_say():
    assert T_MAX == pytest.approx(10.23599, rel=1e-6)
    assert M_R == pytest.approx(0.15687, rel=1e-4)  # MODELS.md: 0.157 kg for the first form of (27)


def test_required_torque(p):
    assert required_torque(p.inertia, p.speed, p.acceleration_time, p.resisting_torque) == pytest.approx(T_MAX, rel=1e-12)


def test_closed_form_weight_mass(p):
    assert closed_form_weight_mass(p) == pytest.approx(M_R, rel=1e-12)


def test_closed_form_finger_diameter(p):
    # at the closed-form mass each finger carries T_max / z at lever h_n = (r1 + r2)/2, and F_fr h_n = T_max / z:
    d_n = (32 * T_MAX / Z / (math.pi * 160e6)) ** (1 / 3)
    assert d_n == pytest.approx(5.4616e-3, rel=1e-4)
    assert closed_form_finger_diameter(p, M_R) == pytest.approx(d_n, rel=1e-12)


def test_flank_pressure_of_closed_form_design(p):
    f_u = M_R * W**2 * R_C
    q = f_u / math.tan(ALPHA) / (GAMMA * (R2**2 - R1**2))  # N = F_u/(2 sin a) on an area gamma(r2^2-r1^2)/(2 cos a)
    assert q == pytest.approx(0.34697e6, rel=1e-4)
    assert flank_pressure(f_u, p.flank_angle, p.sector_angle, R1, R2) == pytest.approx(q, rel=1e-12)


def test_paper_forms_of_eq27(p):
    first = 2 * T_MAX * math.sin(ALPHA) / (F * Z * 2.2 * R1 * W**2 * (1.2 * R1 - 2 / 3 * H_R))
    second = 6 * (0.5 * W + 5 * 10) * math.sin(ALPHA) / (F * Z * 2.2 * R1 * W**2 * (3 * 1.2 * R1 - 2 * H_R))
    assert paper_eq27_first_form(p) == pytest.approx(first, rel=1e-12)
    assert paper_eq27_second_form(p) == pytest.approx(second, rel=1e-12)
    assert second / first == pytest.approx(10.0, rel=1e-12)  # t_p multiplies instead of dividing (errata W2)
    assert first == pytest.approx(0.157, abs=5e-4) and second == pytest.approx(1.57, abs=5e-3)


def test_paper_eq28_reproduces_the_printed_3_1_mm(p):
    # the paper's arithmetic: [p] and [sigma] in MPa, m_r = 0.235 kg, the cube root read as mm
    number = 32 * 0.15 * 0.235 * W**2 * (3 * 1.2 * 0.05 - 2 * 0.02) * 4 * math.cos(ALPHA) / (3 * math.pi * 0.785 * 0.2 * 160)
    assert number ** (1 / 3) == pytest.approx(3.05, abs=0.01)
    assert paper_eq28(p, 0.235) == pytest.approx(number ** (1 / 3) * 1e-3, rel=1e-12)


def test_weight_body_matches_numerical_integration():
    r_in, r1, r2, b, alpha, gamma, rho = 0.04, 0.05, 0.06, 0.025, math.radians(15), 0.785, 7850.0

    def width(r):
        return b if r < r1 else b - 2 * (r - r1) * math.tan(alpha)

    mass = rho * integrate.dblquad(lambda r, th: width(r) * r, -gamma / 2, gamma / 2, r_in, r2, epsabs=1e-13)[0]
    moment = rho * integrate.dblquad(lambda r, th: width(r) * r * r * math.cos(th), -gamma / 2, gamma / 2, r_in, r2,
                                     epsabs=1e-13)[0]
    got_mass, got_centroid = weight_body(r_in, r1, r2, b, alpha, gamma, rho)
    assert got_mass == pytest.approx(mass, rel=1e-9)
    assert got_centroid == pytest.approx(moment / mass, rel=1e-9)


def test_weight_base_width_of_the_papers_example_by_hand():
    # m = rho gamma [b (r2^2 - r_in^2)/2 + r1 t (r2^2 - r1^2) - 2 t (r2^3 - r1^3)/3], t = tan(alpha): at m_r = M_R
    # (0.156873 kg), m_r / (rho gamma) = 2.54571e-5 m^3, the trapezoid's term t (50 mm (60^2 - 50^2) mm^2
    # - 2/3 (60^3 - 50^3) mm^3) = 0.267949 x (-5.66667e-6) = -1.51838e-6 m^3, (r2^2 - r_in^2)/2 = 1e-3 m^2
    t = math.tan(ALPHA)
    trapezoid = t * (R1 * (R2**2 - R1**2) - 2 / 3 * (R2**3 - R1**3))
    assert trapezoid == pytest.approx(-1.51838e-6, rel=1e-5)
    b = (M_R / (7850 * GAMMA) - trapezoid) / ((R2**2 - (R2 - H_R) ** 2) / 2)
    assert b == pytest.approx(0.0269755, rel=1e-5)  # wider than the rectangular sector's 25.457 mm
    assert weight_base_width(M_R, R2 - H_R, R1, R2, ALPHA, GAMMA, 7850.0) == pytest.approx(b, rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(r1=st.floats(0.005, 1.0), ratio=st.floats(1.1, 1.35), inner=st.floats(0.0, 0.95),
       alpha=st.floats(math.radians(5), math.radians(45)), gamma=st.floats(math.radians(5), math.radians(170)),
       rho=st.floats(1000.0, 20000.0), extra=st.floats(1e-3, 10.0))
def test_weight_base_width_inverts_weight_body(r1, ratio, inner, alpha, gamma, rho, extra):
    """b(m) is weight_body's mass solved for b (affine in b): weight_body at b(m) has mass m, to 1e-12."""
    r2 = ratio * r1
    r_in = inner * r1  # below r1: the weight covers its flanks (26)
    top_width = 2 * (r2 - r1) * math.tan(alpha)  # b at which the top land closes
    b = top_width * (1 + extra)
    mass = weight_body(r_in, r1, r2, b, alpha, gamma, rho)[0]
    assert weight_base_width(mass, r_in, r1, r2, alpha, gamma, rho) == pytest.approx(b, rel=1e-12)
    assert weight_body(r_in, r1, r2, weight_base_width(mass, r_in, r1, r2, alpha, gamma, rho), alpha, gamma,
                       rho)[0] == pytest.approx(mass, rel=1e-12)


def test_rectangular_sector_centroid_is_the_textbook_one():
    # alpha = 0: plain annular sector, r_c = (2 sin(g/2) / g) * (2/3) (R^3 - r^3) / (R^2 - r^2)
    g, r, big = 0.785, 0.04, 0.06
    expected = 2 * math.sin(g / 2) / g * 2 / 3 * (big**3 - r**3) / (big**2 - r**2)
    assert expected == pytest.approx(0.04937, rel=1e-3)  # the paper's r2 - 2/3 h_r gives 0.04667 (errata W5)
    assert weight_body(r, 0.05, big, 0.02, 0.0, g, 7850.0)[1] == pytest.approx(expected, rel=1e-12)


def test_self_locking_angle():
    assert math.degrees(self_locking_angle(0.15)) == pytest.approx(8.530765609948133, rel=1e-12)
