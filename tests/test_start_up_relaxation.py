"""What a start-up problem's relaxation at fixed integers is (issue 26, the cut "static optimum first"), pinned
before any solve relies on it (docs/start_up.md, "The start-up's relaxation at fixed integers").

The start-up problem at fixed integers n is: minimise m(x) over the design x (and the collocated states z) subject to
the start-up formulation's own rows g_s(x) <= 0 (``with_start_up``: the coupling's rows WITHOUT the papers'
constant-acceleration torque row), the start-up's limits h(x, z) <= 0 and the collocation c(x, z) = 0. Dropping h
and c leaves min m(x) s.t. g_s(x) <= 0: a relaxation (same objective, a superset of the feasible designs), so its
optimum m_R <= the start-up optimum m_S; and a relaxation optimum whose start meets every start-up limit is
feasible for the start-up problem, hence m_S <= m_R: it IS the start-up optimum at n. The relaxation is the
start-up formulation posed without its start-up, NOT the papers' sizing (``Problem.static_problem``): the sizing
keeps the constant-acceleration ``torque`` row, which the wedge's and the lever's start-up drops (their sizing is no
relaxation: it may be heavier than their start-up optimum), and it lacks the spring preload, a design variable the
wedge's and the lever's cases free and no static row holds (their relaxation leaves it undetermined).
"""

import math
from dataclasses import replace

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise.problem import Problem, case_problem
from tests.conftest import CASES


def relaxation(problem: Problem) -> Problem:
    """The start-up formulation's own rows posed without the start-up (IPOPT's optimum, unpolished as the NLP's)."""
    return Problem(problem.posed.formulation, problem.objective.name, replace(problem.options, polish=False), None)


@pytest.mark.parametrize("name, dropped", [("wedge", {"torque"}), ("lever", {"torque"}), ("ball", set()),
                                           ("cable", set())])
def test_the_sizing_is_a_relaxation_only_without_a_constant_acceleration_row(name, dropped):
    """The papers' sizing's rows against the start-up's own static rows: the wedge's and the lever's sizing carry the
    constant-acceleration torque row (weight_set.py, toggles.py: ``constant_acceleration=True``) the start-up drops;
    the ball's and the cable's are the same rows. Every start-up adds the spring preload."""
    problem = case_problem(load_case(CASES / f"{name}_motor_start.toml"))
    sizing = problem.static_problem.posed
    own = problem.posed.row_names[:problem.posed.n_checked]
    assert set(sizing.row_names) - set(own) == dropped
    assert set(own) <= set(sizing.row_names)
    assert [n for n in problem.posed.names if n not in sizing.names] == ["spring_preload"]


def test_the_cables_start_up_design_is_its_relaxations_optimum():
    """cable_motor_start: the solve keeps 8 cables, 3.95257 kg (docs/start_up.md, cablestart's profile), its
    simulated start meeting every limit with no start-up row active. The relaxation at 8 cables (the spring preload
    fixed by the case) then has the same optimum (the argument above): m_R <= m_S to IPOPT's tolerance, and every
    design variable the same to 1e-9 relative (measured 1.4e-13)."""
    case = load_case(CASES / "cable_motor_start.toml")
    problem = case_problem(case)
    solved = problem.solve(case)
    assert solved.status == "optimal" and solved.design["cable_count"] == 8.0
    assert solved.objective == pytest.approx(3.9525729, rel=1e-7)
    started = solved.constraints[problem.posed.n_checked:]
    assert started and all(c.feasible and not c.active for c in started)
    fixed = replace(case, bounds={**case.bounds, "cable_count": (8.0, 8.0)})
    relaxed = relaxation(problem).solve(fixed, start=solved.design)
    assert relaxed.status == "optimal"
    assert relaxed.objective <= solved.objective * (1 + 1e-9)
    for name, value in solved.design.items():
        assert math.isclose(relaxed.design[name], value, rel_tol=1e-9, abs_tol=1e-12), name
