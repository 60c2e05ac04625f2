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
from dataclasses import dataclass, field
from types import SimpleNamespace

import casadi as ca
import numpy as np

from clutchopt.cases import Case
from clutchopt.model import Formulation, Output, namespace
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

    @property
    def lbx(self) -> np.ndarray:
        return self.lower / self.scale

    @property
    def ubx(self) -> np.ndarray:
        return self.upper / self.scale

    @property
    def x0(self) -> np.ndarray:
        return self.start / self.scale


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
        }


class Problem:
    """One formulation with one objective, built as a CasADi ``nlpsol`` once."""

    def __init__(self, formulation: Formulation, objective: str = "mass", options: SolverOptions = SolverOptions()):
        self.formulation = formulation
        self.objective = formulation.objective(objective)
        self.options = options
        f = formulation
        n, m = len(f.variables), len(f.quantities)
        x_hat = ca.SX.sym("x_hat", n)
        p_case = ca.SX.sym("p_case", m)
        x_scale = ca.SX.sym("x_scale", n)
        f_scale = ca.SX.sym("f_scale")
        x = namespace({v.name: x_hat[i] * x_scale[i] for i, v in enumerate(f.variables)})
        p = namespace({q.name: p_case[j] for j, q in enumerate(f.quantities)})
        constraints = f.constraints(x, p)
        self.constraint_names = [c.name for c in constraints]
        self.constraint_senses = [c.sense for c in constraints]
        g = ca.vertcat(*[c.normalised() for c in constraints])
        self._nlp = {"x": x_hat, "p": ca.vertcat(p_case, x_scale, f_scale),
                     "f": self.objective.function(x, p) / f_scale, "g": g}
        self._solver = ca.nlpsol(f"{f.coupling}_{f.mode}_{objective}", "ipopt", self._nlp, options.ipopt())
        lam_g = ca.SX.sym("lam_g", g.shape[0])
        lagrangian = self._nlp["f"] + ca.dot(lam_g, g)
        self._dlagrangian_dcase = ca.Function("dL_dcase", [x_hat, self._nlp["p"], lam_g],
                                              [ca.gradient(lagrangian, p_case)])
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
                 scale: np.ndarray | None = None):
        """Variable scales |x| (or the bound magnitude where x = 0) unless given, objective scale |f(x)|,
        the NLP parameters."""
        if scale is None:
            scale = np.where(np.abs(x) > 0, np.abs(x), np.maximum(np.abs(lower), np.abs(upper)))
            scale = np.where(np.isfinite(scale) & (scale > 0), scale, 1.0)
        design = dict(zip((v.name for v in self.formulation.variables), x))
        f0 = abs(evaluate_objective(self.formulation, self.objective.name, design, params))
        f_scale = f0 if math.isfinite(f0) and f0 > 0 else 1.0
        return scale, f_scale, np.concatenate([list(vars(params).values()), scale, [f_scale]])

    def _params(self, case: Case) -> SimpleNamespace:
        """The case's SI values of this formulation's quantities; those the case leaves out read as NaN."""
        return namespace({q.name: case.values.get(q.name, math.nan) for q in self.formulation.quantities})

    # --- solving ---------------------------------------------------------------------------------------------------
    def scaled_data(self, case: Case, start: dict[str, float] | None = None,
                    scale: np.ndarray | None = None) -> ScaledData:
        """Bounds, start and scales of one solve (scales from the start unless given)."""
        lower, upper, x0 = self._bounds_and_start(case, start)
        params = self._params(case)
        scale, f_scale, p_vector = self._scaling(params, x0, lower, upper, scale)
        return ScaledData(params, lower, upper, x0, scale, f_scale, p_vector)

    def solve(self, case: Case, start: dict[str, float] | None = None, warm: Solution | None = None) -> Solution:
        """Solve for one case. ``warm``: a previous solution of this problem, whose design and scales start this one."""
        warm_ok = warm is not None and warm.status == "optimal" and warm.scale is not None
        data = self.scaled_data(case, warm.design, warm.scale) if warm_ok else self.scaled_data(case, start)
        lower, upper, x0, params = data.lower, data.upper, data.start, data.params
        scale, f_scale, p_vector = data.scale, data.f_scale, data.p
        names = [v.name for v in self.formulation.variables]
        runs = []
        if warm_ok and warm.multipliers is not None and len(warm.multipliers[1]) == len(self.constraint_names):
            lam_x, lam_g = warm.multipliers  # (a warm start from another problem, e.g. uncapped, gives its point only)
            runs.append(self._run(p_vector, lower / scale, upper / scale, x0 / scale, {"lam_x": lam_x, "lam_g": lam_g},
                                  solver=self._warm()))
        if not runs or not runs[-1]["ok"]:
            runs.append(self._run(p_vector, lower / scale, upper / scale, x0 / scale, None))
        x_opt = runs[-1]["x"] * scale
        off = (np.abs(x_opt) > 0) & ((np.abs(x_opt) > 10 * scale) | (np.abs(x_opt) < 0.1 * scale))
        if runs[-1]["ok"] and off.any():  # the start was far off: solve again, scaled by the first optimum
            scale, f_scale, p_vector = self._scaling(params, x_opt, lower, upper)
            runs.append(self._run(p_vector, lower / scale, upper / scale, x_opt / scale, None))
        relaxed = runs[-1]
        integer = [i for i, v in enumerate(self.formulation.variables) if v.integer and lower[i] < upper[i]]
        kept = relaxed
        search = []
        for reach in (1, 2) if integer and relaxed["ok"] else ():
            kept = None
            for combo in self._integer_neighbours(relaxed["x"] * scale, integer, lower, upper, reach):
                if any(all(entry[names[i]] == c for i, c in zip(integer, combo)) for entry in search):
                    continue
                lo, hi = lower.copy(), upper.copy()
                lo[integer] = hi[integer] = combo
                run = self._run(p_vector, lo / scale, hi / scale, np.clip(relaxed["x"], lo / scale, hi / scale), relaxed)
                runs.append(run)
                design = dict(zip(names, run["x"] * scale))
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

    def _warm(self):
        if self._warm_solver is None:
            f = self.formulation
            self._warm_solver = ca.nlpsol(f"{f.coupling}_{f.mode}_{self.objective.name}_warm", "ipopt", self._nlp,
                                          self.options.ipopt_warm())
        return self._warm_solver

    def _run(self, p_vector, lbx, ubx, x0, warm, solver=None):
        """One IPOPT solve; ``warm`` multipliers are used by the warm solver only (the cold one ignores them)."""
        solver = solver or self._solver
        args = {"x0": x0, "p": p_vector, "lbx": lbx, "ubx": ubx, "lbg": -np.inf, "ubg": 0.0}
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
        design = {n: float(value) for n, value in zip(names, run["x"] * scale)}
        for i in (i for i, v in enumerate(f.variables) if v.integer):
            design[names[i]] = float(round(design[names[i]]))
        checks = check_design(f, design, params)
        objective = evaluate_objective(f, self.objective.name, design, params)
        for check, lam in zip(checks, run["lam_g"]):
            check.multiplier = float(lam)
            check.elasticity = _elasticity(check, float(lam), f_scale, objective)
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
            worst = min(checks, key=lambda c: c.margin)
            diagnosis = (f"IPOPT reported success but the float64 check finds {worst.name} violated by "
                         f"{-worst.margin:.3g} (relative)")
        else:
            status, diagnosis = self.diagnose(run["p"], lower / scale, upper / scale, run["x"], scale)
        bounds = {n: (float(lo), float(hi)) for n, lo, hi in zip(names, lower, upper)}
        sensitivities = self._sensitivities(run, params, scale, f_scale, objective) if status == "optimal" else {}
        return Solution(f.coupling, f.mode, self.objective.name, self.objective.unit, status, objective, design,
                        evaluate_outputs(f, design, params), checks, info, diagnosis, search, bounds,
                        sensitivities, scale, (run["lam_x"], run["lam_g"]), {v.name: v.unit for v in f.variables})

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
        """Elastic relaxation: min sum(s) s.t. g(x) <= s, s >= 0. Positive slacks name the conflict."""
        if self._elastic is None:
            n_g = self._nlp["g"].shape[0]
            slack = ca.SX.sym("slack", n_g)
            nlp = {"x": ca.vertcat(self._nlp["x"], slack), "p": self._nlp["p"], "f": ca.sum1(slack),
                   "g": self._nlp["g"] - slack}
            self._elastic = ca.nlpsol("elastic", "ipopt", nlp, self.options.ipopt())
        n_g = len(self.constraint_names)
        result = self._elastic(x0=np.concatenate([x0, np.ones(n_g)]), p=p_vector,
                               lbx=np.concatenate([lbx, np.zeros(n_g)]), ubx=np.concatenate([ubx, np.full(n_g, np.inf)]),
                               lbg=-np.inf, ubg=0.0)
        slacks = np.array(result["x"]).ravel()[len(lbx):]
        lam_g = np.array(result["lam_g"]).ravel()
        x = np.array(result["x"]).ravel()[: len(lbx)]
        if slacks.sum() <= 10 * FEASIBILITY_TOL:
            return "solver_failed", ("IPOPT did not converge, yet a feasible point exists (elastic check); "
                                     "try other bounds or a start point")
        violated = [f"{name} ({'over' if sense == '<=' else 'short of'} its limit by {s:.3g} relative)"
                    for name, sense, s in zip(self.constraint_names, self.constraint_senses, slacks)
                    if s > 10 * FEASIBILITY_TOL]
        binding = [name for name, s, lam in zip(self.constraint_names, slacks, lam_g)
                   if s <= 10 * FEASIBILITY_TOL and lam > 1e-6]
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


def problem_for(formulation: Formulation, objective: str = "mass", options: SolverOptions = SolverOptions()) -> Problem:
    """Build a problem once per (formulation, objective, options) in this process and reuse it."""
    key = (formulation.coupling, formulation.mode, objective, options)
    if key not in _CACHE:
        _CACHE[key] = Problem(formulation, objective, options)
    return _CACHE[key]


def solve_case(case: Case, mode: str | None = None, objective: str | None = None,
               options: SolverOptions = SolverOptions()) -> Solution:
    """Solve a case in a mode (default: the case's option, then the coupling's default)."""
    from clutchopt.formulations import get_coupling

    coupling = get_coupling(case.coupling)
    formulation = coupling.formulation(mode or case.options.get("mode"))
    return problem_for(formulation, objective or case.options.get("objective", "mass"), options).solve(case)
