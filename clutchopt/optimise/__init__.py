"""Turning formulations into solved problems: CasADi/IPOPT first, comparisons beside the papers."""

from clutchopt.optimise.problem import Problem, Solution, SolverOptions, problem_for, solve_case

__all__ = ["Problem", "Solution", "SolverOptions", "problem_for", "solve_case"]
