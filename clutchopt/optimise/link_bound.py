"""An elastic link's integer choice refuted before its start-up NLP is solved.

The link's start is one locked phase: motor and machine run up as one, (J + J_m) dw/dt = T_m - T_c, whatever the
coupling's design, and at each collocation node the link carries the locked drive's share of the torque,
(J_m T_c + J T_m) / (J + J_m). The node speeds and times are therefore the same in every point of the NLP that meets
its drive's rows (those no design variable enters); a solved point's are those of every other, and a seed off the rows
(a sweep's point before's optimum: another drive's nodes) is brought onto them (:func:`on_the_drive`). At them the
coupling's law bounds the stress from below for the integers and fixed variables alone (``ElasticLaw.least_stress``:
the cable's with the least pull its weights' row weight_turns_cable admits, whatever their thread's lead angle); where
that bound is above the stress limit at some node, no design of the choice meets ``link_stress`` and its NLP is not
solved (cable_motor_start: 6 cables at 376.0 MPa against 350, 35 IPOPT iterations to ``Infeasible_Problem_Detected``;
at the limit 7 cables' start moved in, 314.22 MPa, 7 cables at 341.4, 19, and 8 cables at 314.243, 21). The same least
stress bounds modifier adaptation's corrected row from below (:func:`clutchopt.optimise.modifier.no_lighter`).
``posed``: the posed problem (``Posed``), ``data`` its ``ScaledData`` (not imported: the posed problem imports
modifier adaptation, which imports this).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from clutchopt.model import namespace
from clutchopt.optimise.sparsity import entries
from clutchopt.optimise.verify import FEASIBILITY_TOL
from clutchopt.start_up.drive import Drive

NEWTON_STEPS = 8  # Newton's steps that bring a seed onto the drive's rows (:func:`on_the_drive`; the cable's
# neighbours take 1-3)
MARGIN = 1e-6  # relative: the bound over the limit by far more than the nodes' speeds can be off where the drive's
# rows are met to FEASIBILITY_TOL (normalised by the speed and the torque scales)


def refuted(posed, data, x0: np.ndarray, lbx: np.ndarray, ubx: np.ndarray) -> list[str]:
    """``["link_stress"]`` where the integers fixed by ``lbx == ubx`` cannot carry the locked drive's torque at the
    nodes of the point ``x0`` within the stress limit (``x0`` meeting the drive's rows at ``data.p``: its nodes are
    the NLP's), else ``[]``. Only the plain NLP: not a robust design's corners, not modifier adaptation's limits
    (the caller's: ``integers.fixing``)."""
    least = least_stress(posed, data, x0, lbx, ubx)
    return ["link_stress"] if least is not None and least > data.params.max_link_stress * (1.0 + MARGIN) else []


def least_stress(posed, data, x0: np.ndarray, lbx: np.ndarray, ubx: np.ndarray) -> float | None:
    """The least peak stress (Pa) of every design of the box ``lbx``..``ubx`` (scaled) at the nodes of ``x0``
    whatever its variables not fixed there (``ElasticLaw.least_stress``), ``x0`` moved onto the drive's rows at
    ``data.p`` where it does not meet them (:func:`on_the_drive`: another point's seed, a sweep's neighbour); None
    where no such bound is had (not an elastic link, a robust design's corners, a seed not brought onto the rows)."""
    block, law = posed.start_up, posed.formulation.speed_law
    if (block is None or not block.s.elastic or getattr(law, "least_stress", None) is None
            or posed.formulation.start_up_view is not None):
        return None
    x0 = on_the_drive(posed, x0, data.p, lbx, ubx)
    if x0 is None:
        return None  # (no point of the box near the seed meets the drive's rows: no nodes to go by)
    n = len(data.scale)
    fixed = lbx[:n] == ubx[:n]
    x = namespace({name: lbx[i] * data.scale[i] if fixed[i] else np.nan for i, name in enumerate(posed.names)})
    _, times, speeds, *_ = (path.full().ravel()[1:] for path in posed.start_up_figures(x0, data.p))  # (the
    # locked phase's start, at rest and untwisted, is no node of the link's rows)
    torque = Drive(block.s, law, x, data.params).carried(speeds, times)
    return float(np.max(law.least_stress(x, data.params, speeds, torque)))


def on_the_drive(posed, x0: np.ndarray, p: np.ndarray, lbx: np.ndarray, ubx: np.ndarray) -> np.ndarray | None:
    """``x0`` (scaled) where it meets the drive's rows at ``p`` to FEASIBILITY_TOL; else moved onto them by Newton's
    steps on those rows alone (over the variables they enter that the box leaves free, as many as the rows: the
    drive's states and times, no design variable), the point they reach where it meets them to a tenth of
    FEASIBILITY_TOL within the box ``lbx``..``ubx``: a point of the NLP on the drive, whose nodes are every such
    point's. None where the steps do not get there (NEWTON_STEPS, a singular step) or the rows are not square in
    those variables. A sweep's point seeds its warm runs with the point before's optimum, whose nodes are another
    drive's: cable_motor_start over its driven inertia, 8 cables' warm run at the limit 7 cables' start moved in
    (313.9-321.8 MPa) ended infeasible in 19-20 IPOPT iterations at three of the bench's 20 points; their least
    stress at this drive's nodes, 315.0-322.9 MPa, refutes them unsolved."""
    rows = posed.mapped(drive_rows(posed), 1)  # (on NumPy arrays)
    met = rows(x0, p)[0].ravel()
    if not np.max(np.abs(met), initial=0.0) > FEASIBILITY_TOL:
        return x0
    jacobian, entered = drive_jacobian(posed)
    jacobian = posed.mapped(jacobian, 1)
    moved = lbx[entered] < ubx[entered]
    columns, x = entered[moved], np.array(x0, dtype=float)
    if len(columns) != len(met):
        return None  # (the rows do not determine the variables they enter: no nodes every point shares)
    for _ in range(NEWTON_STEPS):
        try:
            x[columns] -= np.linalg.solve(jacobian(x, p)[0][:, moved], met)
        except np.linalg.LinAlgError:
            return None
        met = rows(x, p)[0].ravel()
        if not np.all(np.isfinite(met)):
            return None
        if np.max(np.abs(met), initial=0.0) <= FEASIBILITY_TOL / 10:
            return x if np.all((x >= lbx) & (x <= ubx)) else None
    return None


def drive_jacobian(posed) -> tuple[ca.Function, np.ndarray]:
    """The Jacobian of the drive's rows (:func:`drive_rows`) in the variables they enter, dense, as a function of
    (x, p), and those variables (indices into x); built once a problem."""
    def build(number):
        x, p = posed.nlp["x"], posed.nlp["p"]
        g = drive_rows(posed)(x, p)
        entered = np.flatnonzero(entries(ca.jacobian_sparsity(g, x)).any(axis=0))
        jacobian = ca.densify(ca.jacobian(g, x)[:, [int(i) for i in entered]])
        return ca.Function(f"drive_jacobian_{number}", [x, p], [jacobian]), entered

    return posed.built("drive_jacobian", None, build)


def drive_rows(posed) -> ca.Function:
    """The NLP's equality rows no design variable enters (the drive's collocation and its phase's end), normalised,
    as a function of (x, p); built once a problem."""
    def build(number):
        g = posed.nlp["g"][posed.n_ineq:]
        design = entries(ca.jacobian_sparsity(g, posed.nlp["x"]))[:, : len(posed.names)].any(axis=1)
        rows = [int(i) for i in np.flatnonzero(~design)]
        return ca.Function(f"drive_rows_{number}", [posed.nlp["x"], posed.nlp["p"]], [ca.densify(g[rows])])

    return posed.built("drive_rows", None, build)
