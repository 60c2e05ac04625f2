"""The system chance optimum (``--robust system_chance=P``): the split of 1 - P between the constraints chosen by the
NLP, not fixed beforehand (docs/robust.md, "The system").

The design fails when any constraint fails. Constraint i at its performance point on the sphere ||u|| = beta_i
fails with probability p_i ~ Phi(-beta_i) (FORM), and the series system with at most sum_i p_i (Bonferroni, the
first-order Ditlevsen upper bound; exact when the failure events are disjoint). So each beta_i is a design variable
of the NLP, with the one constraint

    system_risk:  sum_i Phi(-(beta_i + s_i)) <= B,

each constraint i evaluated at its performance point u_i = beta_i alpha_i, alpha_i the unit direction of the
previous SORA iteration (Du & Chen 2004), mapped exactly into physical space inside the NLP as a function of beta_i
(x = F^-1(Phi(z)), z = L u: :func:`mapped`). At the fixed point the derivative the NLP sees along alpha_i is that of
the smallest g_i on the sphere (the gradient is parallel to alpha_i at the performance point), so the KKT point is
the optimum of the allocation itself. s_i is the index importance sampling adds (the generalised index
-Phi^-1(p_IS) of the constraint at the design, minus beta_i), held where sampling does not refute FORM; B starts at
1 - P and is scaled by (1 - P) / P(system fails) (importance sampling of the system) where the bound is loose, until
the system meets 1 - P. Nothing here knows a clutch.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field, replace

import casadi as ca
import numpy as np

from clutchopt.backend import exp, is_symbolic
from clutchopt.model import Formulation, Quantity, Variable, at_most
from clutchopt.optimise.reliability import REACH, generalised_beta, ndtr, ndtri
from clutchopt.optimise.robust_models import at_point, corner_name
from clutchopt.scatter import correlated

RISK = "system_risk"  # the constraint sum_i Phi(-(beta_i + s_i)) <= B
BUDGET = "risk_budget"  # B, the case quantity of its limit
SYSTEM_TOL = 0.01  # of ln((1 - P) / P(system fails)): the system meets its target to 1 %
AIM_BELOW = 0.005  # relative: a new budget (and robust's root find) aims this far below 1 - P, so that the estimate
# ends at or below it
SYSTEM_SAMPLES = 400_000  # importance samples of the allocation's estimates: the system's mixture spends a share on
#   the origin (defensive), so 50,000 give it +-4 % at 1e-3 on the centrifuge; 400,000 +-1.4 %, 0.2 s of CPU
LOOSE = 0.02  # relative: a budget further than this from 1 - P says the bound is loose (correlated failure modes)


def beta_name(constraint: str) -> str:
    """The design variable beta_i of constraint i: the radius of its performance point."""
    return f"beta@{constraint}"


def direction_name(quantity: str, constraint: str) -> str:
    """The case quantity (an NLP parameter) of the direction of constraint i's performance point in the correlated
    standard normal variable of ``quantity``: z_q = beta_i d_q."""
    return f"direction_{quantity}@{constraint}"


def shift_name(constraint: str) -> str:
    """The case quantity (an NLP parameter) s_i: the index importance sampling adds to beta_i."""
    return f"index_shift@{constraint}"


# --- The exact map, on floats and CasADi symbols alike -----------------------------------------------------------
def phi(z):
    """Phi(z), the standard normal distribution function: 0.5 (1 + erf(z / sqrt 2)) on a CasADi symbol."""
    return 0.5 * (1.0 + ca.erf(z / math.sqrt(2.0))) if is_symbolic(z) else ndtr(z)


def phi_inverse(p):
    """Phi^-1(p): on a CasADi symbol sqrt 2 erfinv(2 p - 1) and one Newton step z - (Phi(z) - p) / phi(z) (CasADi's
    erfinv is good to about 1e-7 relative in the tails; the step squares the error)."""
    if is_symbolic(p):
        z = math.sqrt(2.0) * ca.erfinv(2.0 * p - 1.0)
        return z - (phi(z) - p) * math.sqrt(2.0 * math.pi) * exp(0.5 * z * z)
    return ndtri(p)


def mapped(scatter, z):
    """x = F^-1(Phi(z)) of one scattered quantity at its (correlated) standard normal z, a float or a CasADi
    symbol: the map :meth:`clutchopt.scatter.Scatter.from_standard` computes on floats from the nearer tail
    (``tests/test_risk_allocation.py`` compares the two): normal mean + sd z; lognormal exp(mu + sigma z); a range
    or uniform low + (high - low) Phi(z); a normal cut to [low, high] mean + sd Phi^-1(Phi(a) + Phi(z) (Phi(b) -
    Phi(a))), a, b the cuts in sd."""
    if scatter.kind == "normal":
        return scatter.mean + scatter.sd * z
    if scatter.kind == "lognormal":
        mu, sigma = scatter.log_parameters()
        return exp(mu + sigma * z)
    if scatter.kind == "truncated":
        below, above = (float(phi((end - scatter.mean) / scatter.sd)) for end in (scatter.low, scatter.high))
        return scatter.mean + scatter.sd * phi_inverse(below + phi(z) * (above - below))
    return scatter.low + (scatter.high - scatter.low) * phi(z)


# --- The NLP -------------------------------------------------------------------------------------------------------
def allocation_formulation(derived: Formulation, base: Formulation, scatter, names: tuple[str, ...],
                           allocated: tuple[str, ...]) -> Formulation:
    """``derived`` (each constraint at its corner ``q@name``, :func:`clutchopt.optimise.robust_models.
    worst_case_formulation`) with each constraint of ``allocated`` instead at its performance point beta_i d_i in
    the correlated standard normal space, beta_i a design variable (``beta@name``) and d_i the parameters
    ``direction_q@name``, and the constraint ``system_risk`` sum_i Phi(-(beta_i + s_i)) <= ``risk_budget``."""
    quantities = (
        *(Quantity(direction_name(s.name, c), "", f"direction of {c}'s performance point in {s.name}'s standard "
                                                  "normal variable", section="scatter", default=None)
          for c in allocated for s in scatter),
        *(Quantity(shift_name(c), "", f"index importance sampling adds to {c}'s beta", section="scatter",
                   default=None) for c in allocated),
        Quantity(BUDGET, "", "B: the first-order series bound's limit, 1 - P unless the bound is loose",
                 section="scatter", default=None))
    betas = tuple(Variable(beta_name(c), "", f"reliability index of {c}'s performance point: its share "
                                             "Phi(-beta) of 1 - P", "beta", lower=0.0, upper=REACH)
                  for c in allocated)
    scattered = tuple(s.name for s in scatter)

    def constraints(x, p):
        rows = []
        for i, name in enumerate(names):
            if name in allocated:
                beta = getattr(x, beta_name(name))
                values = {s.name: mapped(s, beta * getattr(p, direction_name(s.name, name))) for s in scatter}
            else:
                values = {q: getattr(p, corner_name(q, name)) for q in scattered}
            rows.append(base.constraints(*at_point(vars(x), vars(p), values))[i])
        risk = sum(phi(-(getattr(x, beta_name(c)) + getattr(p, shift_name(c)))) for c in allocated)
        return rows + [at_most(RISK, risk, getattr(p, BUDGET), equation="Bonferroni: P(any) <= sum_i P_i",
                               description="the constraints' shares of 1 - P: the first-order series bound")]

    digest = hashlib.sha1(repr(tuple(scatter)).encode()).hexdigest()[:12]  # the map's constants are in the NLP
    return replace(derived, quantities=derived.quantities + quantities, variables=base.variables + betas,
                   constraints=constraints,
                   variant=f"{derived.variant}; risk allocated over {', '.join(allocated)} [{digest}]")


# --- The iteration -------------------------------------------------------------------------------------------------
@dataclass
class RiskAllocation:
    """The state of the allocation between solves: each allocated constraint's beta (the NLP's), the direction of
    its performance point (SORA), its index shift s_i (importance sampling), and the budget B."""

    allowed: float  # 1 - P
    scatter: tuple
    correlation: object
    betas: dict[str, float]
    directions: dict[str, np.ndarray] = field(default_factory=dict)  # correlated standard normal space, unit
    shifts: dict[str, float] = field(default_factory=dict)
    budget: float = math.nan
    system: object = None  # the last Estimate of P(system fails)
    shares: dict[str, object] = field(default_factory=dict)  # constraint -> its last Estimate

    def __post_init__(self):
        self.budget = self.allowed if math.isnan(self.budget) else self.budget
        self.shifts = {name: self.shifts.get(name, 0.0) for name in self.betas}

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(self.betas)

    def variables(self) -> dict[str, float]:
        """The beta variables, as a start point or beside a design."""
        return {beta_name(name): beta for name, beta in self.betas.items()}

    def parameters(self) -> dict[str, float]:
        """The NLP parameters: directions, index shifts, budget."""
        return {**{direction_name(s.name, c): float(d[k]) for c, d in self.directions.items()
                   for k, s in enumerate(self.scatter)},
                **{shift_name(c): s for c, s in self.shifts.items()}, BUDGET: self.budget}

    def read(self, design: dict) -> dict[str, float]:
        """The betas the NLP chose."""
        self.betas = {name: float(design[beta_name(name)]) for name in self.betas}
        return self.betas

    def aim(self, points: dict[str, np.ndarray]) -> None:
        """The directions of the performance points ``points`` (independent standard normal u, at the current
        betas) in the correlated space the map takes: d = L u / ||u||."""
        for name in self.betas:
            u = np.asarray(points[name], dtype=float)
            norm = float(np.linalg.norm(u))
            self.directions[name] = correlated(u[:, None] / norm, self.correlation)[:, 0] if norm > 0 else 0 * u

    def model(self, name: str) -> float:
        """The share the NLP counts for ``name``: Phi(-(beta + s))."""
        return float(ndtr(-(self.betas[name] + self.shifts[name])))

    def step(self, reliability, margins: dict[str, float], active: float) -> bool:
        """After a settled solve: each active constraint's index shift set where importance sampling refutes the
        share the NLP counted (its interval does not hold it); then, once none moved, the budget scaled by
        (1 - P) / P(system fails) where the system misses its target. A budget the NLP left unused (``system_risk``
        not active: its objective does not change with the betas, as where each allocated constraint's point lies
        at a uniform range's end) is not raised: the design meets 1 - P and a larger budget does not move an
        optimum it does not bind; where the system misses, the bound the NLP reached is scaled, not the budget
        (which the NLP might leave unused again). False when nothing moves."""
        self.system = reliability.system
        moved = False
        for name in self.betas:
            shown = reliability.constraints.get(name)
            if shown is None:
                continue
            self.shares[name] = best = shown.best
            if (not shown.point.found or margins.get(name, 1.0) > active or best.probability <= 0
                    or best.estimator != "importance sampling" or best.low <= self.model(name) <= best.high):
                continue
            self.shifts[name] = generalised_beta(best.probability) - self.betas[name]
            moved = True
        system = reliability.system.probability
        if moved or not system > 0:
            return moved
        unused = margins.get(RISK, 0.0) > active
        if system <= self.allowed and (unused or math.log(self.allowed / system) <= SYSTEM_TOL):
            return False
        reached = self.budget * (1 - margins[RISK]) if unused else self.budget  # the NLP's series bound
        self.budget = reached * self.allowed * (1 - AIM_BELOW) / system
        return True

    def claim(self) -> str:
        """What the design is, in one sentence."""
        bound = sum(self.model(name) for name in self.betas)
        system = self.system.probability if self.system is not None else math.nan
        ratio = self.budget / self.allowed
        text = (f"risk allocation optimised (each constraint's beta an NLP variable, sum_i Phi(-beta_i) <= "
                f"{self.budget:.3g}, corrected by importance sampling): first-order series bound {bound:.3g}, "
                f"system {system:.3g} by importance sampling")
        if abs(ratio - 1) <= LOOSE:
            return text + f"; the bound is tight: the lightest design whose series bound meets {self.allowed:.3g}"
        return text + (f"; the bound is loose (failure modes overlap), budget scaled by {ratio:.3g} and re-solved: "
                       f"the lightest design whose series bound meets {self.budget:.3g}, the system meeting "
                       f"{self.allowed:.3g}")

    def as_dict(self) -> dict:
        return {"method": "risk allocation optimised: beta_i NLP variables, sum_i Phi(-(beta_i + s_i)) <= budget "
                          "(first-order series bound), s_i by importance sampling, the system by importance sampling",
                "claim": self.claim(), "target": self.allowed, "budget": self.budget,
                "series_bound": sum(self.model(name) for name in self.betas),
                "system": self.system.as_dict() if self.system is not None else None,
                "constraints": {name: {"beta": self.betas[name], "index_shift": self.shifts[name],
                                       "share": self.model(name),
                                       "failure_probability": self.shares[name].as_dict()
                                       if name in self.shares else None} for name in self.betas}}
