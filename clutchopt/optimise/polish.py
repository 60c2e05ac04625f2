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
counted in the solve's; it is not another design solve. A static solve's rounded integers kept by SQP from the
relaxation (``integers.FROM_THE_RELAXATION``) are not polished: a polish from that SQP's end, a KKT point to the
solver's tolerance already, takes no step (on ball_compressor in design mode at tol 1e-6 it stays 3.1e-9 heavier than
the optimum at 1e-10, within the tolerance asked for).

Where the SQP fails, it is tried once more without the active rows whose gradient is a combination of those of the
active bounds and the rows kept before it (taken in order of IPOPT's multiplier, largest first;
``without_dependent_rows``): linearly dependent active rows leave its QPs singular, where it stopped at once and the
polish was lost; the float64 re-check still judges every row, the one left out included. The same quantity held
from both sides (the ball's paper mode at K5 = width_ratio = width_ratio_max = 0.8, ball_compressor: g and -g, the
case that showed it) is no longer one: the solvers see it as one row with both limits (``optimise/two_sided.py``);
this stays for other dependencies. Looked for only where the SQP failed: the Jacobian and its SVD cost 0.1-0.17 ms,
a third of the polish.
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


ACCEPTABLE = 100  # IPOPT's acceptable tolerance over its tol (SolverOptions.ipopt): how much heavier than an end
#                   outside a row (relative, times tol) its polished vertex may be, where that end met no row exactly
DEPENDENT = 1e-8  # a row's unit gradient this near (least singular value) the span of those kept is dependent on
#                   them: a duplicated row's is 0 to round-off (1e-16); the active sets at the optima of every static
#                   case file in each mode have least singular values 1.3e-3 (the ball's design mode) to 0.9


def without_dependent_rows(posed: Posed, data: ScaledData, x: np.ndarray, g: np.ndarray, lam_x: np.ndarray,
                           lam_g: np.ndarray, lbx: np.ndarray, ubx: np.ndarray):
    """The active rows to leave out of the polish and the multipliers to start it from: ``(dropped, lam_x, lam_g)``.
    Active: a row with a non-zero multiplier ``lam_g`` and ``g`` (scaled, g <= 0) within SNAP of 0; a bound with a
    non-zero ``lam_x`` that ``x`` (scaled, :func:`snapped`) is on. A row is dropped where its gradient at ``x`` lies,
    within DEPENDENT, in the span of the active bounds' and the rows kept before it, the rows taken by decreasing
    multiplier (of two dependent rows, the one IPOPT's multipliers press on more is kept). Where one is dropped, the
    kept rows' and bounds' multipliers are those of the stationarity grad f + J' lam = 0 on the kept set (least
    squares): IPOPT's on dependent rows may be both large (4.8e9 on the compressor's K5 rows g and -g, their
    difference 0.436, before they were one row), and the SQP started from them stopped at once with its search
    direction too small."""
    dropped = np.zeros(posed.lbg.shape, dtype=bool)
    active = np.flatnonzero((lam_g[: posed.n_ineq] != 0) & (np.abs(g[: posed.n_ineq]) <= SNAP))
    bounds = np.flatnonzero((lam_x != 0) & ((x == lbx) | (x == ubx)))
    if len(active) + len(bounds) < 2:
        return dropped, lam_x, lam_g
    derivatives = posed.derivatives()  # (IPOPT's own, of the run being polished: not derived again)
    jacobian = derivatives["jac_g"](x, data.p)[1].full()[: posed.n_ineq]
    gradient = derivatives["grad_f"](x, data.p)[1].full()
    kept = [row for row in np.eye(len(x))[bounds]]
    for i in sorted(active, key=lambda i: -abs(lam_g[i])):
        norm = np.linalg.norm(jacobian[i])
        candidate = np.array([*kept, jacobian[i] / max(norm, np.finfo(float).tiny)])
        if norm == 0 or len(candidate) > len(x) or np.linalg.svd(candidate, compute_uv=False)[-1] <= DEPENDENT:
            dropped[i] = True
        else:
            kept.append(candidate[-1])
    if not dropped.any():
        return dropped, lam_x, lam_g
    rows = [i for i in active if not dropped[i]]
    normals = np.vstack([np.eye(len(x))[bounds], jacobian[rows]])
    multipliers = np.linalg.lstsq(normals.T, -gradient.ravel(), rcond=None)[0]
    lam_x, lam_g = lam_x.copy(), np.where(dropped, 0.0, lam_g)
    lam_x[bounds], lam_g[rows] = multipliers[: len(bounds)], multipliers[len(bounds):]
    return dropped, lam_x, lam_g


def polished(posed: Posed, data: ScaledData, ended: Run) -> Run:
    """``ended`` (a static problem's IPOPT run that ended optimal on ``data``) on the exact KKT point of its active
    set: the SQP run from it, with IPOPT's name, IPOPT's status followed by POLISHED (the design is the SQP's),
    iterations and seconds summed with IPOPT's, where that point is verified, feasible and no heavier (than IPOPT's
    end where that is feasible in float64); else ``ended`` with the polish's iterations and seconds added."""
    lam_x, lam_g = warm_multipliers(posed, ended["lam_x"], ended["lam_g"])
    x0 = snapped(ended["x"], ended["lbx"], ended["ubx"], lam_x)
    runs = []
    step = attempt(posed, data, ended["lbx"], ended["ubx"], x0, {"lam_x": lam_x, "lam_g": lam_g}, ("sqp",), runs)
    if not step["ok"]:  # (its QPs singular where two active rows are dependent: those looked for only here)
        dropped, lam_x, lam_g = without_dependent_rows(posed, data, x0, ended["g"], lam_x, lam_g, ended["lbx"],
                                                       ended["ubx"])
        if dropped.any():
            step = attempt(posed, data, ended["lbx"], ended["ubx"], x0, {"lam_x": lam_x, "lam_g": lam_g}, ("sqp",),
                           runs, np.where(dropped, np.inf, 0.0))
    spent = {"iterations": ended["iterations"] + sum(r["iterations"] for r in runs),
             "time": ended["time"] + sum(r["time"] for r in runs)}
    heavier = 0.0 if ended["feasible"] else ACCEPTABLE * posed.options.tol * abs(ended["value"])  # (an end outside
    # a row: its vertex may weigh what the row's violation saved, within IPOPT's acceptable tolerance; review 20b)
    if step["ok"] and step["feasible"] and step["value"] <= ended["value"] + heavier:  # (ok: its KKT point verified)
        step.update(solver=ended["solver"], status=f"{ended['status']} {POLISHED}", **spent)
        return step
    ended.update(spent)
    return ended


def polishable(posed: Posed, ended: Run) -> bool:
    """Whether a kept run is polished: a static problem's (a start-up's collocation has its own tolerance contract)
    IPOPT run that ended optimal, its design feasible in float64 or not (IPOPT at a looser ``--tol`` ends up to it
    outside a row, where the sweep's SQP lands on the vertex: wedge_paper in geometry mode at 3000 rpm and tol 1e-6,
    torque 5.5e-7 short, ``unverified`` alone and optimal in the sweep; review 20); unless its options say not to
    (the papers' sizing of a start-up: ``SolverOptions.polish``)."""
    return posed.start_up is None and posed.options.polish and ended["solver"] == "ipopt" and ended["ok"]
