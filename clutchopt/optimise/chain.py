"""Verdicts on primal-dual points of a posed problem, apart from the solver, and SQP re-solves chained for sweeps.

The KKT verdict checks what a solver reports (CasADi's SQP can stop at the start when handed a previous point's
multipliers); the curvature's, that a warm re-solve's KKT point is no saddle or maximum along a direction its holding
rows leave free (a Newton-type re-solve converges to the stationary point nearest its start). A chained SQP re-solves
a batch of sweep points in one CasADi call, and the chain verdict tests them all at once: their KKT conditions, their
curvature and whether ``Problem.solve``'s warm integer search (or its re-scaling) would go on from them. Every
function here is built once per posed problem (``Posed.built``) and called on NumPy arrays.
"""

from __future__ import annotations

import functools
import itertools

import casadi as ca
import numpy as np

from clutchopt.optimise.compiled import compiled_function, is_compiled
from clutchopt.optimise.in_place import InPlace
from clutchopt.optimise.posed import Posed, off_scale_entries
from clutchopt.optimise.verify import FEASIBILITY_TOL


def kkt(posed: Posed) -> ca.Function:
    """KKT conditions checked apart from the solver that reports them: the Lagrangian stationary, multipliers of
    the right sign, complementary to their constraints and bounds, the constraints held (CasADi's SQP can stop at
    the start when handed a previous point's multipliers, e.g. of a constraint that has become slack). A function
    (x, p, lam_x, lam_g, lbx, ubx) -> 1 where all hold, else 0 (also where a number is NaN)."""
    return posed.built("kkt", None, lambda _: kkt_of(posed.nlp, posed.n_ineq, posed.kkt_tolerance, "kkt"))


def kkt_of(nlp: dict, n_ineq: int, tol: float, name: str) -> ca.Function:
    """:func:`kkt`'s function for any scaled NLP (``x``, ``p``, ``f``, ``g``: rows ``g <= 0`` first, ``n_ineq`` of
    them, then equalities ``g = 0``), to the tolerance ``tol``."""
    x, g = nlp["x"], nlp["g"]
    lam_g = ca.SX.sym("lam_g", g.shape[0])
    gradient = ca.gradient(nlp["f"] + ca.dot(lam_g, g), x)
    lam_x, lbx, ubx = (ca.SX.sym(label, x.shape[0]) for label in ("lam_x", "lbx", "ubx"))
    ineq, g = lam_g[:n_ineq], g[:n_ineq]
    width = tol * ca.fmax(1.0, ca.fabs(x))
    wrong_bound = ca.logic_or(ca.logic_and(lam_x > tol, ubx - x > width),
                              ca.logic_and(lam_x < -tol, x - lbx > width))
    holds = [ca.fabs(gradient + lam_x) <= tol, ineq >= -tol, ineq * ca.fmax(-g, 0.0) <= tol,
             ca.logic_not(wrong_bound), g <= FEASIBILITY_TOL]
    failures = sum(ca.sum1(1 - condition) for condition in holds)  # a comparison with NaN fails
    return ca.Function(name, [x, nlp["p"], lam_x, lam_g, lbx, ubx], [failures == 0])


CURVATURE_PENALTY = 1e6  # on the rows and bounds that hold a point, against the scaled Lagrangian's curvature (of order
# 1e-2-1e2): a direction they leave free keeps its curvature in the penalised matrix, every other is lifted
CURVATURE_TOL = 1e-6  # the least curvature a minimum may show along a free direction (the penalty's coupling to a
# flat direction, an objective that does not price a variable, leaves about -1e-10 there)
NULL_SHARE = 1e-10  # an eigenvalue of the holding rows' sum a a^T below this share of its largest: a free direction


def curvature(posed: Posed, batched: bool = False) -> ca.Function:
    """(x, p, lam_x, lam_g, lbx, ubx) -> (H, P), each column by column (n * n rows each, H's first): H the Hessian in x
    of the Lagrangian f + lam_g . g, P the sum of a a^T over the gradient a of each row and bound that holds the
    point (a multiplier beyond the KKT tolerance; every equality row; every variable its bounds fix). Along a
    direction none of those changes to first order (P's null space) the curvature is H's: negative there, the point
    is no minimum (the second-order necessary condition fails: a saddle, or a maximum along it); :func:`curved_up`
    reads them. Built once per posed problem, static problems only (a start-up's collocation has hundreds of
    variables); ``batched`` (a sweep's chains), compiled where the batched sweep's NLP functions are
    (``clutchopt.optimise.compiled``: the ball's Hessian, 4,400 instructions, 17 us a point on CasADi's virtual
    machine)."""
    def build(_):
        nlp, tol = posed.nlp, posed.kkt_tolerance
        x, g = nlp["x"], nlp["g"]
        lam_x, lbx, ubx = (ca.SX.sym(label, x.shape[0]) for label in ("lam_x", "lbx", "ubx"))
        hessian = ca.hessian(posed.lagrangian, x)[0]
        jacobian = ca.jacobian(g, x)
        rows = ca.vertcat(ca.fabs(posed.lam_g[:posed.n_ineq]) > tol, ca.DM.ones(g.shape[0] - posed.n_ineq))
        bounds = ca.logic_or(ca.fabs(lam_x) > tol, lbx == ubx)
        held = ca.mtimes(jacobian.T, ca.diag(rows) @ jacobian) + ca.diag(bounds)
        function = ca.Function("curvature", [x, nlp["p"], lam_x, posed.lam_g, lbx, ubx],
                               [ca.densify(ca.vertcat(ca.vec(hessian), ca.vec(held)))])
        return compiled_function(function) if batched and is_compiled(posed.solver("sqp_chain")) else function

    return posed.built("curvature", batched, build)


def compiled_apart(posed: Posed) -> bool:
    """Whether a batched sweep evaluates :func:`curvature` compiled, in a call of its own (the ball's Hessian), not
    inside its chain verdict on CasADi's virtual machine (one call a chain: a one-point chain's call costs about as
    much as its checks)."""
    return curvature(posed, batched=True).is_a("External")


def leaves_free(posed: Posed, lam_x, lam_g, lbx, ubx) -> np.ndarray:
    """Per column (primal-dual points; a 1-D argument serves every column), whether fewer rows and bounds hold the
    point (as :func:`curvature` counts them) than it has variables: only there can a direction be left free, and
    :func:`curvature` say anything (a vertex is a minimum of its own; rows that hold it with gradients that
    depend on each other are counted each: such a vertex's free direction is not tested)."""
    tol = posed.kkt_tolerance
    lam_x, lam_g = (np.asarray(a, dtype=float).reshape(len(a), -1) for a in (lam_x, lam_g))
    fixed = (np.asarray(lbx) == np.asarray(ubx)).reshape(len(lam_x), -1)
    rows = (np.abs(lam_g[:posed.n_ineq]) > tol).sum(axis=0) + (lam_g.shape[0] - posed.n_ineq)
    return rows + ((np.abs(lam_x) > tol) | fixed).sum(axis=0) < lam_x.shape[0]


def curved_up(values: np.ndarray) -> np.ndarray:
    """Per column of :func:`curvature`'s values (H then P, n * n rows each), whether no direction the holding rows and
    bounds leave free has curvature below -CURVATURE_TOL (False where a number is not finite): H + CURVATURE_PENALTY P
    positive semidefinite to that, all at once (a direction they hold is lifted: Finsler's lemma); where it is not,
    H on P's null space itself (the penalty lifts a direction that holding rows whose gradients nearly depend on each
    other barely hold, least singular value 1e-3, by only about 1: ``ball_conveyor``'s 45 rows at a vertex)."""
    count, n = values.shape[1], int(round(np.sqrt(values.shape[0] / 2)))
    stack = values.T.reshape(count, 2, n, n)
    hessian, held = stack[:, 0], stack[:, 1]
    finite = np.isfinite(stack).all(axis=(1, 2, 3))
    least = np.full(count, -np.inf)
    if finite.any():
        least[finite] = np.linalg.eigvalsh(hessian[finite] + CURVATURE_PENALTY * held[finite])[:, 0]
    for j in np.flatnonzero(finite & (least < -CURVATURE_TOL)):  # (the exact test: rare)
        weights, vectors = np.linalg.eigh(held[j])
        free = vectors[:, weights <= NULL_SHARE * max(weights[-1], 1.0)]
        least[j] = np.linalg.eigvalsh(free.T @ hessian[j] @ free)[0] if free.shape[1] else np.inf
    return least >= -CURVATURE_TOL


def no_descent_curvature(posed: Posed, x, p, lam_x, lam_g, lbx, ubx) -> np.ndarray:
    """:func:`curved_up` at primal-dual points (one per column; a 1-D argument serves every column), by one mapped
    CasADi evaluation of :func:`curvature`."""
    count = max(np.shape(a)[1] if np.ndim(a) == 2 else 1 for a in (x, p, lam_x, lam_g, lbx, ubx))
    return curved_up(posed.mapped(curvature(posed), count)(x, p, lam_x, lam_g, lbx, ubx)[0])


def first_order_optimal(posed: Posed, x, p, lam_x, lam_g, lbx, ubx) -> np.ndarray:
    """The KKT verdict at primal-dual points (one per column; a 1-D argument serves every column), by one mapped
    CasADi evaluation (see :func:`kkt`)."""
    count = max(np.shape(a)[1] if np.ndim(a) == 2 else 1 for a in (x, p, lam_x, lam_g, lbx, ubx))
    return posed.mapped(kkt(posed), count)(x, p, lam_x, lam_g, lbx, ubx)[0][0] > 0.5


def chain_verdict(posed: Posed, integer: list[int], fixed: np.ndarray) -> ca.Function:
    """The tests of a re-solve along a sweep as one CasADi function (x, p, lam_x, lam_g, lbx, ubx, f, lower, upper)
    -> (kkt, moves, curvature): ``kkt`` its KKT verdict (:func:`kkt`); ``curvature`` :func:`curvature`'s matrix
    (:func:`curved_up` reads it; empty where the batch's curvature is compiled apart: :func:`compiled_apart`);
    ``moves`` 1 where ``Problem.solve``'s warm search would
    go on from this point. With free integers ``integer`` (fixed through their bounds in the re-solve; ``f`` its
    scaled objective, ``lower``, ``upper`` the case's bounds, SI): a neighbouring combination that
    ``integers.downhill`` steps to (each integer whose bound multiplier promises a gain beyond ``Posed.negligible``,
    one unit that way inside the bounds) and that breaks no constraint of the variables ``fixed`` (a mask, integers
    included) alone (``integers.violated_whatever_the_rest``); without, an optimum ``off_scale``. Built once per
    integers and mask; no start-up."""
    def build(number):
        nlp = posed.nlp
        x, p, lam_x, lam_g, lbx, ubx, f_hat = (ca.SX.sym(name, *shape) for name, shape in (
            ("x", nlp["x"].shape), ("p", nlp["p"].shape), ("lam_x", nlp["x"].shape), ("lam_g", nlp["g"].shape),
            ("lbx", nlp["x"].shape), ("ubx", nlp["x"].shape), ("f", (1, 1))))
        n, m = len(posed.names), nlp["p"].shape[0] - len(posed.names) - 1
        lower, upper = ca.SX.sym("lower", n), ca.SX.sym("upper", n)
        verdict = kkt(posed)(x, p, lam_x, lam_g, lbx, ubx)
        held = ca.DM.zeros(0, 1) if compiled_apart(posed) else curvature(posed)(x, p, lam_x, lam_g, lbx, ubx)
        if integer:
            moves = _search_moves(posed, integer, fixed, x, p, lam_x, f_hat, lower, upper, n, m)
        else:
            moves = ca.sum1(off_scale_entries(x[:n])) > 0
        return ca.Function(f"chain_verdict_{number}", [x, p, lam_x, lam_g, lbx, ubx, f_hat, lower, upper],
                           [verdict, moves, held])

    key = np.asarray(integer, dtype=np.int64).tobytes() + b"|" + np.asarray(fixed, dtype=bool).tobytes()
    return posed.built("verdict", key, build)


def _search_moves(posed: Posed, integer, fixed, x, p, lam_x, f_hat, lower, upper, n: int, m: int) -> ca.SX:
    """:func:`chain_verdict`'s test with integers, symbolic (see ``integers.downhill``)."""
    entered = np.zeros_like(fixed)
    entered[integer] = True
    _, fixed_values = posed.fixed_only(fixed, entered)
    scale = p[m:m + n]
    combo = [ca.floor(x[i] * scale[i] + 0.5) for i in integer]
    negligible = posed.negligible(f_hat)
    direction = [ca.if_else(ca.fabs(lam_x[i]) / scale[i] > negligible, ca.sign(lam_x[i]), 0) for i in integer]
    unit = ca.vertcat(p[:m], ca.DM.ones(n + 1))  # unit scales: x in SI
    moves = ca.SX(0)
    for step in itertools.product((-1.0, 0.0, 1.0), repeat=len(integer)):
        if not any(step):
            continue
        neighbour = [ca.fmin(ca.fmax(c + s, lower[i]), upper[i]) for c, s, i in zip(combo, step, integer)]
        stays = [nb == c for nb, c in zip(neighbour, combo)]  # no step, or one against a bound
        tried = functools.reduce(ca.logic_and, [ca.logic_or(stay, d == s) for stay, d, s in
                                                zip(stays, direction, step)],
                                 ca.logic_not(functools.reduce(ca.logic_and, stays)))
        design = [lower[i] for i in range(n)]
        for i, nb in zip(integer, neighbour):
            design[i] = nb
        g = fixed_values(ca.vertcat(*design), unit)
        excluded = ca.sum1(g > 10 * FEASIBILITY_TOL) > 0
        moves = ca.logic_or(moves, ca.logic_and(tried, ca.logic_not(excluded)))
    return moves


def chained_sqp(posed: Posed, count: int, method: str = "sqp_chain") -> InPlace:
    """``count`` SQP re-solves in one CasADi call, each started from the optimum of the one before, moved on by
    the secant predictor: (live, x, lam_x, lam_g, dx, dlam_x, dlam_g, ratio, p, lbx, ubx) -> (x, lam_x, lam_g,
    dx, dlam_x, dlam_g, f), one column per point (``live``, ``ratio``, ``p``, ``lbx``, ``ubx``: a column per
    point, or one for all; ``f`` the scaled objective). A column whose ``live`` is 0 pads a chain to its length
    and calls no solver (a conditional that evaluates one branch only: it hands on the point before, with no
    step and ``f`` 0). A point starts at x + ratio * dx, with dx the step between the two
    optima before it and ``ratio`` this point's step in the case against that one (0: no prediction), clipped
    to the bounds; its multipliers likewise, where that keeps their sign. Beside a smooth path this halves the
    SQP iterations (2 to 1, each with an exact Hessian: most of a re-solve on the ball clutch). ``method``:
    ``sqp_chain``, or ``sqp_search`` (its Hessian convexified). Built once per method and count, called on NumPy
    arrays."""
    def build(_):
        n_x, n_g = posed.nlp["x"].shape[0], posed.nlp["g"].shape[0]
        x, lam_x, dx, dlam_x, lbx, ubx = (ca.MX.sym(name, n_x) for name in ("x", "lam_x", "dx", "dlam_x", "lbx", "ubx"))
        lam_g, dlam_g = ca.MX.sym("lam_g", n_g), ca.MX.sym("dlam_g", n_g)
        ratio, p = ca.MX.sym("ratio"), ca.MX.sym("p", posed.nlp["p"].shape[0])

        def predicted(lam, step):  # a multiplier keeps its sign or starts at 0
            guess = lam + ratio * step
            return ca.if_else(lam * guess > 0, guess, 0)

        lbg, ubg = posed.sides.bounds(p)  # (a quantity held from both sides: one row, optimise/two_sided.py)
        out = posed.solver(method)(x0=ca.fmin(ca.fmax(x + ratio * dx, lbx), ubx), lam_x0=predicted(lam_x, dlam_x),
                                   lam_g0=posed.sides.posed(predicted(lam_g, dlam_g), p), p=p, lbx=lbx, ubx=ubx,
                                   lbg=lbg, ubg=ubg)
        out = {**out, "lam_g": posed.sides.named(out["lam_g"], p)}
        inputs = [x, lam_x, lam_g, dx, dlam_x, dlam_g, ratio, p, lbx, ubx]
        step = ca.Function("sqp_step", inputs, [out["x"], out["lam_x"], out["lam_g"], out["x"] - x,
                                                out["lam_x"] - lam_x, out["lam_g"] - lam_g, out["f"]])
        padded = ca.Function("sqp_padded", inputs, [x, lam_x, lam_g, ca.MX.zeros(n_x), ca.MX.zeros(n_x),
                                                    ca.MX.zeros(n_g), ca.MX.zeros(1)])
        live = ca.Function.if_else("sqp_live", step, padded)  # inputs: live, then the step's
        return InPlace(live.mapaccum(method, count, list(range(1, 7)), list(range(6))))

    return posed.built("chain", (method, count), build)
