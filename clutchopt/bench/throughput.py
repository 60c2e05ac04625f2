"""Throughput: one built CasADi problem re-solved, warm-started, over a sweep of one case quantity.

The sweep runs the first non-integer quantity of the case's first section (the duty: inertia, torque or power)
from 0.5x to 2x its value. Serial: one process, each point warm-started from the previous optimum (and, for
comparison, each from the case's own start: "cold starts"). Pool: warm, the sweep cut into contiguous chunks,
one per worker process, each worker building its own problem (counted). Per row: solver calls per point (IPOPT
and SQP, integer neighbours included), the share of the wall time spent inside them (the rest: case data, scaling,
float64 checks, sensitivities, bookkeeping) and, for serial sweeps, points/s against the wedge paper mode's.
"""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.cases import Case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.problem import Problem, SolverOptions


def sweep_quantity(case: Case) -> str:
    quantities = [q for q in get_coupling(case.coupling).quantities if not q.integer and q.name in case.values]
    return next(q.name for q in quantities if q.section == quantities[0].section)


def warm_sweep(case: Case, name: str, values, warm: bool = True, options: SolverOptions = SolverOptions(),
               mode: str | None = None) -> dict:
    """Solve the case at each value of ``name`` in turn, warm-started from the previous optimum unless ``warm`` is
    false (each point from the case's own start): points, optimal, solver calls, seconds inside them."""
    problem = Problem(get_coupling(case.coupling).formulation(mode or reference_mode(case.coupling)), "mass", options)
    previous, tally = None, {"points": len(values), "optimal": 0, "solves": 0, "solver_s": 0.0}
    for value in values:
        solution = problem.solve(case.with_values(**{name: float(value)}), warm=previous if warm else None)
        tally["optimal"] += solution.status == "optimal"
        tally["solves"] += solution.solver.solves
        tally["solver_s"] += solution.solver.time_s
        previous = solution if solution.status == "optimal" else None
    return tally


def _merged(tallies: list[dict]) -> dict:
    return {key: sum(t[key] for t in tallies) for key in tallies[0]}


def throughput_rows(config) -> list[dict]:
    rows = []
    for case in bench_cases():
        name = sweep_quantity(case)
        values = case.values[name] * np.geomspace(0.5, 2.0, config.sweep_points)
        Problem(get_coupling(case.coupling).formulation(reference_mode(case.coupling))).solve(case)  # warm-up
        for how, warm in (("serial", True), ("serial, cold starts", False)):
            started = time.perf_counter()
            tally = warm_sweep(case, name, values, warm)
            rows.append(_row(case, name, how, 1, tally, time.perf_counter() - started))
        chunks = np.array_split(values, config.processes)
        started = time.perf_counter()
        with ProcessPoolExecutor(config.processes) as pool:
            tally = _merged(list(pool.map(warm_sweep, [case] * len(chunks), [name] * len(chunks), chunks)))
        rows.append(_row(case, name, "process pool", config.processes, tally, time.perf_counter() - started))
    wedge = next((r for r in rows if (r["coupling"], r["how"]) == ("wedge", "serial")), None)
    for row in rows:
        row["vs_wedge_paper"] = row["points_per_s"] / wedge["points_per_s"] if wedge and row["processes"] == 1 else None
    return rows


def _row(case, name, how, processes, tally, seconds):
    return {"coupling": case.coupling, "mode": reference_mode(case.coupling), "swept": f"{name} x0.5..2",
            "how": how, "processes": processes, "points": tally["points"], "optimal": tally["optimal"],
            "solves_per_point": tally["solves"] / tally["points"], "wall_s": seconds,
            "points_per_s": tally["points"] / seconds,
            "solver_share": tally["solver_s"] / seconds if processes == 1 else None}
