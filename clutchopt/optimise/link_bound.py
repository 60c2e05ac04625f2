"""An elastic link's integer choice refuted before its start-up NLP is solved.

The link's start is one locked phase: motor and machine run up as one, (J + J_m) dw/dt = T_m - T_c, whatever the
coupling's design, and at each collocation node the link carries the locked drive's share of the torque,
(J_m T_c + J T_m) / (J + J_m). The node speeds and times are therefore the same in every point of the NLP that
meets its drive's rows (those no design variable enters); a solved point's are those of every other. At them the
coupling's law bounds the stress from below for the integers and fixed variables alone (``ElasticLaw.least_stress``:
the cable's with the least pull its weights' row weight_turns_cable admits, whatever their thread's lead angle);
where that bound is above the stress limit at some node, no design of the choice meets
``link_stress`` and its NLP is not solved (cable_motor_start: 6 cables at 376.0 MPa against 350, 35 IPOPT
iterations to ``Infeasible_Problem_Detected``; at the limit 7 cables' start moved in, 314.22 MPa, 7 cables at 341.4,
19, and 8 cables at 314.243, 21). The same least stress bounds modifier adaptation's corrected row from below
(:func:`clutchopt.optimise.modifier.no_lighter`). ``posed``: the posed problem (``Posed``), ``data`` its
``ScaledData`` (not imported: the posed problem imports modifier adaptation, which imports this).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from clutchopt.model import namespace
from clutchopt.optimise.sparsity import entries
from clutchopt.optimise.verify import FEASIBILITY_TOL
from clutchopt.start_up.drive import Drive

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
    whatever its variables not fixed there (``ElasticLaw.least_stress``), where ``x0`` meets the drive's rows at
    ``data.p``; None where no such bound is had (not an elastic link, a robust design's corners, another point's
    seed)."""
    block, law = posed.start_up, posed.formulation.speed_law
    if (block is None or not block.s.elastic or getattr(law, "least_stress", None) is None
            or posed.formulation.start_up_view is not None):
        return None
    if np.max(np.abs(drive_rows(posed)(x0, data.p).full()), initial=0.0) > FEASIBILITY_TOL:
        return None  # (a seed from another point: a sweep's neighbour, the sizing's simulated start)
    n = len(data.scale)
    fixed = lbx[:n] == ubx[:n]
    x = namespace({name: lbx[i] * data.scale[i] if fixed[i] else np.nan for i, name in enumerate(posed.names)})
    _, times, speeds, *_ = (path.full().ravel()[1:] for path in posed.start_up_figures(x0, data.p))  # (the
    # locked phase's start, at rest and untwisted, is no node of the link's rows)
    torque = Drive(block.s, law, x, data.params).carried(speeds, times)
    return float(np.max(law.least_stress(x, data.params, speeds, torque)))


def drive_rows(posed) -> ca.Function:
    """The NLP's equality rows no design variable enters (the drive's collocation and its phase's end), normalised,
    as a function of (x, p); built once a problem."""
    def build(number):
        g = posed.nlp["g"][posed.n_ineq:]
        design = entries(ca.jacobian_sparsity(g, posed.nlp["x"]))[:, : len(posed.names)].any(axis=1)
        rows = [int(i) for i in np.flatnonzero(~design)]
        return ca.Function(f"drive_rows_{number}", [posed.nlp["x"], posed.nlp["p"]], [ca.densify(g[rows])])

    return posed.built("drive_rows", None, build)
