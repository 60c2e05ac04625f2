"""A formulation posed as a scaled CasADi NLP: its functions, bounds and scaling, and its solvers, knowing no strategy.

The NLP sees scaled numbers only: each design variable is ``x = s * x_hat`` with the scale ``s`` a parameter (taken
from the start point of each solve), every constraint is normalised by its own scale (relative margin), and the
objective is divided by its value at the start point. Case values, variable scales and the objective scale are all
NLP parameters, so one posed problem serves every case of its formulation at every size. Solvers and derived CasADi
functions are built on first use, once per problem (:meth:`Posed.built`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property
from types import SimpleNamespace
from typing import Callable, NamedTuple

import casadi as ca
import numpy as np

from clutchopt.backend import fmax
from clutchopt.cases import Case
from clutchopt.model import Formulation, namespace
from clutchopt.optimise.compiled import compiled_solver
from clutchopt.optimise.in_place import InPlace
from clutchopt.optimise.modifier import modified
from clutchopt.optimise.solution import IPOPT_OWN_FIGURES, START_UP_RESTORATION, SolverOptions
from clutchopt.optimise.start_up_compiled import compiled_when_ready
from clutchopt.optimise.sparsity import entries
from clutchopt.optimise.two_sided import TwoSided
from clutchopt.optimise.verify import FEASIBILITY_TOL, evaluate_objective
from clutchopt.start_up.drive import Structure, graded_part
from clutchopt.start_up.equations import with_start_up
from clutchopt.start_up.transcription import StartUpBlock, first_mesh_of_the_start, initial_states

IPOPT_METHODS = ("ipopt", "warm", "warm_near")  # the solvers IPOPT runs (one NLP, one set of derivatives)
START_UP_ITERATIONS = 500  # IPOPT's with a start-up: its solves take 15 to 300, a drive that cannot start the
#                            machine ran the default 3,000 (5 ms each) in each solve and diagnosis


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


class Posed:
    """One formulation with one objective as a scaled NLP (``nlp``), built once; its solvers built on first use."""

    library: str | None = None  # its NLP's functions compiled, where its IPOPT solvers evaluate them (use_compiled)

    def __init__(self, formulation: Formulation, objective: str = "mass", options: SolverOptions = SolverOptions(),
                 start_up: Structure | None = None):
        self.base = formulation
        self.formulation = f = with_start_up(formulation) if start_up else formulation
        self.objective = formulation.objective(objective)
        self.options = options
        self.solver_options = (replace(options, max_iter=min(options.max_iter, START_UP_ITERATIONS)) if start_up
                               else options)  # what IPOPT is built with
        n, m = len(f.variables), len(f.quantities)
        x_hat = ca.SX.sym("x_hat", n)
        self.p_case = ca.SX.sym("p_case", m)
        x_scale = ca.SX.sym("x_scale", n)
        f_scale = ca.SX.sym("f_scale")
        x = namespace({v.name: x_hat[i] * x_scale[i] for i, v in enumerate(f.variables)})
        p = namespace({q.name: self.p_case[j] for j, q in enumerate(f.quantities)})
        constraints = f.constraints(x, p)
        self.n_checked = len(constraints)  # the formulation's own constraints, re-evaluated by check_design
        view = f.start_up_view  # a robust design's corners
        seen = (lambda name: tuple(map(namespace, view(vars(x), vars(p), name)))) if view else None
        self.start_up = StartUpBlock(start_up, f.speed_law, x, p, seen) if start_up else None
        internal, equalities = (self.start_up.hat, self.start_up.equalities) if start_up else (ca.SX(0, 1), [])
        constraints += modified(self.start_up.constraints, x, p) if start_up else []  # (modifiers: their own problem)
        rows = [ca.SX(c.normalised()) for c in constraints]
        self.constraint_rows = [row.shape[0] for row in rows]  # a start-up constraint may hold along a path
        self.row_names = [c.name for c, row in zip(constraints, rows) for _ in range(row.shape[0])]
        self.row_senses = [c.sense for c, row in zip(constraints, rows) for _ in range(row.shape[0])]
        g = ca.vertcat(*rows, *equalities)
        self.n_ineq = len(self.row_names)
        self.lbg = np.concatenate([np.full(self.n_ineq, -np.inf), np.zeros(len(equalities))])
        x_all = ca.vertcat(x_hat, internal)
        mesh = self.start_up.mesh_parameters if start_up else ca.SX(0, 1)
        self.sides = TwoSided(constraints[: self.n_checked], x_hat, ca.vertcat(self.p_case, x_scale, f_scale, mesh),
                              self.lbg)  # a quantity held from both sides: posed as one row
        self.constraint_values = ca.Function("g", [x_all, ca.vertcat(self.p_case, x_scale, f_scale, mesh)],
                                             [g[: self.n_ineq]])
        self.row_depends = entries(ca.jacobian_sparsity(g[: self.n_ineq], x_all))  # row i uses x_j
        self.fixed_rows = [int(i) for i in np.flatnonzero(~self.row_depends.any(axis=1))]  # no design enters (read
        # from the Jacobian's structure: a depends_on a row took 9 ms a start-up problem)
        self.names = [v.name for v in f.variables]
        self.integer = [i for i, v in enumerate(f.variables) if v.integer]
        self.nlp = {"x": x_all, "p": ca.vertcat(self.p_case, x_scale, f_scale, mesh),
                    "f": self.objective.function(x, p) / f_scale, "g": g}  # the scaled NLP, g <= 0
        self.lam_g = ca.SX.sym("lam_g", g.shape[0])  # the Lagrangian, for KKT verdicts and sensitivities
        self.lagrangian = self.nlp["f"] + ca.dot(self.lam_g, g)
        if start_up:
            paths = [ca.vertcat(*column) for column in self.start_up.trajectory().values()]
            self.start_up_figures = ca.Function("start_up", [x_all, self.nlp["p"]],
                                                [ca.vertcat(*self.start_up.outputs().values()), *paths])
            self.internal_scale = ca.Function("internal_scale", [self.p_case], [ca.vertcat(*self.start_up.scales)])
        self._built: dict[str, dict] = {"solver": {}}  # (IPOPT's solvers too on first use: a modifiers' problem
        # solves warm only)

    def ipopt_options(self, method: str) -> dict:
        """IPOPT's options for ``ipopt`` (cold), ``warm`` or ``warm_near`` (warm from a start-up's optimum on the same
        mesh): a start-up's collocation has its own first barrier parameters (:meth:`SolverOptions.ipopt_start_up`,
        :meth:`SolverOptions.ipopt_warm_start_up`), returns IPOPT's own figures (``IPOPT_OWN_FIGURES``) and ends a
        restoration phase that finds no feasible point sooner (``START_UP_RESTORATION``)."""
        chosen = self.solver_options
        cold = chosen.ipopt_start_up if self.start_up is not None else chosen.ipopt
        options = {"warm_near": chosen.ipopt_warm_start_up, "warm": chosen.ipopt_warm}.get(method, cold)()
        return {**options, **IPOPT_OWN_FIGURES, **START_UP_RESTORATION} if self.start_up is not None else options

    def built(self, kind: str, key, build: Callable[[int], object]):
        """The object of ``kind`` (a solver, a CasADi function) for ``key``, built once: ``build(number)``, with
        ``number`` how many of that kind were built before (unique names)."""
        store = self._built.setdefault(kind, {})
        if key not in store:
            store[key] = build(len(store))
        return store[key]

    def solver(self, method: str):
        """The solver of a method (``ipopt``, ``warm``, ``warm_near``, ``sqp``, ``sqp_chain``, ``sqp_search``), built on
        first use. A start-up problem's IPOPT solvers are built over its NLP's compiled functions where the cache
        links a library whole to its NLP (:func:`~clutchopt.optimise.start_up_compiled.compiled_when_ready`: a sweep's
        library, in any solve of the same NLP; the same numbers, no symbolic differentiation)."""
        def build(_):
            f = self.formulation
            chosen = self.solver_options
            name = f"{f.coupling}_{f.mode}_{self.objective.name}" + ("" if method == "ipopt" else f"_{method}")
            if method in IPOPT_METHODS and self.start_up is not None and self.library is None:
                compiled_when_ready(self)  # (the link read once a problem: its digest 7-9 ms where the cache has links)
            if method in IPOPT_METHODS:  # the first IPOPT solver's derivatives, not derived again (0.06 s a start-up
                # problem)
                solver = ca.nlpsol(name, "ipopt", self.library or self.nlp,
                                   {**self.ipopt_options(method), **self.derivatives()})
            else:
                options = {"sqp": chosen.sqp, "sqp_chain": chosen.sqp_chain, "sqp_search": chosen.sqp_search}[method]()
                solver = ca.nlpsol(name, "sqpmethod", self.nlp, options)
            if method in ("sqp_chain", "sqp_search"):  # a batched sweep's: compiled where that pays
                solver = compiled_solver(name, solver, options)
            return solver

        return self.built("solver", method, build)

    def derivatives(self) -> dict[str, ca.Function]:
        """The gradient, constraint Jacobian and Lagrangian Hessian of the first IPOPT solver built for this NLP
        (CasADi's autogenerated ``nlp_grad_f``, ``nlp_jac_g``, ``nlp_hess_l``; none before it), as options the next
        ones (cold, ``warm``, ``warm_near``) are built with: their builds skip the symbolic differentiation
        (ball_motor_start's warm solver: 64 ms -> 2 ms) and evaluate the same functions, so their iterates are those
        of solvers that derived them themselves (IPOPT's options change no derivative)."""
        solvers = self._built["solver"]
        first = next((solvers[method] for method in solvers if method in IPOPT_METHODS), None)
        if first is None:
            return {}
        return {"grad_f": first.get_function("nlp_grad_f"), "jac_g": first.get_function("nlp_jac_g"),
                "hess_lag": first.get_function("nlp_hess_l")}

    def use_compiled(self, library: str) -> bool:
        """This problem's IPOPT solvers built again over ``library``, its NLP's functions compiled (the same operations
        in the same order: the same numbers; a start-up sweep's, :mod:`clutchopt.optimise.start_up_compiled`), and
        those built later too; False (nothing changed) where the library does not load or is another NLP's (its
        oracle's shapes not this one's: a link left from a build of another NLP, which IPOPT would refuse at its first
        call)."""
        solvers = self._built["solver"]
        try:
            oracle = ca.external("nlp", library)
            if [oracle.size_in(i) for i in (0, 1)] + [oracle.size_out(1)] != [self.nlp[k].shape for k in "xpg"]:
                return False
            rebuilt = {method: ca.nlpsol(solvers[method].name(), "ipopt", library, self.ipopt_options(method))
                       for method in IPOPT_METHODS if method in solvers}
        except RuntimeError:  # (a damaged cache)
            return False
        solvers.update(rebuilt)
        self.library = library
        return True

    def mapped(self, function: ca.Function, count: int) -> InPlace:
        """``function`` evaluated at ``count`` points at once (columns) on NumPy arrays, built once per count."""
        return self.built("map", (function.name(), count),
                          lambda _: InPlace(function if count == 1 else function.map(count)))

    def fixed_only(self, fixed: np.ndarray, entered: np.ndarray | None = None) -> tuple[np.ndarray, ca.Function]:
        """The constraint rows that no variable outside ``fixed`` (a mask over x) enters (and, if given, some variable
        of ``entered`` does), and their normalised values as a CasADi function of (x, p), built once per masks."""
        def build(number):
            depends, internal = self.row_depends[:, : len(fixed)], self.row_depends[:, len(fixed):]
            outside = np.any(depends & ~fixed, axis=1) | np.any(internal, axis=1)
            rows = np.flatnonzero(~outside & (True if entered is None else np.any(depends & entered, axis=1)))
            name = f"g_fixed_{number}"  # one name per mask: mapped functions are cached by name
            g = ca.densify(self.nlp["g"][[int(r) for r in rows]])
            return rows, ca.Function(name, [self.nlp["x"], self.nlp["p"]], [g])

        key = np.asarray(fixed, dtype=bool).tobytes() + (b"" if entered is None else b"|" + entered.tobytes())
        return self.built("fixed_only", key, build)

    # --- data of one solve -------------------------------------------------------------------------------------
    def named_bounds(self, lower, upper) -> dict[str, tuple[float, float]]:
        """Each design variable's bounds (SI) by name, as a Solution reports them."""
        return {name: (float(lo), float(hi)) for name, lo, hi in zip(self.names, lower, upper)}

    def bounds_and_start(self, case: Case, start: dict[str, float] | None):
        """The design's bounds and start point (SI): variables the case fixes at its value, a start within bounds."""
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

    def _scaling(self, case: Case, params: SimpleNamespace, x: np.ndarray, lower: np.ndarray, upper: np.ndarray,
                 scale: np.ndarray | None = None, mesh: np.ndarray | None = None):
        """Variable scales |x| (or the bound magnitude where x = 0) unless given, objective scale |f(x)|,
        the NLP parameters (a start-up's collocation mesh last: ``mesh``, or ``case``'s first one)."""
        if scale is None:
            scale = np.where(np.abs(x) > 0, np.abs(x), np.maximum(np.abs(lower), np.abs(upper)))
            scale = np.where(np.isfinite(scale) & (scale > 0), scale, 1.0)
        design = dict(zip(self.names, x))
        f0 = abs(evaluate_objective(self.formulation, self.objective.name, design, params))
        f_scale = f0 if math.isfinite(f0) and f0 > 0 else 1.0
        if self.start_up is not None and mesh is None:
            mesh = self.start_up.initial_mesh(graded_part(self.start_up.s.spec, case.values))
        return scale, f_scale, np.concatenate([list(vars(params).values()), scale, [f_scale],
                                               mesh if mesh is not None else []])

    def params(self, case: Case) -> SimpleNamespace:
        """The case's SI values of this formulation's quantities; those the case leaves out read as NaN."""
        return namespace({q.name: case.values.get(q.name, math.nan) for q in self.formulation.quantities})

    def params_of(self, cases: list[Case]) -> SimpleNamespace:
        """:meth:`params` of each of ``cases``, an array over them by name (one design checked at several cases)."""
        return namespace({q.name: np.array([case.values.get(q.name, math.nan) for case in cases])
                          for q in self.formulation.quantities})

    def scaled_data(self, case: Case, start: dict[str, float] | None = None, scale: np.ndarray | None = None,
                    internal: np.ndarray | None = None, mesh: np.ndarray | None = None,
                    checked: SimpleNamespace | None = None) -> ScaledData:
        """Bounds, start and scales of one solve (scales from the start unless given); with a start-up, its states
        start from ``internal`` (a previous solve's) or from a simulation of the start design, on ``mesh``;
        ``checked``: the case values the design is checked against (moved limits solve, the case's own check)."""
        lower, upper, x0 = self.bounds_and_start(case, start)
        params = self.params(case)
        scale, f_scale, p_vector = self._scaling(case, params, x0, lower, upper, scale, mesh)
        data = ScaledData(params, lower, upper, x0, scale, f_scale, p_vector, checked=checked)
        if self.start_up is not None:
            data.internal_lower, data.internal_upper = self.start_up.bounds()
            if internal is None or len(internal) != self.start_up.size:
                seen, design = self.start_up_seen(case, self.design(x0 / scale, scale))
                if mesh is None:  # a cold start: the slip phase graded over the knee of the design's own start
                    p_vector[-self.mesh_size:] = first_mesh_of_the_start(self.start_up, seen, self.formulation, design)
                internal = initial_states(self.start_up, seen, self.formulation, design,
                                          np.array(self.internal_scale(p_vector[: len(params.__dict__)])).ravel(),
                                          p_vector[-self.mesh_size:])
            data.internal_start = np.clip(internal, data.internal_lower, data.internal_upper)
        return data

    def design(self, x: np.ndarray, scale: np.ndarray) -> dict[str, float]:
        """Design variables by name (SI) from the NLP's (scaled) x, internal variables left out."""
        return {v.name: float(value) for v, value in zip(self.formulation.variables, x[: len(scale)] * scale)}

    def rounded(self, design: dict[str, float]) -> dict[str, float]:
        """Integers rounded (IPOPT may leave them 1e-9 off their fixed bounds)."""
        for i in self.integer:
            design[self.names[i]] = float(round(design[self.names[i]]))
        return design

    def free_integers(self, data: ScaledData) -> list[int]:
        """The integer variables a solve's bounds leave free."""
        return [i for i in self.integer if data.lower[i] < data.upper[i]]

    def seen_by(self, case: Case, design: dict[str, float]):
        """name -> the design and case values ``(x, p)`` the start-up's constraint ``name`` is checked with, ``None``
        -> those its start is simulated at: the case's and the design's, a robust design's at their corners."""
        view, params = self.formulation.start_up_view, vars(self.params(case))
        if not view:  # one pair for every name: each constraint is the start's (``seen_constraints`` sees it at once)
            values = (namespace(design), namespace(params))
            return lambda name: values
        return lambda name: tuple(map(namespace, view(design, params, name)))

    def start_up_seen(self, case: Case, design: dict[str, float]) -> tuple[Case, dict[str, float]]:
        """The case and the design as the start-up's simulated start sees them (a robust design's: at its corner)."""
        view = self.formulation.start_up_view
        if not view:
            return case, design
        design, values = view(design, case.values, None)
        return replace(case, values=case.followed(values)), design

    @cached_property
    def paired(self) -> set[str]:
        """The names of the rows held from both sides (``TwoSided``'s pairs)."""
        return {self.row_names[row] for pair in self.sides.pairs for row in pair}

    def conflicting(self, case: Case) -> bool:
        """Whether two rows hold one quantity from both sides with no room between at ``case``'s values
        (``TwoSided.conflicts``: infeasible whatever the design), read from the case alone: the pairs' limits and
        scales are its quantities (no start scaled, no start-up simulated for it)."""
        return bool(self.sides.pairs) and bool(self.sides.conflicts(self._given_p(case), FEASIBILITY_TOL))

    def conflicting_at(self, cases: list[Case]) -> list[bool]:
        """:meth:`conflicting` at each of ``cases`` (a run of a sweep's points), in one evaluation."""
        if not self.sides.pairs:
            return [False] * len(cases)
        return self.conflicting_over(np.array([list(vars(self.params(case)).values()) for case in cases], dtype=float))

    def conflicting_over(self, values: np.ndarray) -> list[bool]:
        """:meth:`conflicting` at each row of ``values`` (a point's case values in the order of the formulation's
        quantities, as :meth:`params` reads them: a batched sweep's arrays), in one evaluation."""
        if not self.sides.pairs:
            return [False] * len(values)
        units = np.ones((self.nlp["p"].shape[0] - values.shape[1], len(values)))
        return self.sides.conflicting(np.vstack([values.T, units]), FEASIBILITY_TOL).tolist()

    def _given_p(self, case: Case) -> np.ndarray:
        """The NLP's parameter vector of ``case``'s values alone (scales 1: what the pairs' limits read)."""
        given = np.array(list(vars(self.params(case)).values()), dtype=float)
        return np.concatenate([given, np.ones(self.nlp["p"].shape[0] - len(given))])

    @property
    def mesh_size(self) -> int:
        return self.start_up.mesh_parameters.shape[0] if self.start_up is not None else 0

    def mesh_of(self, p_vector: np.ndarray) -> np.ndarray | None:
        """A start-up's collocation mesh in an NLP parameter vector (None without a start-up)."""
        return p_vector[len(p_vector) - self.mesh_size:] if self.start_up is not None else None

    def named_multipliers(self, lam_g: np.ndarray) -> list[float]:
        """The multiplier of each named constraint: the sum over its rows (one row, or the points of a path)."""
        ends = np.cumsum(self.constraint_rows)
        return [float(lam_g[end - rows:end].sum()) for rows, end in zip(self.constraint_rows, ends)]

    @property
    def kkt_tolerance(self) -> float:
        """The KKT verdict's tolerance (10 tol): of the scaled stationarity, feasibility and complementarity."""
        return 10 * self.options.tol

    def negligible(self, f_hat):
        """A change of the scaled objective within the solver's tolerance of it (elementwise for arrays; symbolic
        for CasADi)."""
        return self.kkt_tolerance * fmax(abs(f_hat), 1e-300)


def off_scale(x_hat: np.ndarray) -> np.ndarray:
    """An optimum more than tenfold off its variable scales (per column for a 2-D ``x_hat``): solved again, scaled by
    it."""
    return np.any(off_scale_entries(x_hat), axis=0)


def off_scale_entries(x_hat):
    """Per variable: 1 (true) where it has moved more than tenfold from its scale; floats, arrays or CasADi."""
    moved = abs(x_hat)
    return (moved > 0) * ((moved > 10) + (moved < 0.1)) > 0


def scaled_box(lower, upper, scale, internal_bounds) -> tuple[np.ndarray, np.ndarray]:
    """The NLP's variable bounds: design bounds scaled, then the (already scaled) internal ones."""
    return (np.concatenate([lower / scale, internal_bounds[0]]), np.concatenate([upper / scale, internal_bounds[1]]))
