"""Design-review report: one self-contained HTML page (inline CSS, inline SVG figures, no scripts, no links out),
written from Jinja2 templates (templates/), and the same page as PDF (pdf.py).

At the top what was verified (verification.py); then the requirements, the optimal design with a dimensioned
sketch, constraint margins, sensitivities, the comparison with the paper's method, the start-up simulation, the
scatter where the case has one, and a sweep plot when a sweep table is given (sections.py).
"""

from __future__ import annotations

from datetime import datetime, timezone

import pandas as pd

from clutchopt.cases import Case
from clutchopt.optimise.problem import case_formulation
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.report.page import Section, render
from clutchopt.report.sections import (
    comparison,
    design,
    drawing,
    margins,
    requirements,
    designed,
    design_title,
    scatter,
    scattered_designs,
    sensitivities,
    simulation,
    sweep_plot,
)
from clutchopt.report.verification import robust_label, verification
from clutchopt.store import versions

__all__ = ["build_report", "sweep_plot"]


def build_report(case: Case, solution: Solution, sweep: pd.DataFrame | None = None, robust=None,
                 notes: tuple[str, ...] = (), options: SolverOptions = SolverOptions()) -> str:
    """The HTML page for a case and its solution (and a sweep table, if given); with ``robust`` (a
    :class:`~clutchopt.optimise.robust.RobustResult`) the solution is its robust design, the nominal one beside it
    under Scatter; ``notes``: lines of the command's own to show under the headline (the choice it made);
    ``options``: what the solution was solved with, and the page's other designs are (its comparison, its scatter's
    designs in the solution's mode and objective)."""
    formulation = case_formulation(case, solution.mode)
    designs = scattered_designs(case, solution, options, robust) if case.scatter else None
    scattered = scatter(case, designs, robust) if case.scatter else None
    nominal_failure = scattered[1] if scattered is not None and robust is None and designed(solution) else None
    sections = [
        Section("Requirements", "requirements", requirements(case)),
        Section(design_title(solution, robust), "design", design(solution, formulation)),
        Section("Dimensioned sketch", "sketch", drawing(case, solution, formulation)),
        Section("Constraint margins", "margins", margins(case, solution, robust)),
        Section("Sensitivities", "sensitivities", sensitivities(solution, formulation)),
        Section("Comparison with the paper's method", "comparison",
                comparison(case, solution, options, robust, designs)),
        Section("Start-up simulation", "simulation", simulation(case, solution, robust)),
    ]
    if scattered is not None:
        sections.append(Section("Scatter", "scatter", scattered[0]))
    if sweep is not None:
        sections.append(Section("Sweep", "sweep", [sweep_plot(sweep)]))
    return render(
        "review.html.j2", title=case.title or case.path, formulation=formulation.title, case_path=case.path,
        kind=f"Robust design ({robust_label(robust)})" if robust is not None else "Design", ok=solution.status == "optimal",
        status=solution.status, objective_name=solution.objective_name,
        objective=f"{solution.objective:.6g} {solution.objective_unit}" if designed(solution) else
        "none (no design: the solver's last point is shown)", notes=notes,
        nominal=(f"{nominal_failure[0]} fails with probability {nominal_failure[1]:.3g} under the scatter"
                 + (" (its constraints; its start-up limits not sampled: clutchopt solve --robust samples a robust "
                    "design's)" if case.start_up is not None else "") if nominal_failure is not None else None),
        diagnosis=solution.diagnosis, generated=f"{datetime.now(timezone.utc):%Y-%m-%d %H:%M}",
        versions=", ".join(f"{k} {v}" for k, v in versions().items()),
        checks=verification(case, solution, robust, nominal_failure), sections=sections)  # (no design: none quoted)
