"""Throughput: one built CasADi problem re-solved, warm-started, over a sweep of one case quantity.

The sweep runs the first non-integer quantity of the case's first section (the duty: inertia, torque or power)
from 0.5x to 2x its value. Serial, in one process: in batches (``clutchopt.optimise.batch``, what ``clutchopt
sweep`` runs: chained SQP re-solves in one CasADi call, checked together), point by point (``Problem.solve`` warm
from the previous optimum, as sweeps ran before) and point by point from the case's own start ("cold starts").
Batched "with records": each point's record built as well (``Solution.as_dict()``, the JSON that ``clutchopt sweep``
tabulates and stores; a window's records are built together from its arrays); the other rows stop at the solve
(batched: a status per point; point by point: a Solution per point, which ``Problem.solve`` builds).
Pool: batched, the sweep cut into contiguous chunks, one per worker process, each worker building its own problem
(counted). Each row is the run of median wall time among ``sweep_repeats`` runs. Per row: solver calls per point
(IPOPT and SQP, integer neighbours and the chained attempts a failed batch wastes included), the shares of the wall
time inside the solver calls (an infeasibility diagnosis's IPOPT call included), in the batches' compiled checks
(mapped CasADi evaluations of the KKT verdicts with the integer test, and of the exclusion tables) and in Python
(the rest: case data, scaling, the float64 checks, bookkeeping; point by point, and batched with records, also
outputs and sensitivities), and for serial sweeps points/s against the same sweep point by point and against the
wedge paper mode's batched sweep.
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor

import numpy as np

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.bench.timing import time_once
from clutchopt.cases import Case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.batch import BatchSweep
from clutchopt.optimise.problem import Problem, SolverOptions, problem_for


def sweep_quantity(case: Case) -> str:
    quantities = [q for q in get_coupling(case.coupling).quantities if not q.integer and q.name in case.values]
    return next(q.name for q in quantities if q.section == quantities[0].section)


def _problem(case: Case, options: SolverOptions, mode: str | None) -> Problem:
    """The process's built problem (built on first use: in the warm-up, or once in each pool worker)."""
    return problem_for(get_coupling(case.coupling).formulation(mode or reference_mode(case.coupling)), "mass", options)


def batched_sweep(case: Case, name: str, values, options: SolverOptions = SolverOptions(),
                  mode: str | None = None, records: bool = False) -> dict:
    """The case solved at each value of ``name`` in batches: points, optimal, solver calls, seconds inside them
    and in the batches' compiled checks. ``records``: each point's record built too (``Solution.as_dict()``: what
    ``clutchopt sweep`` hands to its table and run store)."""
    sweep = BatchSweep(_problem(case, options, mode), case, {name: values})
    if records:
        optimal = sum(record["status"] == "optimal" for window in sweep.run() for record in window.records())
    else:
        optimal = sum(statuses.count("optimal") for statuses in (window.statuses for window in sweep.run()))
    return {"points": len(values), "optimal": optimal, "solves": sweep.solves, "solver_s": sweep.solver_s,
            "check_s": sweep.check_s}


def warm_sweep(case: Case, name: str, values, warm: bool = True, options: SolverOptions = SolverOptions(),
               mode: str | None = None) -> dict:
    """Solve the case at each value of ``name`` in turn by ``Problem.solve``, warm-started from the previous optimum
    unless ``warm`` is false (each point from the case's own start): points, optimal, solver calls, seconds inside
    them."""
    problem = _problem(case, options, mode)
    previous, tally = None, {"points": len(values), "optimal": 0, "solves": 0, "solver_s": 0.0, "check_s": 0.0}
    for value in values:
        solution = problem.solve(case.with_values(**{name: float(value)}), warm=previous if warm else None)
        tally["optimal"] += solution.status == "optimal"
        tally["solves"] += solution.solver.solves
        tally["solver_s"] += solution.solver.time_s
        previous = solution if solution.status == "optimal" else None
    return tally


def _merged(tallies: list[dict]) -> dict:
    return {key: sum(t[key] for t in tallies) for key in tallies[0]}


HOWS = (("batched", batched_sweep, {}), ("batched, with records", batched_sweep, {"records": True}),
        ("point by point", warm_sweep, {}),
        ("point by point, cold starts", warm_sweep, {"warm": False}))


def throughput_rows(config) -> list[dict]:
    rows = []
    for case in bench_cases():
        name = sweep_quantity(case)
        values = case.values[name] * np.geomspace(0.5, 2.0, config.sweep_points)
        batched_sweep(case, name, values)  # warm-up: the problem, its solvers, the chained and mapped functions
        for how, run, keywords in HOWS:
            tally, seconds = _median(lambda: run(case, name, values, **keywords), config.sweep_repeats)
            rows.append(_row(case, name, how, 1, tally, seconds, config.sweep_repeats))
        chunks = np.array_split(values, config.processes)

        def pooled() -> dict:
            with ProcessPoolExecutor(config.processes) as pool:
                return _merged(list(pool.map(batched_sweep, [case] * len(chunks), [name] * len(chunks), chunks)))

        tally, seconds = _median(pooled, config.sweep_repeats)
        rows.append(_row(case, name, "batched, process pool", config.processes, tally, seconds, config.sweep_repeats))
    wedge = next((r for r in rows if (r["coupling"], r["how"]) == ("wedge", "batched")), None)
    for row in rows:
        alone = next(r for r in rows if (r["coupling"], r["how"]) == (row["coupling"], "point by point"))
        serial = row["processes"] == 1
        row["vs_point_by_point"] = row["points_per_s"] / alone["points_per_s"]
        row["vs_wedge_paper"] = row["points_per_s"] / wedge["points_per_s"] if wedge and serial else None
    return rows


def _median(run, repeats: int) -> tuple[dict, float]:
    """``run()`` timed ``repeats`` times: the tally and wall time of the run of median wall time."""
    timed = sorted((time_once(run) for _ in range(repeats)), key=lambda pair: pair[0])
    seconds, tally = timed[len(timed) // 2]
    return tally, seconds


def _row(case, name, how, processes, tally, seconds, runs):
    serial = processes == 1
    solver, check = (tally["solver_s"] / seconds, tally["check_s"] / seconds) if serial else (None, None)
    return {"coupling": case.coupling, "mode": reference_mode(case.coupling), "swept": f"{name} x0.5..2",
            "how": how, "processes": processes, "runs": runs, "points": tally["points"], "optimal": tally["optimal"],
            "solves_per_point": tally["solves"] / tally["points"], "wall_s": seconds,
            "points_per_s": tally["points"] / seconds, "solver_share": solver, "check_share": check,
            "python_share": 1 - solver - check if serial else None}
