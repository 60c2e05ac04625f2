"""Paper mode meets every limit the case names (lever, wedge, ball modes.py, ``_case_limits``): the same named
constraint as design/geometry mode, re-checked in float64 with value, limit and margin; a case that breaks one is
infeasible, with the diagnosis naming it."""

import math

import pytest

from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise import solve_case
from clutchopt.optimise.design import design_case
from clutchopt.optimise.verify import check_design
from conftest import CASES


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
