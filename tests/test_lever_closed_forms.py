"""Lever coupling: the paper's relations, the toggle statics and the closed forms against hand calculation."""

import math
from types import SimpleNamespace

import pytest
from hypothesis import given
from hypothesis import strategies as st

from clutchopt.cases import load_case
from clutchopt.formulations.lever.closed_forms import closed_form_characteristic_number, closed_form_link_diameter
from clutchopt.formulations.lever.equations import (
    characteristic_number,
    disc_push,
    euler_stress,
    lever_offset,
    link_force,
    mean_diameter,
    minimum_lever_length,
    paper_mean_width,
    start_radius,
)
from clutchopt.formulations.lever.modes import PAPER
from clutchopt.formulations.lever.paper import paper_characteristic_number, paper_geometry, paper_k
from tests.conftest import CASES

# cases/lever_wedge_duty.toml by hand (the wedge paper's duty).
W = 1000 * 2 * math.pi / 60  # 104.7197551 rad/s
T_MAX = 0.5 * W / 10 + 5  # 10.2359878 N m
G0, GPR = math.radians(15), math.radians(2)
DELTA, D_B, D_PHI, L_PR, F, Z = 0.003, 0.025, 0.045, 0.025, 0.3, 4
L2 = DELTA / (math.cos(GPR) - math.cos(G0))  # 0.003 / (0.9993908 - 0.9659258) = 89.646 mm
S_OV = L2 * math.sin(G0)  # 23.202 mm
R_0 = D_B / 2 + (D_PHI - D_B) / 4 + L_PR  # 12.5 + 5 + 25 = 42.5 mm
D_CP = 2 * (S_OV + R_0)  # 131.404 mm
K = D_B + D_PHI + 4 * L_PR  # 170 mm = 4 R_0
# Two discs, one lined face each: T = 2 f [z m w^2 R_0 / (2 tan g0)] d_cp / 2  =>  m z = 2 T tan g0 / (f w^2 R_0 d_cp)
MZ = 2 * T_MAX * math.tan(G0) / (F * W**2 * R_0 * D_CP)
MZ_PRINTED = 32 * T_MAX * math.tan(G0) / (F * W**2 * K * (4 * L2 * math.sin(G0) + K))
# Worn linings: weight moved out by l_2 (sin g0 - sin gpr), spring stretched as much, pulling m g + 2 W_ax tan g0 / z
TRAVEL = L2 * (math.sin(G0) - math.sin(GPR))  # 20.073 mm
SPRING = MZ / Z * 9.80665 + 2 * 10 * math.tan(G0) / Z  # m g 0.7320 N + 1.3397 N (W_ax = 10 N)
F_WORN = MZ / Z * W**2 * (R_0 + TRAVEL) - SPRING
S_WORN = F_WORN / (2 * math.sin(GPR))  # link compression at gamma_pr
B_CP = 2 * (S_OV + 1.5 * DELTA)  # 55.404 mm


@pytest.fixture(scope="module")
def p():
    return load_case(CASES / "lever_wedge_duty.toml").params()


def test_hand_values():
    assert L2 == pytest.approx(0.0896459, rel=1e-6)
    assert D_CP == pytest.approx(0.1314041, rel=1e-6)
    assert K == pytest.approx(4 * R_0, rel=1e-15)
    assert MZ == pytest.approx(0.2985628, rel=1e-6)
    assert MZ_PRINTED == pytest.approx(2 * MZ, rel=1e-12)  # errata L1: the printed 32 counts one friction surface
    assert SPRING == pytest.approx(2.0717213, rel=1e-6)
    assert S_WORN == pytest.approx(704.1126, rel=1e-6)


def test_paper_geometry(p):
    assert minimum_lever_length(DELTA, GPR, G0) == pytest.approx(L2, rel=1e-12)
    assert lever_offset(L2, G0) == pytest.approx(S_OV, rel=1e-12)
    assert start_radius(D_B, D_PHI, L_PR) == pytest.approx(R_0, rel=1e-12)
    assert mean_diameter(S_OV, R_0) == pytest.approx(D_CP, rel=1e-12)
    assert paper_k(D_B, D_PHI, L_PR) == pytest.approx(K, rel=1e-12)
    assert paper_mean_width(S_OV, DELTA, 1.5) == pytest.approx(B_CP, rel=1e-12)
    assert paper_geometry(p) == pytest.approx((L2, B_CP), rel=1e-12)


def test_characteristic_numbers(p):
    assert paper_characteristic_number(T_MAX, F, W, G0, L2, K) == pytest.approx(MZ_PRINTED, rel=1e-12)
    assert characteristic_number(T_MAX, F, W, G0, R_0, D_CP, 2) == pytest.approx(MZ, rel=1e-12)
    assert closed_form_characteristic_number(p) == pytest.approx(MZ, rel=1e-12)


def test_closed_form_link_diameter(p):
    buckling = (64 * 3 * S_WORN * L2**2 / (math.pi**3 * 210e9)) ** 0.25  # Euler, n_b = 3, i = d/4
    compression = math.sqrt(4 * S_WORN / (math.pi * 150e6))
    assert buckling == pytest.approx(3.59405e-3, rel=1e-5) and compression == pytest.approx(2.44473e-3, rel=1e-5)
    assert closed_form_link_diameter(p, MZ / Z) == pytest.approx(buckling, rel=1e-12)


def test_worn_state_pressure_spring_and_pin(p):
    outputs = PAPER.outputs(SimpleNamespace(weight_mass=MZ / Z, link_diameter=0.004), p)
    push = Z * F_WORN / (2 * math.tan(GPR))
    assert outputs["lining_pressure"].value == pytest.approx(push / (math.pi * D_CP * B_CP), rel=1e-12)
    assert outputs["lining_pressure"].value == pytest.approx(0.1230655e6, rel=1e-6)
    assert outputs["spring_stiffness"].value == pytest.approx(SPRING / TRAVEL, rel=1e-12)  # 103.2 N/m
    assert outputs["pin_diameter"].value == pytest.approx(math.sqrt(2 * S_WORN / (math.pi * 80e6)), rel=1e-12)
    assert outputs["torque"].value == pytest.approx(T_MAX, rel=1e-12)
    # the printed "stiffness": pi (d_cp/2)^2 delta g tan g0 / (z l_2 (sin g0 - sin gpr)), in m^3/s^2 (errata L2)
    printed = math.pi * (D_CP / 2) ** 2 * DELTA * 9.80665 * math.tan(G0) / (Z * TRAVEL)
    assert outputs["paper_spring_stiffness"].value == pytest.approx(printed, rel=1e-12)
    assert printed == pytest.approx(1.33143e-3, rel=1e-5)


def test_printed_formula_is_the_one_surface_model(p):
    one_face = SimpleNamespace(**{**vars(p), "friction_surfaces": 1})
    assert closed_form_characteristic_number(one_face) == pytest.approx(MZ_PRINTED, rel=1e-12)


def _knee_geometry(angle, lever_length):
    """Knee radius below the disc pins and half axial span of a toggle: r_w = -l sin(g), x = l cos(g)."""
    return -lever_length * math.sin(angle), lever_length * math.cos(angle)


@given(angle=st.floats(math.radians(1), math.radians(30)), lever_length=st.floats(0.01, 1.0),
       force=st.floats(1.0, 1e5))
def test_toggle_statics_by_virtual_work(angle, lever_length, force):
    # F dr_w = 2 P dx (the knee moves out by dr_w, each of the two discs by dx): P = F (dr_w/dgamma) / (2 dx/dgamma)
    h = 1e-6 * angle
    (r1, x1), (r2, x2) = _knee_geometry(angle - h, lever_length), _knee_geometry(angle + h, lever_length)
    push = force * (r2 - r1) / (2 * (x2 - x1))
    assert disc_push(force, angle) == pytest.approx(push, rel=1e-6)
    # link force along the link: its axial component is the push
    assert link_force(force, angle) * math.cos(angle) == pytest.approx(push, rel=1e-6)


@given(d_b=st.floats(0.01, 0.2), flange_extra=st.floats(0.001, 0.2), l_pr=st.floats(0.005, 0.2),
       delta=st.floats(0.001, 0.01), g0=st.floats(math.radians(4), math.radians(15)),
       gpr=st.floats(math.radians(1.5), math.radians(3)), surfaces=st.integers(1, 4))
def test_printed_over_consistent_is_the_surface_count(d_b, flange_extra, l_pr, delta, g0, gpr, surfaces):
    d_phi = d_b + flange_extra
    length = minimum_lever_length(delta, gpr, g0)
    radius = start_radius(d_b, d_phi, l_pr)
    diameter = mean_diameter(lever_offset(length, g0), radius)
    printed = paper_characteristic_number(50.0, 0.3, 150.0, g0, length, paper_k(d_b, d_phi, l_pr))
    consistent = characteristic_number(50.0, 0.3, 150.0, g0, radius, diameter, surfaces)
    assert printed / consistent == pytest.approx(surfaces, rel=1e-10)


def test_euler_stress_of_a_round_link():
    # P_cr = pi^2 E I / l^2, I = pi d^4 / 64, A = pi d^2 / 4: sigma_E = pi^2 E d^2 / (16 l^2)
    d, length, e = 0.006, 0.15, 210e9
    p_cr = math.pi**2 * e * math.pi * d**4 / 64 / length**2
    assert euler_stress(e, d, length) == pytest.approx(p_cr / (math.pi * d**2 / 4), rel=1e-12)
    assert euler_stress(e, d, length) == pytest.approx(207.26e6, rel=1e-4)


def test_the_outputs_compute_each_toggle_property_once_to_the_same_bits(monkeypatch):
    # the lever's outputs read R_0 20 times through its toggles' properties (d_cp, the pushes, forces and masses):
    # computed once each (formulations.common.computed_once), the numbers bit for bit those of the toggles read as
    # they are; the constraints, which make the NLP's graph, still build R_0 where each reads it
    import casadi as ca

    from clutchopt.formulations.lever import toggles
    from clutchopt.formulations.lever.modes import paper_toggles
    from clutchopt.optimise.problem import case_problem

    case = load_case(CASES / "lever_wedge_duty.toml")
    posed = case_problem(case, "paper", "mass").posed
    p, x = posed.params(case), SimpleNamespace(weight_mass=0.3, link_diameter=0.006)
    calls = []
    monkeypatch.setattr(toggles, "start_radius", lambda *args: calls.append(args) or start_radius(*args))
    outputs = PAPER.outputs(x, p)
    assert len(calls) == 1
    t = paper_toggles(x, p)
    plain = {**toggles._duty_outputs(t, x, p), **toggles._envelope(t, x, p).outputs()}
    assert list(outputs) == list(plain) and len(outputs) == 27
    assert [out.value.hex() for out in outputs.values()] == [float(out.value).hex() for out in plain.values()]
    assert outputs["start_radius"].value == R_0 and outputs["lever_length"].value == pytest.approx(L2, rel=1e-12)
    calls.clear()
    PAPER.constraints(SimpleNamespace(weight_mass=ca.SX.sym("m"), link_diameter=ca.SX.sym("d")), p)
    assert len(calls) > 1


def test_only_a_frozen_dataclass_state_is_computed_once_and_its_own_properties_resolved():
    # (found in review) a state that could go stale (not a frozen dataclass) is left as it is; a subclass that
    # overrides a property with a plain attribute keeps it (inspect.getattr_static), the others computed once
    from dataclasses import dataclass
    from types import SimpleNamespace

    from clutchopt.formulations.common import computed_once

    @dataclass(frozen=True)
    class Base:
        a: float

        @property
        def twice(self):
            return 2 * self.a

        @property
        def other(self):
            return 1.0

    @dataclass(frozen=True)
    class Sub(Base):
        other = 5.0

    @dataclass
    class Loose:
        a: float

    once = computed_once(Sub(1.5))
    assert (once.twice, once.other) == (3.0, 5.0) and once.__dict__["twice"] == 3.0  # (cached)
    for state in (SimpleNamespace(a=1.0), Loose(1.0)):
        assert computed_once(state) is state
