"""Lever coupling NLP: paper mode equals the closed form; design mode feasible, integer, no heavier; diagnoses."""

import math
from dataclasses import replace

import pytest

from clutchopt.cases import load_case
from clutchopt.formulations.duty import required_torque
from clutchopt.formulations.lever.closed_forms import closed_form_characteristic_number, closed_form_link_diameter
from clutchopt.formulations.lever.modes import DESIGN, PAPER
from clutchopt.formulations.lever.paper import paper_characteristic_number, paper_geometry, paper_k
from clutchopt.optimise import problem_for, solve_case
from tests.conftest import CASES

LEVER_CASES = ["lever_centrifuge.toml", "lever_homogeniser.toml", "lever_wedge_duty.toml"]


@pytest.fixture(scope="module", params=LEVER_CASES)
def case(request):
    return load_case(CASES / request.param)


def test_paper_mode_optimum_is_the_closed_form(case):
    solution = solve_case(case, "paper", "mass")
    p = case.params()
    mass = closed_form_characteristic_number(p) / p.weight_count
    assert solution.status == "optimal"
    assert solution.design["weight_mass"] == pytest.approx(mass, rel=1e-6)
    assert solution.design["link_diameter"] == pytest.approx(closed_form_link_diameter(p, mass), rel=1e-6)
    assert {c.name for c in solution.constraints if c.active} == {"torque", "link_buckling"}


def test_one_friction_surface_reproduces_the_printed_formula():
    # one face doubles m z and the worn-lining pressure (0.123 -> 0.246 MPa, still within 0.25 MPa)
    case = load_case(CASES / "lever_wedge_duty.toml").with_values(friction_surfaces=1)
    p = case.params()
    printed = paper_characteristic_number(
        required_torque(p.inertia, p.speed, p.acceleration_time, p.resisting_torque), p.friction_coefficient,
        p.speed, p.engagement_angle, paper_geometry(p)[0],
        paper_k(p.shaft_diameter, p.flange_diameter, p.spring_free_length))
    solution = solve_case(case, "paper", "mass")
    assert solution.status == "optimal"
    assert solution.outputs["characteristic_number"].value == pytest.approx(printed, rel=1e-6)


def test_cost_objective_gives_the_same_paper_design(case):
    # paper mode fixes the geometry: cost = price * (weights + links) + constants, the same optimum
    mass, cost = solve_case(case, "paper", "mass"), solve_case(case, "paper", "cost")
    assert cost.status == "optimal"
    assert cost.design["weight_mass"] == pytest.approx(mass.design["weight_mass"], rel=1e-6)
    assert cost.design["link_diameter"] == pytest.approx(mass.design["link_diameter"], rel=1e-6)


def test_design_mode_is_feasible_and_no_heavier_than_paper_mode(case):
    # each case's paper design lies inside its design-mode box, so design mode can only do better
    paper, design = solve_case(case, "paper", "mass"), solve_case(case, "design", "mass")
    assert design.status == "optimal"
    assert all(c.margin >= -1e-8 for c in design.constraints)
    assert design.objective <= paper.objective * (1 + 1e-9)
    assert design.outputs["torque"].value >= design.outputs["required_torque"].value * (1 - 1e-8)
    assert float(design.design["weight_count"]).is_integer()
    assert math.radians(1.5) * (1 - 1e-8) <= design.design["limit_angle"] <= math.radians(3) * (1 + 1e-8)
    assert design.design["engagement_angle"] <= math.radians(15) * (1 + 1e-8)


def test_integer_weight_count_is_the_best_of_all_counts():
    case = load_case(CASES / "lever_homogeniser.toml")  # z in [4, 8]
    chosen = solve_case(case, "design", "cost")
    problem = problem_for(DESIGN, "cost")
    fixed = [problem.solve(replace(case, bounds={**case.bounds, "weight_count": (z, z)})) for z in range(4, 9)]
    best = min(fixed, key=lambda s: s.objective if s.status == "optimal" else math.inf)
    assert chosen.status == "optimal"
    assert chosen.design["weight_count"] == best.design["weight_count"]
    assert chosen.objective == pytest.approx(best.objective, rel=1e-6)


def test_impossible_lining_pressure_is_diagnosed_in_paper_mode():
    # the paper design of the centrifuge presses its worn linings at 0.186 MPa
    case = load_case(CASES / "lever_centrifuge.toml").with_values(allowable_pressure=0.1e6)
    solution = solve_case(case, "paper", "mass")
    assert solution.status == "infeasible"  # proven: interval branch and bound
    assert "lining_pressure" in solution.diagnosis and "torque" in solution.diagnosis


def test_too_small_housing_is_proven_infeasible_in_design_mode():
    case = load_case(CASES / "lever_centrifuge.toml").with_values(outer_diameter_max=0.15)
    solution = solve_case(case, "design", "mass")
    assert solution.status == "infeasible"  # proven: no lever geometry fits a 150 mm housing, whatever the torque
    assert "outer_diameter" in solution.diagnosis and "toggle_span" in solution.diagnosis


def test_one_built_problem_serves_many_cases():
    problem = problem_for(PAPER, "mass")
    base = load_case(CASES / "lever_wedge_duty.toml")
    for factor in (0.01, 0.1, 1.0, 1.5):  # the inertia term of T_max over two decades
        case = base.with_values(inertia=0.5 * factor)
        solution = problem.solve(case)
        p = case.params()
        assert solution.status == "optimal"
        assert solution.design["weight_mass"] == pytest.approx(
            closed_form_characteristic_number(p) / p.weight_count, rel=1e-6)
