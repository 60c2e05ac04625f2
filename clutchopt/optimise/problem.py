"""A formulation turned into a CasADi/IPOPT problem: built once, solved many times with new case data.

The NLP sees scaled numbers only: each design variable is ``x = s * x_hat`` with the scale ``s`` a
parameter (taken from the start point of each solve), every constraint is normalised by its own scale
(relative margin), and the objective is divided by its value at the start point. Case values, variable
scales and the objective scale are all NLP parameters, so one built problem serves every case of its
formulation at every size.

Integer variables: the continuous relaxation is solved first, then the neighbouring integers (floor and
ceiling, each fixed through its bounds, warm-started) and the best verified-feasible one is kept.

Sensitivities: at the optimum, the elasticity of the objective to every case quantity and every fixed design
variable, d ln f* / d ln p, from the gradient of the Lagrangian in the parameters (envelope theorem), with the
multipliers IPOPT returns. A built problem also re-solves warm: ``solve(case, warm=previous)`` starts from a
previous optimum, keeps its scales and hands IPOPT its multipliers (``warm_start_init_point`` with a small
initial barrier parameter, a second solver built on first use); should that fail, the cold solve follows.

Infeasibility: when IPOPT fails, an elastic problem (min sum of slacks on the normalised constraints) names
the requirements that cannot hold together and by how much the least relaxation misses.
"""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import dataclass, field, replace
from types import SimpleNamespace

import casadi as ca
import numpy as np

from clutchopt.cases import Case
from clutchopt.formulations.start_up import with_start_up
from clutchopt.model import Formulation, Output, namespace
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

    def ipopt_warm(self) -> dict:
        """IPOPT started from a previous primal-dual point, barely pushed off the bounds."""
        push = {f"ipopt.warm_start_{name}": 1e-9 for name in (
            "bound_push", "bound_frac", "mult_bound_push", "slack_bound_push", "slack_bound_frac")}
        return {**self.ipopt(), "ipopt.warm_start_init_point": "yes", "ipopt.mu_init": 1e-6, **push}

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
    iterations: int  # summed over the relaxation and integer neighbours
    time_s: float  # wall time of all solves, without problem construction
    solves: int = 1


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

    @property
    def lbx(self) -> np.ndarray:
        return np.concatenate([self.lower / self.scale, self.internal_lower])

    @property
    def ubx(self) -> np.ndarray:
        return np.concatenate([self.upper / self.scale, self.internal_upper])

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
        self._nlp = {"x": x_all, "p": ca.vertcat(p_case, x_scale, f_scale, mesh),
                     "f": self.objective.function(x, p) / f_scale, "g": g}
        self._solver = ca.nlpsol(f"{f.coupling}_{f.mode}_{objective}", "ipopt", self._nlp, options.ipopt())
        lam_g = ca.SX.sym("lam_g", g.shape[0])
        lagrangian = self._nlp["f"] + ca.dot(lam_g, g)
        self._dlagrangian_dcase = ca.Function("dL_dcase", [x_all, self._nlp["p"], lam_g],
                                              [ca.gradient(lagrangian, p_case)])
        if start_up:
            self._start_up_figures = ca.Function("start_up", [x_all, self._nlp["p"]],
                                                 [ca.vertcat(*self.start_up.outputs().values()),
                                                  *[ca.vertcat(*column) for column in self.start_up.trajectory().values()]])
            self._internal_scale = ca.Function("internal_scale", [p_case], [ca.vertcat(*self.start_up.scales)])
        self._elastic = None
        self._warm_solver = None

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
                    internal: np.ndarray | None = None, mesh: np.ndarray | None = None) -> ScaledData:
        """Bounds, start and scales of one solve (scales from the start unless given); with a start-up, its states
        start from ``internal`` (a previous solve's) or from a simulation of the start design, on ``mesh``."""
        lower, upper, x0 = self._bounds_and_start(case, start)
        params = self._params(case)
        scale, f_scale, p_vector = self._scaling(params, x0, lower, upper, scale, mesh)
        data = ScaledData(params, lower, upper, x0, scale, f_scale, p_vector)
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

    def solve(self, case: Case, start: dict[str, float] | None = None, warm: Solution | None = None,
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
        overturn. Integer variables keep their values while limits are moved in. ``refine=False``: one solve on
        ``mesh`` (or the warm solution's, or the first one), as it comes (for measuring what accuracy costs)."""
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
            if error > structure.spec.tolerance:
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
                integers = {v.name: (solution.design[v.name],) * 2 for v in self.formulation.variables if v.integer}
                nlp_case = replace(nlp_case.with_values(**limits), bounds={**nlp_case.bounds, **integers})
                solution = self._solve(case, warm=solution, nlp_case=nlp_case)
            else:
                break
            solves.append(solution.solver)
        solution.solver = SolverInfo(solution.solver.name, solution.solver.status, sum(s.iterations for s in solves),
                                     sum(s.time_s for s in solves), sum(s.solves for s in solves))
        return solution

    def _solve(self, case: Case, start: dict[str, float] | None = None, warm: Solution | None = None,
               nlp_case: Case | None = None, mesh: np.ndarray | None = None) -> Solution:
        """One solve (with its integer search); the NLP sees ``nlp_case`` (moved limits), the checks ``case``;
        a start-up's mesh is ``mesh``, else the warm solution's, else the first one."""
        warm_ok = warm is not None and warm.status in ("optimal", "unverified") and warm.scale is not None
        solved = nlp_case or case
        if mesh is None and warm_ok and warm.mesh is not None and len(warm.mesh[0]) == self._mesh_size:
            mesh = warm.mesh[0]
        data = (self.scaled_data(solved, warm.design, warm.scale, warm.internal, mesh) if warm_ok
                else self.scaled_data(solved, start, mesh=mesh))
        lower, upper, params = data.lower, data.upper, data.params
        scale, f_scale, p_vector = data.scale, data.f_scale, data.p
        internal_bounds = data.internal_lower, data.internal_upper
        n = len(scale)
        names = [v.name for v in self.formulation.variables]
        runs = []
        if warm_ok and warm.multipliers is not None and len(warm.multipliers[1]) == len(self._lbg):
            lam_x, lam_g = warm.multipliers  # (a warm start from another problem, e.g. uncapped, gives its point only)
            runs.append(self._run(p_vector, data.lbx, data.ubx, data.x0, {"lam_x": lam_x, "lam_g": lam_g},
                                  solver=self._warm()))
        if not runs or not runs[-1]["ok"]:
            runs.append(self._run(p_vector, data.lbx, data.ubx, data.x0, None))
        x_opt = runs[-1]["x"][:n] * scale
        off = (np.abs(x_opt) > 0) & ((np.abs(x_opt) > 10 * scale) | (np.abs(x_opt) < 0.1 * scale))
        if runs[-1]["ok"] and off.any():  # the start was far off: solve again, scaled by the first optimum
            scale, f_scale, p_vector = self._scaling(params, x_opt, lower, upper, mesh=self._mesh_of(p_vector))
            runs.append(self._run(p_vector, *self._scaled_box(lower, upper, scale, internal_bounds),
                                  np.concatenate([x_opt / scale, runs[-1]["x"][n:]]), None))
        relaxed = runs[-1]
        integer = [i for i, v in enumerate(self.formulation.variables) if v.integer and lower[i] < upper[i]]
        kept = relaxed
        search = []
        for reach in (1, 2) if integer and relaxed["ok"] else ():
            kept = None
            for combo in self._integer_neighbours(relaxed["x"][:n] * scale, integer, lower, upper, reach):
                if any(all(entry[names[i]] == c for i, c in zip(integer, combo)) for entry in search):
                    continue
                lo, hi = lower.copy(), upper.copy()
                lo[integer] = hi[integer] = combo
                lbx, ubx = self._scaled_box(lo, hi, scale, internal_bounds)
                run = self._run(p_vector, lbx, ubx, np.clip(relaxed["x"], lbx, ubx), relaxed)
                runs.append(run)
                design = self._design(run["x"], scale)
                feasible = all(c.feasible for c in check_design(self.formulation, design, params))
                value = evaluate_objective(self.formulation, self.objective.name, design, params)
                search.append({**{names[i]: int(c) for i, c in zip(integer, combo)},
                               "status": run["status"], "feasible": feasible, "objective": value})
                if run["ok"] and feasible and (kept is None or value < kept["value"]):
                    kept = {**run, "value": value}
            if kept is not None:
                break
        if kept is None:  # the relaxation is feasible, no integer near it is
            tried = "; ".join(", ".join(f"{k}={v}" for k, v in e.items() if k in names) for e in search)
            return self._finish(case, runs[-1], runs, scale, f_scale, lower, upper, search,
                                ("infeasible", f"infeasible in integers: the continuous relaxation is feasible "
                                 f"but none of the integer neighbours is ({tried})"))
        return self._finish(case, kept, runs, scale, f_scale, lower, upper, search)

    def _start_up_case(self, case: Case) -> Case:
        """The case as the start-up sees it (a robust design's: its corner)."""
        view = self.formulation.start_up_view
        return replace(case, values=view(case.values)) if view else case

    @property
    def _mesh_size(self) -> int:
        return self.start_up.mesh_parameters.shape[0] if self.start_up is not None else 0

    def _mesh_of(self, p_vector: np.ndarray) -> np.ndarray | None:
        return p_vector[len(p_vector) - self._mesh_size:] if self.start_up is not None else None

    @staticmethod
    def _scaled_box(lower, upper, scale, internal_bounds) -> tuple[np.ndarray, np.ndarray]:
        """The NLP's variable bounds: design bounds scaled, then the (already scaled) internal ones."""
        return (np.concatenate([lower / scale, internal_bounds[0]]), np.concatenate([upper / scale, internal_bounds[1]]))

    def _warm(self):
        if self._warm_solver is None:
            f = self.formulation
            self._warm_solver = ca.nlpsol(f"{f.coupling}_{f.mode}_{self.objective.name}_warm", "ipopt", self._nlp,
                                          self.options.ipopt_warm())
        return self._warm_solver

    def _run(self, p_vector, lbx, ubx, x0, warm, solver=None):
        """One IPOPT solve; ``warm`` multipliers are used by the warm solver only (the cold one ignores them)."""
        solver = solver or self._solver
        args = {"x0": x0, "p": p_vector, "lbx": lbx, "ubx": ubx, "lbg": self._lbg, "ubg": 0.0}
        if warm is not None:
            args.update(lam_x0=warm["lam_x"], lam_g0=warm["lam_g"])
        started = time.perf_counter()
        result = solver(**args)
        elapsed = time.perf_counter() - started
        stats = solver.stats()
        return {"x": np.array(result["x"]).ravel(), "lam_g": np.array(result["lam_g"]).ravel(),
                "lam_x": np.array(result["lam_x"]).ravel(), "f": float(result["f"]), "ok": bool(stats["success"]),
                "status": stats["return_status"], "iterations": int(stats.get("iter_count", 0)), "time": elapsed,
                "p": p_vector, "lbx": lbx, "ubx": ubx}

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

    def _finish(self, case, run, runs, scale, f_scale, lower, upper, search, verdict=None) -> Solution:
        f = self.formulation
        params = self._params(case)
        names = [v.name for v in f.variables]
        design = self._design(run["x"], scale)
        for i in (i for i, v in enumerate(f.variables) if v.integer):
            design[names[i]] = float(round(design[names[i]]))
        checks = check_design(f, design, params)
        start_up = mesh = None
        if self.start_up is not None:  # re-checked by the independent simulator
            seen = self._start_up_case(case)
            start_up, simulated, suggested = start_up_report(self.start_up, seen, f, design, self._params(seen),
                                                             self._start_up_figures(run["x"], run["p"]))
            checks += simulated
            mesh = (self._mesh_of(run["p"]), suggested)
        objective = evaluate_objective(f, self.objective.name, design, params)
        for check, lam in zip(checks, self._named_multipliers(run["lam_g"])):
            check.multiplier = lam
            check.elasticity = _elasticity(check, lam, f_scale, objective)
        info = SolverInfo("ipopt", run["status"], sum(r["iterations"] for r in runs), sum(r["time"] for r in runs),
                          len(runs))
        feasible = all(c.feasible for c in checks)
        diagnosis = None
        if verdict is not None:
            status, diagnosis = verdict
        elif run["ok"] and feasible:
            status = "optimal"
        elif run["ok"]:
            status = "unverified"
            worst = min(checks, key=lambda c: c.margin if math.isfinite(c.margin) else -math.inf)
            check = "the simulated start-up" if worst in checks[self.n_checked:] else "the float64 check"
            diagnosis = (f"IPOPT reported success but {check} finds {worst.name} violated by "
                         f"{-worst.margin:.3g} (relative)")
        else:
            status, diagnosis = self.diagnose(run["p"], run["lbx"], run["ubx"], run["x"], scale)
        bounds = {n: (float(lo), float(hi)) for n, lo, hi in zip(names, lower, upper)}
        sensitivities = self._sensitivities(run, params, scale, f_scale, objective) if status == "optimal" else {}
        return Solution(f.coupling, f.mode, self.objective.name, self.objective.unit, status, objective, design,
                        evaluate_outputs(f, design, params), checks, info, diagnosis, search, bounds,
                        sensitivities, scale, (run["lam_x"], run["lam_g"]), {v.name: v.unit for v in f.variables},
                        start_up, run["x"][len(scale):] if self.start_up is not None else None, mesh)

    def _named_multipliers(self, lam_g: np.ndarray) -> list[float]:
        """The multiplier of each named constraint: the sum over its rows (one row, or the points of a path)."""
        ends = np.cumsum(self.constraint_rows)
        return [float(lam_g[end - rows:end].sum()) for rows, end in zip(self.constraint_rows, ends)]

    def _sensitivities(self, run, params, scale, f_scale, objective) -> dict[str, float]:
        """d ln f* / d ln p for every case quantity with a finite non-zero value and every fixed variable.

        Case quantities: f_scale * dL/dp (L the scaled Lagrangian). A variable fixed through its bounds at b:
        its bound multiplier gives d f_hat / d(b / scale) = -lam_x.
        """
        if objective == 0 or not math.isfinite(objective):
            return {}
        gradient = np.array(self._dlagrangian_dcase(run["x"], run["p"], run["lam_g"])).ravel()
        result: dict[str, float] = {}
        for q, value, dl in zip(self.formulation.quantities, vars(params).values(), gradient):
            if math.isfinite(value) and value != 0 and math.isfinite(dl):
                result[q.name] = value * f_scale * dl / objective
        for i, v in enumerate(self.formulation.variables):
            if run["lbx"][i] == run["ubx"][i] and not v.integer:
                value = run["lbx"][i] * scale[i]
                if value != 0:
                    result[v.name] = result.get(v.name, 0.0) - value * f_scale * run["lam_x"][i] / (scale[i] * objective)
        return result

    # --- infeasibility diagnosis ------------------------------------------------------------------------------------
    def diagnose(self, p_vector, lbx, ubx, x0, scale) -> tuple[str, str]:
        """Elastic relaxation: min sum(s) s.t. g(x) <= s, s >= 0 on the inequalities (the start-up's dynamics stay
        equalities). Positive slacks name the conflict."""
        n_g = self.n_ineq
        g0 = np.array(self._constraint_values(x0, p_vector)).ravel()
        given = sorted({self.row_names[i] for i in self._fixed_rows if g0[i] > FEASIBILITY_TOL},
                       key=self.row_names.index)
        if given:  # requirements that no design variable enters: nothing to relax but the case itself
            return "infeasible", ("infeasible whatever the design: " + ", ".join(
                f"{name} ({'over' if self.row_senses[self.row_names.index(name)] == '<=' else 'short of'} its limit by "
                f"{g0[self.row_names.index(name)]:.3g} relative)" for name in given))
        if self._elastic is None:
            slack = ca.SX.sym("slack", n_g)
            g = self._nlp["g"]
            nlp = {"x": ca.vertcat(self._nlp["x"], slack), "p": self._nlp["p"], "f": ca.sum1(slack),
                   "g": ca.vertcat(g[:n_g] - slack, g[n_g:])}
            self._elastic = ca.nlpsol("elastic", "ipopt", nlp, self.options.ipopt())
        result = self._elastic(x0=np.concatenate([x0, np.ones(n_g)]), p=p_vector,
                               lbx=np.concatenate([lbx, np.zeros(n_g)]), ubx=np.concatenate([ubx, np.full(n_g, np.inf)]),
                               lbg=self._lbg, ubg=0.0)
        slacks = np.array(result["x"]).ravel()[len(lbx):]
        lam_g = np.array(result["lam_g"]).ravel()[:n_g]
        x = np.array(result["x"]).ravel()[: len(lbx)]
        if slacks.sum() <= 10 * FEASIBILITY_TOL:
            return "solver_failed", ("IPOPT did not converge, yet a feasible point exists (elastic check); "
                                     "try other bounds or a start point")
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
        return "infeasible", text


def _elasticity(check: ConstraintCheck, lam: float, f_scale: float, objective: float) -> float | None:
    """d ln f* / d ln(limit) from the multiplier of the normalised constraint (envelope theorem).

    For "<=": g = (v - l)/s, so df*/d ln l = -lam f_s l/s; for ">=" the sign flips.
    """
    if objective == 0 or not math.isfinite(objective):
        return None
    sign = -1.0 if check.sense == "<=" else 1.0
    return sign * lam * f_scale * check.limit / (check.scale * objective)


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
