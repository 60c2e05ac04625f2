"""Elasticities of the optimum from the multipliers against central finite differences of re-solves."""

import math

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.errors import InputError
from clutchopt.formulations import get_coupling
from clutchopt.optimise import problem_for, solve_case
from conftest import CASES

STEP = 1e-4


def _finite_difference(problem, case, solution, name):
    objectives = []
    for sign in (1, -1):
        perturbed = case.with_values(**{name: case.values[name] * (1 + sign * STEP)})
        result = problem.solve(perturbed, warm=solution)
        assert result.status == "optimal"
        objectives.append(result.objective)
    return (math.log(objectives[0]) - math.log(objectives[1])) / (math.log1p(STEP) - math.log1p(-STEP))


def _movable(case, name):
    """Both perturbed cases are valid (a quantity at the edge of its valid range cannot be moved both ways)."""
    try:
        for sign in (1, -1):
            case.with_values(**{name: case.values[name] * (1 + sign * STEP)})
    except InputError:
        return False
    return True


@pytest.mark.parametrize("case_file, mode", [
    ("wedge_paper.toml", "paper"), ("wedge_paper.toml", "geometry"), ("wedge_fan.toml", "geometry"),
    ("lever_centrifuge.toml", None), ("cable_pump.toml", None),
])
def test_elasticities_match_finite_differences(case_file, mode):
    case = load_case(CASES / case_file)
    solution = solve_case(case, mode)
    problem = problem_for(get_coupling(case.coupling).formulation(mode or case.options.get("mode")),
                          case.options.get("objective", "mass"))
    ranked = sorted(solution.sensitivities.items(), key=lambda item: -abs(item[1]))
    checked = [(name, value) for name, value in ranked if name in case.values and _movable(case, name)][:4]
    assert checked, "no sensitivities to check"
    for name, elasticity in checked:
        assert elasticity == pytest.approx(_finite_difference(problem, case, solution, name), rel=1e-5, abs=1e-7), name


def test_an_allowable_with_slack_has_zero_elasticity_and_a_binding_one_does_not():
    solution = solve_case(load_case(CASES / "wedge_paper.toml"), "paper")
    active = {c.name: c.active for c in solution.constraints}
    assert active["torque"] and not active["flank_pressure"]
    assert solution.sensitivities["allowable_pressure"] == pytest.approx(0.0, abs=1e-9)
    assert abs(solution.sensitivities["friction_coefficient"]) > 0.1


def test_warm_resolve_reaches_the_cold_optimum():
    case = load_case(CASES / "wedge_fan.toml")
    formulation = get_coupling("wedge").formulation("geometry")
    problem = problem_for(formulation)
    first = problem.solve(case)
    moved = case.with_values(speed=case.values["speed"] * 1.01)  # a sweep's step
    cold = problem.solve(moved)
    warm = problem.solve(moved, warm=first)
    assert warm.status == cold.status == "optimal"
    assert warm.objective == pytest.approx(cold.objective, rel=1e-9)
    # the re-solve starts from the previous optimum and its multipliers: SQP first (here its search direction
    # vanishes after 5 iterations, the KKT check refuses it), then IPOPT with a small barrier parameter (8)
    assert warm.solver.iterations < cold.solver.iterations


def test_a_failing_warm_start_falls_back_to_the_cold_solve():
    case = load_case(CASES / "wedge_fan.toml")
    problem = problem_for(get_coupling("wedge").formulation("geometry"))
    first = problem.solve(case)
    first.multipliers = tuple(np.full_like(m, 1e12) for m in first.multipliers)  # nonsense duals
    again = problem.solve(case.with_values(speed=case.values["speed"] * 1.05), warm=first)
    assert again.status == "optimal"
    assert again.objective == pytest.approx(problem.solve(case.with_values(speed=case.values["speed"] * 1.05)).objective,
                                            rel=1e-9)
