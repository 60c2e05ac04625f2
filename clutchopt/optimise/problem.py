"""A formulation turned into a CasADi/IPOPT problem: built once, solved many times with new case data.

The NLP sees scaled numbers only: each design variable is ``x = s * x_hat`` with the scale ``s`` a
parameter (taken from the start point of each solve), every constraint is normalised by its own scale
(relative margin), and the objective is divided by its value at the start point. Case values, variable
scales and the objective scale are all NLP parameters, so one built problem serves every case of its
formulation at every size.

Integer variables, fixed through their bounds at each integer tried: a first solve rounds its relaxation, a
re-solve starts at the previous point's integers. From there the search steps to a neighbouring integer only in
a direction in which the fixed integer's bound multiplier says the objective falls, and stops when a step does
not lower it or the relaxation's objective (a bound on every integer choice) is reached; an integer choice that
violates a constraint of fixed variables alone (e.g. cable stress against the cable count) is excluded without a
solve. Where f*(n) is convex in the integers (the premise of rounding a relaxation at all) this finds the best of
the relaxation's floor and ceiling, in about one solve per point along a sweep. Should the first integers fail,
the floor and ceiling of the relaxation (then one further) are tried as before.

Sensitivities: at the optimum, the elasticity of the objective to every case quantity and every fixed design
variable, d ln f* / d ln p, from the gradient of the Lagrangian in the parameters (envelope theorem), with the
multipliers the solver returns. A built problem also re-solves warm: ``solve(case, warm=previous)`` starts from a
previous optimum, keeps its scales and hands its multipliers to CasADi's SQP method (dense active-set QPs,
``qrqp``: next to a known optimum a few Newton steps; 1.5-3.7x faster than warm IPOPT on these small NLPs), whose KKT
point is checked apart from it; then to IPOPT (``warm_start_init_point``, small initial barrier parameter); should
both fail, the cold solve from the case's own start follows. Each solver is built on first use. Sweeps chain such
SQP re-solves in one CasADi call (``chained_sqp``) and check them together (``clutchopt.optimise.batch``).

Infeasibility: when IPOPT fails, an elastic problem (min sum of slacks on the normalised constraints) names
the requirements that cannot hold together and by how much the least relaxation misses.
"""

from __future__ import annotations

import functools
import itertools
import math
import time
from dataclasses import dataclass, field, replace
from types import SimpleNamespace
from typing import NamedTuple

import casadi as ca
import numpy as np

from clutchopt.cases import Case
from clutchopt.backend import fmax
from clutchopt.formulations.start_up import with_start_up
from clutchopt.model import Formulation, Output, namespace
from clutchopt.optimise.compiled import compiled_solver
from clutchopt.optimise.in_place import InPlace
from clutchopt.optimise.start_up import (
    BACK_OFF_STEPS,
    MAX_INTERVALS,
    MESH_STEPS,
    StartUpBlock,
    Structure,
    initial_states,
    start_up_report,
    tightened_limits,
)
from clutchopt.units import si_unit
from clutchopt.optimise.verify import (
    FEASIBILITY_TOL,
    ConstraintCheck,
    check_design,
    evaluate_objective,
    evaluate_outputs,
)


@dataclass(frozen=True)
class SolverOptions:
    tol: float = 1e-10
    max_iter: int = 3000
    warm_sqp: bool = True  # warm re-solves try SQP before warm IPOPT (False: warm IPOPT alone, for comparison)

    def ipopt_warm(self) -> dict:
        """IPOPT started from a previous primal-dual point, barely pushed off the bounds."""
        push = {f"ipopt.warm_start_{name}": 1e-9 for name in (
            "bound_push", "bound_frac", "mult_bound_push", "slack_bound_push", "slack_bound_frac")}
        return {**self.ipopt(), "ipopt.warm_start_init_point": "yes", "ipopt.mu_init": 1e-6, **push}

    def sqp(self) -> dict:
        """CasADi's SQP method with its dense active-set QP solver (qrqp), for re-solves beside a known optimum:
        no barrier to drive down, so a small problem's re-solve costs a few QP solves."""
        quiet = {"print_header": False, "print_iteration": False, "print_status": False, "print_time": False}
        return {**quiet, "qpsol": "qrqp", "qpsol_options": {"print_iter": False, "print_header": False,
                                                            "error_on_fail": False},
                "tol_pr": self.tol, "tol_du": self.tol, "max_iter": 30, "error_on_fail": False, "calc_lam_p": False}

    def sqp_chain(self) -> dict:
        """SQP in a chained batch: at most 10 iterations (a warm re-solve takes 2 or 3; one that does not converge
        leaves the batch for ``Problem.solve``), so that the points after a failed one cost little."""
        return {**self.sqp(), "max_iter": 10}

    def sqp_search(self) -> dict:
        """SQP for the integer search in a batch, whose start may be off the optimum (a relaxation from the
        previous integers): the Hessian's negative eigenvalues clipped, so that a first step does not overshoot (3
        iterations instead of 10 on the cable's relaxations; a regularised Hessian stalled at one of them)."""
        return {**self.sqp_chain(), "convexify_strategy": "eigen-clip"}

    def ipopt(self) -> dict:
        return {
            "ipopt.tol": self.tol,
            "ipopt.constr_viol_tol": self.tol,
            "ipopt.acceptable_tol": self.tol * 1e2,
            "ipopt.acceptable_constr_viol_tol": self.tol * 1e2,
            "ipopt.max_iter": self.max_iter,
            "ipopt.bound_relax_factor": 1e-9,
            "ipopt.print_level": 0,
            "ipopt.sb": "yes",
            "print_time": False,
        }


@dataclass
class SolverInfo:
    name: str
    status: str  # IPOPT's return status of the final (kept) solve
    iterations: int | None  # summed over the relaxation and integer neighbours (None: solved in a chained batch)
    time_s: float  # wall time of all solver calls (an infeasibility diagnosis included), without problem construction
    solves: int = 1  # design solves (the diagnosis not counted)


class _Run(dict):
    """One solve's figures (``x``, ``lam_x``, ``lam_g``, ``f``, ``ok``, ``status``, ``design``, ...). Its float64
    check (``checks``, ``feasible``, ``value``) is made when one of them is first read: a relaxation whose integers
    are searched next needs none."""

    check = None  # design -> the check's figures

    def __missing__(self, key):
        if key not in ("checks", "feasible", "value") or self.check is None:
            raise KeyError(key)
        self.update(self.check(self["design"]))
        return self[key]


class Box(NamedTuple):
    """The design's box in one solve: variable scales and bounds (SI)."""

    scale: np.ndarray
    lower: np.ndarray
    upper: np.ndarray


@dataclass
class ScaledData:
    """The numbers one solve hands to the NLP: parameter vector, scaled bounds and start, and the scales."""

    params: SimpleNamespace  # case values of the formulation's quantities (SI)
    lower: np.ndarray  # variable bounds (SI)
    upper: np.ndarray
    start: np.ndarray  # start point (SI)
    scale: np.ndarray  # x = scale * x_hat
    f_scale: float  # objective normaliser
    p: np.ndarray  # the NLP's parameter vector: case values, scales, objective scale
    internal_lower: np.ndarray = field(default_factory=lambda: np.zeros(0))  # start-up states, already scaled
    internal_upper: np.ndarray = field(default_factory=lambda: np.zeros(0))
    internal_start: np.ndarray = field(default_factory=lambda: np.zeros(0))
    checked: SimpleNamespace | None = None  # the case values the design is checked against, if not ``params``

    @property
    def lbx(self) -> np.ndarray:
        return np.concatenate([self.lower / self.scale, self.internal_lower])

    @property
    def ubx(self) -> np.ndarray:
        return np.concatenate([self.upper / self.scale, self.internal_upper])

    @property
    def box(self) -> Box:
        return Box(self.scale, self.lower, self.upper)

    @property
    def x0(self) -> np.ndarray:
        return np.concatenate([self.start / self.scale, self.internal_start])


@dataclass
class Solution:
    coupling: str
    mode: str
    objective_name: str
    objective_unit: str
    status: str  # optimal | infeasible | solver_failed | unverified
    objective: float
    design: dict[str, float]
    outputs: dict[str, Output]  # derived quantities (SI value, display unit, description)
    constraints: list[ConstraintCheck]
    solver: SolverInfo
    diagnosis: str | None = None
    integer_search: list[dict] = field(default_factory=list)
    bounds: dict[str, tuple[float, float]] = field(default_factory=dict)  # search box of each variable (SI)
    sensitivities: dict[str, float] = field(default_factory=dict)  # d ln objective / d ln parameter
    scale: np.ndarray | None = field(default=None, repr=False)  # variable scales of the kept solve (warm starts)
    multipliers: tuple[np.ndarray, np.ndarray] | None = field(default=None, repr=False)  # (lam_x, lam_g), scaled
    design_units: dict[str, str] = field(default_factory=dict)  # display unit of each design variable
    start_up: dict | None = None  # the NLP's start-up beside the simulated one (cases with [start_up])
    internal: np.ndarray | None = field(default=None, repr=False)  # scaled start-up states of the kept solve
    mesh: tuple[np.ndarray, np.ndarray] | None = field(default=None, repr=False)  # start-up mesh: used, suggested

    def _repr_html_(self) -> str:
        """Jupyter shows a solution as the tables of ``clutchopt solve``."""
        from clutchopt.output import solution_html

        return solution_html(self)

    def at_bound(self, name: str) -> str:
        """"fixed", "lower", "upper" (within 1e-7 relative) or "" for a design variable."""
        lo, hi = self.bounds[name]
        value = self.design[name]
        tol = 1e-7 * abs(value) if value else 1e-12
        if lo == hi:
            return "fixed"
        return "lower" if value - lo <= tol else "upper" if hi - value <= tol else ""

    @property
    def feasible(self) -> bool:
        return all(c.feasible for c in self.constraints)

    @property
    def worst_violation(self) -> float:
        return max([0.0] + [-c.margin for c in self.constraints])

    def as_dict(self) -> dict:
        return {
            "coupling": self.coupling,
            "mode": self.mode,
            "status": self.status,
            "objective": {"name": self.objective_name, "value": self.objective, "unit": self.objective_unit},
            "design": self.design,
            "outputs": {name: out.value for name, out in self.outputs.items()},
            "units": {"design": {name: si_unit(unit) for name, unit in self.design_units.items()},
                      "outputs": {name: si_unit(out.unit) for name, out in self.outputs.items()}},
            "constraints": [c.as_dict() for c in self.constraints],
            "solver": vars(self.solver),
            "diagnosis": self.diagnosis,
            "integer_search": self.integer_search,
            "bounds": {name: list(pair) for name, pair in self.bounds.items()},
            "sensitivities": self.sensitivities,
            **({"start_up": self.start_up} if self.start_up is not None else {}),
        }


@dataclass
class WarmStart:
    """What a warm re-solve takes from a previous solve (a :class:`Solution` has these too): its design (SI),
    variable scales and multipliers (lam_x, lam_g, scaled)."""

    design: dict[str, float]
    scale: np.ndarray
    multipliers: tuple[np.ndarray, np.ndarray]
    status: str = "optimal"
    mesh: None = None  # no start-up
    internal: None = None


class Problem:
    """One formulation with one objective, built as a CasADi ``nlpsol`` once."""

    def __init__(self, formulation: Formulation, objective: str = "mass", options: SolverOptions = SolverOptions(),
                 start_up: Structure | None = None):
        self._base = formulation
        self.formulation = f = with_start_up(formulation) if start_up else formulation
        self.objective = formulation.objective(objective)
        self.options = options
        n, m = len(f.variables), len(f.quantities)
        x_hat = ca.SX.sym("x_hat", n)
        p_case = ca.SX.sym("p_case", m)
        x_scale = ca.SX.sym("x_scale", n)
        f_scale = ca.SX.sym("f_scale")
        x = namespace({v.name: x_hat[i] * x_scale[i] for i, v in enumerate(f.variables)})
        p = namespace({q.name: p_case[j] for j, q in enumerate(f.quantities)})
        constraints = f.constraints(x, p)
        self.n_checked = len(constraints)  # the formulation's own constraints, re-evaluated by check_design
        at_start = namespace(f.start_up_view(vars(p))) if f.start_up_view else p
        self.start_up = StartUpBlock(start_up, f.speed_law, x, at_start) if start_up else None
        internal, equalities = (self.start_up.hat, self.start_up.equalities) if start_up else (ca.SX(0, 1), [])
        constraints += self.start_up.constraints if start_up else []
        rows = [ca.SX(c.normalised()) for c in constraints]
        self.constraint_names = [c.name for c in constraints]
        self.constraint_rows = [row.shape[0] for row in rows]  # a start-up constraint may hold along a path
        self.row_names = [c.name for c, row in zip(constraints, rows) for _ in range(row.shape[0])]
        self.row_senses = [c.sense for c, row in zip(constraints, rows) for _ in range(row.shape[0])]
        g = ca.vertcat(*rows, *equalities)
        self.n_ineq = len(self.row_names)
        self._lbg = np.concatenate([np.full(self.n_ineq, -np.inf), np.zeros(len(equalities))])
        x_all = ca.vertcat(x_hat, internal)
        mesh = self.start_up.mesh_parameters if start_up else ca.SX(0, 1)
        self._fixed_rows = [i for i in range(self.n_ineq) if not ca.depends_on(g[i], x_all)]  # no design enters
        self._constraint_values = ca.Function("g", [x_all, ca.vertcat(p_case, x_scale, f_scale, mesh)],
                                              [g[: self.n_ineq]])
        self._row_depends = np.array(ca.DM(ca.jacobian(g[: self.n_ineq], x_all).sparsity(), 1)) != 0  # row i uses x_j
        self._names = [v.name for v in f.variables]
        self._integer = [i for i, v in enumerate(f.variables) if v.integer]
        self._nlp = {"x": x_all, "p": ca.vertcat(p_case, x_scale, f_scale, mesh),
                     "f": self.objective.function(x, p) / f_scale, "g": g}
        self._solver = ca.nlpsol(f"{f.coupling}_{f.mode}_{objective}", "ipopt", self._nlp, options.ipopt())
        lam_g = ca.SX.sym("lam_g", g.shape[0])
        lagrangian = self._nlp["f"] + ca.dot(lam_g, g)
        self._kkt = self._kkt_verdict(x_all, lam_g, ca.gradient(lagrangian, x_all), g[: self.n_ineq])
        self._case_gradient = ca.Function("dL_dcase", [x_all, self._nlp["p"], lam_g],  # sensitivities
                                          [ca.gradient(lagrangian, p_case)])
        if start_up:
            paths = [ca.vertcat(*column) for column in self.start_up.trajectory().values()]
            self._start_up_figures = ca.Function("start_up", [x_all, self._nlp["p"]],
                                                 [ca.vertcat(*self.start_up.outputs().values()), *paths])
            self._internal_scale = ca.Function("internal_scale", [p_case], [ca.vertcat(*self.start_up.scales)])
        self._elastic = None
        self._solvers = {"ipopt": self._solver}
        self._maps: dict[tuple[str, int], InPlace] = {}
        self._fixed_only: dict[bytes, tuple[np.ndarray, ca.Function]] = {}
        self._chains: dict[tuple[str, int], InPlace] = {}
        self._verdicts: dict[bytes, ca.Function] = {}

    @property
    def nlp(self) -> dict:
        """The scaled NLP as CasADi expressions: ``x`` (x_hat), ``p``, ``f``, ``g`` (g <= 0)."""
        return self._nlp

    # --- data of one solve -------------------------------------------------------------------------------------
    def _bounds_and_start(self, case: Case, start: dict[str, float] | None):
        lower, upper, x0 = [], [], []
        for v in self.formulation.variables:
            if v.fixed_unless_freed and v.name not in case.free:
                fixed = case.values[v.name]
                lower.append(fixed), upper.append(fixed), x0.append(fixed)
                continue
            lo, hi = case.bounds.get(v.name, (v.lower, v.upper))
            lower.append(lo), upper.append(hi)
            guess = (start or {}).get(v.name, case.values.get(v.name))
            if guess is None or not math.isfinite(guess):
                guess = math.sqrt(lo * hi) if lo > 0 and math.isfinite(hi) else (lo + hi) / 2
            x0.append(min(max(guess, lo), hi))
        return np.array(lower), np.array(upper), np.array(x0)

    def _scaling(self, params: SimpleNamespace, x: np.ndarray, lower: np.ndarray, upper: np.ndarray,
                 scale: np.ndarray | None = None, mesh: np.ndarray | None = None):
        """Variable scales |x| (or the bound magnitude where x = 0) unless given, objective scale |f(x)|,
        the NLP parameters (a start-up's collocation mesh last: ``mesh``, or its first one)."""
        if scale is None:
            scale = np.where(np.abs(x) > 0, np.abs(x), np.maximum(np.abs(lower), np.abs(upper)))
            scale = np.where(np.isfinite(scale) & (scale > 0), scale, 1.0)
        design = dict(zip((v.name for v in self.formulation.variables), x))
        f0 = abs(evaluate_objective(self.formulation, self.objective.name, design, params))
        f_scale = f0 if math.isfinite(f0) and f0 > 0 else 1.0
        if self.start_up is not None and mesh is None:
            mesh = self.start_up.initial_mesh()
        return scale, f_scale, np.concatenate([list(vars(params).values()), scale, [f_scale],
                                               mesh if mesh is not None else []])

    def _params(self, case: Case) -> SimpleNamespace:
        """The case's SI values of this formulation's quantities; those the case leaves out read as NaN."""
        return namespace({q.name: case.values.get(q.name, math.nan) for q in self.formulation.quantities})

    # --- solving ---------------------------------------------------------------------------------------------------
    def scaled_data(self, case: Case, start: dict[str, float] | None = None, scale: np.ndarray | None = None,
                    internal: np.ndarray | None = None, mesh: np.ndarray | None = None,
                    checked: SimpleNamespace | None = None) -> ScaledData:
        """Bounds, start and scales of one solve (scales from the start unless given); with a start-up, its states
        start from ``internal`` (a previous solve's) or from a simulation of the start design, on ``mesh``;
        ``checked``: the case values the design is checked against (moved limits solve, the case's own check)."""
        lower, upper, x0 = self._bounds_and_start(case, start)
        params = self._params(case)
        scale, f_scale, p_vector = self._scaling(params, x0, lower, upper, scale, mesh)
        data = ScaledData(params, lower, upper, x0, scale, f_scale, p_vector, checked=checked)
        if self.start_up is not None:
            data.internal_lower, data.internal_upper = self.start_up.bounds()
            if internal is None or len(internal) != self.start_up.size:
                internal = initial_states(self.start_up, self._start_up_case(case), self.formulation,
                                          self._design(x0 / scale, scale),
                                          np.array(self._internal_scale(p_vector[: len(params.__dict__)])).ravel(),
                                          p_vector[-self.start_up.mesh_parameters.shape[0]:])
            data.internal_start = np.clip(internal, data.internal_lower, data.internal_upper)
        return data

    def _design(self, x: np.ndarray, scale: np.ndarray) -> dict[str, float]:
        """Design variables by name (SI) from the NLP's (scaled) x, internal variables left out."""
        return {v.name: float(value) for v, value in zip(self.formulation.variables, x[: len(scale)] * scale)}

    def solve(self, case: Case, start: dict[str, float] | None = None, warm: Solution | WarmStart | None = None,
              mesh: np.ndarray | None = None, refine: bool = True) -> Solution:
        """Solve for one case. ``warm``: a previous solution of this problem, whose design and scales start this one.

        With a start-up, the simulated start is what the limits are checked against, and the collocation's own
        error is the NLP's start time against the simulated one. While that error exceeds the case's tolerance,
        the mesh is adapted to the simulated start (MESH_STEPS times, or until an adaptation no longer halves the
        error), then the intervals doubled (up to
        MAX_INTERVALS). Should the simulated start still miss a limit, the missed limits are moved in by what the
        simulation adds to the NLP's figure (defect correction) and the problem re-solves warm. Limits are always
        reported as the case gives them. A start-up problem without a start point starts from the optimum the
        papers' sizing gives (the same mode without the start-up), a design the start-up changes but does not
        overturn. Integer variables keep their values while limits are moved in (an elastic link's excepted).
        ``refine=False``: one solve on ``mesh`` (or the warm solution's, or the first one), as it comes (for
        measuring what accuracy costs)."""
        case.require(self.objective.name, quantities=self.formulation.quantities)
        if self.start_up is None or not refine:
            return self._solve(case, start, warm, mesh=mesh)
        if start is None and warm is None:
            sized = problem_for(self._base, self.objective.name, self.options).solve(case)
            start = sized.design if sized.status == "optimal" else None
        solution = self._solve(case, start, warm, mesh=mesh)
        nlp_case, adapted, last_error, solves = case, 0, math.inf, [solution.solver]
        structure = self.start_up.s
        for _ in range(MESH_STEPS + BACK_OFF_STEPS):
            if solution.status not in ("optimal", "unverified"):
                break
            error = abs(solution.start_up["discretisation_error"]["start_time"])
            if error > structure.spec.tolerance and not structure.elastic:  # an elastic link: its quasi-static
                # NLP differs from the simulated dynamics by the model, not by the mesh
                if adapted == MESH_STEPS or error > 0.5 * last_error:  # adapting no longer pays: more intervals
                    if 2 * structure.intervals > MAX_INTERVALS:
                        break
                    finer = replace(structure, intervals=2 * structure.intervals)
                    halved = np.repeat(solution.mesh[1], 2) / 2.0  # each interval of each phase split in two
                    solution = problem_for(self._base, self.objective.name, self.options, finer).solve(
                        case, solution.design, mesh=halved)
                    solves.append(solution.solver)
                    break
                adapted, last_error = adapted + 1, error
                solution = self._solve(case, warm=solution, nlp_case=nlp_case, mesh=solution.mesh[1])
            elif solution.status == "unverified" and (limits := tightened_limits(solution, nlp_case)):
                # integers kept, unless the difference is the model's (an elastic link's dynamics), not a small one
                integers = {v.name: (solution.design[v.name],) * 2 for v in self.formulation.variables
                            if v.integer and not structure.elastic}
                nlp_case = replace(nlp_case.with_values(**limits), bounds={**nlp_case.bounds, **integers})
                solution = self._solve(case, warm=solution, nlp_case=nlp_case)
            else:
                break
            solves.append(solution.solver)
        solution.solver = SolverInfo(solution.solver.name, solution.solver.status, sum(s.iterations for s in solves),
                                     sum(s.time_s for s in solves), sum(s.solves for s in solves))
        return solution

    def _solve(self, case: Case, start: dict[str, float] | None = None, warm: Solution | WarmStart | None = None,
               nlp_case: Case | None = None, mesh: np.ndarray | None = None) -> Solution:
        """One solve (with its integer search); the NLP sees ``nlp_case`` (moved limits), the checks ``case``;
        a start-up's mesh is ``mesh``, else the warm solution's, else the first one."""
        warm_ok = warm is not None and warm.status in ("optimal", "unverified") and warm.scale is not None
        if mesh is None and warm_ok and warm.mesh is not None and len(warm.mesh[0]) == self._mesh_size:
            mesh = warm.mesh[0]
        solved, checked = nlp_case or case, self._params(case)
        duals = self.warm_multipliers(*warm.multipliers) if warm_ok else None
        if duals is not None and len(duals[1]) != len(self._lbg):
            duals = None  # a warm start from another problem (e.g. uncapped) gives its point only
        runs: list[dict] = []
        search: list[dict] = []
        relaxed = None
        if warm_ok:
            data = self.scaled_data(solved, warm.design, warm.scale, warm.internal, mesh, checked)
            integer = self._free_integers(data)
            seed = {"x": data.x0, "lam_x": duals[0], "lam_g": duals[1]} if duals is not None else None
            combo = np.array([warm.design[self._names[i]] for i in integer])
            sqp = ("sqp",) if self.options.warm_sqp and self.start_up is None else ()  # small dense NLPs only
            methods = sqp + ("warm",) if seed is not None else ("ipopt",)
            if integer and seed is not None and self._within(data, integer, combo):
                kept = self.descend(data.box, integer, combo, seed, search, self._fixing(data, runs, search),
                                     first=methods)
                if kept is not None:
                    return self._finish(case, kept, runs, data, search)
                seed, methods = self.relaxation_seed(seed, integer), ("warm",)  # the previous integers fail here
            run = self._attempt(data, data.lbx, data.ubx, data.x0, seed, methods, runs)
            relaxed = run if run["ok"] else None
        if relaxed is None:  # cold: from the case's own start
            data = self.scaled_data(solved, start, mesh=mesh, checked=checked)
            relaxed = self._attempt(data, data.lbx, data.ubx, data.x0, None, ("ipopt",), runs)
        n = len(data.scale)
        x_opt = relaxed["x"][:n] * data.scale
        if relaxed["ok"] and self.off_scale(relaxed["x"][:n]):  # the start was far off: solve again, scaled by the
            # first optimum
            data = self.scaled_data(solved, dict(zip(self._names, x_opt)), None, relaxed["x"][n:],
                                    self._mesh_of(data.p), checked)
            relaxed = self._attempt(data, data.lbx, data.ubx, data.x0, None, ("ipopt",), runs)
        integer = self._free_integers(data)
        if not integer or not relaxed["ok"]:
            return self._finish(case, relaxed, runs, data, search)
        kept = self.nearest_integers(data.box, integer, relaxed, search, self._fixing(data, runs, search))
        if kept is None:  # the relaxation is feasible, no integer near it is
            tried = "; ".join(", ".join(f"{k}={v}" for k, v in e.items() if k in self._names) for e in search)
            return self._finish(case, runs[-1], runs, data, search,
                                ("infeasible", f"infeasible in integers: the continuous relaxation is feasible "
                                 f"but none of the integer neighbours is ({tried})"))
        return self._finish(case, kept, runs, data, search)

    # --- integer search -------------------------------------------------------------------------------------------
    def _free_integers(self, data: ScaledData) -> list[int]:
        return [i for i in self._integer if data.lower[i] < data.upper[i]]

    @staticmethod
    def _within(data: ScaledData, integer: list[int], combo: np.ndarray) -> bool:
        return bool(np.all((combo >= data.lower[integer]) & (combo <= data.upper[integer])))

    def _tried(self, search: list[dict], integer: list[int], combo) -> bool:
        return any(all(entry[self._names[i]] == c for i, c in zip(integer, combo)) for entry in search)

    def descend(self, box: Box, integer, combo, seed, search, attempt, bound: float | None = None,
                first: tuple[str, ...] = ("ipopt",)) -> dict | None:
        """From the integers ``combo``, step to a neighbouring integer while the bound multipliers of the fixed
        integers say the objective falls that way and the step lowers it; None if ``combo`` itself fails.
        ``attempt(combo, seed, methods)``: the run with the integers fixed at ``combo`` if it is a verified optimum,
        else None, logged in ``search`` (``Problem.solve``: :meth:`_try_integers`; a batched sweep: one-point SQP).
        ``bound``: the relaxation's scaled objective; an integer point that reaches it cannot be beaten.
        ``first``: the methods for ``combo``; the neighbours are solved by IPOPT from a cold start."""
        kept, queue, methods = None, [combo], first
        while queue:
            combo = queue.pop(0)
            if self._tried(search, integer, combo):
                continue
            run = attempt(combo, kept or seed, methods)
            methods = ("ipopt",)
            if run is None and kept is None:
                return None
            if run is not None and (kept is None or run["value"] < kept["value"]):
                kept, queue = run, self._downhill(run, box, integer)
                if bound is not None and run["f"] <= bound + self.negligible(bound):
                    break
        return kept

    def nearest_integers(self, box: Box, integer, relaxed: dict, search, attempt) -> dict | None:
        """The integer point of a relaxation's optimum ``relaxed``: :meth:`descend` from its rounded integers, bounded
        by its objective; should they fail, the best of its floor and ceiling, then one further (``attempt`` as for
        :meth:`descend`). None: no integer point near the relaxation is feasible."""
        nearest = np.clip(np.round(relaxed["x"][integer] * box.scale[integer]), box.lower[integer], box.upper[integer])
        kept = self.descend(box, integer, nearest, relaxed, search, attempt, bound=relaxed["f"])
        for reach in (1, 2) if kept is None else ():
            x_relaxed = relaxed["x"][: len(box.scale)] * box.scale
            for combo in self._integer_neighbours(x_relaxed, integer, box.lower, box.upper, reach):
                if not self._tried(search, integer, combo):
                    run = attempt(combo, relaxed, ("ipopt",))
                    if run is not None and (kept is None or run["value"] < kept["value"]):
                        kept = run
            if kept is not None:
                break
        return kept

    def negligible(self, f_hat):
        """A change of the scaled objective within the solver's tolerance of it (elementwise for arrays; symbolic
        for CasADi)."""
        return 10 * self.options.tol * fmax(abs(f_hat), 1e-300)

    @staticmethod
    def off_scale(x_hat: np.ndarray) -> np.ndarray:
        """An optimum more than tenfold off its variable scales (per column for a 2-D ``x_hat``): solved again,
        scaled by it."""
        return np.any(Problem._off_scale_entries(x_hat), axis=0)

    @staticmethod
    def _off_scale_entries(x_hat):
        """Per variable: 1 (true) where it has moved more than tenfold from its scale; floats, arrays or CasADi."""
        moved = abs(x_hat)
        return (moved > 0) * ((moved > 10) + (moved < 0.1)) > 0

    def _downhill(self, run: dict, box: Box, integer: list[int]) -> list[np.ndarray]:
        """Neighbours of a fixed-integer optimum in the directions its objective falls to first order.

        With integer i fixed through its bounds, d f_hat / d x_hat_i = -lam_x_i, so one unit step changes the
        scaled objective by about -|lam_x_i| / scale_i in the direction sign(lam_x_i). Where f*(n) is convex in
        the integers (the premise of rounding a relaxation at all), the other direction cannot win, nor can this
        one when the first-order gain is below the solver's tolerance of the objective."""
        lam = run["lam_x"][integer]
        gain = np.abs(lam) / box.scale[integer]
        steps = np.where(gain > self.negligible(run["f"]), np.sign(lam), 0.0)
        current = np.round(run["x"][integer] * box.scale[integer])
        choices = [sorted({c, min(max(c + s, lo), hi)}, key=lambda k: k != c + s)
                   for c, s, lo, hi in zip(current, steps, box.lower[integer], box.upper[integer])]
        return [np.array(combo) for combo in itertools.product(*choices) if not np.array_equal(combo, current)]

    def _fixing(self, data: ScaledData, runs: list[dict], search: list[dict]):
        """``Problem.solve``'s ``attempt`` for :meth:`descend`: :meth:`_try_integers` on ``data``."""
        integer = self._free_integers(data)
        return lambda combo, seed, methods: self._try_integers(data, integer, combo, seed, runs, search, methods)

    def _try_integers(self, data, integer, combo, seed, runs, search,
                      methods: tuple[str, ...] = ("ipopt",)) -> dict | None:
        """The NLP with the integers fixed at ``combo``: the run if it is a verified-feasible optimum, else None.
        A combination that violates a constraint depending on the integers and fixed variables alone is
        excluded without a solve."""
        lower, upper = data.lower.copy(), data.upper.copy()
        lower[integer] = upper[integer] = combo
        lbx, ubx = self._scaled_box(lower, upper, data.scale, (data.internal_lower, data.internal_upper))
        x0 = np.clip(seed["x"], lbx, ubx)
        excluded = self.violated_whatever_the_rest(data.p, lbx, ubx, x0)
        if excluded:
            search.append(self.excluded_entry(integer, combo, excluded))
            return None
        run = self._attempt(data, lbx, ubx, x0, seed, methods, runs)
        search.append(self.search_entry(integer, combo, run["status"], run["feasible"], run["value"]))
        return run if run["ok"] and run["feasible"] else None

    def search_entry(self, integer: list[int], combo, status: str, feasible: bool, objective: float) -> dict:
        """An ``integer_search`` entry: the integer choice ``combo`` by name, how its solve ended, its objective."""
        return {**{self._names[i]: int(c) for i, c in zip(integer, combo)}, "status": status, "feasible": feasible,
                "objective": objective}

    def excluded_entry(self, integer: list[int], combo, violated: list[str]) -> dict:
        """The ``integer_search`` entry of a choice excluded without a solve: the constraints it breaks."""
        return self.search_entry(integer, combo, f"excluded: {', '.join(violated)}", False, math.nan)

    @staticmethod
    def relaxation_seed(seed: dict, integer: list[int]) -> dict:
        """A warm start for the relaxation from a fixed-integer optimum: the same point, the integers' bound
        multipliers dropped (their bounds are opened)."""
        lam_x = seed["lam_x"].copy()
        lam_x[integer] = 0.0
        return {**seed, "lam_x": lam_x}

    def violated_whatever_the_rest(self, p, lbx, ubx, x0) -> list[str]:
        """Constraints that depend only on fixed variables (integers included) and are violated at ``x0`` (scaled;
        the fixed variables at their bounds)."""
        rows, values = self.fixed_only(lbx == ubx)
        if not len(rows):
            return []
        g = self.mapped(values, 1)(x0, p)[0].ravel()
        return list(dict.fromkeys(self.row_names[k] for k, gk in zip(rows, g) if gk > 10 * FEASIBILITY_TOL))

    def fixed_only(self, fixed: np.ndarray, entered: np.ndarray | None = None) -> tuple[np.ndarray, ca.Function]:
        """The constraint rows that no variable outside ``fixed`` (a mask over x) enters (and, if given, some variable
        of ``entered`` does), and their normalised values as a CasADi function of (x, p), built once per masks."""
        key = np.asarray(fixed, dtype=bool).tobytes() + (b"" if entered is None else b"|" + entered.tobytes())
        if key not in self._fixed_only:
            depends, internal = self._row_depends[:, : len(fixed)], self._row_depends[:, len(fixed):]
            outside = np.any(depends & ~fixed, axis=1) | np.any(internal, axis=1)
            rows = np.flatnonzero(~outside & (True if entered is None else np.any(depends & entered, axis=1)))
            name = f"g_fixed_{len(self._fixed_only)}"  # one name per mask: mapped functions are cached by name
            g = ca.densify(self._nlp["g"][[int(r) for r in rows]])
            self._fixed_only[key] = rows, ca.Function(name, [self._nlp["x"], self._nlp["p"]], [g])
        return self._fixed_only[key]

    def _rounded(self, design: dict[str, float]) -> dict[str, float]:
        """Integers rounded (IPOPT may leave them 1e-9 off their fixed bounds)."""
        for i in self._integer:
            design[self._names[i]] = float(round(design[self._names[i]]))
        return design

    @staticmethod
    def _scaled_box(lower, upper, scale, internal_bounds) -> tuple[np.ndarray, np.ndarray]:
        """The NLP's variable bounds: design bounds scaled, then the (already scaled) internal ones."""
        return (np.concatenate([lower / scale, internal_bounds[0]]),
                np.concatenate([upper / scale, internal_bounds[1]]))

    # --- one solve ------------------------------------------------------------------------------------------------
    def _attempt(self, data: ScaledData, lbx, ubx, x0, seed: dict | None, methods: tuple[str, ...],
                 runs: list[dict]) -> dict:
        """Solve by each method in turn until one ends in a verified optimum; every run goes into ``runs``.
        Methods: ``ipopt`` (cold), ``warm`` (IPOPT from ``seed``'s primal-dual point), ``sqp`` (CasADi's
        sequential QP from ``seed``: for a re-solve next to a known optimum, a few Newton steps)."""
        for i, method in enumerate(methods):
            run = self._run(data, lbx, ubx, x0, seed if method != "ipopt" else None, method)
            runs.append(run)
            if method == "sqp" and run["ok"]:
                run["ok"] = self._first_order_optimal(run)
            if i == len(methods) - 1 or run["ok"] and run["feasible"]:
                break
        return run

    def warm_multipliers(self, lam_x: np.ndarray, lam_g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Multipliers to warm-start from: those within the KKT verdict's tolerance (10 tol) set to 0. IPOPT leaves
        about 1e-11 on inactive bounds and constraints (an interior point); CasADi's SQP (qrqp) reads any non-zero
        multiplier as an active bound, fixes the variable there and stops on a search direction too small (the
        wedge's first re-solve after a cold IPOPT solve did)."""
        tol = 10 * self.options.tol
        return tuple(np.where(np.abs(lam) > tol, lam, 0.0) for lam in (lam_x, lam_g))

    def _first_order_optimal(self, run: dict) -> bool:
        """The KKT check of one run (see :meth:`first_order_optimal`)."""
        return bool(self.first_order_optimal(*(run[k] for k in ("x", "p", "lam_x", "lam_g", "lbx", "ubx")))[0])

    def first_order_optimal(self, x, p, lam_x, lam_g, lbx, ubx) -> np.ndarray:
        """The KKT verdict at primal-dual points (one per column; a 1-D argument serves every column), by one mapped
        CasADi evaluation (see :meth:`_kkt_verdict`)."""
        count = max(np.shape(a)[1] if np.ndim(a) == 2 else 1 for a in (x, p, lam_x, lam_g, lbx, ubx))
        return self.mapped(self._kkt, count)(x, p, lam_x, lam_g, lbx, ubx)[0][0] > 0.5

    def _kkt_verdict(self, x, lam_g, gradient, g) -> ca.Function:
        """KKT conditions checked apart from the solver that reports them: the Lagrangian stationary, multipliers of
        the right sign, complementary to their constraints and bounds, the constraints held (CasADi's SQP can stop at
        the start when handed a previous point's multipliers, e.g. of a constraint that has become slack). A function
        (x, p, lam_x, lam_g, lbx, ubx) -> 1 where all hold, else 0 (also where a number is NaN)."""
        lam_x, lbx, ubx = (ca.SX.sym(name, x.shape[0]) for name in ("lam_x", "lbx", "ubx"))
        tol = 10 * self.options.tol
        ineq = lam_g[: self.n_ineq]
        width = tol * ca.fmax(1.0, ca.fabs(x))
        wrong_bound = ca.logic_or(ca.logic_and(lam_x > tol, ubx - x > width),
                                  ca.logic_and(lam_x < -tol, x - lbx > width))
        holds = [ca.fabs(gradient + lam_x) <= tol, ineq >= -tol, ineq * ca.fmax(-g, 0.0) <= tol,
                 ca.logic_not(wrong_bound), g <= FEASIBILITY_TOL]
        failures = sum(ca.sum1(1 - condition) for condition in holds)  # a comparison with NaN fails
        return ca.Function("kkt", [x, self._nlp["p"], lam_x, lam_g, lbx, ubx], [failures == 0])

    def chain_verdict(self, integer: list[int], fixed: np.ndarray) -> ca.Function:
        """The tests of a re-solve along a sweep as one CasADi function (x, p, lam_x, lam_g, lbx, ubx, f, lower, upper)
        -> (kkt, moves): ``kkt`` its KKT verdict (:meth:`_kkt_verdict`); ``moves`` 1 where ``Problem.solve``'s warm
        search would go on from this point. With free integers ``integer`` (fixed through their bounds in the
        re-solve; ``f`` its scaled objective, ``lower``, ``upper`` the case's bounds, SI): a neighbouring
        combination that :meth:`_downhill` steps to (each integer whose bound multiplier promises a gain beyond
        :meth:`negligible`, one unit that way inside the bounds) and that breaks no constraint of the variables
        ``fixed`` (a mask, integers included) alone (:meth:`violated_whatever_the_rest`); without, an optimum
        :meth:`off_scale`. Built once per integers and mask; no start-up."""
        key = np.asarray(integer, dtype=np.int64).tobytes() + b"|" + np.asarray(fixed, dtype=bool).tobytes()
        if key not in self._verdicts:
            x, p, lam_x, lam_g, lbx, ubx, f_hat = (ca.SX.sym(name, *shape) for name, shape in (
                ("x", self._nlp["x"].shape), ("p", self._nlp["p"].shape), ("lam_x", self._nlp["x"].shape),
                ("lam_g", self._nlp["g"].shape), ("lbx", self._nlp["x"].shape), ("ubx", self._nlp["x"].shape),
                ("f", (1, 1))))
            n, m = len(self._names), self._nlp["p"].shape[0] - len(self._names) - 1
            lower, upper = ca.SX.sym("lower", n), ca.SX.sym("upper", n)
            kkt = self._kkt(x, p, lam_x, lam_g, lbx, ubx)
            if integer:
                moves = self._search_moves(integer, fixed, x, p, lam_x, f_hat, lower, upper, n, m)
            else:
                moves = ca.sum1(self._off_scale_entries(x[:n])) > 0
            self._verdicts[key] = ca.Function(f"chain_verdict_{len(self._verdicts)}",
                                              [x, p, lam_x, lam_g, lbx, ubx, f_hat, lower, upper], [kkt, moves])
        return self._verdicts[key]

    def _search_moves(self, integer, fixed, x, p, lam_x, f_hat, lower, upper, n: int, m: int) -> ca.SX:
        """:meth:`chain_verdict`'s test with integers, symbolic (see :meth:`_downhill`)."""
        entered = np.zeros_like(fixed)
        entered[integer] = True
        _, fixed_values = self.fixed_only(fixed, entered)
        scale = p[m:m + n]
        combo = [ca.floor(x[i] * scale[i] + 0.5) for i in integer]
        negligible = self.negligible(f_hat)
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

    def mapped(self, function: ca.Function, count: int) -> InPlace:
        """``function`` evaluated at ``count`` points at once (columns) on NumPy arrays, built once per count."""
        key = (function.name(), count)
        if key not in self._maps:
            self._maps[key] = InPlace(function if count == 1 else function.map(count))
        return self._maps[key]

    def chained_sqp(self, count: int, method: str = "sqp_chain") -> InPlace:
        """``count`` SQP re-solves in one CasADi call, each started from the optimum of the one before, moved on by
        the secant predictor: (x, lam_x, lam_g, dx, dlam_x, dlam_g, ratio, p, lbx, ubx) -> (x, lam_x, lam_g, dx,
        dlam_x, dlam_g, f), one column per point (``ratio``, ``p``, ``lbx``, ``ubx``: a column per point, or one
        for all; ``f`` the scaled objective). A point starts at x + ratio * dx, with dx the step between the two
        optima before it and ``ratio`` this point's step in the case against that one (0: no prediction), clipped
        to the bounds; its multipliers likewise, where that keeps their sign. Beside a smooth path this halves the
        SQP iterations (2 to 1, each with an exact Hessian: most of a re-solve on the ball clutch). ``method``:
        ``sqp_chain``, or ``sqp_search`` (its Hessian convexified). Built once per method and count, called on NumPy
        arrays."""
        if (method, count) not in self._chains:
            n_x, n_g = self._nlp["x"].shape[0], self._nlp["g"].shape[0]
            x, lam_x, dx, dlam_x, lbx, ubx = (ca.MX.sym(name, n_x) for name in (
                "x", "lam_x", "dx", "dlam_x", "lbx", "ubx"))
            lam_g, dlam_g = ca.MX.sym("lam_g", n_g), ca.MX.sym("dlam_g", n_g)
            ratio, p = ca.MX.sym("ratio"), ca.MX.sym("p", self._nlp["p"].shape[0])

            def predicted(lam, step):  # a multiplier keeps its sign or starts at 0
                guess = lam + ratio * step
                return ca.if_else(lam * guess > 0, guess, 0)

            out = self._solver_for(method)(x0=ca.fmin(ca.fmax(x + ratio * dx, lbx), ubx),
                                           lam_x0=predicted(lam_x, dlam_x), lam_g0=predicted(lam_g, dlam_g), p=p,
                                           lbx=lbx, ubx=ubx, lbg=self._lbg, ubg=0.0)
            step = ca.Function("sqp_step", [x, lam_x, lam_g, dx, dlam_x, dlam_g, ratio, p, lbx, ubx],
                               [out["x"], out["lam_x"], out["lam_g"], out["x"] - x, out["lam_x"] - lam_x,
                                out["lam_g"] - lam_g, out["f"]])
            accumulated = list(range(6))
            self._chains[method, count] = InPlace(step.mapaccum(method, count, accumulated, accumulated))
        return self._chains[method, count]

    def _run(self, data: ScaledData, lbx, ubx, x0, seed: dict | None, method: str = "ipopt") -> dict:
        """One solve, its design checked in float64 (``design``, ``checks``, ``value``, ``feasible``)."""
        solver = self._solver_for(method)
        args = {"x0": x0, "p": data.p, "lbx": lbx, "ubx": ubx, "lbg": self._lbg, "ubg": 0.0}
        if seed is not None:
            args.update(lam_x0=seed["lam_x"], lam_g0=seed["lam_g"])
        started = time.perf_counter()
        result = solver(**args)
        elapsed = time.perf_counter() - started
        stats = solver.stats()
        x = result["x"].full().ravel()
        run = _Run(x=x, lam_g=result["lam_g"].full().ravel(), lam_x=result["lam_x"].full().ravel(),
                   f=float(result["f"]), ok=bool(stats["success"]), status=stats["return_status"],
                   iterations=int(stats.get("iter_count", 0)), time=elapsed, p=data.p, lbx=lbx, ubx=ubx,
                   solver="sqpmethod" if method == "sqp" else "ipopt",
                   design=self._rounded(self._design(x, data.scale)))
        run.check = lambda design, params=data.checked or data.params: self._checked(design, params)
        return run

    def _checked(self, design: dict[str, float], params: SimpleNamespace) -> dict:
        """A design's float64 check: ``checks``, ``feasible``, ``value`` (the objective)."""
        checks = check_design(self.formulation, design, params)
        return {"checks": checks, "feasible": all(c.feasible for c in checks),
                "value": evaluate_objective(self.formulation, self.objective.name, design, params)}

    def _solver_for(self, method: str):
        """The solver of a method (``ipopt`` built with the problem; ``warm``, ``sqp`` on first use)."""
        if method not in self._solvers:
            f = self.formulation
            plugin, options = {"warm": ("ipopt", self.options.ipopt_warm()),
                               "sqp": ("sqpmethod", self.options.sqp()),
                               "sqp_chain": ("sqpmethod", self.options.sqp_chain()),
                               "sqp_search": ("sqpmethod", self.options.sqp_search())}[method]
            name = f"{f.coupling}_{f.mode}_{self.objective.name}_{method}"
            self._solvers[method] = ca.nlpsol(name, plugin, self._nlp, options)
            if method in ("sqp_chain", "sqp_search"):  # a batched sweep's: compiled where that pays
                self._solvers[method] = compiled_solver(name, self._solvers[method], options)
        return self._solvers[method]

    def _start_up_case(self, case: Case) -> Case:
        """The case as the start-up sees it (a robust design's: its corner)."""
        view = self.formulation.start_up_view
        return replace(case, values=case.followed(view(case.values))) if view else case

    @property
    def _mesh_size(self) -> int:
        return self.start_up.mesh_parameters.shape[0] if self.start_up is not None else 0

    def _mesh_of(self, p_vector: np.ndarray) -> np.ndarray | None:
        return p_vector[len(p_vector) - self._mesh_size:] if self.start_up is not None else None

    @staticmethod
    def _integer_neighbours(x, integer, lower, upper, reach: int = 1):
        """Floor and ceiling of each relaxed integer (within bounds), nearest combinations first."""
        choices = []
        for i in integer:
            low, high = math.floor(x[i] + 1e-9), math.ceil(x[i] - 1e-9)
            options = sorted({min(max(k, lower[i]), upper[i]) for k in range(low - reach + 1, high + reach)},
                             key=lambda k: abs(k - x[i]))
            choices.append(options)
        return [np.array(combo, dtype=float) for combo in itertools.product(*choices)]

    def _finish(self, case, run, runs, data: ScaledData, search, verdict=None) -> Solution:
        f = self.formulation
        params, scale, f_scale = data.checked or data.params, data.scale, data.f_scale
        design, objective, checks = run["design"], run["value"], list(run["checks"])
        start_up = mesh = None
        if self.start_up is not None:  # re-checked by the independent simulator
            seen = self._start_up_case(case)
            start_up, simulated, suggested = start_up_report(self.start_up, seen, f, design, self._params(seen),
                                                             self._start_up_figures(run["x"], run["p"]))
            checks += simulated
            mesh = (self._mesh_of(run["p"]), suggested)
        for check, lam in zip(checks, self._named_multipliers(run["lam_g"])):
            check.multiplier = lam
            check.elasticity = limit_elasticity(check, lam, f_scale, objective)
        feasible = all(c.feasible for c in checks)
        diagnosis, diagnosis_s = None, 0.0
        if verdict is not None:
            status, diagnosis = verdict
        elif run["ok"] and feasible:
            status = "optimal"
        elif run["ok"]:
            status = "unverified"
            worst = min(checks, key=lambda c: c.margin if math.isfinite(c.margin) else -math.inf)
            check = "the simulated start-up" if worst in checks[self.n_checked:] else "the float64 check"
            diagnosis = (f"{'IPOPT' if run['solver'] == 'ipopt' else 'SQP'} reported success but {check} finds "
                         f"{worst.name} violated by {-worst.margin:.3g} (relative)")
        else:
            status, diagnosis, diagnosis_s = self.diagnose(run["p"], run["lbx"], run["ubx"], run["x"], scale)
        info = SolverInfo(run["solver"], run["status"], sum(r["iterations"] for r in runs),
                          sum(r["time"] for r in runs) + diagnosis_s, len(runs))
        bounds = {n: (float(lo), float(hi)) for n, lo, hi in zip(self._names, data.lower, data.upper)}
        sensitivities = self.sensitivities(run, objective) if status == "optimal" else {}
        return Solution(f.coupling, f.mode, self.objective.name, self.objective.unit, status, objective, design,
                        evaluate_outputs(f, design, params), checks, info, diagnosis, search, bounds,
                        sensitivities, scale, (run["lam_x"], run["lam_g"]), {v.name: v.unit for v in f.variables},
                        start_up, run["x"][len(scale):] if self.start_up is not None else None, mesh)

    def _named_multipliers(self, lam_g: np.ndarray) -> list[float]:
        """The multiplier of each named constraint: the sum over its rows (one row, or the points of a path)."""
        ends = np.cumsum(self.constraint_rows)
        return [float(lam_g[end - rows:end].sum()) for rows, end in zip(self.constraint_rows, ends)]

    def sensitivities(self, run: dict, objective: float) -> dict[str, float]:
        """d ln f* / d ln p for every case quantity with a finite non-zero value and every fixed variable, at a
        run's primal-dual point (``x``, ``p``, ``lam_x``, ``lam_g``, ``lbx``, ``ubx``); see
        :meth:`sensitivity_columns`."""
        column = (np.reshape(run[key], (-1, 1)) for key in ("x", "p", "lam_x", "lam_g", "lbx", "ubx"))
        return self.sensitivity_columns(*column, np.array([objective]))[0]

    def sensitivity_columns(self, x, p, lam_x, lam_g, lbx, ubx, objective: np.ndarray) -> list[dict[str, float]]:
        """:meth:`sensitivities` of primal-dual points given as columns (their objectives in ``objective``), the case
        gradients by one mapped CasADi evaluation (columns padded to a power of two).

        Case quantities: f_scale * dL/dp (L the scaled Lagrangian). A variable fixed through its bounds at b:
        its bound multiplier gives d f_hat / d(b / scale) = -lam_x. None (an empty dict) where the objective is 0 or
        not finite.
        """
        count = len(objective)
        width = 1 << (count - 1).bit_length()
        padded = [np.pad(a, ((0, 0), (0, width - count)), mode="edge") if width > count else a for a in (x, p, lam_g)]
        m, n = len(self.formulation.quantities), len(self.formulation.variables)
        gradient = self.mapped(self._case_gradient, width)(*padded)[0][:, :count]
        values, scale, f_scale = p[:m], p[m:m + n], p[m + n]
        with np.errstate(invalid="ignore", divide="ignore"):
            elasticity = values * f_scale * gradient / objective
            fixed = []  # (name, where it applies, its term) of each continuous variable fixed through its bounds
            for i, v in enumerate(self.formulation.variables):
                if not v.integer:
                    value = lbx[i] * scale[i]
                    fixed.append((v.name, ((lbx[i] == ubx[i]) & (value != 0)).tolist(),
                                  (value * f_scale * lam_x[i] / (scale[i] * objective)).tolist()))
        names = [q.name for q in self.formulation.quantities]
        kept = (np.isfinite(elasticity) & (values != 0)).T.tolist()
        valid = ((objective != 0) & np.isfinite(objective)).tolist()
        result = []
        for j, (row, keep) in enumerate(zip(elasticity.T.tolist(), kept)):
            point = dict(itertools.compress(zip(names, row), keep)) if valid[j] else {}
            for name, applies, term in fixed if valid[j] else ():
                if applies[j]:
                    point[name] = point.get(name, 0.0) - term[j]
            result.append(point)
        return result

    # --- infeasibility diagnosis ------------------------------------------------------------------------------------
    def diagnose(self, p_vector, lbx, ubx, x0, scale) -> tuple[str, str, float]:
        """Elastic relaxation: min sum(s) s.t. g(x) <= s, s >= 0 on the inequalities (the start-up's dynamics stay
        equalities). Positive slacks name the conflict. Returns status, diagnosis and the time of the IPOPT call on
        the elastic problem (a solver call, not a design solve)."""
        n_g = self.n_ineq
        g0 = np.array(self._constraint_values(x0, p_vector)).ravel()
        given = sorted({self.row_names[i] for i in self._fixed_rows if g0[i] > FEASIBILITY_TOL},
                       key=self.row_names.index)
        if given:  # requirements that no design variable enters: nothing to relax but the case itself
            return "infeasible", ("infeasible whatever the design: " + ", ".join(
                f"{name} ({'over' if self.row_senses[self.row_names.index(name)] == '<=' else 'short of'} its limit by "
                f"{g0[self.row_names.index(name)]:.3g} relative)" for name in given)), 0.0
        if self._elastic is None:
            slack = ca.SX.sym("slack", n_g)
            g = self._nlp["g"]
            nlp = {"x": ca.vertcat(self._nlp["x"], slack), "p": self._nlp["p"], "f": ca.sum1(slack),
                   "g": ca.vertcat(g[:n_g] - slack, g[n_g:])}
            self._elastic = ca.nlpsol("elastic", "ipopt", nlp, self.options.ipopt())
        started = time.perf_counter()
        slack_bounds = np.zeros(n_g), np.full(n_g, np.inf)
        result = self._elastic(x0=np.concatenate([x0, np.ones(n_g)]), p=p_vector, lbg=self._lbg, ubg=0.0,
                               lbx=np.concatenate([lbx, slack_bounds[0]]), ubx=np.concatenate([ubx, slack_bounds[1]]))
        seconds = time.perf_counter() - started
        slacks = np.array(result["x"]).ravel()[len(lbx):]
        lam_g = np.array(result["lam_g"]).ravel()[:n_g]
        x = np.array(result["x"]).ravel()[: len(lbx)]
        if slacks.sum() <= 10 * FEASIBILITY_TOL:
            return "solver_failed", ("IPOPT did not converge, yet a feasible point exists (elastic check); "
                                     "try other bounds or a start point"), seconds
        worst: dict[str, float] = {}
        binding: list[str] = []
        for name, s, lam in zip(self.row_names, slacks, lam_g):
            worst[name] = max(worst.get(name, 0.0), s)
            if s <= 10 * FEASIBILITY_TOL and lam > 1e-6 and name not in binding:
                binding.append(name)
        senses = dict(zip(self.row_names, self.row_senses))
        violated = [f"{name} ({'over' if senses[name] == '<=' else 'short of'} its limit by {s:.3g} relative)"
                    for name, s in worst.items() if s > 10 * FEASIBILITY_TOL]
        binding = [name for name in binding if worst[name] <= 10 * FEASIBILITY_TOL]
        at_bounds = []
        lam_x = np.array(result["lam_x"]).ravel()[: len(lbx)]
        for i, v in enumerate(self.formulation.variables):
            if lbx[i] < ubx[i] and abs(lam_x[i]) > 1e-6:
                side = "upper" if lam_x[i] > 0 else "lower"
                at_bounds.append(f"{v.name} at its {side} bound ({v.show(x[i] * scale[i])})")
            elif lbx[i] == ubx[i] and abs(lam_x[i]) > 1e-6:
                at_bounds.append(f"{v.name} fixed at {v.show(x[i] * scale[i])}")
        others = binding + at_bounds
        text = "infeasible: cannot satisfy " + ", ".join(violated)
        if others:
            text += " together with " + ", ".join(others)
        return "infeasible", text, seconds


def limit_elasticity(check: ConstraintCheck, lam: float, f_scale: float, objective: float) -> float | None:
    """d ln f* / d ln(limit) from the multiplier of the normalised constraint (envelope theorem).

    For "<=": g = (v - l)/s, so df*/d ln l = -lam f_s l/s; for ">=" the sign flips.
    """
    if objective == 0 or not math.isfinite(objective):
        return None
    return limit_elasticities(sense_sign(check.sense), lam, f_scale, check.limit, check.scale, objective)


def sense_sign(sense: str) -> float:
    """-1 for a "<=" constraint, 1 for ">=": the sign of d f* / d ln(limit) per unit multiplier."""
    return -1.0 if sense == "<=" else 1.0


def limit_elasticities(sign, lam, f_scale, limit, scale, objective):
    """:func:`limit_elasticity`'s formula, sign * lam f_s l / (s f*), on floats or arrays alike."""
    return sign * lam * f_scale * limit / (scale * objective)


_CACHE: dict[tuple, Problem] = {}


def problem_for(formulation: Formulation, objective: str = "mass", options: SolverOptions = SolverOptions(),
                start_up: Structure | None = None) -> Problem:
    """Build a problem once per (formulation, objective, options, start-up structure) in this process and reuse it."""
    key = (formulation.coupling, formulation.mode, formulation.variant, objective, options, start_up)
    if key not in _CACHE:
        _CACHE[key] = Problem(formulation, objective, options, start_up)
    return _CACHE[key]


def case_formulation(case: Case, mode: str | None = None) -> Formulation:
    """The formulation a case is solved with, as shown: the coupling's in ``mode`` (default: the case's option,
    then the coupling's), with the start-up's quantities and spring preload if the case has a [start_up] section."""
    from clutchopt.formulations import get_coupling

    formulation = get_coupling(case.coupling).formulation(mode or case.options.get("mode"))
    return with_start_up(formulation) if case.start_up is not None else formulation


def case_problem(case: Case, mode: str | None = None, objective: str | None = None,
                 options: SolverOptions = SolverOptions()) -> Problem:
    """The built problem that solves ``case`` in ``mode`` (default: the case's option, then the coupling's)."""
    from clutchopt.formulations import get_coupling

    formulation = get_coupling(case.coupling).formulation(mode or case.options.get("mode"))
    structure = Structure.of(case) if case.start_up is not None else None
    return problem_for(formulation, objective or case.options.get("objective", "mass"), options, structure)


def solve_case(case: Case, mode: str | None = None, objective: str | None = None,
               options: SolverOptions = SolverOptions()) -> Solution:
    """Solve a case in a mode (default: the case's option, then the coupling's default)."""
    return case_problem(case, mode, objective, options).solve(case)
