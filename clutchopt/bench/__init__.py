"""``clutchopt bench``: what accuracy costs in time, one table per section.

Each section is one function ``rows(config) -> list[dict]`` registered in :data:`SECTIONS`; ``clutchopt bench``
and ``benchmarks/run_full.py`` print every registered section.
"""

from __future__ import annotations

import math
import os
import platform
import time
from dataclasses import asdict, dataclass
from importlib.metadata import version
from typing import Callable

import pandas as pd

from clutchopt.bench.accuracy import accuracy_rows
from clutchopt.bench.cli_launch import cli_launch_rows
from clutchopt.bench.reliability import reliability_rows
from clutchopt.bench.resolve import resolve_rows
from clutchopt.bench.scaleout import scaleout_rows
from clutchopt.bench.start_up_designs import start_up_design_rows, start_up_solve_rows
from clutchopt.bench.throughput import throughput_rows
from clutchopt.bench.transient import effects_rows, stiffness_rows, tolerance_rows
from clutchopt.bench.user_sweeps import IN_THE_CACHE, NO_LIBRARY, user_sweep_rows
from clutchopt.optimise.start_up_compiled import wait_for_builds


@dataclass(frozen=True)
class BenchConfig:
    repeats: int = 20  # timed re-solves per method, after one warm-up
    sweep_points: int = 1000
    sweep_repeats: int = 5  # timed runs of each throughput sweep (the median is reported)
    processes: int = 2
    start_up_intervals: tuple[int, ...] = (8, 16, 32, 64)  # collocation intervals per phase measured
    start_up_compiled: tuple[str, ...] = (IN_THE_CACHE, NO_LIBRARY)  # the compiled-code cache's states a start-up
    # sweep is timed in (clutchopt.bench.user_sweeps.start_up_rows)

    @classmethod
    def quick(cls) -> "BenchConfig":
        return cls(repeats=3, sweep_points=50, sweep_repeats=3, processes=2, start_up_intervals=(16,),
                   start_up_compiled=(NO_LIBRARY,))  # (no library built: 8-26 s of compiling a start-up case)


@dataclass(frozen=True)
class Section:
    name: str
    title: str
    rows: Callable[[BenchConfig], list[dict]]
    quick: bool = True  # part of ``--quick`` (the Dask clusters are not)


SECTIONS: tuple[Section, ...] = (
    Section("cli_launch", "Command-line launch: whole command-line runs as new processes (median wall time), "
                          "against python -c 'import casadi, numpy'", cli_launch_rows),
    Section("accuracy", "Accuracy vs time (one case per coupling, every mode; rel_error against IPOPT tol 1e-10; "
                        "violation re-evaluated in float64, relative; times in ms)", accuracy_rows),
    Section("throughput", "Throughput: one built problem re-solved over a sweep, warm-started unless said (batched: "
                          "chained SQP re-solves checked together, as clutchopt sweep runs; sweep: Sweep.run, with "
                          "its table, and with a run store); solver calls per point, shares of the wall time in the "
                          "solver calls, in the batches' compiled checks (KKT verdicts, exclusion tables) and in "
                          "Python; points/s against the same sweep point by point and the wedge paper mode's",
            throughput_rows),
    Section("user_sweeps", "The sweeps users run (Sweep.run, no store): every coupling over its duty quantity, speed, "
                           "friction coefficient and allowable (0.5x-2x), into an infeasible region (1x-10x) and on "
                           "either side of the edge it meets (a point beyond it against one before it: "
                           "point_cost_vs_designed), into an infeasible region in each of its other modes too (1x-10x, "
                           "or the widest span its checks accept), ball_crusher over 250-1000 kW, and each start-up "
                           "case over its "
                           "driven inertia (once per state of the compiled-code cache, compiled: 'in the cache', its "
                           "NLPs' libraries built first, untimed, as a second run meets them; 'none', an empty cache, "
                           "as a first run meets it less the build it starts beside itself; compiled_used: whether the "
                           "run's solvers evaluated them by its end, found at its first point by the link beside the "
                           "library; "
                           "no build runs while anything is timed), wedge_motor_start's again over five times the "
                           "points; points with and without a design, "
                           "solver calls per point, points/s against the wedge paper sweep of its duty quantity "
                           "(its runs at the section's start and after the static sweeps pooled)",
            user_sweep_rows),
    Section("resolve", "Warm re-solves along the same sweeps: warm IPOPT alone (before) and SQP first (now); times per "
                       "re-solve, largest relative difference of the verified optima", resolve_rows),
    Section("scaleout", "Scale-out: the ball design sweep (clutchopt sweep's code) in this process and on a local Dask "
                        "cluster of 1, 2 and 4 workers; cluster start-up not counted", scaleout_rows, quick=False),
    Section("transient_tolerance", "Simulator accuracy vs time: the paper scene's t_c and L against the closed "
                                   "forms, per solve_ivp (DOP853) tolerance; times in ms", tolerance_rows),
    Section("transient_stiffness", "Simulator on a stiff scene: the motor scene by DOP853 and by the integrator "
                                   "picked by stiffness, errors against DOP853 at rtol 1e-13; times in ms",
            stiffness_rows),
    Section("transient_effects", "Simulator cost per effect: the solved wedge design on a motor with springs, "
                                 "effects added one by one; times in ms", effects_rows),
    Section("start_up_accuracy", "Start-up inside the NLP: start time against the simulator per collocation "
                                 "intervals (per phase) and mesh; the default adapts, then doubles, to the case's "
                                 "tolerance; one run each, in ms, with the problem's build (first row of an "
                                 "interval count) and the re-simulation", start_up_design_rows),
    Section("start_up_solve", "Start-up solves against their static solves (the case without [start_up]): reading "
                              "the case, the first solve in this process (its problems built anew, as in a new "
                              "process) and the re-solve of the same case (median), in ms; the ratios (goal: at most "
                              "10); compiled_used: whether its start-up NLP's compiled functions (a library a sweep "
                              "left in the cache) were evaluated",
            start_up_solve_rows),
    Section("reliability", "Failure probabilities against OpenTURNS: the wedge centrifuge's active constraints at its "
                           "worst-case and nominal designs under its [scatter], each estimator's probability with its "
                           "95 % interval (Monte Carlo: Clopper-Pearson for the tool, OpenTURNS' own), its samples and "
                           "its median time for all of the design's limit states, in ms", reliability_rows),
)


def machine() -> dict:
    """Where the numbers were taken."""
    cpu = platform.processor()
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as info:
            cpu = next(line.split(":", 1)[1].strip() for line in info if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return {"cpu": cpu, "cores": os.cpu_count(), "system": platform.platform(), "python": platform.python_version(),
            **{package: version(package) for package in ("casadi", "cvxpy", "scipy", "numpy")}}


def run_bench(config: BenchConfig, sections: tuple[Section, ...] = SECTIONS, quick: bool = False) -> dict:
    report = {"machine": machine(), "config": asdict(config), "sections": {}}
    for section in (s for s in sections if s.quick or not quick):
        wait_for_builds()  # (no compiler beside a section timed: a start-up sweep's build, started in the background)
        started = time.perf_counter()
        rows = section.rows(config)
        report["sections"][section.name] = {"title": section.title, "rows": rows,
                                            "seconds": time.perf_counter() - started}
    return report


COLUMN_UNITS = {  # the SI unit of every column of every section ("": a count, ratio or relative error)
    **dict.fromkeys(("median_s", "iqr_s", "first_s", "resolve_median_s", "resolve_iqr_s", "wall_s", "python_fixed_s",
                     "solver_per_resolve_s", "per_resolve_s", "start_time_s", "time_s", "load_s", "static_first_s",
                     "static_median_s"), "s"),
    "objective": "kg",  # every section minimises the mass
    "points_per_s": "1/s",
    **dict.fromkeys(("runs", "ratio_to_import", "rel_error", "worst_violation", "iterations", "processes", "points",
                     "optimal", "solves_per_point", "solver_share", "check_share", "python_share",
                     "python_per_point_share", "vs_point_by_point", "vs_wedge_paper", "resolves", "speedup",
                     "max_rel_diff_objective", "workers", "rtol", "t_c_rel_error", "L_rel_error", "intervals",
                     "start_time_rel_error", "solves", "designed", "without_design", "first_vs_static",
                     "resolve_vs_static", "point_cost_vs_designed", "probability", "interval_low", "interval_high",
                     "samples"), ""),
}


def bench_json(report: dict) -> dict:
    """The report with the unit of every number (``clutchopt bench --json``, ``benchmarks/latest.json``)."""
    from clutchopt.output import with_units

    return with_units(report, {"machine": {"cores": ""}, "config": "", "sections": {
        name: {"seconds": "s", "rows": COLUMN_UNITS} for name in report["sections"]}})


_MS = ("first_s", "resolve_median_s", "resolve_iqr_s", "median_s", "iqr_s", "time_s", "solver_per_resolve_s",
       "per_resolve_s", "python_fixed_s", "load_s", "static_first_s", "static_median_s")


def _shown(row: dict) -> dict:
    """A row as text: times in ms, objectives to 10 digits, other numbers to 4, missing values as "-"."""
    shown = {}
    for key, value in row.items():
        missing = value is None or value == "" or (isinstance(value, float) and math.isnan(value))
        if key in _MS:
            shown[key.replace("_s", "_ms")] = "-" if missing else f"{value * 1e3:.3g}"
        elif missing:
            shown[key] = "-"
        elif isinstance(value, float):
            shown[key] = f"{value:.10g}" if key == "objective" else f"{value:.4g}"
        else:
            shown[key] = value
    return shown


def bench_text(report: dict) -> str:
    m = report["machine"]
    lines = [f"machine: {m['cpu']}, {m['cores']} cores, {m['system']}; python {m['python']}, casadi {m['casadi']}, "
             f"cvxpy {m['cvxpy']}, scipy {m['scipy']}", f"config: {report['config']}"]
    for section in report["sections"].values():
        lines += ["", section["title"], pd.DataFrame([_shown(r) for r in section["rows"]]).to_string(index=False)]
    return "\n".join(lines)
