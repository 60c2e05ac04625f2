"""A static solve's IPOPT optimum polished onto the exact KKT point of the active set IPOPT identified.

IPOPT is an interior-point method: it stops (tol 1e-10) with the active bounds and constraints a barrier's width
away, 1e-11 to 1e-10 of each variable inside its bounds, its objective 1e-11 to 1e-9 relative above the optimum
(the ball compressor at 2858 rad/s: 50.000000021 mm and 40.000000069 mm on bounds of 50 mm and 40 mm, 2.6e-9
heavier; the wedge centrifuge in geometry mode 1.2e-9). A sweep re-solves the same point warm by CasADi's SQP
(dense active-set QPs), which lands on the vertex itself: one question would get two answers beyond the 1e-9 of
a static point (tests/test_sweep_agrees.py). The polish is the sweep's own step from IPOPT's end: SQP from IPOPT's
primal-dual point, its multipliers within the KKT tolerance set to 0 (``warm_multipliers``: those of the bounds and
constraints IPOPT found active stay, so qrqp starts on that active set and puts them exactly on their limits), its
KKT point verified apart from the solver (``first_order_optimal``). Kept only where it is verified, feasible in the
float64 re-check and no heavier than IPOPT's; else IPOPT's optimum stays as it was. Its iterations and seconds are
counted in the solve's; it is not another design solve.
"""

from __future__ import annotations

import numpy as np

from clutchopt.optimise.attempts import Run, attempt, warm_multipliers
from clutchopt.optimise.posed import Posed, ScaledData

POLISHED = "(polished by SQP)"  # after IPOPT's status where the design shown is the polish's
SNAP = 1e-6  # a bound IPOPT found active (its multiplier beyond the KKT tolerance) this near (relative, scaled x) is
#              where the polish starts: IPOPT at tol 1e-10 leaves such variables up to 6e-9 inside (wedge_paper in
#              geometry mode: the weight width at 1.59999999 of its scaled bound 1.6, 40 mm), where qrqp, handed the
#              bound's multiplier and finding the KKT conditions met, stops at once without putting it on its bound


def snapped(x: np.ndarray, lbx: np.ndarray, ubx: np.ndarray, lam_x: np.ndarray) -> np.ndarray:
    """``x`` (scaled) with each variable whose bound multiplier ``lam_x`` is non-zero (upper: positive, lower:
    negative) put on that bound where it is within SNAP (relative) of it; the SQP then restores the constraints."""
    width = SNAP * np.maximum(1.0, np.abs(x))
    x = np.where((lam_x > 0) & (ubx - x <= width), ubx, x)
    return np.where((lam_x < 0) & (x - lbx <= width), lbx, x)


def polished(posed: Posed, data: ScaledData, ended: Run) -> Run:
    """``ended`` (a static problem's IPOPT run that ended optimal on ``data``, its design feasible in float64) on
    the exact KKT point of its active set: the SQP run from it, with IPOPT's name, IPOPT's status followed by
    POLISHED (the design is the SQP's), iterations and seconds summed with IPOPT's, where that point is verified,
    feasible and no heavier; else ``ended`` with the polish's iterations and seconds added."""
    lam_x, lam_g = warm_multipliers(posed, ended["lam_x"], ended["lam_g"])
    x0 = snapped(ended["x"], ended["lbx"], ended["ubx"], lam_x)
    step = attempt(posed, data, ended["lbx"], ended["ubx"], x0, {"lam_x": lam_x, "lam_g": lam_g}, ("sqp",), [])
    spent = {"iterations": ended["iterations"] + step["iterations"], "time": ended["time"] + step["time"]}
    if step["ok"] and step["feasible"] and step["value"] <= ended["value"]:  # (ok: its KKT point verified)
        step.update(solver=ended["solver"], status=f"{ended['status']} {POLISHED}", **spent)
        return step
    ended.update(spent)
    return ended


def polishable(posed: Posed, ended: Run) -> bool:
    """Whether a kept run is polished: a static problem's (a start-up's collocation has its own tolerance contract)
    IPOPT run that ended optimal, its design feasible in float64; unless its options say not to (the papers' sizing
    of a start-up: ``SolverOptions.polish``)."""
    return (posed.start_up is None and posed.options.polish and ended["solver"] == "ipopt" and ended["ok"]
            and ended["feasible"])
