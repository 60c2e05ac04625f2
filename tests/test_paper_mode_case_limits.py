"""Paper mode meets every limit the case names (lever, wedge, cable, ball modes.py): the same named constraint as
design/geometry mode, re-checked in float64 with value, limit and margin; a case that breaks one is infeasible, with
the diagnosis naming it. The audit of every rule per coupling: docs/errata.md, "Paper mode and the case's rules"."""

import math

import pytest

from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise import solve_case
from clutchopt.optimise.design import design_case
from clutchopt.optimise.verify import check_design
from conftest import CASES, COUPLING_CASES


def _rows(solution):
    return {c.name: c for c in solution.constraints}


def test_lever_paper_mode_checks_the_housing_diameter_and_the_toggle_span():
    # lever_centrifuge.toml: delta = 4 mm, gamma_0 = 15 deg, gamma_pr = 3 deg. The l_2 rule (paper) gives the
    # shortest links l_2 = delta / (cos gamma_pr - cos gamma_0) = 4 / (0.9986295 - 0.9659258) = 122.3103 mm, so the
    # toggle spans 2 l_2 cos gamma_pr = 244.2853 mm (limit 300 mm: margin (300 - 244.2853) / 300 = 0.18572); the
    # housing d_cp + b + 2 s = 299.62 mm (docs/lever.md) is within 360 mm. With toggle_span_max = 240 mm no m, d_l
    # helps: infeasible, naming toggle_span. The flange d_phi = 80 mm against limits.flange_hub_ratio 1.6 x d_b 42 mm
    # = 67.2 mm: margin 12.8 / 67.2 = 0.19048; at ratio 2 (84 mm) the paper's flange is too small: infeasible.
    l2 = 4e-3 / (math.cos(math.radians(3)) - math.cos(math.radians(15)))
    span = 2 * l2 * math.cos(math.radians(3))
    assert l2 == pytest.approx(122.3103e-3, rel=1e-6) and span == pytest.approx(244.2853e-3, rel=1e-6)
    case = load_case(CASES / "lever_centrifuge.toml")
    solution = solve_case(case, "paper")
    rows = _rows(solution)
    assert solution.status == "optimal" and solution.objective == pytest.approx(1.726531102086192, rel=1e-9)
    assert rows["toggle_span"].value == pytest.approx(span, rel=1e-12)
    assert rows["toggle_span"].margin == pytest.approx((0.3 - span) / 0.3, rel=1e-12)
    assert rows["outer_diameter"].value == pytest.approx(0.2996249278, rel=1e-9) and not rows["outer_diameter"].active
    assert rows["flange_over_shaft"].margin == pytest.approx(12.8 / 67.2, rel=1e-12)
    narrow = solve_case(case.with_values(flange_hub_ratio=2.0), "paper")
    assert narrow.status == "infeasible" and "flange_over_shaft" in narrow.diagnosis
    tight = solve_case(case.with_values(toggle_span_max=0.24), "paper")
    assert tight.status == "infeasible" and "toggle_span" in tight.diagnosis
    assert _rows(tight)["toggle_span"].margin == pytest.approx((0.24 - span) / 0.24, rel=1e-12)


def test_wedge_paper_mode_checks_release_and_diameter_and_choose_ranks_no_self_locking_pair(tmp_path):
    # wedge_paper.toml: alpha = 15 deg against atan f + 2 deg (above eq. 24): f = 0.15 gives 8.5308 + 2 = 10.5308
    # deg, margin (15 - 10.5308) / 10.5308 = 0.42440; the housing 2 (lambda r1 + s) = 2 (1.2 x 50 + 10) = 140 mm
    # within 200 mm. At f = 0.3 the limit is 16.6992 + 2 = 18.6992 deg > 15 deg: infeasible, margin -0.19783.
    limit = math.atan(0.15) + math.radians(2)
    assert math.degrees(limit) == pytest.approx(10.5308, abs=1e-4)
    case = load_case(CASES / "wedge_paper.toml")
    solution = solve_case(case, "paper")
    rows = _rows(solution)
    assert solution.status == "optimal" and solution.objective == pytest.approx(0.6679507848466743, rel=1e-9)
    assert rows["not_self_locking"].margin == pytest.approx((math.radians(15) - limit) / limit, rel=1e-12)
    assert rows["outer_diameter"].value == pytest.approx(0.140, rel=1e-12)
    assert rows["outer_diameter"].margin == pytest.approx(0.3, rel=1e-12)
    locking = solve_case(case.with_values(friction_coefficient=0.3), "paper")
    limit = math.atan(0.3) + math.radians(2)
    assert locking.status == "infeasible" and "not_self_locking" in locking.diagnosis
    assert _rows(locking)["not_self_locking"].margin == pytest.approx((math.radians(15) - limit) / limit, rel=1e-12)
    assert (math.radians(15) - limit) / limit == pytest.approx(-0.19783, abs=1e-5)
    # options.choose between the library's pairs (f 0.18, 0.05, 0.3): the bronze one self-locks, so it is shown
    # infeasible (ranked after the optimal ones), not best; the lightest that releases is steel on steel, dry.
    path = tmp_path / "choose.toml"
    path.write_text((CASES / "wedge_paper.toml").read_text().replace("friction_coefficient = 0.15\n", "")
                    + '\n[options]\nchoose = { friction_pair = ["steel_steel_dry", "steel_steel_oiled", '
                    '"sintered_bronze_dry"] }\n')
    ranked = design_case(load_case(path), "paper")
    assert [(d.choice["friction_pair"], d.solution.status) for d in ranked] == [
        ("steel_steel_dry", "optimal"), ("steel_steel_oiled", "optimal"), ("sintered_bronze_dry", "infeasible")]
    assert "not_self_locking" in ranked[2].solution.diagnosis


def test_ball_paper_mode_checks_the_drum_diameter_and_the_longest_drum():
    # ball_crusher.toml, paper mode: R_a from the fifth root (4), l = K5 R_a = 0.5 R_a: R_a = 320.344 mm, drum
    # 2 (R_a + s) = 2 (320.344 + 30) = 700.689 mm within 1000 mm, K5 = 0.5 within width_ratio_max = 3. Its Hertz
    # stress p_0 (9) is 847 MPa, over the case's 0.5 GPa (tests/test_ball_nlp.py, by hand): as given the case is
    # proven infeasible in paper mode, naming contact_stress; here 1 GPa is allowed so that the drum is the subject.
    # With outer_diameter_max = 500 mm, R_a <= 250 - 30 = 220 mm and l <= 3 R_a = 660 mm; the leading torque (4)
    # grows as l R_a^4, so at that corner it is (660 / 160.172) (220 / 320.344)^4 = 4.12056 x 0.222446 = 0.91660 of
    # M_c: no design carries the torque, proven infeasible, naming outer_diameter and width_ratio_max.
    given = solve_case(load_case(CASES / "ball_crusher.toml"), "paper")
    assert given.status == "infeasible" and "proven" in given.diagnosis and "contact_stress" in given.diagnosis
    case = load_case(CASES / "ball_crusher.toml").with_values(allowable_contact_stress=1e9)
    solution = solve_case(case, "paper")
    rows = _rows(solution)
    radius = solution.design["active_radius"]
    assert solution.status == "optimal" and radius == pytest.approx(0.3203443137, rel=1e-9)
    assert rows["outer_diameter"].value == pytest.approx(2 * (radius + 0.03), rel=1e-12)
    assert rows["width_ratio_max"].value == pytest.approx(0.5, rel=1e-9) and rows["width_ratio_max"].limit == 3.0
    assert rows["contact_stress"].value == pytest.approx(847.148e6, rel=1e-6) and rows["contact_stress"].limit == 1e9
    small = case.with_values(outer_diameter_max=0.5)
    corner = check_design(get_coupling("ball").formulation("paper"), {"active_radius": 0.22, "active_width": 0.66},
                          small.params())
    torque = next(c for c in corner if c.name == "torque")
    assert torque.value / torque.limit == pytest.approx((0.66 / (0.5 * radius)) * (0.22 / radius) ** 4, rel=1e-9)
    assert torque.value / torque.limit == pytest.approx(0.91660, abs=1e-5)
    tight = solve_case(small, "paper")
    assert tight.status == "infeasible" and "proven" in tight.diagnosis
    assert "outer_diameter" in tight.diagnosis and "width_ratio_max" in tight.diagnosis


def test_a_requirement_no_design_variable_enters_is_judged_without_a_solve_and_a_sweep_agrees():
    # wedge_paper.toml, paper mode: the flank half-angle is given (15 deg), so the release condition alpha >= atan f +
    # 2 deg (above eq. 24) is a row no design variable enters; at f = 0.3, atan 0.3 + 2 deg = 18.699 deg: short by
    # (18.699 - 15) / 18.699 = 0.1978 relative, whatever m_r and d_n. The verdict is given without a solve (an IPOPT
    # solve took 13 iterations to end at a point of its own, then was diagnosed), at the case's start design, and a
    # sweep's point gets the same verdict at the same design (it solves the point through the same path)
    from clutchopt.optimise.problem import PROVEN
    from clutchopt.optimise.sweep import Sweep, Vary

    case = load_case(CASES / "wedge_paper.toml")
    at = case.with_values(friction_coefficient=0.3)
    solved = solve_case(at, "paper")
    assert solved.status == "infeasible" and solved.solver.name == PROVEN and solved.solver.solves == 0
    short = (math.degrees(math.atan(0.3)) + 2.0 - 15.0) / (math.degrees(math.atan(0.3)) + 2.0)
    assert solved.diagnosis == f"infeasible whatever the design: not_self_locking (short of its limit by {short:.3g} " \
                               "relative)"
    assert _rows(solved)["not_self_locking"].margin == pytest.approx(-short, rel=1e-9)
    quantity = next(q for q in case.quantities if q.name == "friction_coefficient")
    record = Sweep(case, [Vary(quantity, (0.1, 0.3))], mode="paper").run(progress=False).solutions[-1]
    assert record["status"] == "infeasible" and record["diagnosis"] == solved.diagnosis
    assert record["design"] == solved.design


@pytest.mark.parametrize("values", [{}, {"service_factor": 1.4914285714285713}, {"power": 605693.4230086812}],
                         ids=["as_given", "service_factor_1_49", "power_606_kW"])
def test_ball_motor_start_in_paper_mode_is_proven_infeasible_by_its_contact_stress(values):
    # ball_motor_start.toml is ball_crusher.toml started on its motor: the paper mode's fifth root (4) has p_0 (9) =
    # 847 MPa over the case's 0.5 GPa (tests/test_ball_nlp.py, by hand). p_0 rises with R_a alone (the ball load as
    # R_a^2, its Hertz stress as its cube root), the torque (4) with R_a and l <= 3 R_a (width_ratio_max): at
    # p_0 = 0.5 GPa, R_a = 149.1 mm and l = 447 mm carry 0.131 M_c (at 1.2 x 500 kW; less of the more M_c asks). Static, so no start-up enters it: proven infeasible (interval
    # branch and bound), naming contact_stress, at the service factor (1.49) and power (606 kW) where the start-up
    # NLP once ended not_found, and the start-up rows are not its cause
    solved = solve_case(load_case(CASES / "ball_motor_start.toml").with_values(**values), "paper")
    assert solved.status == "infeasible" and solved.diagnosis.startswith("proven infeasible")
    assert "contact_stress" in solved.diagnosis and "start_time" not in solved.diagnosis


# --- The property: paper mode meets every rule its other mode poses on the case (or is infeasible naming one) ------
# The audit (docs/errata.md, "Paper mode and the case's rules"): each rule of the other mode that reads a case
# quantity, and whether paper mode poses it. Posed unless listed here, with the reason.
OTHER_MODE = {"wedge": "geometry", "lever": "design", "cable": "threads"}
NOT_POSED_IN_PAPER = {
    "wedge": (),  # every rule, the width rules at the real weight's b(m_r) (weight_base_width)
    "lever": ("lever_length",),  # met by construction: the paper's l_2 is this rule at equality (paper_geometry)
    "cable": (),  # both modes are CableCoupling's one set of rules
}
# The wedge's duty rows (15)-(16), (13), (19) in geometry mode are of the real weight body (weight_body), in paper
# mode of the paper's m_r at r_c = r2 - 2/3 h_r: the same equations of two different weights, not compared here.
WEIGHT_BODY_ROWS = {"wedge": ("torque", "flank_pressure", "finger_bending")}


def _as_other_mode(coupling, design, p):
    """The paper-mode design in the other mode's variables: the case's given geometry, the paper's rules for what
    it derives (lever: l_2 and B_cp), the width of the wedge's real weight of mass m_r (weight_base_width)."""
    if coupling == "wedge":
        from clutchopt.formulations.wedge.equations import weight_base_width

        r2 = p.radius_ratio * p.flank_inner_radius
        return dict(design, flank_inner_radius=p.flank_inner_radius, radius_ratio=p.radius_ratio,
                    weight_height=p.weight_height, sector_angle=p.sector_angle, flank_angle=p.flank_angle,
                    weight_count=p.weight_count,
                    weight_width=weight_base_width(design["weight_mass"], r2 - p.weight_height,
                                                   p.flank_inner_radius, r2, p.flank_angle, p.sector_angle,
                                                   p.density))
    if coupling == "lever":
        from clutchopt.formulations.lever.paper import paper_geometry

        lever, width = paper_geometry(p)
        return dict(design, lever_length=lever, lining_width=width, engagement_angle=p.engagement_angle,
                    limit_angle=p.limit_angle, weight_count=p.weight_count, flange_diameter=p.flange_diameter)
    return dict(design)


@pytest.mark.parametrize("path", [
    pytest.param(p, id=p.stem) for p in COUPLING_CASES if load_case(p).coupling in OTHER_MODE])
def test_paper_mode_meets_every_rule_its_other_mode_poses(path):
    from types import SimpleNamespace

    case = load_case(path)
    coupling, p = case.coupling, case.params()
    other = get_coupling(coupling).formulation(OTHER_MODE[coupling])
    solution = solve_case(case, "paper")
    assert solution.status == "optimal", solution.diagnosis
    posed = _rows(solution)
    design = _as_other_mode(coupling, solution.design, p)
    replaced = {c.name for c in other.constraints(SimpleNamespace(**design), p) if c.constant_acceleration} \
        if case.start_up else set()  # (a start-up's own rows take the place of the constant-acceleration torque)
    at_paper = check_design(other, design, p)
    left = [row for row in at_paper if row.name in NOT_POSED_IN_PAPER[coupling]]
    for row in at_paper:
        if row.name in NOT_POSED_IN_PAPER[coupling] or row.name in WEIGHT_BODY_ROWS.get(coupling, ()):
            continue
        if row.name in replaced:
            assert row.name not in posed
            continue
        assert row.name in posed, f"{path.name}: paper mode does not pose {row.name}"
        assert posed[row.name].feasible and row.feasible
        assert posed[row.name].value == pytest.approx(row.value, rel=1e-12, abs=1e-15)  # one definition
        assert posed[row.name].limit == pytest.approx(row.limit, rel=1e-12, abs=1e-15)
    if coupling == "lever":
        assert [row.name for row in left] == ["lever_length"] and left[0].margin == pytest.approx(0.0, abs=1e-12)
    for row in left:
        assert row.feasible, f"{path.name}: {row.name} margin {row.margin:.3g} at the paper-mode design"


def test_wedge_paper_mode_poses_the_weights_construction_by_hand():
    # wedge_paper.toml: r1 = 50 mm, r2 = 1.2 r1 = 60 mm, h_r = 20 mm, inner edge r_in = r2 - h_r = 40 mm, gamma =
    # 0.785 rad, z = 4. The paper's optimum: w = 1000 rpm = 104.7198 rad/s, T_max = I w / t_p + T_c = 0.5 x 104.7198
    # / 10 + 5 = 10.23599 N m (5), (17); r_c = r2 - 2/3 h_r = 46.6667 mm (11); m_r = 2 T_max sin(alpha) / (f z (r1 +
    # r2) w^2 r_c) (27, consistent form); the finger h_n = (r1 + r2) / 2 = 55 mm long carries F_fr = f m_r w^2 r_c /
    # sin(alpha) (14): d_n = cbrt(32 F_fr h_n / (pi [sigma])) (28) = 5.46156 mm. Then, each row's margin relative to
    # its scale (r1 = 50 mm for lengths, the limit otherwise):
    #   (26) h_r >= r2 - r1: (20 - 10) / 50 = 0.2; hub r_in >= 25 mm: (40 - 25) / 50 = 0.3;
    #   sectors z (gamma + 2 deg) = 4 (0.785 + 0.0349066) = 3.279626 rad <= 2 pi: margin 0.478031;
    #   guide h_r >= 1.5 d_n = 8.19234 mm: (20 - 8.19234) / 50 = 0.236153;
    #   chord d_n <= 0.5 x 2 r_in sin(gamma / 2) = 40 sin(0.3925) = 15.29998 mm: (15.29998 - 5.46156) / 50 = 0.196768.
    # A hub of 45 mm radius breaks the clearance whatever m_r and d_n: (40 - 45) / 50 = -0.1, judged without a solve.
    # A guide ratio of 4 asks d_n <= 5 mm < 5.46156 mm, which the finger's bending (19) forbids: proven infeasible.
    w = 1000 * 2 * math.pi / 60
    t_max, alpha, r_c = 0.5 * w / 10 + 5, math.radians(15), 0.06 - 2 / 3 * 0.02
    mass = 2 * t_max * math.sin(alpha) / (0.15 * 4 * 0.11 * w**2 * r_c)
    finger = (32 * 0.15 * mass * w**2 * r_c / math.sin(alpha) * 0.055 / (math.pi * 160e6)) ** (1 / 3)
    assert finger == pytest.approx(5.46156e-3, rel=1e-5)
    expected = {"weight_covers_flank": 0.2, "hub_clearance": 0.3,
                "sectors_fit": (2 * math.pi - 4 * (0.785 + math.radians(2))) / (2 * math.pi),
                "finger_guide_length": (0.02 - 1.5 * finger) / 0.05,
                "finger_fits_chord": (0.04 * math.sin(0.3925) - finger) / 0.05}
    assert expected["sectors_fit"] == pytest.approx(0.478031, abs=1e-6)
    assert expected["finger_fits_chord"] == pytest.approx(0.196768, abs=1e-6)
    case = load_case(CASES / "wedge_paper.toml")
    solution = solve_case(case, "paper")
    rows = _rows(solution)
    assert solution.design["finger_diameter"] == pytest.approx(finger, rel=1e-8)
    for name, margin in expected.items():
        assert rows[name].margin == pytest.approx(margin, rel=1e-8), name
        assert not rows[name].active
    hub = solve_case(case.with_values(hub_radius=0.045), "paper")
    assert hub.status == "infeasible" and hub.solver.solves == 0
    assert hub.diagnosis == "infeasible whatever the design: hub_clearance (short of its limit by 0.1 relative)"
    assert _rows(hub)["hub_clearance"].margin == pytest.approx(-0.1, rel=1e-12)
    guide = solve_case(case.with_values(guide_length_ratio=4.0), "paper")
    assert guide.status == "infeasible" and "proven" in guide.diagnosis
    assert "finger_guide_length" in guide.diagnosis and "finger_bending" in guide.diagnosis


def test_lever_paper_mode_checks_that_the_linings_clear_the_flange_by_hand():
    # lever_centrifuge.toml: the weight at engagement R_0 = d_b/2 + (d_phi - d_b)/4 + l_pr = 21 + 9.5 + 40 = 70.5 mm;
    # the paper's d_cp = 2 (S_ov + R_0) and B_cp = 2 (S_ov + 1.5 delta), so the linings' inner diameter d_cp - B_cp =
    # 2 R_0 - 3 delta = 141 - 12 = 129 mm whatever l_2; against d_phi = 80 mm: margin (129 - 80) / 80 = 0.6125. With
    # springs of l_pr = 10 mm, R_0 = 40.5 mm, d_cp - B_cp = 69 mm < 80 mm: infeasible whatever m and d_l, short by
    # (80 - 69) / 80 = 0.1375, judged without a solve.
    case = load_case(CASES / "lever_centrifuge.toml")
    row = _rows(solve_case(case, "paper"))["lining_clears_flange"]
    assert row.value == pytest.approx(0.129, rel=1e-12) and row.limit == pytest.approx(0.080, rel=1e-12)
    assert row.margin == pytest.approx(0.6125, rel=1e-12) and not row.active
    short = solve_case(case.with_values(spring_free_length=0.010), "paper")
    assert short.status == "infeasible" and short.solver.solves == 0
    assert short.diagnosis == "infeasible whatever the design: lining_clears_flange (short of its limit by 0.137 " \
                              "relative)"
    assert _rows(short)["lining_clears_flange"].margin == pytest.approx(-0.1375, rel=1e-12)


def test_the_centrifuges_former_paper_geometry_is_proven_infeasible_by_its_width_rules():
    """The centrifuge's geometry before it was made buildable (6 weights of 50 deg, h_r = 35 mm): torque (15) and
    bending (19) ask m_r = 0.111542 kg and d_n = 10.4532 mm, and a weight of that mass is b(m_r) = 9.18 mm wide
    (weight_base_width: r1 = 90, r2 = 112.5, r_in = 77.5 mm, t = tan 15 deg, gamma = 50 deg: (m_r / (rho gamma) - t
    (r1 (r2^2 - r1^2) - 2/3 (r2^3 - r1^3))) / ((r2^2 - r_in^2) / 2)): top land 9.18 - 2 x 22.5 tan 15 deg = -2.88 mm,
    a 10.5 mm finger in a 9.2 mm weight. A heavier weight is wider (b affine in m_r) but its finger thicker and its
    flank pressure higher: no m_r, d_n meets every rule, proven, naming both width rules."""
    r1, r2, r_in, t, gamma = 0.09, 0.1125, 0.0775, math.tan(math.radians(15)), math.radians(50)
    b = (0.111542 / (7850 * gamma) - t * (r1 * (r2**2 - r1**2) - 2 / 3 * (r2**3 - r1**3))) / ((r2**2 - r_in**2) / 2)
    assert b == pytest.approx(0.00918065, rel=1e-5) and b - 2 * (r2 - r1) * t < 0 and 0.5 * b < 0.0104532
    former = load_case(CASES / "wedge_centrifuge.toml").with_values(weight_count=6, sector_angle=gamma,
                                                                    weight_height=0.035)
    solved = solve_case(former, "paper")
    assert solved.status == "infeasible" and solved.diagnosis.startswith("proven infeasible")
    assert "top_land_width" in solved.diagnosis and "finger_fits_width" in solved.diagnosis


def test_paper_mode_width_rules_of_the_papers_example_by_hand():
    """wedge_paper keeps its numbers, and its weight is buildable: m_r = 0.156873 kg (torque (15)), d_n = 5.46156 mm
    (bending (19)); b(m_r) = 26.9755 mm (tests/test_wedge_closed_forms.py, by hand); top land 26.9755 - 2 x 10 mm x
    tan 15 deg = 21.6165 mm, margin (21.6165 - 2) / 26.9755 = +0.727197; finger 5.46156 <= 0.5 x 26.9755 =
    13.4877 mm, margin (13.4877 - 5.46156) / 26.9755 = +0.297536."""
    solution = solve_case(load_case(CASES / "wedge_paper.toml"), "paper")
    assert solution.status == "optimal"
    assert solution.design["weight_mass"] == pytest.approx(0.156873, rel=1e-5)
    assert solution.design["finger_diameter"] == pytest.approx(5.46156e-3, rel=1e-5)
    assert solution.outputs["weight_width"].value == pytest.approx(0.0269755, rel=1e-5)
    rows = _rows(solution)
    assert rows["top_land_width"].value == pytest.approx(0.0216165, rel=1e-5)
    assert rows["top_land_width"].margin == pytest.approx(0.727197, rel=1e-5)
    assert rows["finger_fits_width"].limit == pytest.approx(0.0134877, rel=1e-5)
    assert rows["finger_fits_width"].margin == pytest.approx(0.297536, rel=1e-5)
