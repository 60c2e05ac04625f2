"""``options.choose`` ranked by solving: every variant of a case the material library makes, solved."""

from __future__ import annotations

from clutchopt.formulations import get_coupling
from clutchopt.materials import variants
from clutchopt.optimise.problem import SolverOptions, solve_case


def solve_choices(case, mode: str | None = None, objective: str | None = None, options=None) -> list[tuple]:
    """Solve every variant of ``options.choose``: [(choice, case, solution)], optimal ones first by objective,
    then the others in the order listed. Without ``options.choose``: the case alone."""
    options = options or SolverOptions()
    solved = [(choice, variant, solve_case(variant, mode, objective, options))
              for choice, variant in variants(case, get_coupling(case.coupling))]
    return sorted(solved, key=lambda item: (item[2].status != "optimal",
                                            item[2].objective if item[2].status == "optimal" else 0.0))
