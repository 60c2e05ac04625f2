"""Throughput: one built CasADi problem re-solved, warm-started, over a sweep of one case quantity.

The sweep runs the first non-integer quantity of the case's first section (the duty: inertia, torque or power)
from 0.5x to 2x its value. Serial, in one process: in batches (``clutchopt.optimise.batch``, what ``clutchopt
sweep`` runs: chained SQP re-solves in one CasADi call, checked together), point by point (``Problem.solve`` warm
from the previous optimum, as sweeps ran before) and point by point from the case's own start ("cold starts").
"Sweep, tabulated": the whole ``Sweep(...).run()`` of the Python API, which ``clutchopt sweep --no-store`` runs (the
points checked, solved in batches, and the table built, the batched points' rows from their windows' arrays);
"sweep, tabulated and stored" records each point in a run store as well (its record built and written as JSON, a
batched point's compact: ``clutchopt sweep``'s default). The batched row stops at the solve (a status per point), point
by point at a Solution per point (which ``Problem.solve`` builds).
Pool: batched, the sweep cut into contiguous chunks, one per worker process, each worker building its own problem
(counted). Each row is the run of median wall time among ``sweep_repeats`` runs; the two sweep rows' among
``PAIRED_RUNS * sweep_repeats`` runs each, timed alternately (tabulated, stored, tabulated, ...: their ratio, the
store's cost, is not the machine's drift between two blocks of runs). Per row: solver calls per point
(IPOPT and SQP, integer neighbours and the chained attempts a failed batch wastes included), the shares of the wall
time inside the solver calls (an infeasibility diagnosis's IPOPT call included), in the batches' compiled checks
(mapped CasADi evaluations of the KKT verdicts with the integer test, and of the exclusion tables) and in Python
(the rest: case data, scaling, the float64 checks, bookkeeping; point by point also outputs and sensitivities; the
sweeps also the table, and with a store the records and their writing), and for serial sweeps points/s against the
same sweep point by point and against the wedge paper mode's batched sweep. Serial rows also split the Python in
two: what the same run spends over the sweep's first point alone (``python_fixed_s``, the median of
``ONE_POINT_RUNS * sweep_repeats`` one-point runs: set-up, the first point's cold solve, a window's checks, the
table; with a store, opening and closing it), which a sweep pays whatever its size, and the share of the wall time
in Python beyond that (``python_per_point_share``: the overhead that grows with the points).
"""

from __future__ import annotations

import os
import tempfile
from concurrent.futures import ProcessPoolExecutor
from functools import partial

import numpy as np

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.bench.timing import interleaved_median_runs, median_run
from clutchopt.cases import Case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.batch import BatchSweep
from clutchopt.optimise.problem import Problem, problem_for
from clutchopt.optimise.solution import SolverOptions


def sweep_quantity(case: Case) -> str:
    quantities = [q for q in get_coupling(case.coupling).quantities if not q.integer and q.name in case.values]
    return next(q.name for q in quantities if q.section == quantities[0].section)


def _problem(case: Case, options: SolverOptions, mode: str | None) -> Problem:
    """The process's built problem (built on first use: in the warm-up, or once in each pool worker)."""
    return problem_for(get_coupling(case.coupling).formulation(mode or reference_mode(case.coupling)), "mass", options)


def batched_sweep(case: Case, name: str, values, options: SolverOptions = SolverOptions(),
                  mode: str | None = None) -> dict:
    """The case solved at each value of ``name`` in batches: points, optimal, solver calls, seconds inside them
    and in the batches' compiled checks."""
    sweep = BatchSweep(_problem(case, options, mode), case, {name: values})
    optimal = sum(statuses.count("optimal") for statuses in (window.statuses for window in sweep.run()))
    return {"points": len(values), "optimal": optimal, "solves": sweep.solves, "solver_s": sweep.solver_s,
            "check_s": sweep.check_s}


def tabulated_sweep(case: Case, name: str, values, store_path: str | None = None) -> dict:
    """``Sweep(case, ...).run()`` over the values of ``name`` (the default mode and objective): the table, and with
    ``store_path`` each point recorded in that run store; the tally of :func:`batched_sweep`."""
    from clutchopt.optimise.sweep import Sweep
    from clutchopt.optimise.sweep_grid import Vary
    from clutchopt.store import RunStore

    quantity = next(q for q in case.quantities if q.name == name)
    sweep = Sweep(case, [Vary(quantity, tuple(values.tolist()))], mode=reference_mode(case.coupling))
    if store_path is None:
        result = sweep.run(progress=False)
    else:
        with RunStore(store_path) as store:
            result = sweep.run(store, progress=False)
    return {"points": len(values), "optimal": int((result.frame["status"].to_numpy() == "optimal").sum()),
            **result.spent}


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


STORE = "bench-runs.sqlite"  # in a throw-away folder: the stored sweeps' run store
ONE_POINT_RUNS = 3  # one-point runs per timed sweep run: they measure the Python a sweep spends whatever its size
PAIRED_RUNS = 3  # the two sweep rows' runs per sweep run, timed alternately (interleaved_median_runs)
PAIRED = ("sweep, tabulated", "sweep, tabulated and stored")  # the rows timed so

HOWS = (("batched", batched_sweep, {}), ("sweep, tabulated", tabulated_sweep, {}),
        ("sweep, tabulated and stored", tabulated_sweep, {"store_path": STORE}),
        ("point by point", warm_sweep, {}),
        ("point by point, cold starts", warm_sweep, {"warm": False}))


def throughput_rows(config) -> list[dict]:
    with tempfile.TemporaryDirectory(prefix="clutchopt-bench-") as folder:
        return _throughput_rows(config, os.path.join(folder, STORE))


def _throughput_rows(config, store: str) -> list[dict]:
    rows = []
    for case in bench_cases():
        name = sweep_quantity(case)
        values = case.values[name] * np.geomspace(0.5, 2.0, config.sweep_points)
        tabulated_sweep(case, name, values, store)  # warm-up: the problem, its solvers, chained and mapped functions
        hows = [(how, run, {key: store if value is STORE else value for key, value in keywords.items()})
                for how, run, keywords in HOWS]
        pairs = [(how, partial(run, case, name, values, **keywords)) for how, run, keywords in hows if how in PAIRED]
        paired = dict(zip([how for how, _ in pairs], interleaved_median_runs([run for _, run in pairs],
                                                                             PAIRED_RUNS * config.sweep_repeats)))
        for how, run, keywords in hows:
            repeats = (PAIRED_RUNS if how in PAIRED else 1) * config.sweep_repeats
            tally, seconds = paired.get(how) or median_run(lambda: run(case, name, values, **keywords), repeats)
            row = _row(case, name, how, 1, tally, seconds, repeats)
            one, one_s = median_run(lambda: run(case, name, values[:1], **keywords),
                                 ONE_POINT_RUNS * config.sweep_repeats)
            row["python_fixed_s"] = _python_s(one, one_s)
            row["python_per_point_share"] = (_python_s(tally, seconds) - _python_s(one, one_s)) / seconds
            rows.append(row)
        chunks = np.array_split(values, config.processes)

        def pooled() -> dict:
            with ProcessPoolExecutor(config.processes) as pool:
                return _merged(list(pool.map(batched_sweep, [case] * len(chunks), [name] * len(chunks), chunks)))

        tally, seconds = median_run(pooled, config.sweep_repeats)
        rows.append(_row(case, name, "batched, process pool", config.processes, tally, seconds, config.sweep_repeats))
    wedge = next((r for r in rows if (r["coupling"], r["how"]) == ("wedge", "batched")), None)
    for row in rows:
        alone = next(r for r in rows if (r["coupling"], r["how"]) == (row["coupling"], "point by point"))
        serial = row["processes"] == 1
        row["vs_point_by_point"] = row["points_per_s"] / alone["points_per_s"]
        row["vs_wedge_paper"] = row["points_per_s"] / wedge["points_per_s"] if wedge and serial else None
    return rows


def _python_s(tally: dict, seconds: float) -> float:
    """A run's seconds outside the solver calls and the batches' compiled checks."""
    return seconds - tally["solver_s"] - tally["check_s"]


def _row(case, name, how, processes, tally, seconds, runs):
    serial = processes == 1
    solver, check = (tally["solver_s"] / seconds, tally["check_s"] / seconds) if serial else (None, None)
    return {"coupling": case.coupling, "mode": reference_mode(case.coupling), "swept": f"{name} x0.5..2",
            "how": how, "processes": processes, "runs": runs, "points": tally["points"], "optimal": tally["optimal"],
            "solves_per_point": tally["solves"] / tally["points"], "wall_s": seconds,
            "points_per_s": tally["points"] / seconds, "solver_share": solver, "check_share": check,
            "python_share": 1 - solver - check if serial else None, "python_fixed_s": None,
            "python_per_point_share": None}
