"""Turning formulations into solved problems: CasADi/IPOPT first, comparisons beside the papers."""

from clutchopt.optimise.posed import ScaledData
from clutchopt.optimise.problem import Problem, problem_for, solve_case
from clutchopt.optimise.solution import Solution, SolverOptions

__all__ = ["Problem", "ScaledData", "Solution", "SolverOptions", "choose_coupling", "problem_for", "solve_case"]


def choose_coupling(case, options: SolverOptions = SolverOptions()):
    """Every coupling designed for one neutral case (a path or its parsed TOML) and ranked by like-for-like mass:
    :func:`clutchopt.optimise.choose.choose_coupling` (docs/envelope.md)."""
    from clutchopt.optimise.choose import choose_coupling as choose

    return choose(case, options)
