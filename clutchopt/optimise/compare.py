"""A coupling's published method beside its NLP optima: one row per quantity, one column per method."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from clutchopt.cases import Case, check_across
from clutchopt.errors import InputError
from clutchopt.formulations import get_coupling
from clutchopt.model import ComparisonRow
from clutchopt.optimise.problem import case_problem, problem_for
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.records import DESIGN_STATUSES
from clutchopt.records import target_text
from clutchopt.units import si_unit


@dataclass
class ComparisonTable:
    coupling: str
    columns: list[str]
    baseline: str
    rows: list[dict]  # {"quantity", "unit" (SI), "display_unit", "description", <column>: SI value (in ``unit``),
    # "relative": {<column>: its relative difference against the baseline, unitless}} (no ``unit`` beside those)
    notes: dict[str, str]
    solutions: dict[str, Solution]

    def _repr_html_(self) -> str:
        """Jupyter shows the comparison as the tables of ``clutchopt compare``."""
        from clutchopt.output import comparison_html

        return comparison_html(self.as_dict())

    def as_dict(self) -> dict:
        return {
            "coupling": self.coupling,
            "columns": self.columns,
            "baseline": self.baseline,
            "rows": self.rows,
            "column_notes": self.notes,
            "solves": {column: {"status": s.status, "diagnosis": s.diagnosis, "objective": s.objective,
                                "solver": vars(s.solver)} for column, s in self.solutions.items()},
        }


def relative_difference(value: float | None, reference: float | None) -> float | None:
    if value is None or reference is None or not math.isfinite(value) or not math.isfinite(reference) or reference == 0:
        return None
    return (value - reference) / abs(reference)


def compare_case(case: Case, options: SolverOptions = SolverOptions(), robust=None, solved: list | None = None,
                 mode: str | None = None, objective: str | None = None) -> ComparisonTable:
    """The paper's method, the closed forms and the NLP optima of each mode side by side; with a [start_up], the
    case's mode sized as the papers size and with its start-up; with a [scatter], the nominal design beside the
    worst-case and chance designs, or beside the one of ``robust`` (a
    :class:`~clutchopt.optimise.design.Robustness`); ``solved``: those designs made already (their
    :class:`~clutchopt.optimise.robust.RobustResult`, in that order: a review page's), shown as they are; ``mode``,
    ``objective``: those of the start-up's and the scatter's designs (default: the case's; a review page's own)."""
    # (review 29: a page's start-up columns had been the case's paper-mode designs beside a geometry-mode page)
    coupling = get_coupling(case.coupling)
    spec = coupling.comparison
    if spec is None:
        raise InputError("coupling", f"{coupling.name} has no comparison with a paper method")
    check_across(case)  # (as solve_case: a case moved by with_values is checked as a case file is)
    own = (coupling.formulation(case.mode_of(mode)).mode, case.objective_of(objective))  # the case's own columns'

    params = case.params()
    with np.errstate(invalid="ignore", divide="ignore"):  # a closed form undefined at this duty reads as NaN ("-")
        columns = {name: dict(values) for name, values in spec.references(params).items()}
    solutions, notes = {}, dict(spec.column_notes)
    for column, mode, objective in spec.solves:
        missing = case.missing_for(objective)
        if missing:  # a ball case without prices: compared by mass only
            columns[column] = {}
            notes[column] = (f"not solved: the {objective} objective needs "
                             f"{', '.join(q.key for q in missing)}, which the case does not give")
            continue
        solution = problem_for(coupling.formulation(mode), objective, options).solve(case)
        solutions[column] = solution
        columns[column] = _design_rows(spec, mode, solution, params)
        if case.start_up is not None:  # a static optimum on a start-up case: started on its drive, as
            columns[column].update(_started(case, mode, solution))  # constant_acceleration is
            notes[column] = f"{notes.get(column, column)}; {STATIC_NOTE}"
    rows_shown = spec.rows
    if case.start_up is not None:
        start_columns = _start_up_columns(case, coupling, spec, options, *own)
        for column, (solution, values) in start_columns.items():
            solutions[column] = solution
            columns[column] = values
        rows_shown = spec.rows + START_UP_ROWS
        notes.update({column: note.format(*own) for column, note in START_UP_NOTES.items()})
    if case.scatter:
        for column, (solution, values) in _scatter_columns(case, coupling, spec, options, own, robust, solved).items():
            solutions[column] = solution
            columns[column] = values
        rows_shown = rows_shown + SCATTER_ROWS
        notes.update({column: note for column, note in SCATTER_NOTES.items() if column in columns})
        nominal = solutions["nominal"]
        notes["nominal"] = f"the {nominal.mode} mode optimised for {nominal.objective_name} at the nominal values"
        if robust is not None and robust.target is not None:
            notes[_column(robust)] = robust_note(robust, case.start_up is not None)
    names = list(columns)
    rows = []
    for row in rows_shown:
        # (a row without a unit is a count, a ratio, a margin or a probability: "", not a case's dimensionless "1")
        entry = {"quantity": row.name, "unit": si_unit(row.unit) if row.unit else "", "display_unit": row.unit,
                 "description": row.description}
        for name in names:
            value = columns[name].get(row.name)
            entry[name] = None if value is None or not math.isfinite(value) else float(value)
        entry["relative"] = {name: relative_difference(entry[name], entry.get(spec.baseline))
                             for name in names if name != spec.baseline}
        rows.append(entry)
    return ComparisonTable(coupling.name, names, spec.baseline, rows, notes, solutions)


START_UP_ROWS = (
    ComparisonRow("start_time_simulated", "s", "switch-on to lock-up on the case's drive, simulated"),
    ComparisonRow("friction_work_simulated", "kJ", "heat released by slip in that start, simulated"),
    ComparisonRow("temperature_rise_simulated", "K", "largest temperature rise in that start, simulated"),
    ComparisonRow("link_stress_simulated", "MPa", "largest stress of an elastic link (cables) in that start, "
                                                  "simulated"),
)
STATIC_NOTE = "the case's [start_up] not in it; started on the case's drive in the rows *_simulated"
START_UP_NOTES = {  # (of a mode and an objective)
    "constant_acceleration": "the {} mode optimised for {} as the papers size (constant acceleration), started on "
                             "the case's drive",
    "nlp_start_up": "the {} mode optimised for {} with the start-up on the case's drive inside the NLP",
}


SCATTER_ROWS = (
    ComparisonRow("worst_corner_margin", "", "smallest relative margin of any constraint over the corners of the "
                                             "[scatter] ranges"),
    ComparisonRow("failure_probability", "", "largest failure probability of any constraint, Monte Carlo over the "
                                             "[scatter] distributions"),
)
CHANCE_SHOWN = 0.999  # the chance-constrained column of compare
SCATTER_NOTES = {
    "worst_case": "every constraint at its own worst corner of the [scatter] ranges",
    f"chance_{target_text(CHANCE_SHOWN)}": f"each constraint fails with probability at most {1 - CHANCE_SHOWN:.3g}",
}


def robust_note(robust, start_up: bool) -> str:
    """What a chance design's column claims: each constraint's failure probability at most 1 - P, or the design's
    (system_chance; a start-up's limits within it, each moved one with its share: a union bound)."""
    if robust.method != "system_chance":
        return f"each constraint fails with probability at most {1 - robust.target:.3g}"
    return (f"the design fails with probability at most {1 - robust.target:.3g}"
            + ("; the start-up limits within it (each the scatter moves with its share; a union bound)"
               if start_up else ""))


def _column(robust) -> str:
    """The column of a robust design: worst_case, chance_P or system_chance_P (its method and target as given)."""
    return "worst_case" if robust.target is None else f"{robust.method}_{target_text(robust.target)}"


def _scatter_columns(case: Case, coupling, spec, options: SolverOptions, own: tuple[str, str], robust=None,
                     solved: list | None = None) -> dict:
    """The nominal and robust designs of ``own`` (mode, objective): worst-case and chance 0.999, or the method of
    ``robust`` (``solved``: those made already), each checked at every corner of the ranges and by Monte Carlo over
    the distributions."""
    from clutchopt.optimise.design import Robustness
    from clutchopt.optimise.robust import CHANCE, WORST_CASE
    from clutchopt.optimise.robust_models import corner_checks, failure_probabilities

    methods = [robust] if robust is not None else [Robustness(WORST_CASE), Robustness(CHANCE, CHANCE_SHOWN)]
    results = solved if solved is not None else [m.solve(case, *own, options) for m in methods]
    worst = results[0]
    mode = worst.nominal.mode
    params = case.params()
    columns = {}
    for column, solution in (("nominal", worst.nominal),
                             *((_column(m), result.solution) for m, result in zip(methods, results))):
        values = _design_rows(spec, mode, solution, params)
        if solution.status in DESIGN_STATUSES:
            checks = corner_checks(worst.formulation, solution.design, params, case.scatter)
            failure = failure_probabilities(worst.formulation, solution.design, params, case.scatter, methods[0].samples,
                                            correlation=case.correlation)
            values.update(worst_corner_margin=min(c.margin for c in checks),
                          failure_probability=max(p for p, _, _ in failure.values()))
        columns[column] = (solution, values)
    return columns


def _start_up_columns(case: Case, coupling, spec, options: SolverOptions, mode: str, objective: str) -> dict:
    """``mode`` and ``objective`` optimised without and with the start-up; both designs started on the case's
    drive by the simulator."""
    params = case.params()
    columns = {}
    for column, problem in (("constant_acceleration", problem_for(coupling.formulation(mode), objective, options)),
                            ("nlp_start_up", case_problem(case, mode, objective, options))):
        solution = problem.solve(case)
        values = _design_rows(spec, mode, solution, params)
        values.update(_started(case, mode, solution))
        columns[column] = (solution, values)
    return columns


def _design_rows(spec, mode: str, solution: Solution, params) -> dict:
    """The rows of a solve's design, none where it ended without one (infeasible, not_found: its last point meets
    no requirement; review 27: an infeasible column had shown a design 30 % lighter than the closed form, with a
    torque of 6.5 N*m where 10.2 are needed; its status and diagnosis are said below the table)."""
    if solution.status not in DESIGN_STATUSES:
        return {}
    outputs = {name: out.value for name, out in solution.outputs.items()}
    return spec.rows_from_design(mode, solution.design, outputs, params)


def _started(case: Case, mode: str, solution: Solution) -> dict:
    """The START_UP_ROWS of a design started on the case's drive by the simulator (none without a design)."""
    from clutchopt.start_up.simulation import run_start_up, start_up_model

    if solution.status not in DESIGN_STATUSES:
        return {}
    head = run_start_up(start_up_model(case, mode, solution.design)).headline
    return dict(start_time_simulated=head["start_time"], friction_work_simulated=head["friction_work"],
                temperature_rise_simulated=head.get("temperature_rise", math.nan),
                link_stress_simulated=head.get("peak_stress", math.nan))
