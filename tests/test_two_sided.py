"""A quantity held from both sides posed once, as one two-sided row (clutchopt/optimise/two_sided.py): the solvers'
row bounds and multipliers, the named rows (each with its own multiplier) for everything else."""

import casadi as ca
import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.model import at_least, at_most
from clutchopt.optimise import solve_case
from clutchopt.optimise.polish import POLISHED
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.two_sided import TwoSided
from conftest import CASES


def _rows(lower=2.0):
    # v = x held within [L_l, L_u] = [lower, 5] from both sides, S_u = 10 and S_l = 4 (its own scale, not the limit),
    # with an unrelated row between them: g_u = (v - 5) / 10, g_l = (lower - v) / 4, g_other = x - 1
    x, p = ca.SX.sym("x"), ca.SX.sym("p", 0)
    constraints = [at_most("upper", x, 5.0, equation="-", scale=10.0),
                   at_most("other", x, 1.0, equation="-", scale=1.0),
                   at_least("lower", x, lower, equation="-", scale=4.0)]
    return x, p, TwoSided(constraints, x, p, np.full(3, -np.inf))


def test_two_rows_on_one_quantity_at_one_value_are_one_row_with_both_limits_else_as_they_are():
    # kept: the ">=" row g_l (row 2), g_u <= 0 is v <= 5 = 5 - 4 g_l... : g_l >= (L_l - 5) / 4. With room between
    # (L_l = 2: g_l >= -0.75) both rows are posed as they are (the ball's design-mode sweeps' chained SQP took 5 times
    # as long a call with one two-sided row); at one value (L_l = 5: g_l >= 0) row 2 has both limits and row 0 is free
    none, zero = np.zeros(0), np.zeros(3)
    assert _rows()[2].pairs == [(2, 0)]
    lbg, ubg = _rows()[2].bounds(none, zero)
    assert list(lbg) == [-np.inf] * 3 and list(ubg) == [0.0] * 3
    sides = _rows(5.0)[2]
    lbg, ubg = sides.bounds(none, zero)
    assert list(lbg) == [-np.inf, -np.inf, 0.0] and list(ubg) == [np.inf, 0.0, 0.0]
    lbg, ubg = sides.bounds(none, np.array([np.inf, 0.0, 0.0]))  # the upper side left out (polish): no lower limit
    assert list(lbg) == [-np.inf] * 3 and list(ubg) == [np.inf, 0.0, 0.0]
    assert sides.conflicts(none, 1e-9) == []


def test_a_two_sided_row_s_multiplier_goes_to_the_side_it_presses():
    # at one value (L_l = L_u = 5): the solvers' lam on the kept row g_l positive is g_l's own (v pressed onto its
    # lower limit); negative, v pressed onto its upper limit: g_u's, by the Lagrangian: lam g_l = lam (5 - v) / 4 and
    # lam_u g_u = lam_u (v - 5) / 10 have the same gradient in v where lam_u = -lam 10 / 4. With room, the identity.
    none = np.zeros(0)
    sides = _rows(5.0)[2]
    assert list(sides.named(np.array([0.0, 3.0, 2.0]), none)) == [0.0, 3.0, 2.0]
    assert list(sides.named(np.array([0.0, 3.0, -2.0]), none)) == [5.0, 3.0, 0.0]
    assert list(sides.posed(np.array([5.0, 3.0, 0.0]), none)) == [0.0, 3.0, -2.0]  # and back
    lam = np.array([1.0, 3.0, 2.0])
    assert _rows()[2].named(lam, none) is lam and _rows()[2].posed(lam, none) is lam
    # the same maps as CasADi expressions (the chained SQP's): at one value and with room
    for sides, expected in ((_rows(5.0)[2], [5.0, 3.0, 0.0]), (_rows()[2], [0.0, 3.0, -2.0])):
        p = ca.SX.sym("p", 0)
        assert list(np.array(ca.evalf(sides.named(ca.DM([0.0, 3.0, -2.0]), p))).ravel()) == expected


def test_only_a_quantity_held_from_both_sides_is_paired():
    # the ball's K5 = l / R_a: in paper mode the paper's K5 (">=") and width_ratio_max; in design mode width_ratio_min
    # and width_ratio_max; no other formulation holds one quantity from both sides (its maps the identity)
    pairs = {}
    for name, mode in [("ball_compressor", "paper"), ("ball_compressor", "design"), ("wedge_paper", "paper"),
                       ("wedge_paper", "geometry"), ("cable_pump", None), ("lever_centrifuge", None)]:
        posed = case_problem(load_case(CASES / f"{name}.toml"), mode).posed
        pairs[name, mode] = [(posed.row_names[k], posed.row_names[f]) for k, f in posed.sides.pairs]
    assert pairs.pop(("ball_compressor", "paper")) == [("width_ratio", "width_ratio_max")]
    assert pairs.pop(("ball_compressor", "design")) == [("width_ratio_min", "width_ratio_max")]
    assert all(found == [] for found in pairs.values())


def test_k5_held_at_one_value_from_both_sides_is_an_equality_ipopt_solves_as_such():
    # ball_compressor.toml, paper mode: the paper's K5 = 0.8 (eqs. 3, 5: l >= K5 R_a) and the case's width_ratio_max
    # = 0.8 (its default, the paper's range 0.4 to 0.8) hold K5 = l / R_a from both sides. Posed as two rows g and
    # -g, IPOPT had no interior (4.8e9 on each row, 30 iterations with the polish); as one row with both limits 0,
    # 8. By hand, the fifth root (4): R_a = (3 M_c / (2 pi rho Psi_n f w^2 K5 (1 - K2^3)))^(1/5) and
    # mass ~ R_a^2 l = K5 R_a^3 ~ M_c^(3/5) K5^(2/5): elasticities 0.6 to the torque and 0.4 to the paper's K5, 0 to
    # width_ratio_max (K5 held at it from below: the multiplier on the side it presses); p_0 = 871 MPa within 1 GPa
    from clutchopt.formulations.ball.equations import filling_coefficient, paper_active_radius, required

    case = load_case(CASES / "ball_compressor.toml")
    p = case.params()
    radius = paper_active_radius(required(p), p.friction_coefficient, p.density, p.packing_density, p.speed, 0.8,
                                 filling_coefficient(p.construction_density, p.packing_density))
    solved = solve_case(case, mode="paper")
    assert solved.status == "optimal" and solved.solver.status == f"Solve_Succeeded {POLISHED}"
    assert solved.solver.iterations <= 10
    assert solved.design["active_radius"] == pytest.approx(radius, rel=1e-9)
    assert solved.design["active_width"] == pytest.approx(0.8 * radius, rel=1e-9)
    rows = {c.name: c for c in solved.constraints}
    assert rows["width_ratio"].active and rows["width_ratio_max"].active  # both named, each with its own figures
    assert rows["width_ratio"].limit == rows["width_ratio_max"].limit == 0.8
    assert rows["torque"].elasticity == pytest.approx(0.6, rel=1e-6)
    assert rows["width_ratio"].elasticity == pytest.approx(0.4, rel=1e-6) and rows["width_ratio_max"].multiplier == 0
    assert rows["contact_stress"].value == pytest.approx(871.05e6, rel=1e-4) and not rows["contact_stress"].active


def test_limits_with_no_room_between_are_infeasible_whatever_the_design_never_an_ill_posed_solve(tmp_path):
    # _rows() with the lower limit 7 above the upper 5: g_l >= (7 - 5) / 4 = 0.5 > 0 = its upper bound. The solvers see
    # the kept row where the two rows cross, each violated alike: g_l = 0.5 / (1 + S_u / S_l) = 0.5 / 3.5 = 1/7 (so
    # v = 7 - 4/7 and g_u = (v - 5) / 10 = 1/7 too; lbg <= ubg: IPOPT refused lbg > ubg with an assertion, an internal
    # error; the chained SQP's symbolic bounds the same), and the pair is named apart by 0.5 relative to the kept row's scale: in conflict where that is more than
    # the tolerance allows on both rows, tol (1 + 2.5)
    sides = _rows(7.0)[2]
    assert sides.conflicts(np.zeros(0), 1e-9) == [(2, 0, 0.5)]
    assert sides.conflicts(np.zeros(0), 0.5 / 3.5) == [] and sides.conflicts(np.zeros(0), 0.14) == [(2, 0, 0.5)]
    lbg, ubg = sides.bounds(np.zeros(0), np.zeros(3))
    assert list(lbg) == [-np.inf, -np.inf, 0.5 / 3.5] and list(ubg) == [np.inf, 0.0, 0.5 / 3.5]
    assert [list(np.array(b).ravel()) for b in sides.bounds_of(np.zeros(0))] == [list(lbg), list(ubg)]
    # one side left out of a solve (the polish): the other at its own limit, not at the crossing (review h12: the
    # kept row was posed at g_l <= 1/7 with the upper side out, 62 times the float64 check's tolerance on the ball)
    lbg, ubg = sides.bounds(np.zeros(0), np.array([np.inf, 0.0, 0.0]))  # the upper row out: g_l <= 0
    assert list(lbg) == [-np.inf] * 3 and list(ubg) == [np.inf, 0.0, 0.0]
    lbg, ubg = sides.bounds(np.zeros(0), np.array([0.0, 0.0, np.inf]))  # the lower row out: g_u <= 0, g_l >= 0.5
    assert list(lbg) == [-np.inf, -np.inf, 0.5] and list(ubg) == [np.inf, 0.0, np.inf]
    # ball_compressor.toml in paper mode: K5 at least the paper's 0.8 (width_ratio) and at most width_ratio_max = 0.5:
    # apart by (0.8 - 0.5) / 0.8 = 0.375 of the kept row's scale (its limit 0.8). Proven without a solve, both named.
    case = load_case(CASES / "ball_compressor.toml").with_values(width_ratio_max=0.5)
    solution = solve_case(case, "paper")
    assert solution.status == "infeasible" and solution.solver.iterations == 0
    assert solution.diagnosis == ("infeasible whatever the design: width_ratio and width_ratio_max (one quantity held "
                                  "from both sides, their limits apart by 0.375 relative)")
    rows = {c.name: c for c in solution.constraints}
    assert rows["width_ratio"].limit == 0.8 and rows["width_ratio_max"].limit == 0.5
    assert not (rows["width_ratio"].feasible and rows["width_ratio_max"].feasible)


def test_conflicts_read_over_a_run_of_points_at_once_are_each_point_s_own():
    # ball_compressor.toml in paper mode, K5 at least the paper's 0.8: width_ratio_max 0.5 (apart by 0.375) and
    # 0.8 - 1.2e-6 (by 1.5e-6, more than the check's tolerance allows on both rows) conflict; 0.8 - 1e-9 (within it),
    # 0.8 and 1.0 leave room. Posed.conflicting_at reads a region proof's points in one call, as each alone.
    posed = case_problem(load_case(CASES / "ball_compressor.toml"), "paper").posed
    cases = [load_case(CASES / "ball_compressor.toml").with_values(width_ratio_max=v)
             for v in (0.5, 0.8 - 1.2e-6, 0.8 - 1e-9, 0.8, 1.0)]
    assert posed.conflicting_at(cases) == [True, True, False, False, False]
    assert [posed.conflicting(case) for case in cases] == [True, True, False, False, False]
