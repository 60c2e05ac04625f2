"""``solve --robust ... --verify``: the robust design's start simulated at every corner of its scatter, where the
nominal design's is simulated at the case's values (``clutchopt.start_up.simulation.verify``)."""

from __future__ import annotations

import math
from dataclasses import replace

from clutchopt.cases import Case
from clutchopt.errors import InputError
from clutchopt.optimise.robust_models import corner_table, design_at
from clutchopt.optimise.robust_start_up import MAX_START_CORNERS, corner_points, quantile_ends


def check_verifiable(case: Case) -> None:
    """A robust design is verified at every corner of its scatter: up to MAX_START_CORNERS scattered quantities,
    unless its [start_up] was simulated at the corners already (refused by name before any solve)."""
    if case.start_up is None and len(case.scatter) > MAX_START_CORNERS:
        raise InputError("--verify", f"simulates a robust design at every corner of its scatter, up to "
                                     f"{MAX_START_CORNERS} scattered quantities ({2 ** MAX_START_CORNERS} starts); "
                                     f"this case scatters {len(case.scatter)}: drop --verify (the robust design is "
                                     "checked at every corner of its constraints) or scatter fewer")


def verify_robust(case: Case, result) -> dict:
    """The robust design (``RobustResult``) started at every corner of its scatter: those its [start_up] was
    simulated at (chance: each start-up limit's performance point), else the corners of the ranges (worst case) or of the quantiles P^(1/n) (chance P, n scattered
    quantities, as a start-up's); the check (``verify``) of the corner where the start comes closest to its limit,
    or misses it most, with that ``corner`` (SI) and the number of ``corners``."""
    from clutchopt.start_up.simulation import verify

    scatter = case.scatter
    points = result.start_up_points or corner_points(corner_table(scatter, None if result.target is None else
                                                                  quantile_ends(case, scatter,
                                                                                result.target ** (1 / len(scatter)))))
    checks = [(point, verify(case.with_values(**point),
                             replace(result.solution, design=design_at(result.solution.design, point)), afresh=True))
              for point in points]
    corner, check = max(checks, key=lambda pair: _lateness(pair[1]))
    return {**check, "corner": corner, "corners": len(points)}


def _lateness(check: dict) -> float:
    """The simulated start over the time it is allowed; infinite where it was not simulated or does not end."""
    if "max_start_time" in check:
        return check["simulated_start_time"] / check["max_start_time"]
    if "sized_acceleration_time" in check:
        return check["simulated_acceleration_time"] / check["sized_acceleration_time"]
    return math.inf
