"""Scale-out: one sweep (``clutchopt sweep``'s own code, :class:`clutchopt.optimise.sweep.Sweep`) in this process and
on a local Dask cluster of 1, 2 and 4 worker processes (one thread each). The cluster's start-up is not counted, nor
a first solve on each worker (imports, the problem built); the sweep goes out in chunks of 25 neighbouring points,
each chunk warm-started within itself. On a 2-core machine 4 workers share 2 cores."""

from __future__ import annotations

import time

import numpy as np

from clutchopt.bench.reference import CASES
from clutchopt.cases import load_case
from clutchopt.optimise.sweep import Sweep, dask_runner, solve_chunk
from clutchopt.optimise.sweep_grid import Points, parse_vary

CASE, MODE, VARY = "ball_compressor.toml", "design", "power={start}:{stop}:{count}"
WORKERS = (1, 2, 4)


def scaleout_rows(config) -> list[dict]:
    from distributed import Client, LocalCluster

    case = load_case(CASES / CASE)
    kw = case.values["power"] / 1e3  # the display unit of power is kW
    vary = parse_vary(VARY.format(start=0.5 * kw, stop=2 * kw, count=config.sweep_points), case.coupling)
    sweep = Sweep(case, [vary], mode=MODE)
    started = time.perf_counter()
    serial = sweep.run(progress=False)
    rows = [_row("this process", 0, serial, time.perf_counter() - started)]
    for workers in WORKERS:
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
            with Client(cluster) as client:  # every worker imports clutchopt and builds the problem
                client.run(solve_chunk, case, MODE, "mass", 1e-10, None, Points(np.arange(1), {}))
            started = time.perf_counter()
            result = sweep.run(runner=dask_runner(cluster.scheduler_address), progress=False, chunk_size=None)
            rows.append(_row("local Dask cluster", workers, result, time.perf_counter() - started))
    return rows


def _row(how: str, workers: int, result, seconds: float) -> dict:
    return {"coupling": "ball", "mode": MODE, "how": how, "workers": workers, "points": len(result.solutions),
            "optimal": int((result.frame["status"] == "optimal").sum()), "wall_s": seconds,
            "points_per_s": len(result.solutions) / seconds}
