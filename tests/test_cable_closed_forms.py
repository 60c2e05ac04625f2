"""Cable coupling: every equation and closed form against hand calculation (arithmetic written here, not by the code)."""

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchopt.cases import load_case
from clutchopt.formulations.cable.closed_forms import (
    _weight_wear_interval,
    closed_form,
    hub_lead_angle_optimum,
    weight_lead_angle_optimum,
)
from clutchopt.formulations.cable.equations import (
    cable_diameter,
    clamp_screw_stress,
    finger_bending_stress,
    half_coupling_mass,
    hub_axial_force,
    hub_thread_load,
    inertia_force,
    reduced_friction_angle,
    required_cable_count,
    thread_pitch,
    thread_pressure,
    torsional_stiffness,
    turns_in_nut,
    weight_mass,
)
from clutchopt.formulations.cable.paper import (
    paper_design,
    paper_eq7,
    paper_eq9,
    paper_eq19,
    paper_eq20,
    paper_eq21,
    paper_eq22,
)
from tests.conftest import CASES

DEG = math.pi / 180
G = 9.80665

# cases/cable_pump.toml by hand
W = 1460 * 2 * math.pi / 60  # 152.8908 rad/s
PHI = math.atan(0.1 / math.cos(15 * DEG))  # 5.9106 deg, eq. (14)
BETA, BETA_W = 11.18 * DEG, 15 * DEG
LOAD = 6 * 15000 * 0.003 + 20000 * 0.005  # z c_k x + c_pr x_1 = 270 + 100 = 370 N, eqs. (2)-(4), z = 6
M_HUB = LOAD * math.tan(BETA + PHI) / (0.070 * W**2 - G)  # consistent (7)
PHI_1 = 2 * DEG
D_2W = 2 * 0.05e-3 / (PHI_1 * math.tan(BETA_W))  # x_2 = phi_1 (d_2w / 2) tan(beta_w)
TWIST_FORCE = 2 * 10 * PHI_1 / (D_2W * math.tan(BETA_W - PHI))  # axial force that turns c_kk phi_1 through thread 16
M_WEIGHT = (1.3e7 * 0.05e-3 + TWIST_FORCE) / (0.100 * W**2 - G)  # consistent (9)
TWIST = 3 * DEG
D_K = 0.160 * 0.5**2 / (4 * math.sqrt(12 * 0.5**2 + 3 * TWIST**2))  # (17), psi = 80/160
Z_REQ = 108 * (4 * 0.5**2 + TWIST**2) / (0.785 * 0.080 * TWIST * 0.5 * D_K**2 * 350e6)  # (18)
TENSION = 108 * (4 * 0.5**2 + TWIST**2) / (0.080 * TWIST * 6)  # N per cable at z = 6
D_1 = math.sqrt(1.3 * TENSION / (2 * 0.15) / (math.pi / 4 * 200e6))  # clamp: 2 f F_s = N, sigma_E = 1.3 F_s / A
D_N = (32 * (2 * 108 / (6 * 0.160)) * 0.030 / 2 / (math.pi * 120e6)) ** (1 / 3)  # load 2T/(zD) at l_n/2


@pytest.fixture(scope="module")
def p():
    return load_case(CASES / "cable_pump.toml").params()


def test_hand_values_in_plain_numbers():
    assert math.degrees(PHI) == pytest.approx(5.91064, rel=1e-5)
    assert M_HUB == pytest.approx(0.069943, rel=1e-4)
    assert D_2W == pytest.approx(10.6915e-3, rel=1e-4)
    assert TWIST_FORCE == pytest.approx(408.15, rel=1e-4)
    assert M_WEIGHT == pytest.approx(0.45458, rel=1e-4)
    assert D_K == pytest.approx(5.7656e-3, rel=1e-4)
    assert Z_REQ == pytest.approx(5.6614, rel=1e-4)
    assert TENSION == pytest.approx(4308.96, rel=1e-5)
    assert D_1 == pytest.approx(10.9028e-3, rel=1e-4) and D_N == pytest.approx(6.5922e-3, rel=1e-4)


def test_single_equations(p):
    assert inertia_force(2.0, 0.07, W, G) == pytest.approx(2.0 * (0.07 * W**2 - G), rel=1e-14)  # (1)
    assert reduced_friction_angle(0.1, 15 * DEG) == pytest.approx(PHI, rel=1e-14)  # (14)
    assert hub_axial_force(100.0, BETA, PHI) == pytest.approx(100 / math.tan(BETA + PHI), rel=1e-14)  # (5)
    assert hub_thread_load(p, 6) == pytest.approx(LOAD, rel=1e-14)  # (2)-(4)
    assert half_coupling_mass(LOAD, BETA, PHI, 0.07, W, G) == pytest.approx(M_HUB, rel=1e-14)  # (7)
    assert weight_mass(p, BETA_W, PHI) == pytest.approx(M_WEIGHT, rel=1e-12)  # (9)
    assert cable_diameter(0.16, 0.5, 4, TWIST) == pytest.approx(D_K, rel=1e-14)  # (17)
    assert required_cable_count(p) == pytest.approx(Z_REQ, rel=1e-12)  # (18)
    assert clamp_screw_stress(p, 6, D_1) == pytest.approx(200e6, rel=1e-12)  # (20)
    assert finger_bending_stress(p, 6, D_N) == pytest.approx(120e6, rel=1e-12)  # (22)
    assert torsional_stiffness(108, TWIST) == pytest.approx(2062.65, rel=1e-5)  # (23)


def test_thread_pressure_and_turns(p):
    # Tr 32x18 (P6): lead 18 mm, 3 starts; (16) q = F_a / (pi d_2 h z_e) with h = 3 mm, z_e = 40 / 6
    pitch = thread_pitch(0.029, math.atan(18 / (math.pi * 29)), 3)
    assert pitch == pytest.approx(0.006, rel=1e-12)
    assert turns_in_nut(0.040, pitch) == pytest.approx(40 / 6, rel=1e-12)
    assert thread_pressure(370, 0.029, 0.003, 40 / 6) == pytest.approx(370 / (math.pi * 0.029 * 0.003 * 40 / 6),
                                                                             rel=1e-14)
    assert 370 / (math.pi * 0.029 * 0.003 * 40 / 6) == pytest.approx(0.20306e6, rel=1e-4)  # far below [q] = 8 MPa


def test_closed_form_at_the_case_threads(p):
    design = closed_form(p)
    expected = {"half_coupling_mass": M_HUB, "weight_mass": M_WEIGHT, "cable_count": 6, "finger_diameter": D_N,
                "screw_diameter": D_1, "lead_angle": BETA, "weight_lead_angle": BETA_W}
    for name, value in expected.items():
        assert design[name] == pytest.approx(value, rel=1e-12), name


def test_lightest_hub_thread_is_the_flattest_that_does_not_self_lock(p):
    assert hub_lead_angle_optimum(p) == pytest.approx(PHI + 2 * DEG, rel=1e-14)
    assert hub_lead_angle_optimum(p, (10 * DEG, 45 * DEG)) == 10 * DEG


def test_weight_thread_optimum_of_the_pump_is_its_smallest_diameter(p):
    # lead 2 pi x_2 / phi_1 = 9 mm; 6 mm smallest diameter -> tan(beta_w) = 9 / (6 pi); 45 + phi'/2 is steeper
    assert weight_lead_angle_optimum(p) == pytest.approx(math.atan(9 / (6 * math.pi)), rel=1e-12)
    assert math.degrees(math.atan(9 / (6 * math.pi))) == pytest.approx(25.5228, rel=1e-5)


def test_paper_printed_forms(p):
    # (5)/(7) put tan(beta + phi') under the mass: tan^2 times the consistent value
    printed = LOAD / ((0.070 * W**2 - G) * math.tan(BETA + PHI))
    assert paper_eq7(p, 6) == pytest.approx(printed, rel=1e-14)
    assert printed / M_HUB == pytest.approx(1 / math.tan(BETA + PHI) ** 2, rel=1e-12)
    assert printed == pytest.approx(0.73988, rel=1e-4)
    # (9) adds a force and a moment and has no gravity term
    assert paper_eq9(p) == pytest.approx((650 + 10 * PHI_1) / (0.1 * W**2 * math.tan(BETA_W + PHI)), rel=1e-14)
    # (19) with tan(phi), (20) with sin(phi): not inverses of each other
    d_19 = math.sqrt(3.31 * 108 * 0.08 / (0.15 * 6 * 0.16**2 * math.tan(TWIST) * 200e6))
    assert paper_eq19(p, 6) == pytest.approx(d_19, rel=1e-14)
    assert paper_eq20(p, 6, d_19) == pytest.approx(200e6 / math.cos(TWIST), rel=1e-12)
    # (21) coefficient 10, (22) D^2: the check is not the inverse of the design formula
    d_21 = (10 * 108 * 0.03 / (0.16 * 6 * 120e6)) ** (1 / 3)
    assert paper_eq21(p, 6) == pytest.approx(d_21, rel=1e-14)
    assert paper_eq22(p, 6, d_21) == pytest.approx(120e6 / 0.16, rel=1e-12)


def test_paper_design_column(p):
    design = paper_design(p)
    assert design["cable_count"] == 6
    assert design["half_coupling_mass"] == pytest.approx(0.73988, rel=1e-4)
    assert design["weight_mass"] == pytest.approx((650 + 10 * PHI_1) / (0.1 * W**2 * math.tan(BETA_W + PHI)), rel=1e-12)


def test_clamp_screw_matches_printed_eq20_to_second_order(p):
    # (20) = 2 x 1.3 x 4/pi T l / (f z D^2 sin phi d^2) is the clamp of (18)'s tension with friction on two faces,
    # up to (1 + phi^2 / (4 psi^2)) sin(phi) / phi and 3.31 vs 3.3104
    ratio = clamp_screw_stress(p, 6, D_1) / paper_eq20(p, 6, D_1)
    assert ratio == pytest.approx((1 + TWIST**2 / (4 * 0.25)) * math.sin(TWIST) / TWIST * (2 * 1.3 * 4 / math.pi) / 3.31,
                                  rel=1e-12)
    assert abs(ratio - 1) < 3e-3


@settings(max_examples=60, deadline=None)
@given(beta=st.floats(5 * DEG, 60 * DEG), travel=st.floats(1e-5, 1e-3), twist=st.floats(0.005, 0.3),
       c_kn=st.floats(0.0, 1e8), c_kk=st.floats(0.1, 100.0))
def test_frictionless_weight_obeys_virtual_work(beta, travel, twist, c_kn, c_kk):
    # phi' = 0: F dx_2 = c_kn x_2 dx_2 + c_kk phi_1 dphi_1 with dphi_1 / dx_2 = phi_1 / x_2 (thread kinematics)
    p = _weight_case(travel, twist, c_kn, c_kk)
    force = weight_mass(p, beta, 0.0) * (p.weight_radius * p.speed**2 - p.gravity)
    assert force == pytest.approx(c_kn * travel + c_kk * twist * twist / travel, rel=1e-10)


@settings(max_examples=60, deadline=None)
@given(f=st.one_of(st.just(0.0), st.floats(0.01, 0.3)), q_allow=st.floats(1e6, 5e7), c_kk=st.floats(1.0, 100.0),
       h_w=st.floats(0.004, 0.05))
def test_weight_wear_interval_bounds_the_pressure(f, q_allow, c_kk, h_w):
    p = _weight_case(5e-5, 0.03, 1e7, c_kk, friction_coefficient=f, allowable_thread_pressure=q_allow,
                     weight_nut_height=h_w)
    phi = math.atan(f)

    def pressure(beta):  # eq. (16) on thread 16 at the weight's optimum, from beta directly
        d = 2 * 5e-5 / (0.03 * math.tan(beta))
        return 2 * c_kk * 0.03 / (d * math.tan(beta - phi)) / (math.pi * d * 0.5 * h_w)

    interval = _weight_wear_interval(p, phi)
    if interval is None:  # then the pressure exceeds [q] everywhere: sample it
        assert min(pressure(phi + k * (math.pi / 2 - phi) / 200) for k in range(1, 200)) > q_allow
        return
    low, high = interval
    assert phi <= low < high < math.pi / 2
    assert pressure((low + high) / 2) <= q_allow
    for beta in (low, high):
        if beta > phi:
            assert pressure(beta) == pytest.approx(q_allow, rel=1e-7)


def _weight_case(travel, twist, c_kn, c_kk, **others):
    from types import SimpleNamespace

    values = dict(elongation=travel, cable_twist=twist, longitudinal_stiffness=c_kn, torsional_stiffness=c_kk,
                  weight_radius=0.1, speed=150.0, gravity=G, height_ratio=0.5, weight_nut_height=0.015,
                  friction_coefficient=0.0, allowable_thread_pressure=8e6)
    values.update(others)
    return SimpleNamespace(**values)
