"""The envelope of the couplings no choose-coupling test solves to a verified optimum (docs/envelope.md), by hand at
a fixed design: the cable coupling (cases/cable_pump.toml) and the wedge in paper mode, whose weights have a mass
but no width."""

import math
from types import SimpleNamespace

import pytest

from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.model import ENVELOPE_PARTS
from tests.conftest import CASES


def test_cable_envelope_by_hand():
    """D = 2 max(R_rv + a_w/2, D_f/2 + d_n/2), L = l + H + l_n; halves m + disc(D_f, l_n); moving parts z m_rv,
    z fingers (d_n x l_n), 2 z screws (d_1 x l_s), z cables rho A_s l with A_s = psi_s 0.785 d_k^2 and
    d_k = D_f psi^2 / (k sqrt(12 psi^2 + 3 phi^2)), psi = l / D_f (eqs. (17), (18))."""
    case = load_case(CASES / "cable_pump.toml")
    p = SimpleNamespace(**case.values)
    x = SimpleNamespace(half_coupling_mass=1.2, weight_mass=0.15, cable_count=6, finger_diameter=0.008,
                        screw_diameter=0.005, lead_angle=math.radians(12), weight_lead_angle=math.radians(20))
    rho = p.density
    psi = p.span / p.finger_circle_diameter
    d_k = p.finger_circle_diameter * psi**2 / (p.cable_coefficient * math.sqrt(12 * psi**2 + 3 * p.twist_angle**2))
    cables = 6 * rho * p.area_ratio * 0.785 * d_k**2 * p.span
    fingers = 6 * rho * math.pi * 0.008**2 / 4 * p.finger_length
    screws = 12 * rho * math.pi * 0.005**2 / 4 * p.clamp_screw_length
    driven = rho * math.pi * (p.finger_circle_diameter / 2) ** 2 * p.finger_length
    envelope = get_coupling("cable").formulation("paper").envelope(x, p)
    assert set(envelope.parts) == set(ENVELOPE_PARTS)
    assert envelope.parts["halves"].mass == pytest.approx(1.2 + driven, rel=1e-12)
    assert envelope.parts["moving_parts"].mass == pytest.approx(6 * 0.15 + fingers + screws + cables, rel=1e-12)
    assert envelope.mass == pytest.approx(1.2 + driven + 6 * 0.15 + fingers + screws + cables, rel=1e-12)
    edge = (0.15 / rho) ** (1 / 3)
    assert envelope.outer_diameter == pytest.approx(
        2 * max(p.weight_radius + edge / 2, p.finger_circle_diameter / 2 + 0.004), rel=1e-12)
    assert envelope.axial_length == pytest.approx(p.span + p.nut_height + p.finger_length, rel=1e-12)


def test_paper_mode_wedge_takes_the_width_of_its_weights_mass():
    """b of the real weight of mass m_r (weight_base_width): m = rho gamma [b (r2^2 - r_in^2)/2 + r1 t (r2^2 - r1^2)
    - 2 t (r2^3 - r1^3)/3], t = tan(alpha), solved for b; L = b + s, D = 2 (r2 + s)."""
    case = load_case(CASES / "wedge_paper.toml")
    p = SimpleNamespace(**case.values)
    x = SimpleNamespace(weight_mass=0.235, finger_diameter=0.0031)
    r1 = p.flank_inner_radius
    r2, t = p.radius_ratio * r1, math.tan(p.flank_angle)
    trapezoid = r1 * t * (r2**2 - r1**2) - 2 * t * (r2**3 - r1**3) / 3
    width = (0.235 / (p.density * p.sector_angle) - trapezoid) / ((r2**2 - (r2 - p.weight_height) ** 2) / 2)
    assert width == pytest.approx(0.0396538, rel=1e-5)  # (3.81354e-5 + 1.51838e-6) m^3 / 1e-3 m^2
    outputs = get_coupling("wedge").formulation("paper").outputs(x, p)
    assert outputs["envelope_length"].value == pytest.approx(width + p.shell_thickness, rel=1e-12)
    assert outputs["envelope_diameter"].value == pytest.approx(2 * (r2 + p.shell_thickness), rel=1e-12)
    objective = get_coupling("wedge").formulation("paper").objective("envelope_mass")
    assert objective.function(x, p) == pytest.approx(outputs["envelope_mass"].value, rel=1e-15)
