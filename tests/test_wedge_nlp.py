"""Wedge coupling NLP: paper mode equals the closed form; geometry mode feasible and at least as light."""

import math
from dataclasses import replace

import pytest

from clutchopt.cases import load_case
from clutchopt.formulations.wedge.closed_forms import closed_form_finger_diameter, closed_form_weight_mass
from clutchopt.formulations.wedge.modes import GEOMETRY, PAPER
from clutchopt.optimise import problem_for, solve_case
from tests.conftest import CASES

WEDGE_CASES = ["wedge_paper.toml", "wedge_centrifuge.toml", "wedge_fan.toml"]


@pytest.fixture(scope="module", params=WEDGE_CASES)
def case(request):
    return load_case(CASES / request.param)


def test_paper_mode_optimum_is_the_closed_form(case):
    solution = solve_case(case, "paper", "mass")
    p = case.params()
    m_r = closed_form_weight_mass(p)
    assert solution.status == "optimal"
    assert solution.design["weight_mass"] == pytest.approx(m_r, rel=1e-6)
    assert solution.design["finger_diameter"] == pytest.approx(closed_form_finger_diameter(p, m_r), rel=1e-6)
    active = {c.name for c in solution.constraints if c.active}
    assert active == {"torque", "finger_bending"}


def test_cost_objective_gives_the_same_paper_design(case):
    # in paper mode the geometry is fixed, so cost = price * mass + constants: same optimum
    mass, cost = solve_case(case, "paper", "mass"), solve_case(case, "paper", "cost")
    assert cost.design["weight_mass"] == pytest.approx(mass.design["weight_mass"], rel=1e-6)


def test_geometry_mode_is_feasible_and_no_heavier_than_paper_mode(case):
    paper = solve_case(case, "paper", "mass")
    geometry = solve_case(case, "geometry", "mass")
    assert geometry.status == "optimal"
    assert all(c.margin >= -1e-8 for c in geometry.constraints)
    assert geometry.objective <= paper.objective * (1 + 1e-9)
    assert geometry.outputs["torque"].value >= geometry.outputs["required_torque"].value * (1 - 1e-8)
    assert float(geometry.design["weight_count"]).is_integer()


def test_integer_weight_count_is_the_best_of_all_counts():
    case = load_case(CASES / "wedge_centrifuge.toml")  # frees flank angle and weight count, z in [3, 12]
    chosen = solve_case(case, "geometry", "mass")
    problem = problem_for(GEOMETRY, "mass")
    best = min(
        (problem.solve(replace(case.with_values(weight_count=z), free=("flank_angle",))) for z in range(3, 13)),
        key=lambda s: s.objective if s.status == "optimal" else math.inf,
    )
    assert chosen.status == "optimal"
    assert chosen.design["weight_count"] == best.design["weight_count"]
    assert chosen.objective == pytest.approx(best.objective, rel=1e-6)


def test_elasticity_of_the_bending_allowable_is_the_finger_share():
    # paper mode: total = z (m_r + rho pi/4 d^2 h); d ~ sigma^(-1/3), so d ln total / d ln sigma = -2/3 * finger share
    case = load_case(CASES / "wedge_paper.toml")
    solution = solve_case(case, "paper", "mass")
    p = case.params()
    h_n = (p.flank_inner_radius * (1 + p.radius_ratio)) / 2
    finger = p.density * math.pi / 4 * solution.design["finger_diameter"] ** 2 * h_n * p.weight_count
    bending = next(c for c in solution.constraints if c.name == "finger_bending")
    assert bending.elasticity == pytest.approx(-2 / 3 * finger / solution.objective, rel=1e-5)
    torque = next(c for c in solution.constraints if c.name == "torque")
    # mass and finger mass^(2/3)... d ~ T^(1/3): d ln total / d ln T = (weights + 2/3 fingers) / total
    assert torque.elasticity == pytest.approx((solution.objective - finger / 3) / solution.objective, rel=1e-5)


def test_impossible_pressure_is_diagnosed_not_optimised():
    case = load_case(CASES / "wedge_paper.toml").with_values(allowable_pressure=0.1e6)  # closed form needs 0.347 MPa
    solution = solve_case(case, "paper", "mass")
    assert solution.status == "infeasible"  # proven: interval branch and bound
    assert "flank_pressure" in solution.diagnosis and "torque" in solution.diagnosis


def test_too_small_housing_is_diagnosed_in_geometry_mode():
    case = load_case(CASES / "wedge_fan.toml").with_values(outer_diameter_max=0.16)
    solution = solve_case(case, "geometry", "mass")
    assert solution.status == "infeasible"  # proven: no geometry fits a 160 mm housing, whatever the torque
    assert "outer_diameter" in solution.diagnosis and "sectors_fit" in solution.diagnosis


def test_one_built_problem_serves_many_cases():
    problem = problem_for(PAPER, "mass")
    base = load_case(CASES / "wedge_paper.toml")
    for factor in (0.01, 0.1, 1.0, 10.0):  # inertia over three decades (50x pressure would exceed [p])
        case = base.with_values(inertia=0.5 * factor)
        solution = problem.solve(case)
        assert solution.status == "optimal"
        assert solution.design["weight_mass"] == pytest.approx(closed_form_weight_mass(case.params()), rel=1e-6)
    assert problem_for(PAPER, "mass") is problem
