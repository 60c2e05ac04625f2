"""Turning formulations into solved problems: CasADi/IPOPT first, comparisons beside the papers."""

from clutchopt.optimise.problem import Problem, ScaledData, Solution, SolverOptions, problem_for, solve_case

__all__ = ["Problem", "ScaledData", "Solution", "SolverOptions", "problem_for", "solve_case"]
