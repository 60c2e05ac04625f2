"""Infeasibility diagnosis of a posed problem: when IPOPT fails, an elastic problem (min sum of slacks on the
normalised constraints) names the requirements that cannot hold together and by how much the least relaxation
misses."""

from __future__ import annotations

import time

import casadi as ca
import numpy as np

from clutchopt.optimise.posed import Posed
from clutchopt.optimise.solution import START_UP_MU_INIT, Diagnosis
from clutchopt.optimise.verify import FEASIBILITY_TOL

ELASTIC_ITERATIONS = 200  # a start-up's elastic problem: over the four start-up sweeps over driven_inertia (0.6x-1.4x)
# every one converges within 19 iterations; started as it was before SLACK_MARGIN, those that did not converge ran on
# to the start-up's 500 or found no point meeting the dynamics (Infeasible_Problem_Detected) after 88-474
# (ball_motor_start at 509 kg m^2: 474, 4-10 s)
SLACK_MARGIN = 0.1  # each slack starts this far (relative: the rows are normalised) above its row's violation at the
# failed run's point, where the elastic problem starts, and at most at 1, where every slack had started (a row
# violated by more there, or not a number at that point: docs/start_up.md, "The elastic problem's start")
ELASTIC_MU_INIT = START_UP_MU_INIT  # a start-up's elastic problem: its barrier starts where its cold solve's does


def _elastic(posed: Posed) -> ca.Function:
    """The elastic problem's IPOPT solver: slacks on the inequalities (the start-up's dynamics stay equalities); a
    start-up's barrier starts at ELASTIC_MU_INIT: the elastic problem starts at the failed run's point, its states on
    a start, its slacks just above their rows' violations (:func:`diagnose`)."""
    def build(_):
        n_g, nlp = posed.n_ineq, posed.nlp
        slack = ca.SX.sym("slack", n_g)
        g = nlp["g"]
        elastic = {"x": ca.vertcat(nlp["x"], slack), "p": nlp["p"], "f": ca.sum1(slack),
                   "g": ca.vertcat(g[:n_g] - slack, g[n_g:])}
        options = posed.solver_options.ipopt()
        if posed.start_up is not None:
            options["ipopt.max_iter"] = min(options["ipopt.max_iter"], ELASTIC_ITERATIONS)
            options["ipopt.mu_init"] = ELASTIC_MU_INIT
        return ca.nlpsol("elastic", "ipopt", elastic, options)

    return posed.built("elastic", None, build)


def whatever_the_design(posed: Posed, p_vector, x0) -> Diagnosis | None:
    """The proven verdict where a requirement no design variable enters (``posed.fixed_rows``) is broken at the case's
    values ``p_vector`` (nothing to relax but the case itself), or two hold one quantity from both sides with no room
    between (``TwoSided.conflicts``: the ball's K5 at least the paper's and at most the case's width_ratio_max below
    it), naming each such requirement; else None."""
    conflicts = posed.sides.conflicts(p_vector, FEASIBILITY_TOL)
    if not posed.fixed_rows and not conflicts:
        return None
    row_names, row_senses = posed.row_names, posed.row_senses
    g0 = np.array(posed.constraint_values(x0, p_vector)).ravel()
    given = sorted({row_names[i] for i in posed.fixed_rows if g0[i] > FEASIBILITY_TOL}, key=row_names.index)
    if not given and not conflicts:
        return None
    return Diagnosis("infeasible", "infeasible whatever the design: " + ", ".join(
        [f"{name} ({'over' if row_senses[row_names.index(name)] == '<=' else 'short of'} its limit by "
         f"{g0[row_names.index(name)]:.3g} relative)" for name in given]
        + [f"{row_names[k]} and {row_names[f]} (one quantity held from both sides, their limits apart by {gap:.3g} "
           f"relative)" for k, f, gap in conflicts]), 0.0, proven=True)


def _slacks(posed: Posed, p_vector, lbx, ubx, x0) -> np.ndarray:
    """The elastic problem's first slacks: each row's violation at ``x0`` (within its bounds) plus SLACK_MARGIN, at most
    1; 1 where the row is not a number there (the wedge's engagement speeds at corners of its geometry box)."""
    with np.errstate(invalid="ignore"):
        g = np.array(posed.constraint_values(np.clip(x0, lbx, ubx), p_vector)).ravel()[: posed.n_ineq]
        return np.where(np.isfinite(g), np.minimum(np.maximum(g, 0.0) + SLACK_MARGIN, 1.0), 1.0)


def diagnose(posed: Posed, p_vector, lbx, ubx, x0, scale) -> Diagnosis:
    """Elastic relaxation: min sum(s) s.t. g(x) <= s, s >= 0 on the inequalities, from ``x0``, each slack from
    SLACK_MARGIN above its row's violation there (x0 within its bounds, as IPOPT starts), at most 1 (:func:`_slacks`).
    Positive slacks name the conflict; the least relaxation is a local minimum, found from this start (no proof).
    An elastic problem that does not converge (a start-up's within ELASTIC_ITERATIONS) says so: what it names is where
    it stopped, no feasible point is claimed from it, and it names no reason (``violated``) for a run of points to
    share."""
    n_g, row_names, row_senses = posed.n_ineq, posed.row_names, posed.row_senses
    if (given := whatever_the_design(posed, p_vector, x0)) is not None:
        return given
    elastic = _elastic(posed)
    started = time.perf_counter()
    slack_bounds = np.zeros(n_g), np.full(n_g, np.inf)
    result = elastic(x0=np.concatenate([x0, _slacks(posed, p_vector, lbx, ubx, x0)]), p=p_vector, lbg=posed.lbg,
                     ubg=0.0, lbx=np.concatenate([lbx, slack_bounds[0]]), ubx=np.concatenate([ubx, slack_bounds[1]]))
    seconds = time.perf_counter() - started
    stats = elastic.stats()
    stopped = "" if stats["success"] else (f" (where the elastic problem stopped, not converged: "
                                           f"{stats['return_status']} after {stats['iter_count']} iterations)")
    slacks = np.array(result["x"]).ravel()[len(lbx):]
    lam_g = np.array(result["lam_g"]).ravel()[:n_g]
    x = np.array(result["x"]).ravel()[: len(lbx)]
    nearest = {v.name: float(value) for v, value in zip(posed.formulation.variables, x[: len(scale)] * scale)}
    if slacks.sum() <= 10 * FEASIBILITY_TOL and not stopped:  # a feasible point only where it converged
        return Diagnosis("solver_failed", "IPOPT did not converge, yet a feasible point exists (elastic check); "
                                          "try other bounds or a start point", seconds, least=0.0, nearest=nearest,
                         point=x)
    worst: dict[str, float] = {}
    binding: list[str] = []
    for name, s, lam in zip(row_names, slacks, lam_g):
        worst[name] = max(worst.get(name, 0.0), s)
        if s <= 10 * FEASIBILITY_TOL and lam > 1e-6 and name not in binding:
            binding.append(name)
    senses = dict(zip(row_names, row_senses))
    over = [name for name, s in worst.items() if s > 10 * FEASIBILITY_TOL]
    violated = [f"{name} ({'over' if senses[name] == '<=' else 'short of'} its limit by {worst[name]:.3g} relative)"
                for name in over]
    binding = [name for name in binding if worst[name] <= 10 * FEASIBILITY_TOL]
    at_bounds = []
    lam_x = np.array(result["lam_x"]).ravel()[: len(lbx)]
    for i, v in enumerate(posed.formulation.variables):
        if lbx[i] < ubx[i] and abs(lam_x[i]) > 1e-6:
            side = "upper" if lam_x[i] > 0 else "lower"
            at_bounds.append(f"{v.name} at its {side} bound ({v.show(x[i] * scale[i])})")
        elif lbx[i] == ubx[i] and abs(lam_x[i]) > 1e-6:
            at_bounds.append(f"{v.name} fixed at {v.show(x[i] * scale[i])}")
    others = binding + at_bounds
    text = "infeasible: cannot satisfy " + ", ".join(violated)
    if others:
        text += " together with " + ", ".join(others)
    return Diagnosis("infeasible", text + stopped, seconds, least=float(slacks.sum()), nearest=nearest,
                     violated=() if stopped else tuple(over))
