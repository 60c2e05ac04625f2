"""A static cold solve's rounded integers solved by SQP from the relaxation's optimum (integers.FROM_THE_RELAXATION),
IPOPT from cold only where that fails: at the case files, the same design as IPOPT from cold alone, in fewer iterations
(where a fixed-integer NLP has two local optima each path may end at either: docs/tradeoffs.md)."""

import math

import pytest

import clutchopt.optimise.integers as integers
from clutchopt.cases import load_case
from clutchopt.optimise.problem import case_problem
from conftest import CASES

FREE_INTEGERS = [("wedge_centrifuge.toml", "geometry", "weight_count"),
                 ("lever_centrifuge.toml", "design", "weight_count"),
                 ("cable_pump.toml", "paper", "cable_count"),
                 ("ball_crusher.toml", "design", "ball_rows")]


def _ipopt_alone(monkeypatch):
    """``nearest_integers`` as before: the rounded integers by IPOPT from cold."""
    nearest = integers.nearest_integers
    monkeypatch.setattr("clutchopt.optimise.problem.nearest_integers",
                        lambda *args: nearest(*args[:6], ("ipopt",)))


@pytest.mark.parametrize("case_file, mode, integer", FREE_INTEGERS)
def test_rounded_integers_by_sqp_land_on_ipopt_s_optimum_at_each_coupling_s_case(monkeypatch, case_file, mode,
                                                                                 integer):
    case = load_case(CASES / case_file)
    problem = case_problem(case, mode)
    free = problem.posed.free_integers(problem.posed.scaled_data(case, None))
    assert integer in [problem.posed.names[i] for i in free]  # (a search to make: the integer free)
    by_sqp = problem.solve(case)
    _ipopt_alone(monkeypatch)
    by_ipopt = problem.solve(case)
    assert by_sqp.status == by_ipopt.status == "optimal"
    assert by_sqp.design[integer] == by_ipopt.design[integer]
    assert math.isclose(by_sqp.objective, by_ipopt.objective, rel_tol=1e-9)
    assert by_sqp.solver.name == "sqpmethod" and by_ipopt.solver.name == "ipopt"  # (the kept run's solver)
    assert by_sqp.solver.solves == by_ipopt.solver.solves  # (one run a fixed-integer NLP, either way)
    assert by_sqp.solver.iterations < by_ipopt.solver.iterations


def test_a_start_up_keeps_ipopt_from_cold_for_its_rounded_integers(monkeypatch):
    # its fixed-integer NLPs have several local optima (docs/start_up.md): the relaxation's rounded integers by IPOPT,
    # from cold, as before
    seen = []
    nearest = integers.nearest_integers
    monkeypatch.setattr("clutchopt.optimise.problem.nearest_integers",
                        lambda *args: seen.append(args[6]) or nearest(*args))
    case = load_case(CASES / "cable_motor_start.toml")
    case_problem(case).solve(case)
    assert seen and set(seen) == {("ipopt",)}
