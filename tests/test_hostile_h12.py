"""A hostile user and a doubting reviewer on the surfaces new in session 12 (a quantity held from both sides, paper
modes posing the case's limits, resumed sweeps, the compiled library's link): each test is one finding's repro, the
command as a user types it and what it must answer, the reference the same point's ``solve``.

Finding 1: limits with no room between them (ball_compressor in paper mode, K5 at least the paper's 0.8 and at most
width_ratio_max = 0.7) are "infeasible whatever the design" in ``solve``; a sweep reaching that point warm from a
design called it ``unverified`` with the warm point's mass (the solvers see the kept row at its own limit, a
well-posed NLP that SQP solves; the float64 check then broke width_ratio_max), and a sweep starting there called it
"proven infeasible" by an interval search naming five rows. Both now give solve's verdict, text and design.

Finding 2: limits a hair apart (width_ratio_max 2e-12 to 3e-10 relative above the paper's K5 of 0.8, room the float64
check cannot tell from none) were posed as two rows g and -g: IPOPT took 26-29 iterations, the polish failed and
``solve`` called "optimal" a design 7.8e-9 heavier than the vertex (its torque 1.3e-8 over M_c), where a sweep's point
found the vertex. Such a pair is now one row (two_sided.ROOM = 1e-8): the vertex, polished, in 7-8 iterations.

Finding 3: limits crossed by less than the float64 check's tolerance allows on both rows (width_ratio_max 1.2e-8 to
2e-8 relative below the paper's K5 of 0.8) were "infeasible whatever the design", proven, though K5 halfway between
them passes the check on every row (each 6e-9 to 1e-8 short, within its 1e-8): a false verdict. Such limits are now
met where the rows cross (two_sided._crossed), and "whatever the design" starts beyond tol (1 + S_f / S_k).
"""

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from conftest import CASES

COMPRESSOR = load_case(CASES / "ball_compressor.toml")


@pytest.mark.parametrize("values", ["0.9,0.8,0.7", "0.7", "0.7,0.6"], ids=["warm", "first", "first_two"])
def test_a_sweep_point_whose_limits_conflict_gets_solve_s_verdict_whatever_the_design(values):
    sweep = Sweep(COMPRESSOR, [parse_vary(f"width_ratio_max={values}", "ball")], mode="paper").run(progress=False)
    for record, ratio_max in zip(sweep.solutions, map(float, values.split(","))):
        if ratio_max >= 0.8:
            assert record["status"] == "optimal"
            continue
        solved = solve_case(COMPRESSOR.with_values(width_ratio_max=ratio_max), "paper")
        gap = (0.8 - ratio_max) / 0.8
        assert solved.status == "infeasible" and solved.diagnosis == (
            "infeasible whatever the design: width_ratio and width_ratio_max (one quantity held from both sides, "
            f"their limits apart by {gap:.3g} relative)")
        assert record["status"] == "infeasible" and record["diagnosis"] == solved.diagnosis
        assert record["design"] == solved.design and record["objective"]["value"] == solved.objective


@pytest.mark.parametrize("apart", [2e-12, 7e-12, 5e-11, 3e-10])
def test_limits_a_hair_apart_are_one_row_and_solve_finds_the_vertex(apart):
    vertex = solve_case(COMPRESSOR, "paper")  # width_ratio_max 0.8 (the default), the paper's K5 0.8: one value
    assert vertex.status == "optimal" and vertex.objective == pytest.approx(505.686153753, rel=1e-11)
    solved = solve_case(COMPRESSOR.with_values(width_ratio_max=0.8 * (1 + apart)), "paper")
    assert solved.status == "optimal" and "polished by SQP" in solved.solver.status
    assert solved.objective == pytest.approx(vertex.objective, rel=1e-10)
    torque = next(c for c in solved.constraints if c.name == "torque")
    assert torque.margin < 1e-10 and torque.active


@pytest.mark.parametrize("below, met", [(1.2e-8, True), (1.99e-8, True), (2.01e-8, False)])
def test_limits_crossed_within_both_rows_tolerance_are_met_not_infeasible(below, met):
    # K5 between 0.8 (width_ratio, at least) and 0.8 (1 - below) (width_ratio_max, at most), each row's scale its
    # limit: at K5 = 0.8 (1 - below / 2) each row is short by below / 2 relative, within 1e-8 up to below = 2e-8
    solved = solve_case(COMPRESSOR.with_values(width_ratio_max=0.8 * (1 - below)), "paper")
    rows = {c.name: c for c in solved.constraints}
    if met:
        assert solved.status == "optimal" and solved.diagnosis is None
        assert solved.objective == pytest.approx(505.686153753 * (1 - below / 2) ** 0.4, rel=1e-10)  # mass ~ K5^0.4
        for name in ("width_ratio", "width_ratio_max"):
            assert rows[name].margin == pytest.approx(-below / 2, rel=1e-3) and rows[name].feasible
    else:
        assert solved.status == "infeasible" and solved.diagnosis == (
            "infeasible whatever the design: width_ratio and width_ratio_max (one quantity held from both sides, "
            f"their limits apart by {below:.3g} relative)")
        assert not (rows["width_ratio"].feasible and rows["width_ratio_max"].feasible)
