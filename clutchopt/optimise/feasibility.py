"""Whether a posed problem with its integers fixed has a design, decided by SQP on its feasibility problem.

Where a batched sweep's re-solve fails at an integer combination (the chained SQP at the batch's ball rows, as the
power rises past what they carry), ``Problem.solve``'s search would hand that combination to IPOPT, whose answer is
most often ``Infeasible_Problem_Detected``: its restoration phase ended at a local minimum of the constraint
violation. The same verdict comes from the least largest violation, with the design variables in their box (the
fixed integers' bounds closed)::

    minimise t   over (x_hat, t),   subject to   g_i(x_hat, p) <= t (the normalised inequality rows),
                                                 -t <= h_j(x_hat, p) <= t (equalities),   t >= 0,   lbx <= x_hat <= ubx,

solved by CasADi's SQP (``qrqp``, its Hessian's negative eigenvalues clipped) from the previous point's optimum,
with t starting at the largest violation there, so that every QP has a solution. At a KKT point of this problem,
checked apart from the solver (``chain.kkt_of``: the multipliers mu of the rows at t sum to one, since d/dt of the
Lagrangian is 1 - sum mu, and sum mu_i grad g_i + lam_x = 0), t* is a local minimum of the largest violation:
where it exceeds :data:`INFEASIBLE_MARGIN`, no design is near, the claim IPOPT's status makes, here at a few QP
solves (0.3 ms on the ball clutch) instead of a cold IPOPT solve and its restoration phase (5-15 ms). Elsewhere (t*
within the margin, or no verified KKT point) the caller asks IPOPT as before. The rows are relative margins, so t*
is the least relative violation of the worst row.

The verdict asks whether multipliers exist that make the SQP's last point a KKT point, not whether qrqp's are
they: where the SQP stops on a search direction too small, its multipliers may miss stationarity by more than the
tolerance (the ball compressor at 0.75 GPa with 6 rows: by 3.8e-6 on a bound's multiplier of -33.5, t* = 0.004),
and those of its active rows and bounds are taken again by least squares on the stationarity conditions
(:func:`_refitted`), the same verdict asked of them (residual 1e-14 there: IPOPT, asked instead, took 5 ms to end
``Infeasible_Problem_Detected``).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import casadi as ca
import numpy as np

from clutchopt.optimise.chain import kkt_of
from clutchopt.optimise.in_place import InPlace
from clutchopt.optimise.integers import INFEASIBLE
from clutchopt.optimise.posed import Posed
from clutchopt.optimise.verify import FEASIBILITY_TOL

INFEASIBLE_MARGIN = 1e-6  # least relative violation (100 times verify's FEASIBILITY_TOL) read as no design: below it
# the combination is borderline and IPOPT decides (on the ball's rows the least violations at a change were 1e-3 to
# 3e-2, each point's power 2.4 % above the one before)
CERTIFICATE_TOL = INFEASIBLE_MARGIN / 10  # the KKT verdict's tolerance on the feasibility problem: a stationarity
# residual eps lets the largest violation fall by about eps per unit of scaled step to first order, far below t* over a
# box of scaled width O(1) (the SQP stops with "search direction too small" at residuals of 1e-9 on the ball's rows,
# just above the design problem's 10 tol, at the same t*)
LOCALLY_INFEASIBLE = "infeasible (least violation {:.2g}, SQP)"  # the integer_search entry's status


def infeasible(status: str) -> bool:
    """A solve's status that says no design is near: IPOPT's ``Infeasible_Problem_Detected`` or the least violation's
    (:data:`LOCALLY_INFEASIBLE`)."""
    return status == INFEASIBLE or status.startswith(LOCALLY_INFEASIBLE[:LOCALLY_INFEASIBLE.index("{")])


def least_violation_solver(posed: Posed) -> InPlace:
    """(x0, p, lbx, ubx) -> (t*, verified, x*, lam_x*, lam_g*): the least largest violation from ``x0`` (scaled,
    clipped to the box), whether the SQP's answer is a KKT point of the feasibility problem with the SQP's
    multipliers (1, else 0), where (scaled), and those multipliers (of the bounds on (x, t) and of the rows). One
    CasADi call, built once per posed problem (no start-up: its collocation is solved point by point)."""
    def build(_):
        nlp, n_ineq = posed.nlp, posed.n_ineq
        x, p, g = nlp["x"], nlp["p"], nlp["g"]
        problem, name, verdict = _feasibility_problem(posed)
        solver = ca.nlpsol(name, "sqpmethod", problem, {**posed.options.sqp(), "convexify_strategy": "eigen-clip"})
        largest = ca.Function("largest", [x, p], [ca.fmax(0.0, ca.mmax(ca.vertcat(g[:n_ineq], ca.fabs(g[n_ineq:]))))])
        # (the symbolic twin of integers.least_violation, a float)
        x0, p_in, lbx, ubx = (ca.MX.sym(label, *shape) for label, shape in (
            ("x0", x.shape), ("p", p.shape), ("lbx", x.shape), ("ubx", x.shape)))
        start = ca.fmin(ca.fmax(x0, lbx), ubx)
        lower, upper = ca.vertcat(lbx, 0.0), ca.vertcat(ubx, ca.inf)
        out = solver(x0=ca.vertcat(start, largest(start, p_in)), p=p_in, lbx=lower, ubx=upper, lbg=-ca.inf, ubg=0.0)
        verified = verdict(out["x"], p_in, out["lam_x"], out["lam_g"], lower, upper)
        return InPlace(ca.Function(name, [x0, p_in, lbx, ubx], [out["f"], verified, out["x"][: x.shape[0]],
                                                                 out["lam_x"], out["lam_g"]]))

    return posed.built("least_violation", None, build)


def _feasibility_problem(posed: Posed) -> tuple[dict, str, ca.Function]:
    """The feasibility problem of ``posed`` over (x, t) (the module text), its functions' name and its KKT verdict
    ``chain.kkt_of`` (the solver's and the refit's), built once per posed problem."""
    def build(_):
        nlp, n_ineq = posed.nlp, posed.n_ineq
        g, t = nlp["g"], ca.SX.sym("t")
        rows = ca.vertcat(g[:n_ineq] - t, g[n_ineq:] - t, -g[n_ineq:] - t)
        problem = {"x": ca.vertcat(nlp["x"], t), "p": nlp["p"], "f": t, "g": rows}
        name = f"{posed.formulation.coupling}_{posed.formulation.mode}_feasibility"
        return problem, name, kkt_of(problem, rows.shape[0], CERTIFICATE_TOL, f"{name}_kkt")

    return posed.built("feasibility_problem", None, build)


def _refitted(posed: Posed, xt: np.ndarray, p: np.ndarray, lam_x: np.ndarray, lam_g: np.ndarray, lbx: np.ndarray,
              ubx: np.ndarray) -> bool:
    """Whether the feasibility problem's point ``xt`` (x scaled, then t) is a KKT point with the multipliers of the
    rows and bounds active in the SQP's ``lam_g``, ``lam_x`` (non-zero) taken again by least squares on its
    stationarity, 1 + J_A' mu + lam_B = 0 in t's row and 0 in the others (the verdict of
    :func:`least_violation_solver` on them)."""
    if not np.all(np.isfinite(xt)):
        return False
    jacobian, verdict = posed.built("least_violation_refit", None, lambda _: _refit_functions(posed))
    rows, bounds = np.flatnonzero(lam_g > 0), np.flatnonzero(lam_x != 0)
    try:
        normals = np.hstack([jacobian(xt, p)[0][rows].T, np.eye(len(xt))[:, bounds]])
        gradient = np.zeros(len(xt))
        gradient[-1] = 1.0  # (of the objective t)
        mu = np.linalg.lstsq(normals, -gradient, rcond=None)[0]
        lam_g, lam_x = np.zeros_like(lam_g), np.zeros_like(lam_x)
        lam_g[rows], lam_x[bounds] = mu[: len(rows)], mu[len(rows):]
        return bool(verdict(xt, p, lam_x, lam_g, np.append(lbx, 0.0), np.append(ubx, np.inf))[0][0, 0] > 0.5)
    except (RuntimeError, np.linalg.LinAlgError):  # (an evaluation error inside CasADi; no least squares)
        return False


def _refit_functions(posed: Posed) -> tuple[InPlace, InPlace]:
    """(xt, p) -> the feasibility problem's rows' Jacobian in (x, t); (xt, p, lam_x, lam_g, lower, upper) -> its
    KKT verdict (built once per posed problem, on the first refit)."""
    problem, name, verdict = _feasibility_problem(posed)
    jacobian = ca.Function(f"{name}_jacobian", [problem["x"], problem["p"]],
                           [ca.densify(ca.jacobian(problem["g"], problem["x"]))])
    return InPlace(jacobian), InPlace(verdict)


class Least(NamedTuple):
    """The least largest violation found from a start: its value t*, whether it is a verified KKT point of the
    feasibility problem, and where (scaled; None after an evaluation error inside CasADi)."""

    violation: float
    verified: bool
    x: np.ndarray | None

    @property
    def without_design(self) -> bool:
        """The box has no design near: a verified local minimum above :data:`INFEASIBLE_MARGIN`."""
        return self.verified and self.violation > INFEASIBLE_MARGIN

    @property
    def feasible(self) -> bool:
        """A design that meets every row (to verify's FEASIBILITY_TOL) was found: ``x``."""
        return self.verified and self.violation <= FEASIBILITY_TOL


def least(posed: Posed, x0: np.ndarray, p: np.ndarray, lbx: np.ndarray, ubx: np.ndarray) -> Least:
    """The least largest violation in the box ``lbx``, ``ubx`` (scaled, integers fixed) from ``x0``
    (:func:`least_violation_solver`; verified with the SQP's multipliers or, failing them, with those refitted on
    its active set: :func:`_refitted`)."""
    try:
        t, verified, x, lam_x, lam_g = least_violation_solver(posed)(x0, p, lbx, ubx)
    except RuntimeError:  # an evaluation error inside CasADi
        return Least(math.nan, False, None)
    verified = verified[0, 0] > 0.5 or _refitted(posed, np.append(x[:, 0], t[0, 0]), p, lam_x[:, 0], lam_g[:, 0],
                                                  lbx, ubx)
    return Least(float(t[0, 0]), bool(verified), x[:, 0])
