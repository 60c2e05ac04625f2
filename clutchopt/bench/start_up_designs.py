"""What the accuracy of the start time costs: the start-up cases solved at fixed collocation intervals, on the
first (graded) mesh and on meshes adapted to the simulated start, against the independent simulator; and the
default adaptive solve (mesh adaptation, then doubling, until the case's tolerance). What a start-up solve costs
against its static one (issue 26: at most 10x): reading the case, the first solve in a process (its problems built)
and the re-solve of the same case, beside the same case without its [start_up] section."""

from __future__ import annotations

import time
from dataclasses import replace
from pathlib import Path

from clutchopt.bench.timing import repeated, time_once
from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.problem import case_problem, problem_for, problems_set_aside, solve_case
from clutchopt.optimise.solution import SolverOptions
from clutchopt.start_up.drive import Structure
from clutchopt.start_up.mesh import MESH_STEPS

CASES = Path(__file__).resolve().parents[2] / "cases"


def _row(case, label: str, intervals, mesh: str, solution, seconds: float) -> dict:
    start = solution.start_up or {}
    return {"case": label, "intervals": intervals, "mesh": mesh, "status": solution.status,
            "objective": solution.objective, "start_time_s": start.get("start_time"),
            "start_time_rel_error": abs(start["discretisation_error"]["start_time"]) if start else None,
            "solves": solution.solver.solves, "time_s": seconds}


def start_up_design_rows(config) -> list[dict]:
    """One row per case, interval count (``config.start_up_intervals``) and mesh (first, then each adaptation),
    and the default solve; the time of a solve includes its re-simulation. The error is the NLP's start time
    against the simulated one."""
    rows = []
    for path in sorted(CASES.glob("*_motor_start.toml")):
        case = load_case(path)
        if Structure.of(case).elastic:  # its NLP is quasi-static against a dynamic simulation: the difference is
            continue                    # the model's, not the mesh's (tests/test_cable_start_up.py checks it)
        formulation = get_coupling(case.coupling).formulation(case.options.get("mode"))
        objective = case.options.get("objective", "mass")
        start = problem_for(formulation, objective).solve(case).design
        for count in config.start_up_intervals:
            problem = problem_for(formulation, objective, SolverOptions(), replace(Structure.of(case), intervals=count))
            started = time.perf_counter()
            solution = problem.solve(case, start, refine=False)
            rows.append(_row(case, path.stem, count, "graded", solution, time.perf_counter() - started))
            for step in range(1, MESH_STEPS + 1):
                if solution.mesh is None:
                    break
                started = time.perf_counter()
                solution = problem.solve(case, warm=solution, mesh=solution.mesh[1], refine=False)
                rows.append(_row(case, path.stem, count, f"adapted x{step}", solution, time.perf_counter() - started))
        started = time.perf_counter()
        solution = solve_case(case)
        rows.append(_row(case, path.stem, solution.start_up["intervals"] if solution.start_up else None,
                         "default (adaptive)", solution, time.perf_counter() - started))
    return rows


def start_up_solve_rows(config) -> list[dict]:
    """Per start-up case: the seconds to read it, to solve it first (its problems built, as in a new process: the
    start-up's and its sizing's, the static case's for the static solve, whatever the sections before built; the
    simulator's modules loaded in the first case) and again (the median of ``config.repeats``, at least 3), the same
    of the case without its [start_up] section, and the ratios; the simulated start time against the case's limit;
    ``compiled_used``: whether its start-up problem's IPOPT solvers evaluate its NLP's compiled functions (a library
    the cache links to the NLP, a sweep's: :mod:`clutchopt.optimise.start_up_compiled`; the same numbers)."""
    rows = []
    for path in sorted(CASES.glob("*_motor_start.toml")):
        read, case = time_once(lambda: load_case(path))
        static = replace(case, start_up=None)
        with problems_set_aside():
            first, solution = time_once(lambda: solve_case(case))
        again = repeated(lambda: solve_case(case), max(3, config.repeats))["median_s"]
        with problems_set_aside():
            static_first = time_once(lambda: solve_case(static))[0]
        static_again = repeated(lambda: solve_case(static), config.repeats)["median_s"]
        start = solution.start_up or {}
        rows.append({"case": path.stem, "status": solution.status, "objective": solution.objective,
                     "load_s": read, "first_s": first, "resolve_median_s": again, "static_first_s": static_first,
                     "static_median_s": static_again, "first_vs_static": first / static_first,
                     "resolve_vs_static": again / static_again, "solves": solution.solver.solves,
                     "start_time_s": start.get("start_time_simulated"),
                     "compiled_used": case_problem(case).posed.library is not None})
    return rows
