"""Wall-time measurement: a warm-up, then the median and spread of repeated runs."""

from __future__ import annotations

import time
from typing import Callable

import numpy as np


def time_once(run: Callable[[], object]) -> tuple[float, object]:
    started = time.perf_counter()
    result = run()
    return time.perf_counter() - started, result


def median_run(run: Callable[[], object], repeats: int) -> tuple[object, float]:
    """``run()`` timed ``repeats`` times: the result and wall time of the run of median wall time."""
    return median_of([time_once(run) for _ in range(repeats)])


def interleaved_median_runs(runs: list[Callable[[], object]], repeats: int) -> list[tuple[object, float]]:
    """Each of ``runs`` timed ``repeats`` times, in turn (the first, the second, ..., the first again): for each, what
    :func:`median_run` gives. Runs compared by their ratio are timed alternately, so that a drift of the machine (its
    clock, another load) falls on each alike, not on one of them."""
    timed: list[list[tuple[float, object]]] = [[] for _ in runs]
    for _ in range(repeats):
        for times, run in zip(timed, runs):
            times.append(time_once(run))
    return [median_of(times) for times in timed]


def median_of(timed: list[tuple[float, object]]) -> tuple[object, float]:
    """The result and wall time of the run of median wall time among ``timed`` (:func:`time_once`'s pairs; of an even
    count, the slower of the two middle runs)."""
    seconds, result = sorted(timed, key=lambda pair: pair[0])[len(timed) // 2]
    return result, seconds


def repeated(run: Callable[[], object], repeats: int, warmup: int = 1) -> dict[str, float]:
    """Median and interquartile range (seconds) of ``repeats`` runs after ``warmup`` runs not counted."""
    for _ in range(warmup):
        run()
    times = np.array([time_once(run)[0] for _ in range(repeats)])
    q25, median, q75 = np.percentile(times, [25, 50, 75])
    return {"median_s": float(median), "iqr_s": float(q75 - q25), "runs": repeats}
