"""What a solve returns and how it is asked: the solver options, the solution with its solver figures, and a warm
start's data."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from numbers import Integral, Real
from typing import NamedTuple, Sequence

import numpy as np

from clutchopt.model import Output
from clutchopt.records import DESIGN_STATUSES
from clutchopt.optimise.verify import ConstraintCheck
from clutchopt.errors import InputError, Problems
from clutchopt.solver_tolerance import SOLVER_TOL, TOLERANCE_RANGE
from clutchopt.units import si_unit


@dataclass(frozen=True)
class SolverOptions:
    tol: float = SOLVER_TOL
    max_iter: int = 3000
    warm_sqp: bool = True  # warm re-solves try SQP before warm IPOPT, and a static solve's rounded integers SQP from
    # its relaxation before IPOPT (integers.FROM_THE_RELAXATION) (False: IPOPT alone, for comparison)
    polish: bool = True  # a static solve's IPOPT optimum polished onto its exact KKT point (optimise/polish.py;
    #                      False: as IPOPT ends, for the papers' sizing a start-up solve starts from)

    def __post_init__(self):
        """The options the command line would take, or an InputError naming each other one (review 27: the Python
        API took tol 1e3 and called IPOPT's loose end ``optimal``, and 0 or a negative max_iter crashed in CasADi)."""
        problems, (low, high) = Problems(), TOLERANCE_RANGE
        if not isinstance(self.tol, Real) or isinstance(self.tol, bool) or not low <= self.tol <= high:  # (NaN too)
            problems.errors.append(InputError("tol", f"must be a number from {low:g} to {high:g}, got {self.tol!r}"))
        if not isinstance(self.max_iter, Integral) or isinstance(self.max_iter, bool) or self.max_iter < 1:
            problems.errors.append(InputError("max_iter", f"must be a whole number of at least 1, got "
                                                          f"{self.max_iter!r}"))
        for name in ("warm_sqp", "polish"):
            if not isinstance(getattr(self, name), (bool, np.bool_)):
                problems.errors.append(InputError(name, f"must be True or False, got {getattr(self, name)!r}"))
        problems.raise_any()

    def ipopt_warm(self) -> dict:
        """IPOPT started from a previous primal-dual point, barely pushed off the bounds."""
        push = {f"ipopt.warm_start_{name}": 1e-9 for name in (
            "bound_push", "bound_frac", "mult_bound_push", "slack_bound_push", "slack_bound_frac")}
        return {**self.ipopt(), "ipopt.warm_start_init_point": "yes", "ipopt.mu_init": 1e-6, **push}

    def ipopt_start_up(self) -> dict:
        """IPOPT on a start-up's collocation from a cold start: its states start on a simulated start (or a previous
        solve's), its design at the papers' sizing, so the barrier starts at 1e-3, not IPOPT's 0.1 (docs/start_up.md,
        "IPOPT on the collocation": the four motor_start cases 13-136 iterations instead of 18-178, the same optima;
        from 1e-4 the ball at 0.83 times its driven inertia ended at a worse local optimum, 984.72 kg, not 950.755)."""
        return {**self.ipopt(), "ipopt.mu_init": START_UP_MU_INIT}

    def ipopt_warm_start_up(self) -> dict:
        """Warm IPOPT on a start-up's collocation re-solved on the mesh of the optimum it starts from (a limit
        correction, a sweep's next point): the barrier starts at 1e-9 (the wedge's sweep points: six iterations from
        1e-6, four or five from 1e-9)."""
        return {**self.ipopt_warm(), "ipopt.mu_init": START_UP_WARM_MU_INIT}

    def sqp(self) -> dict:
        """CasADi's SQP method with its dense active-set QP solver (qrqp), for re-solves beside a known optimum:
        no barrier to drive down, so a small problem's re-solve costs a few QP solves."""
        quiet = {"print_header": False, "print_iteration": False, "print_status": False, "print_time": False,
                 "show_eval_warnings": False}  # (a NaN at a trial step is the method's to handle, not the user's)
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
            "ipopt.bound_relax_factor": 0.0,
            "ipopt.print_level": 0,
            "ipopt.sb": "yes",
            "print_time": False,
            "show_eval_warnings": False,
        }


START_UP_MU_INIT = 1e-3  # IPOPT's first barrier parameter on a start-up's collocation, cold (IPOPT's default: 0.1)
START_UP_WARM_MU_INIT = 1e-9  # and warm on the same mesh (any other warm IPOPT: 1e-6)
IPOPT_OWN_FIGURES = {"no_nlp_grad": True, "calc_lam_p": False, "calc_lam_x": False, "calc_f": False, "calc_g": False}
# a start-up's IPOPT returns IPOPT's own x, f, g and multipliers (those of fixed variables too, IPOPT 3.14) instead of
# CasADi evaluating f, g and the Lagrangian's gradient again at its optimum: so CasADi does not derive that gradient
# in x and p when it builds the solver (12-25 ms of 63-120 per solver; the four motor_start cases' runs equal to the
# last bit: docs/start_up.md, "IPOPT's cost on the start-up NLP")
START_UP_RESTORATION = {"ipopt.resto.tol": 1e-6}  # a start-up's IPOPT ends a restoration phase that cannot
# return to the NLP once the restoration problem (the least l1 violation) is stationary to 1e-6, not 1e-10: only a run
# that ends `Infeasible_Problem_Detected` changes, by the iterations that drove the restoration's barrier to 1e-11
# around a violation already found (cable_motor_start's 6 cables: 44 to 35 iterations, its least violation 7.7165587e-2
# either way, 9e-10 apart); every run that ends with a design is the same to the last bit (docs/start_up.md,
# "Infeasible integer choices found sooner")


@dataclass
class SolverInfo:
    name: str
    status: str  # IPOPT's return status of the final (kept) solve
    iterations: int | None  # summed over the relaxation and integer neighbours (None: solved in a chained batch)
    time_s: float  # wall time of all solver calls (an infeasibility diagnosis included), without problem construction
    solves: int = 1  # design solves (the diagnosis not counted)

    def summed(self, infos) -> "SolverInfo":
        """This solve's name and status with the iterations, seconds and solves of ``infos`` (every solver call a
        result took: a loop's solves, starts tried, own loops) summed."""
        infos = list(infos)
        return SolverInfo(self.name, self.status, sum(i.iterations or 0 for i in infos), sum(i.time_s for i in infos),
                          sum(i.solves for i in infos))


class Diagnosis(NamedTuple):
    """Why a solve has no design: its status and text, the seconds of the elastic solve (a solver call, not a design
    solve), whether the text is a proof (a requirement no design variable enters, broken whatever the design),
    the least total relaxation found (relative, summed over the constraints) and the design where it was found."""

    status: str
    text: str
    seconds: float
    proven: bool = False
    least: float = math.nan
    nearest: dict[str, float] | None = None
    violated: tuple[str, ...] = ()  # the constraints the least relaxation found violates (the named reason)
    point: np.ndarray | None = None  # the elastic problem's own point (scaled NLP variables: design and states)


@dataclass
class Solution:
    coupling: str
    mode: str
    objective_name: str
    objective_unit: str
    status: str  # optimal | unverified | infeasible (proven) | not_found (no design from the starts tried) | solver_failed
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
    mesh: Sequence[np.ndarray] | None = field(default=None, repr=False)  # start-up: used, suggested (Meshes)
    diagnosed: Diagnosis | None = field(default=None, repr=False)  # a solve without a design: its elastic diagnosis
    starts: tuple[str, ...] = ()  # a solve without a design: the starts it was tried from (optimise/verdict.py)
    limit_shift: dict[str, float] = field(default_factory=dict, repr=False)  # start-up: the last NLP's limit
    #                                                        / the case's, where the defect correction moved it
    along: object | None = field(default=None, repr=False)  # a start-up sweep's point: its limits as its loop
    #                           ended, for the next point's (clutchopt.optimise.start_up_sweep.Along)
    sized: object | None = field(default=None, repr=False)  # a start-up sweep's point: the papers' sizing at it, for
    #     the next point's (clutchopt.optimise.start_up_sweep.SizedOut)
    shift_measured_by: frozenset = field(default_factory=frozenset, repr=False)  # an elastic link's start-up: the
    #     integer choices whose simulated starts moved limit_shift's limits (clutchopt.optimise.own_shift)
    unverified_at_the_case: frozenset = field(default_factory=frozenset, repr=False)  # an elastic link's start-up:
    #     the integer choices whose design of the NLP at the case's own limits its loop simulated, unverified
    collocated: dict[str, float] = field(default_factory=dict, repr=False)  # a start-up: the NLP's own figure of
    #     each start-up limit's check, by name (clutchopt.optimise.start_up_check.corrected_case)
    region_decided: bool = field(default=False, repr=False)  # a start-up sweep's point: its verdict the test against
    #     the point before's reason gave, no ``solve`` of it alone behind it (clutchopt.optimise.start_up_region)
    solve_alone: dict | None = None  # where the design kept is not what ``solve`` of the case alone ends with: that
    #     solve's status and objective (None without a design), also named in the diagnosis (:meth:`beside_alone`)

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
            **({"starts": list(self.starts)} if self.starts else {}),
            **({"solve_alone": self.solve_alone} if self.solve_alone is not None else {}),
        }

    def beside_alone(self, alone: "Solution") -> "Solution":
        """This solution, kept where ``solve`` of its case alone ended otherwise (``alone``: a heavier design, or none
        verified), saying so: ``solve_alone`` holds that solve's status and objective (None without a design), and
        the diagnosis names them ("solve alone: optimal, 687.9176 kg"); a sweep's record, its table and the run store
        show it as they show the diagnosis. Said once: a solution that says so already is kept as it is."""
        if self.solve_alone is not None:
            return self
        designed = alone.status in DESIGN_STATUSES
        note = f"solve alone: {alone.status}" + (f", {alone.objective:.10g} {alone.objective_unit}" if designed else "")
        return replace(self, solve_alone={"status": alone.status, "objective": alone.objective if designed else None},
                       diagnosis=f"{self.diagnosis}; {note}" if self.diagnosis else note)

    def counted(self, other: "Solution | None") -> "Solution":
        """This solution with the solver calls of ``other`` (a solve it was kept over: a warm start or a continuation
        that found no design, ``solve`` alone beside it) counted too; as it is where there is none."""
        return self if other is None else replace(self, solver=self.solver.summed([self.solver, other.solver]))


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
