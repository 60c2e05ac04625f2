"""A static solve's IPOPT optimum polished onto the exact KKT point of its active set (clutchopt/optimise/polish.py):
the optimum where it sits on bounds and active constraints, as a sweep's SQP reaches it, to the last bits."""

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.optimise.attempts import attempt
from clutchopt.optimise.polish import POLISHED, polished
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.verify import evaluate_objective
from conftest import CASES

HIGH_SPEED = 2857.992516770278  # rad/s (27,292 rpm): ball_compressor's torque far from binding
HIGH_SPEED_STRESS = 2e9  # Pa: at that speed the vertex below has p_0 (9) = 1.79 GPa (the ball load grows as
#                          w^2 R_a^2, its Hertz stress as its cube root), over the case's 1 GPa that paper mode
#                          poses: the limit raised so that the vertex stays the subject


def _high_speed():
    return load_case(CASES / "ball_compressor.toml").with_values(speed=HIGH_SPEED,
                                                                 allowable_contact_stress=HIGH_SPEED_STRESS)


def test_the_ball_compressor_at_high_speed_is_solved_on_its_vertex():
    # paper mode, eq. (4): the leading-order torque grows with speed^2 l R_a^4, so at 2858 rad/s it covers M_c 29 %
    # over and the mass (growing with R_a and l) is least at the least R_a, its bound 50 mm, and the least
    # l the width ratio allows, eqs. (3), (5): l = K5 R_a = 0.8 x 50 mm = 40 mm (in float64 0.8 * 0.05 is
    # 0.04000000000000001). IPOPT alone stopped 2.1e-11 m and 6.9e-11 m off that vertex, 2.6e-9 heavier
    case = _high_speed()
    solved = solve_case(case, mode="paper")
    vertex = {"active_radius": 0.05, "active_width": 0.8 * 0.05}
    assert solved.status == "optimal"
    assert solved.design == vertex
    problem = case_problem(case, "paper")
    assert solved.objective == evaluate_objective(problem.formulation, "mass", vertex, problem.posed.params(case))
    margins = {c.name: c.margin for c in solved.constraints}
    assert margins["torque"] > 0.25 and abs(margins["width_ratio"]) <= 1e-15


def test_the_wedge_in_geometry_mode_has_its_bounds_exactly_where_ipopt_found_them_active():
    # README's wedge_paper in geometry mode: the least radius ratio 1.1 and the widest weights 40 mm are bounds the
    # optimum sits on; IPOPT left the width 4.6e-9 inside its bound (6e-9 of its scaled value: the SQP, handed the
    # bound's multiplier, stopped there at once until the polish put it on the bound, polish.SNAP); polished, every
    # active constraint (torque, finger bending, outer diameter, finger guide length) holds to round-off
    solved = solve_case(load_case(CASES / "wedge_paper.toml"), mode="geometry")
    assert solved.status == "optimal"
    assert (solved.design["radius_ratio"], solved.design["weight_width"]) == (1.1, 0.04)
    active = {c.name: c.margin for c in solved.constraints if c.active}
    assert set(active) == {"torque", "finger_bending", "outer_diameter", "finger_guide_length"}
    assert all(abs(margin) <= 1e-15 for margin in active.values())


def test_a_polish_heavier_than_ipopt_s_optimum_is_not_kept():
    # the guard: a polished point is kept only where no heavier than IPOPT's; IPOPT's run told 1e-6 lighter than it
    # is stays as it ended, the polish's iterations and seconds counted in it
    case = _high_speed()
    posed = case_problem(case, "paper").posed
    data = posed.scaled_data(case, checked=posed.params(case))
    ended = attempt(posed, data, data.lbx, data.ubx, data.x0, None, ("ipopt",), [])
    assert ended["ok"] and ended["feasible"]
    exact = polished(posed, data, ended)
    assert exact["design"] == {"active_radius": 0.05, "active_width": 0.8 * 0.05}
    assert exact["value"] < ended["value"]  # (IPOPT's 2.6e-9 heavier)
    assert exact["solver"] == "ipopt" and exact["status"] == f"{ended['status']} {POLISHED}"  # (the design: SQP's)
    iterations, seconds = ended["iterations"], ended["time"]
    ended["value"] = exact["value"] * (1 - 1e-6)
    kept = polished(posed, data, ended)
    assert kept is ended and kept["design"] != exact["design"] and POLISHED not in kept["status"]
    assert kept["iterations"] > iterations and kept["time"] > seconds


def test_a_row_held_from_both_sides_is_polished_without_its_double():
    # ball_compressor.toml, paper mode: the paper's K5 = 0.8 (eqs. 3, 5: l >= K5 R_a) and the case's width_ratio_max
    # = 0.8 (its default, the paper's range 0.4 to 0.8) hold K5 = l / R_a from both sides: two rows g and -g, both
    # active, linearly dependent. IPOPT ended with 4.8e9 on each (their difference the one true multiplier), the SQP's
    # QPs were singular and the polish was lost; the polish leaves the side IPOPT presses less on out (polish.
    # without_dependent_rows). By hand, the fifth root (4): R_a = (3 M_c / (2 pi rho Psi_n f w^2 K5 (1 - K2^3)))^(1/5)
    # and mass ~ R_a^2 l = K5 R_a^3 ~ M_c^(3/5) K5^(2/5): elasticities 0.6 to the torque and 0.4 to the paper's K5,
    # 0 to width_ratio_max (K5 held at it from below); p_0 = 871 MPa within the case's 1 GPa
    from clutchopt.formulations.ball.equations import filling_coefficient, paper_active_radius, required

    case = load_case(CASES / "ball_compressor.toml")
    p = case.params()
    radius = paper_active_radius(required(p), p.friction_coefficient, p.density, p.packing_density, p.speed, 0.8,
                                 filling_coefficient(p.construction_density, p.packing_density))
    solved = solve_case(case, mode="paper")
    assert solved.status == "optimal" and solved.solver.status == f"Solve_Succeeded {POLISHED}"
    assert solved.design["active_radius"] == pytest.approx(radius, rel=1e-9)
    assert solved.design["active_width"] == pytest.approx(0.8 * radius, rel=1e-9)
    rows = {c.name: c for c in solved.constraints}
    assert rows["width_ratio"].active and rows["width_ratio_max"].active
    assert rows["torque"].elasticity == pytest.approx(0.6, rel=1e-6)
    assert rows["width_ratio"].elasticity == pytest.approx(0.4, rel=1e-6) and rows["width_ratio_max"].elasticity == 0
    assert rows["contact_stress"].value == pytest.approx(871.05e6, rel=1e-4) and not rows["contact_stress"].active


def test_a_start_up_s_sizing_is_not_polished():
    # the start-up solves start from the papers' sizing as before the polish (their own tolerance contract)
    problem = case_problem(load_case(CASES / "wedge_motor_start.toml"))
    assert problem.options.polish and not problem.static_problem.options.polish


@pytest.mark.parametrize("mode", ["paper", "geometry"])
def test_a_polished_solve_counts_one_design_solve(mode):
    # wedge_paper: no integers free, one IPOPT solve; the polish is not another design solve
    solved = solve_case(load_case(CASES / "wedge_paper.toml"), mode=mode)
    assert solved.status == "optimal" and solved.solver.solves == 1 and solved.solver.name == "ipopt"
