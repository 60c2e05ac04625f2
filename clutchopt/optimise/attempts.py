"""Solver runs on a posed problem: one run by IPOPT (cold or warm) or CasADi's SQP, its design checked in float64, and
an attempt trying methods in turn.

A warm re-solve starts from a previous optimum's primal-dual point: SQP (dense active-set QPs, ``qrqp``: next to a
known optimum a few Newton steps; 1.5-3.7x faster than warm IPOPT on these small NLPs), whose KKT point is checked
apart from it, then IPOPT (``warm_start_init_point``, small initial barrier parameter).
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from contextvars import ContextVar
from types import SimpleNamespace
from typing import Iterator

import numpy as np

from clutchopt.optimise.chain import first_order_optimal, leaves_free, no_descent_curvature
from clutchopt.optimise.posed import Posed, ScaledData
from clutchopt.optimise.verify import check_design, evaluate_objective


class Tally:
    """The start-up solver runs made while it is open (:func:`tallied`): calls, iterations, seconds."""

    def __init__(self):
        self.calls, self.iterations, self.seconds = 0, 0, 0.0


_TALLIES: ContextVar[tuple[Tally, ...]] = ContextVar("clutchopt_tallies", default=())


@contextmanager
def tallied() -> Iterator[Tally]:
    """A :class:`Tally` of the start-up problems' runs made inside (the papers' sizing's static runs not: a start-up
    solve does not count them), nested ones each counting theirs."""
    tally = Tally()
    token = _TALLIES.set((*_TALLIES.get(), tally))
    try:
        yield tally
    finally:
        _TALLIES.reset(token)


class Run(dict):
    """One solve's figures (``x``, ``g``, ``lam_x``, ``lam_g``, ``f``, ``ok``, ``status``, ``design``, ...). Its float64
    check (``checks``, ``feasible``, ``value``) is made when one of them is first read: a relaxation whose integers
    are searched next needs none."""

    check = None  # design -> the check's figures

    def __missing__(self, key):
        if key not in ("checks", "feasible", "value") or self.check is None:
            raise KeyError(key)
        self.update(self.check(self["design"]))
        return self[key]


def checked(posed: Posed, design: dict[str, float], params: SimpleNamespace) -> dict:
    """A design's float64 check: ``checks``, ``feasible``, ``value`` (the objective)."""
    checks = check_design(posed.formulation, design, params)
    return {"checks": checks, "feasible": all(c.feasible for c in checks),
            "value": evaluate_objective(posed.formulation, posed.objective.name, design, params)}


def run(posed: Posed, data: ScaledData, lbx, ubx, x0, seed: dict | None, method: str = "ipopt", ubg=0.0) -> Run:
    """One solve, its design checked in float64 (``design``, ``checks``, ``value``, ``feasible``); ``ubg`` the rows'
    upper limits (scaled, g <= 0: every row posed; +inf where a row is left out of this solve, ``polish``)."""
    solver = posed.solver(method)
    lbg, ubg = posed.sides.bounds(data.p, ubg)  # (a quantity held from both sides: one row, optimise/two_sided.py)
    args = {"x0": x0, "p": data.p, "lbx": lbx, "ubx": ubx, "lbg": lbg, "ubg": ubg}
    if seed is not None:
        args.update(lam_x0=seed["lam_x"], lam_g0=posed.sides.posed(seed["lam_g"], data.p))
    started = time.perf_counter()
    result = solver(**args)
    elapsed = time.perf_counter() - started
    stats = solver.stats()
    x = result["x"].full().ravel()
    solved = Run(x=x, g=result["g"].full().ravel(), lam_g=posed.sides.named(result["lam_g"].full().ravel(), data.p),
                 lam_x=result["lam_x"].full().ravel(),
                 f=float(result["f"]), ok=bool(stats["success"]), status=stats["return_status"],
                 iterations=int(stats.get("iter_count", 0)), time=elapsed, p=data.p, lbx=lbx, ubx=ubx,
                 solver="sqpmethod" if method == "sqp" else "ipopt",
                 design=posed.rounded(posed.design(x, data.scale)))
    solved.check = lambda design, params=data.checked or data.params: checked(posed, design, params)
    if posed.start_up is not None:
        for tally in _TALLIES.get():
            tally.calls, tally.iterations, tally.seconds = (tally.calls + 1, tally.iterations + solved["iterations"],
                                                            tally.seconds + elapsed)
    return solved


def attempt(posed: Posed, data: ScaledData, lbx, ubx, x0, seed: dict | None, methods: tuple[str, ...],
            runs: list[dict], ubg=0.0) -> Run:
    """Solve by each method in turn until one ends in a verified optimum; every run goes into ``runs``.
    Methods: ``ipopt`` (cold), ``warm`` (IPOPT from ``seed``'s primal-dual point), ``sqp`` (CasADi's
    sequential QP from ``seed``: for a re-solve next to a known optimum, a few Newton steps), whose KKT point is
    checked apart from it. A static problem's warm end (``sqp``, ``warm``, ``warm_near``) is verified only where no
    direction its holding rows and bounds leave free curves down (``chain.no_descent_curvature``): a warm start may
    lead to a saddle; a cold IPOPT's end is ``solve``'s own, as it comes."""
    for i, method in enumerate(methods):
        solved = run(posed, data, lbx, ubx, x0, seed if method != "ipopt" else None, method, ubg)
        runs.append(solved)
        point = [solved[k] for k in ("x", "p", "lam_x", "lam_g", "lbx", "ubx")]
        if method == "sqp" and solved["ok"]:
            solved["ok"] = bool(first_order_optimal(posed, *point)[0])
        if method != "ipopt" and posed.start_up is None and solved["ok"] and leaves_free(posed, *point[2:])[0]:
            solved["ok"] = bool(no_descent_curvature(posed, *point)[0])  # (a warm start's end may be a saddle)
        if i == len(methods) - 1 or solved["ok"] and solved["feasible"]:
            break
    return solved


def warm_multipliers(posed: Posed, lam_x: np.ndarray, lam_g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Multipliers to warm-start from: those within the KKT verdict's tolerance (10 tol) set to 0. IPOPT leaves
    about 1e-11 on inactive bounds and constraints (an interior point); CasADi's SQP (qrqp) reads any non-zero
    multiplier as an active bound, fixes the variable there and stops on a search direction too small (the
    wedge's first re-solve after a cold IPOPT solve did)."""
    tol = posed.kkt_tolerance
    return tuple(np.where(np.abs(lam) > tol, lam, 0.0) for lam in (lam_x, lam_g))
