"""A start-up's limits as limit states of simulated starts in the standard normal space of the scatter: a chance
design's performance point of each limit on the beta-sphere (PMA), and importance sampling of the designed start
around each limit's design point (``clutchopt.optimise.robust``; docs/robust.md, "A start-up under a chance target").

The form of every limit state, as the static ones' (``robust_reliability.limit_states``): the difference
g_i(u) = (limit - value) / s for a ``<=`` limit (value - limit for ``>=``), s its scale at the means of the scatter,
a constant; value and limit those of the design's start simulated (rtol START_RTOL) with the scattered quantities at
their values where the independent standard normals are u (:func:`clutchopt.scatter.values_from_standard`, exact,
correlated as the case's [scatter.correlation], cut where a quantity's valid range ends). A start that does not lock
up fails (g = -inf). One simulated start gives every limit; each point is simulated once per design (cached).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from clutchopt.cases import Case
from clutchopt.optimise.reliability import REACH as FORM_REACH
from clutchopt.optimise.reliability import DesignPoint, Estimate, form, generalised_beta, importance_sampling, ndtr
from clutchopt.optimise.robust_models import SEED, START_UP
from clutchopt.optimise.robust_reliability import ConstraintReliability
from clutchopt.optimise.robust_start_up import Bars, StartUpCorners, simulated_start_ups, start_up_corners
from clutchopt.optimise.verify import ConstraintCheck
from clutchopt.scatter import _within, values_from_standard
from clutchopt.start_up.drive import CLOSED_FORM

STEP = 1e-4  # forward differences in u of a simulated limit state: truncation STEP |g''| / 2 ~ 1e-4 of the gradient
# (in a uniform quantity's tail g'' ~ u g'), the simulation's noise (rtol 1e-9) / STEP ~ 1e-5 of it
SEARCH_STEPS = 40  # BFGS iterations of one search
RESTARTS = 3  # searches before the limit falls back to its quantile corner
TANGENTIAL = 1e-3  # |tangential gradient| / |gradient| at a settled performance point (the sphere's KKT condition):
# an angle of about that much from the minimum, where g exceeds it by about |grad g| beta TANGENTIAL^2 / 2
# ~ 1e-6 |grad g|
FLAT = 1e-6  # of g (a relative margin, the start-up's tolerance): a tangential gradient that moves g less over a
# distance beta holds (a limit the scatter hardly moves: its differences are mostly the simulation's noise)
NEGLIGIBLE = 1e-7  # |grad g| below this (g per unit of u) is a limit the scatter does not move
REACH = 1.0  # a limit whose design point lies within this (in u, to first order) of its performance point is
# sampled around it; one further out fails less than Phi(-beta - REACH): FORM from the performance point
CROSSING_XTOL = 1e-6  # in u: where a limit is crossed strictly along its ray (P to 1e-6 beta, relative)
SHARED_CENTRE = 0.25  # limits whose centres of importance sampling lie this close (in u) share one (and its starts)


class SimulatedLimitStates:
    """g(u), one row per start-up limit, one column per point (u: n rows), from the design's start simulated at
    each point (module docstring), cached by point."""

    def __init__(self, case: Case, mode: str, design: dict, scatter, correlation=None):
        self.case, self.mode, self.design, self.scatter, self.correlation = case, mode, design, scatter, correlation
        self.declared = {q.name: q for q in case.quantities}
        self.simulated: dict[bytes, list[ConstraintCheck]] = {}
        at_means = self.checks(np.zeros(len(scatter)))
        self.names = tuple(c.name for c in at_means)
        self.scale = np.array([c.scale for c in at_means])
        self.sign = np.array([1.0 if c.sense == "<=" else -1.0 for c in at_means])
        self.tolerance = at_means[0].tolerance  # the start-up's (relative, of the margins)

    def point(self, u: np.ndarray) -> dict[str, float]:
        """The scattered quantities' values at u (SI), each cut where its valid range ends."""
        values = values_from_standard(self.scatter, np.asarray(u, dtype=float)[:, None], self.correlation)
        return {q: _within(self.declared[q], float(v[0])) for q, v in values.items()}

    def checks(self, u: np.ndarray) -> list[ConstraintCheck]:
        """Every start-up limit checked with the start simulated at u."""
        return self.simulate(np.asarray(u, dtype=float)[:, None])[0]

    def simulate(self, u: np.ndarray) -> list[list[ConstraintCheck]]:
        keys = [np.ascontiguousarray(column).tobytes() for column in u.T]
        new = {key: column for key, column in zip(keys, u.T) if key not in self.simulated}
        runs = simulated_start_ups(self.case, self.mode, self.design, [self.point(c) for c in new.values()])
        self.simulated.update(zip(new, runs))
        return [self.simulated[key] for key in keys]

    def __call__(self, u: np.ndarray) -> np.ndarray:
        u = np.atleast_2d(np.asarray(u, dtype=float))
        runs = self.simulate(u)
        value, limit = (np.array([[getattr(c, key) for c in run] for run in runs]).T for key in ("value", "limit"))
        g = self.sign[:, None] * (limit - value) / self.scale[:, None]
        return np.where(np.isnan(g), -math.inf, g)  # a start that does not lock up fails

    def value_gradient(self, row: int, u: np.ndarray) -> tuple[float, np.ndarray]:
        """g_row(u) and its gradient by forward differences of step STEP (n + 1 simulated starts, cached)."""
        n = len(u)
        values = self(np.column_stack([u, u[:, None] + STEP * np.eye(n)]))[row]
        return float(values[0]), (values[1:] - values[0]) / STEP


def performance_point(g: SimulatedLimitStates, row: int, beta: float, start: np.ndarray | None = None):
    """(u, settled): PMA's most probable point of a simulated limit at ``beta`` (Tu, Choi & Park 1999): argmin g_row
    on ||u|| = beta. One quantity: the sphere is two points, -beta and beta. More: BFGS over v, u = beta v / |v|
    (unconstrained; the gradient of g projected on the sphere's tangent plane, times beta / |v|), from ``start``
    (the point at the previous design, kept where it still holds) or the advanced mean value step from the means,
    u = -beta grad g / |grad g| (the AMV iteration of ``reliability.performance_point`` alone cycles here: a uniform
    quantity mapped exactly flattens g in its tail, and the iteration jumps between the ends of two quantities).
    Settled where the gradient is normal to the sphere (its tangential part below TANGENTIAL of it, the sphere's
    KKT condition, or so small that g falls by less than FLAT along the sphere) and points away from the origin. A
    limit the scatter does not move at the means (|grad g| < NEGLIGIBLE) is at the means; one whose g or gradient
    is not finite (a start that does not lock up nearby) or that does not settle is not settled."""
    n = len(g.scatter)

    def holds(u: np.ndarray) -> bool:
        value, grad = g.value_gradient(row, u)
        tangential = grad - (grad @ u) * u / (beta * beta)
        return bool(math.isfinite(value) and np.all(np.isfinite(grad)) and grad @ u <= 0
                    and np.linalg.norm(tangential) <= max(TANGENTIAL * np.linalg.norm(grad), FLAT / beta))

    if n > 1 and start is not None and np.any(start) and holds(start):  # a kept start, away from the means
        return start, True
    grad, norm, finite = at_the_means(g, row)
    if not finite or norm < NEGLIGIBLE:
        return np.zeros(n), finite
    if n == 1:  # the sphere's two points (2 simulated starts)
        ends = np.array([[-beta, beta]])
        at = g(ends)[row]
        return ends[:, int(np.argmin(at))], bool(np.all(np.isfinite(at)))
    from scipy.optimize import minimize

    def on_sphere(v: np.ndarray) -> tuple[float, np.ndarray]:
        length = float(np.linalg.norm(v))
        value, grad = g.value_gradient(row, beta * v / length)
        along = v / length
        return value, beta / length * (grad - (grad @ along) * along)

    u = start if start is not None and np.any(start) else -beta * grad / norm
    for _ in range(RESTARTS):  # from the sphere again: the gradient in v shrinks by beta / |v| as v grows
        result = minimize(on_sphere, u, jac=True, method="BFGS",
                          options={"gtol": FLAT / beta / 2, "norm": 2,  # or until the noise stops it
                                   "maxiter": SEARCH_STEPS})
        u = beta * result.x / np.linalg.norm(result.x)
        if holds(u):
            return u, True
    return u, False


def at_the_means(g: SimulatedLimitStates, row: int) -> tuple[np.ndarray, float, bool]:
    """(grad g_row at the means, its norm, whether g and its gradient are finite there): n + 1 simulated starts,
    shared by every limit (cached by point)."""
    value, grad = g.value_gradient(row, np.zeros(len(g.scatter)))
    norm = float(np.linalg.norm(grad))
    return grad, norm, math.isfinite(value) and math.isfinite(norm)


def moved_at_the_means(g: SimulatedLimitStates, row: int) -> bool:
    """Whether the scatter moves limit ``row`` (:func:`performance_point` without a start to keep ends away from the
    means, or does not settle), decided at the means without the search: the search returns the means (settled) only
    where g and its gradient are finite there and |grad g| < NEGLIGIBLE; elsewhere a point on the sphere (one of its
    two points for one quantity; BFGS's, normalised, for more), or the means unsettled where g is not finite."""
    _, norm, finite = at_the_means(g, row)
    return not finite or norm >= NEGLIGIBLE


def strict_reach(g: SimulatedLimitStates, row: int, u: np.ndarray) -> float:
    """Where a limit beyond its value at its performance point ``u`` (failing there, if within the
    start-up's tolerance) is crossed strictly along the ray from the means through u: Brent's method on g's own
    value (no tolerance) to CROSSING_XTOL, each step a simulated start; 0 where it fails at the means already. With
    one scattered quantity the ray is the whole line and Phi(-reach) the exact probability of failing (a limit
    monotone in it); with more, FORM's at that point."""
    from scipy.optimize import brentq

    radius = float(np.linalg.norm(u))
    direction = u / radius

    def value(t: float) -> float:  # (at t = radius u itself: radius * (u / radius) may differ from u in its last
        # bits, a start simulated again whose g, a hair below zero at u, may come out at or above it)
        point = u if t == radius else t * direction
        return float(g(np.asarray(point, dtype=float)[:, None])[row, 0])

    if not value(0.0) > 0:
        return 0.0
    return float(brentq(value, 0.0, radius, xtol=CROSSING_XTOL))



@dataclass
class StartUpPerformancePoints:
    """A chance design's start-up limits at their performance points, found again at each design of the SORA loop
    (``robust.solve_robust``): each limit evaluated at its own, the start simulated in the NLP at the performance
    point of the limit that reads its figures and binds there (its smallest g). A limit whose point does not settle
    falls back to its quantile corner (``robust_start_up.start_up_corners``), named in ``fallbacks``."""

    case: Case
    mode: str
    target: float  # the probability each start-up limit holds with
    correlation: dict | None = None
    previous: dict[str, np.ndarray] = field(default_factory=dict)  # limit -> its point in u at the last design
    fallbacks: set[str] = field(default_factory=set)
    states: SimulatedLimitStates | None = None  # at the last design
    points: dict[str, np.ndarray] = field(default_factory=dict)  # limit -> its performance point in u, last design
    share: float | None = None  # under a system target: each moved limit's share of 1 - P (:meth:`take_shares`)
    quantile: dict[float, StartUpCorners] = field(default_factory=dict)  # target -> the quantile corners at the last
    # design (:meth:`quantile_corners`)
    bars: Bars | None = None  # the tornado's bars at the last design, simulated on first read

    @property
    def beta(self) -> float:
        return generalised_beta(1.0 - self.target)

    def states_at(self, design: dict) -> SimulatedLimitStates:
        """The limit states at ``design``, kept (with their simulated starts) while the design stays."""
        if self.states is None or self.states.design != design:
            self.states = SimulatedLimitStates(self.case, self.mode, design, self.case.scatter, self.correlation)
            self.quantile, self.bars = {}, Bars(self.case, self.mode, design, self.case.scatter)
        return self.states

    def quantile_corners(self) -> dict[str, dict[str, float]]:
        """The quantile corners at the last design and target (``robust_start_up.start_up_corners``), simulated once
        per design and target; their bars are the design's (the same starts)."""
        if self.target not in self.quantile:
            self.quantile[self.target] = start_up_corners(self.case, self.mode, self.states.design, self.case.scatter,
                                                          self.target)
            self.bars.known(self.quantile[self.target].bars)
        return self.quantile[self.target].corners

    def at(self, design: dict) -> StartUpCorners:
        """The start-up's corners at ``design``: START_UP and each limit -> quantity -> value; its bars simulated when
        read (:class:`robust_start_up.Bars`)."""
        g, self.points, self.fallbacks = self.states_at(design), {}, set()
        corners = {}
        for row, name in enumerate(g.names):
            u, settled = performance_point(g, row, self.beta, self.previous.get(name))
            if settled:
                self.points[name] = self.previous[name] = u
                corners[name] = g.point(u)
            else:
                self.fallbacks.add(name)
        if self.fallbacks:
            quantile = self.quantile_corners()
            corners.update({name: quantile[name] for name in self.fallbacks})
        figures = [row for row, name in enumerate(g.names) if name not in CLOSED_FORM and name in self.points]
        if figures:
            at = g(np.column_stack([self.points[g.names[row]] for row in figures]))
            binding = g.names[figures[int(np.argmin([at[row, i] for i, row in enumerate(figures)]))]]
            corners = {START_UP: corners[binding], **corners}
        else:
            corners = {START_UP: self.quantile_corners()[START_UP], **corners}
        return StartUpCorners({}, corners, self.bars)

    def take_shares(self, design: dict, others: int, allowed: float) -> float:
        """Under a system target (``allowed`` = 1 - P, shared with ``others`` constraints): each start-up limit the
        scatter moves at ``design`` (or whose point does not settle) takes an equal share of ``allowed`` and is
        designed to hold with 1 - share; what is left for the others (whose split the NLP chooses). Which limits
        move is decided by the gradients at the means (:func:`moved_at_the_means`, n + 1 simulated starts: called
        before any :meth:`at`, there is no kept start a search would try first, and a search from the means ends
        there exactly where those gradients say the limit is not moved)."""
        g = self.states_at(design)
        moved = [name for row, name in enumerate(g.names) if moved_at_the_means(g, row)]
        if not moved:
            return allowed
        self.share = allowed / (len(moved) + others)
        self.target, self.previous = 1.0 - self.share, {}
        return allowed - self.share * len(moved)

    def distinct_points(self) -> list[dict[str, float]]:
        """The points the start was simulated at for the limits' checks: each limit's performance point, once."""
        out = []
        for u in self.points.values():
            point = self.states.point(u)
            if point not in out:
                out.append(point)
        return out

    def checks(self) -> list[ConstraintCheck]:
        """Each start-up limit checked at its own performance point (a fallback's: at the quantile corners, by the
        caller)."""
        return [self.states.checks(self.points[name])[row] for row, name in enumerate(self.states.names)
                if name in self.points]

    def reliability(self, starts: int) -> dict[str, ConstraintReliability]:
        """Each start-up limit's failure probability at the last design: one the scatter does not move holds or fails
        with certainty; one whose design point lies within REACH of its performance point (first order:
        beta + g / |grad g|; at an active limit g = 0 and the two coincide) by importance sampling of ``starts``
        simulated starts from the standard normal centred there (weight phi(u) / phi(u - u*), 95 % interval from
        the weights' spread), centres closer than SHARED_CENTRE shared; one further out by FORM from its performance
        point, Phi(-(beta + g / |grad g|)), or where that lies beyond ``reliability.REACH`` (9) its bound Phi(-9),
        as the closed forms' (``robust_reliability.reliability_at``). A g met within the start-up's tolerance of 0 is 0
        (the limit is met there as the solver meets it: active, its design point its performance point); one beyond
        0 within the tolerance fails at its point, and its probability is that of the ray beyond its strict crossing
        (:func:`strict_reach`): the failure event is the limit's own, not widened by the tolerance."""
        g, beta, n = self.states, self.beta, len(self.case.scatter)
        out, centres = {}, []
        for row, name in enumerate(g.names):
            if name not in self.points:
                continue
            u = self.points[name]
            values = g.point(u)
            if not np.any(u):
                certain = 0.0 if g.checks(u)[row].margin >= -g.tolerance else 1.0
                out[name] = ConstraintReliability(DesignPoint(u, math.inf if certain == 0 else -math.inf, False),
                                                  values, [Estimate(certain, certain, certain,
                                                                    "exact: independent of the scatter")])
                continue
            value, grad = g.value_gradient(row, u)
            slope = float(np.linalg.norm(grad))
            if -g.tolerance <= value < 0:  # beyond its limit at its point, if within the tolerance: its design point
                # is where it is crossed strictly along the ray (at system_chance=0.999999999 near a range's end
                # 5.02, not beta 6.31: P 2.6e-7, not 1.4e-10; to first order, -2.4e-7 over the end's slope of 1e-9
                # had moved beta to -285 and "P = 1")
                reach = strict_reach(g, row, u)
            elif abs(value) <= g.tolerance:  # met at its point within the tolerance: active there, reach = beta
                reach = beta
            else:
                reach = beta + value / slope if slope > 0 else math.inf  # flat at its point: no failure within reach
            point = DesignPoint(u * reach / np.linalg.norm(u), reach, reach <= FORM_REACH)
            if reach > FORM_REACH:
                bound = float(ndtr(-FORM_REACH))
                out[name] = ConstraintReliability(point, values, [
                    Estimate(0.0, 0.0, bound, f"FORM (no design point within beta {FORM_REACH:g})")])
                continue
            if reach - beta > REACH:
                p = float(ndtr(-reach))
                out[name] = ConstraintReliability(point, g.point(point.u), [Estimate(p, p, p, "FORM")])
                continue
            centre = next((c for c in centres if np.linalg.norm(c - u) <= SHARED_CENTRE), None)
            if centre is None:
                centres.append(centre := u)
            sampled = importance_sampling(g, [row], [centre], n, starts, SEED + 2, g.tolerance, defensive=False)
            out[name] = ConstraintReliability(point, g.point(point.u), [form(point), sampled])
        return out
