"""A start-up sweep's continuation (clutchopt.optimise.sweep.continued) starts each step warm from the step before's
optimum where that is an optimum of the problem (clutchopt.optimise.start_up_sweep.started_warm: its multipliers,
collocation states, mesh and moved limits, as a sweep's point starts from the point before's), else from the design
alone (a stored design, the optimum of a loop's doubled problem), as every step did: each step then ran the whole
accuracy loop from the first mesh (wedge_motor_start from 0.4 to 0.6 kg m^2: 4 solver calls, 41 IPOPT iterations;
ball_motor_start from 300 to 370 kg m^2: 20 calls, 697 iterations; warm 3, 14 and 8, 111), to the same design."""

from dataclasses import replace

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise.problem import Problem, case_problem, problems_set_aside
from clutchopt.optimise.solution import Solution
from clutchopt.optimise.start_up_sweep import of_this_problem
from clutchopt.optimise.sweep import StoredDesign, continued
from conftest import CASES
from test_hostile_agree import START_UP_RTOL


def _followed(monkeypatch, feasible_design, at: float):
    """wedge_motor_start followed from 0.4 kg m^2 (``feasible_design``: its optimum there -> what the continuation
    starts from) to ``at``: the continuation, the start-up problem's ``refined`` calls (the case's driven inertia, the
    warm start given, ``cold``) and its NLP runs (``Problem._solve``)."""
    case = load_case(CASES / "wedge_motor_start.toml")
    calls, runs, refined, solve = [], [], Problem.refined, Problem._solve

    def spied_refined(self, at_case, *args, **kwargs):
        if self.start_up is not None:
            calls.append((at_case.values["driven_inertia"], kwargs.get("warm"), kwargs.get("cold", True)))
        return refined(self, at_case, *args, **kwargs)

    def spied_solve(self, at_case, *args, **kwargs):
        solved = solve(self, at_case, *args, **kwargs)
        if self.start_up is not None:
            runs.append(solved.solver.solves)
        return solved

    with problems_set_aside():
        problem = case_problem(case)
        first = problem.solve(case.with_values(driven_inertia=0.4))
        assert first.status == "optimal" and of_this_problem(problem, first)
        monkeypatch.setattr(Problem, "refined", spied_refined)
        monkeypatch.setattr(Problem, "_solve", spied_solve)
        with problem.failed_starts.along_a_run():
            found = continued(problem, case, ({"driven_inertia": 0.4}, feasible_design(first)), {"driven_inertia": at})
        monkeypatch.undo()
        alone = problem.solve(case.with_values(driven_inertia=at))
    return found, calls, runs, alone


def test_a_continuation_from_an_optimum_of_the_problem_steps_warm_to_solve_s_design(monkeypatch):
    found, calls, runs, alone = _followed(monkeypatch, lambda first: first, 0.6)
    assert [at for at, _, _ in calls] == pytest.approx([0.4 + 0.2 * step / 3 for step in (1, 2, 3)], rel=1e-12)
    assert all(isinstance(warm, Solution) and not cold for _, warm, cold in calls)  # was: from the design alone,
    # cold, each step's loop from the first mesh
    assert calls[1][1] is not calls[0][1] and calls[2][1] is not calls[1][1]  # (each from the step before's)
    assert found.status == alone.status == "optimal"
    assert found.objective == pytest.approx(alone.objective, rel=START_UP_RTOL)  # (0.8834722 kg)
    assert found.solver.solves == sum(runs)  # every NLP run counted


def test_a_continuation_from_a_stored_design_takes_its_first_step_from_the_design_alone(monkeypatch):
    found, calls, runs, alone = _followed(monkeypatch, lambda first: StoredDesign(first.design), 0.45)
    assert len(calls) == 3 and calls[0][1:] == (None, True)  # the first step from the design alone, cold
    assert all(isinstance(warm, Solution) and not cold for _, warm, cold in calls[1:])  # then from its optimum
    assert found.status == "optimal"
    assert found.objective == pytest.approx(alone.objective, rel=START_UP_RTOL)
    assert found.solver.solves == sum(runs)


def test_an_optimum_of_the_loop_s_doubled_problem_does_not_start_a_warm_step():
    case = load_case(CASES / "wedge_motor_start.toml")
    problem = case_problem(case)
    first = problem.solve(case)
    size = problem.posed.start_up.size
    assert of_this_problem(problem, first)
    assert not of_this_problem(problem, replace(first, internal=np.zeros(2 * size)))  # (its intervals doubled)
    assert not of_this_problem(problem, replace(first, status="not_found"))
    assert not of_this_problem(problem, StoredDesign(first.design))
