"""Turning formulations into solved problems: CasADi/IPOPT first, comparisons beside the papers."""

from clutchopt.optimise.posed import ScaledData
from clutchopt.optimise.problem import Problem, problem_for, solve_case
from clutchopt.optimise.solution import Solution, SolverOptions

__all__ = ["Problem", "ScaledData", "Solution", "SolverOptions", "problem_for", "solve_case"]
