"""The integer search on a posed problem: integer variables fixed through their bounds at each integer choice tried.

A first solve rounds its relaxation, a re-solve starts at the previous point's integers. From there the search steps
to a neighbouring integer only in a direction in which the fixed integer's bound multiplier says the objective
falls, and stops when a step does not lower it or the relaxation's objective (a bound on every integer choice) is
reached; an integer choice that violates a constraint of fixed variables alone (e.g. cable stress against the cable
count) is excluded without a solve. Where f*(n) is convex in the integers (the premise of rounding a relaxation at
all) this finds the best of the relaxation's floor and ceiling, in about one solve per point along a sweep. Should
the first integers fail, the floor and ceiling of the relaxation (then one further) are tried.

The search steps are given how to try one integer choice (``attempt``): :func:`fixing` solves it on the posed
problem; a batched sweep re-solves it by a one-point chained SQP.
"""

from __future__ import annotations

import itertools
import math
from typing import Callable

import numpy as np

import clutchopt.optimise.attempts as attempts
from clutchopt.optimise.link_bound import refuted
from clutchopt.optimise.modifier import modifiers_in
from clutchopt.optimise.posed import Box, Posed, ScaledData, scaled_box
from clutchopt.optimise.verify import FEASIBILITY_TOL
from clutchopt.records import UNRANKED

Attempt = Callable[..., "dict | None"]  # (combo, seed, methods) -> the verified run with the integers fixed at combo


def within(data: ScaledData, integer: list[int], combo: np.ndarray) -> bool:
    """The integer choice ``combo`` lies inside a solve's bounds."""
    return bool(np.all((combo >= data.lower[integer]) & (combo <= data.upper[integer])))


def _tried(posed: Posed, search: list[dict], integer: list[int], combo) -> bool:
    return any(all(entry[posed.names[i]] == c for i, c in zip(integer, combo)) for entry in search)


def descend(posed: Posed, box: Box, integer, combo, seed, search, attempt: Attempt, bound: float | None = None,
            first: tuple[str, ...] = ("ipopt",), again: bool = False) -> dict | None:
    """From the integers ``combo``, step to a neighbouring integer while the bound multipliers of the fixed
    integers say the objective falls that way and the step lowers it; None if ``combo`` itself fails.
    ``attempt(combo, seed, methods)``: the run with the integers fixed at ``combo`` if it is a verified optimum,
    else None, logged in ``search`` (``Problem.solve``: :func:`fixing`; a batched sweep: one-point SQP).
    ``bound``: the relaxation's scaled objective; an integer point that reaches it cannot be beaten.
    ``first``: the methods for ``combo``; the neighbours are solved by IPOPT from a cold start. ``again``: ``combo``
    is solved from ``seed`` even where the search tried it before (:func:`from_the_start`)."""
    kept, queue, methods = None, [combo], first
    while queue:
        combo = queue.pop(0)
        if _tried(posed, search, integer, combo) and not again:
            continue
        again = False
        run = attempt(combo, kept or seed, methods)
        methods = ("ipopt",)
        if run is None and kept is None:
            return None
        if run is not None and (kept is None or run["value"] < kept["value"]):
            kept, queue = run, downhill(posed, run, box, integer)
            if bound is not None and run["f"] <= bound + posed.negligible(bound):
                break
    return kept


def nearest_integers(posed: Posed, box: Box, integer, relaxed: dict, search, attempt: Attempt,
                     first: tuple[str, ...] = ("ipopt",)) -> dict | None:
    """The integer point of a relaxation's optimum ``relaxed``: :func:`descend` from its rounded integers, bounded
    by its objective; should they fail, the best of its floor and ceiling, then one further (``attempt`` as for
    :func:`descend`). None: no integer point near the relaxation is feasible. ``first``: the methods for the rounded
    integers, from the relaxation's primal-dual point (FROM_THE_RELAXATION: a static solve's; its seed then a copy of
    ``relaxed`` with the same ``x``)."""
    nearest = np.clip(np.round(relaxed["x"][integer] * box.scale[integer]), box.lower[integer], box.upper[integer])
    seed = relaxed if first == ("ipopt",) else {**relaxed, **dict(zip(("lam_x", "lam_g"), attempts.warm_multipliers(
        posed, relaxed["lam_x"], relaxed["lam_g"])))}  # (qrqp reads IPOPT's 1e-11 as an active bound)
    kept = descend(posed, box, integer, nearest, seed, search, attempt, bound=relaxed["f"], first=first)
    for reach in (1, 2) if kept is None else ():
        x_relaxed = relaxed["x"][: len(box.scale)] * box.scale
        for combo in _neighbours(x_relaxed, integer, box.lower, box.upper, reach):
            if not _tried(posed, search, integer, combo):
                run = attempt(combo, relaxed, ("ipopt",))
                if run is not None and (kept is None or run["value"] < kept["value"]):
                    kept = run
        if kept is not None:
            break
    return kept


FROM_THE_RELAXATION = ("sqp", "ipopt")  # a static solve's rounded integers: SQP from the relaxation's optimum (the
# integers moved by at most a half, the rest near the vertex), KKT-checked, IPOPT from cold where it fails. Cold solves
# of every static formulation with integers at 1,166 points of its duty, speed and friction coefficient (0.5x-2x and
# 1x-10x): 3.8-6.0 ms against 5.3-7.4 (IPOPT from cold, then its polish by SQP), the statuses the same, the objectives
# within 2.5e-10 (review 23: 13,612 random points, the same statuses and integers, at most 2.4e-10 heavier). Where the
# fixed-integer NLP has two local optima, each path may end at either (docs/tradeoffs.md: with bounds set at random one
# point 4.1e-4 heavier, three lighter by 9e-4 to 8.5e-3)


def from_the_start(posed: Posed, data: ScaledData, integer, kept: dict | None, search, attempt: Attempt,
                   start: "tuple[np.ndarray, Callable[[], np.ndarray]] | None" = None) -> dict | None:
    """A first start-up solve's search, completed by its start's integers: the start is the papers' sizing, the
    static optimum, whose objective no start-up design goes below. Where the start meets every row of the NLP
    (its states from its simulated start: the start-up's limits met), the kept design (``kept``, from
    :func:`nearest_integers`) is heavier than it by more than the solver's tolerance, or none was found, and the
    search did not try the start's integers, they are fixed and solved cold from the start, and :func:`descend`
    goes on from there; the lighter of the two is kept. The relaxation and the fixed-integer NLPs of a start-up have
    several local optima: ball_motor_start at 340 kg m^2 relaxes to 24.25 rows at a local optimum (1013 kg),
    24 rows from there end at 1016.18 kg and 25 rows at 1015.94 kg, kept by main; 23 rows (the sizing's) from the
    sizing solve to 950.76 kg, its own design. (At its 375 kg m^2 the sizing misses the start time by 6.3 %, the
    cable's link stress is 93 times over at its 0.25 kg m^2: not tried, no run added.)

    The start's integers are solved from the start too where the search tried them from another point and kept no
    design as light as the start (the kept one heavier, or none): the start is a point of their NLP (every row met),
    so an infeasibility IPOPT reported for them from elsewhere is a local one its restoration ended in, and a
    heavier optimum a local one, both refuted by the start. They are solved first from the start as from a feasible
    point (FROM_A_FEASIBLE_START), then cold. ball_motor_start at 303.95 kg m^2: 23 rows from the relaxation's point
    end ``Infeasible_Problem_Detected`` (43 iterations), 24 rows were kept (977.86 kg); 23 rows from the sizing,
    cold, end infeasible too (106 iterations), from it as a feasible point they solve to 950.76 kg, the design of
    the solve with 23 rows fixed. At 248.08 kg m^2 23 rows from the relaxation's point end at 955.98 kg, from the
    sizing at 950.755 kg.

    ``start``: where the search's own start (``data``'s) is not the sizing, as in a warm solve (a sweep's point from
    the point before's optimum, and the accuracy loop's solves after it), the sizing's design (SI) and a function
    giving its point of this NLP (the design scaled as ``data``, its states from its simulated start, as a first
    solve builds them; None where it cannot be simulated): called only where the tests on the design alone leave the
    sizing a chance, so a point whose kept design is the sizing's simulates nothing. ball_motor_start over
    driven_inertia at 288.2 kg m^2: the loop's second solve, warm from the first's 23-row design (957.55 kg, its
    first mesh's), found 23 rows infeasible and kept 24 (954.264 kg); from the sizing 23 rows solve to 950.755 kg,
    ``solve``'s design of the point."""
    design, point = start if start is not None else (data.start, lambda: data.x0)
    combo = np.round(design[integer])
    start_value = attempts.checked(posed, dict(zip(posed.names, design)), data.checked or data.params)["value"]
    bound = start_value + posed.negligible(start_value)
    if kept is not None and kept["value"] <= bound or not within(data, integer, combo):
        return kept  # (a design with the start's integers as light as the start would be kept: the lightest is)
    x0 = point()
    if x0 is None or not meets_every_row(posed, x0, data.p):
        return kept
    found = descend(posed, data.box, integer, combo, feasible_start(posed, x0), search, attempt,
                    first=FROM_A_FEASIBLE_START, again=True)
    return found if found is not None and (kept is None or found["value"] < kept["value"]) else kept


FROM_A_FEASIBLE_START = ("warm_near", "ipopt")  # IPOPT's barrier at 1e-9, the start barely pushed off its bounds,
# no multipliers; then cold (barrier 1e-3). From a point that meets every row the first stays by it and descends;
# the cold barrier leaves it, and where IPOPT's restoration then ends is chaotic: ball_motor_start at 303.95 kg m^2,
# 23 rows from the papers' sizing end infeasible in 106 iterations, the solve with 23 rows fixed from the same
# start (to 1e-11) converges in 387 (docs/start_up.md, "Integer attempts").


def meets_every_row(posed: Posed, x0: np.ndarray, p) -> bool:
    """Whether the point ``x0`` (scaled) meets every row of the NLP at parameters ``p`` (to 10 FEASIBILITY_TOL): a
    start :func:`from_the_start` solves its integers from."""
    return not least_violation(posed, np.array(posed.constraint_values(x0, p)).ravel()) > 10 * FEASIBILITY_TOL


def feasible_start(posed: Posed, x0: np.ndarray) -> dict:
    """A seed at a point that meets every row of the NLP, without multipliers (none is known there)."""
    return {"x": x0, "lam_x": np.zeros(len(x0)), "lam_g": np.zeros(len(posed.lbg))}


def _neighbours(x, integer, lower, upper, reach: int = 1):
    """Floor and ceiling of each relaxed integer (within bounds), nearest combinations first."""
    choices = []
    for i in integer:
        low, high = math.floor(x[i] + 1e-9), math.ceil(x[i] - 1e-9)
        options = sorted({min(max(k, lower[i]), upper[i]) for k in range(low - reach + 1, high + reach)},
                         key=lambda k: abs(k - x[i]))
        choices.append(options)
    return [np.array(combo, dtype=float) for combo in itertools.product(*choices)]


def priced(posed: Posed, lam: np.ndarray, scale: np.ndarray, f_hat) -> np.ndarray:
    """Per fixed integer (its bound multiplier ``lam``, its ``scale``), the direction of a unit step in which the
    scaled objective falls to first order, -|lam| / scale; 0 where that gain is within the solver's tolerance of
    the objective (``Posed.negligible``)."""
    return np.where(np.abs(lam) / scale > posed.negligible(f_hat), np.sign(lam), 0.0)


def downhill(posed: Posed, run: dict, box: Box, integer: list[int]) -> list[np.ndarray]:
    """Neighbours of a fixed-integer optimum in the directions its objective falls to first order.

    With integer i fixed through its bounds, d f_hat / d x_hat_i = -lam_x_i, so one unit step changes the
    scaled objective by about -|lam_x_i| / scale_i in the direction sign(lam_x_i). Where f*(n) is convex in
    the integers (the premise of rounding a relaxation at all), the other direction cannot win, nor can this
    one when the first-order gain is below the solver's tolerance of the objective."""
    steps = priced(posed, run["lam_x"][integer], box.scale[integer], run["f"])
    current = np.round(run["x"][integer] * box.scale[integer])
    choices = [sorted({c, min(max(c + s, lo), hi)}, key=lambda k: k != c + s)
               for c, s, lo, hi in zip(current, steps, box.lower[integer], box.upper[integer])]
    return [np.array(combo) for combo in itertools.product(*choices) if not np.array_equal(combo, current)]


def fixing(posed: Posed, data: ScaledData, runs: list[dict], search: list[dict],
           ruled: "RuledOut | None" = None, unranked: Callable[[dict], str | None] | None = None) -> Attempt:
    """``Problem.solve``'s ``attempt`` for :func:`descend`: the NLP on ``data`` with the free integers fixed at
    ``combo``, the run if it is a verified-feasible optimum, else None. A combination that violates a constraint
    depending on the integers and fixed variables alone is excluded without a solve, so is one ``ruled`` rules out
    (and records those found infeasible) and an elastic link's whose least stress at the seed's nodes is over its
    limit (:func:`~clutchopt.optimise.link_bound.refuted`). Every run goes into ``runs``. In a start-up, a run that
    ends without a verdict on the choice (:func:`no_verdict`) is tried once more, cold from the solve's own start
    (``data.x0``: the papers' sizing, or the warm design), those integers fixed. ``unranked(seed)``: why a choice
    solved from ``seed`` (a kept run) is not solved on this mesh, recorded as an UNRANKED entry (None: it is)."""
    integer = posed.free_integers(data)

    def fixed_at(combo, seed, methods: tuple[str, ...] = ("ipopt",)) -> dict | None:
        lbx, ubx, x0 = fixed_box(data, integer, combo, seed["x"])
        excluded = (violated_whatever_the_rest(posed, data.p, lbx, ubx, x0)
                    or (ruled.reason(combo) if ruled else [])
                    or ([] if modifiers_in(data.params) else refuted(posed, data, x0, lbx, ubx)))
        if excluded:
            search.append(excluded_entry(posed, integer, combo, excluded))
            return None
        if unranked is not None and (why := unranked(seed)) is not None:
            search.append(search_entry(posed, integer, combo, f"{UNRANKED}{why}", False, math.nan))
            return None
        run = attempts.attempt(posed, data, lbx, ubx, x0, seed, methods, runs)
        if no_verdict(posed, run) and not np.array_equal(second := np.clip(data.x0, lbx, ubx), x0):
            run = attempts.attempt(posed, data, lbx, ubx, second, None, ("ipopt",), runs)
        search.append(search_entry(posed, integer, combo, run["status"], run["feasible"], run["value"]))
        if ruled is not None and run["status"] == INFEASIBLE:
            ruled.found(combo, least_violation(posed, run["g"]))
        elif ruled is not None and run["ok"] and run["feasible"]:
            ruled.designed(combo, run["value"], [posed.names[i] for i in integer])
        return run if run["ok"] and run["feasible"] else None

    return fixed_at


def fixed_box(data: ScaledData, integer: list[int], combo, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The scaled bounds of ``data`` with its free integers (``integer``) fixed at ``combo``, and the point ``x``
    (scaled) clipped into them."""
    lower, upper = data.lower.copy(), data.upper.copy()
    lower[integer] = upper[integer] = combo
    lbx, ubx = scaled_box(lower, upper, data.scale, (data.internal_lower, data.internal_upper))
    return lbx, ubx, np.clip(x, lbx, ubx)


INFEASIBLE = "Infeasible_Problem_Detected"  # IPOPT's restoration phase ended at a local minimum of the violation
SOLVED = "Solve_Succeeded"
EXCLUDED = "excluded: "  # an integer search entry excluded without a solve, the rows it breaks after it
VERDICTS = (SOLVED, INFEASIBLE)  # IPOPT's ends that say something of the choice (not that they are global)


def no_verdict(posed: Posed, run: dict) -> bool:
    """Whether a start-up's fixed-integer run ended without saying anything of its integer choice: at IPOPT's
    iteration limit, a failed restoration, a step it could not compute (not a success, not a local infeasibility),
    so that the search would otherwise move on as if no design were there. ball_motor_start at 345 kg m^2: 24 rows
    from the relaxation's point ended at the iteration limit (500) and the search kept 25 rows (1020.37 kg); from
    the papers' sizing (its start) 24 rows solve in 46 iterations to 954.26 kg, and 23 rows follow, 950.76 kg."""
    return posed.start_up is not None and not run["ok"] and run["status"] not in VERDICTS


RULED_MARGIN = 10.0  # times the collocation error of the solve that found it: a violation no later solve closes


class RuledOut:
    """Integer choices a start-up's accuracy loop found infeasible, or heavier than the one it kept, not solved again
    in its later solves.

    IPOPT reports a problem infeasible where its restoration phase ends at a local minimum of the constraint
    violation; that least violation v (the largest normalised row) is recorded with the solve's collocation error e
    (its start time against the simulated one, relative). The loop's later solves change the NLP by the next mesh
    (whose error is below e) and by limits moved in by what the simulated start adds (about e): a choice with
    v > RULED_MARGIN e stays infeasible and is excluded without a solve. (The ball clutch of ball_motor_start at 24
    rows: v = 1.2e-3 on each mesh against e = 7e-5 and less; it was solved again after every adaptation, 94, 500
    and 84 IPOPT iterations, 1.9 s of the 2.4 s the design took.) Likewise a choice the solve found a design for
    heavier than the design it kept by more than RULED_MARGIN e (relative): the later solves move both objectives by
    about e, so it stays the heavier wherever the kept choice has a design, and it is not solved again in a solve
    whose runs have found one for the kept choice already (a search that has lost the kept choice solves it as
    ever). ball_motor_start over driven_inertia at 382.9 kg m^2: 26 rows, the downhill neighbour of the kept 25 by
    their multiplier, 2.5 % heavier, were solved on each mesh of the loop (14-15 IPOPT iterations each)."""

    def __init__(self, known: dict[tuple, str] | None = None):
        self.violations: dict[tuple, tuple[float, float]] = {}  # choice -> (least violation, error of its solve)
        self._pending: dict[tuple, float] = {}
        self.heavier: dict[tuple, tuple[float, float, tuple]] = {}  # choice -> (how much heavier, relative, the
        # error of its solve, the choice kept then)
        self._designed: dict[tuple, float] = {}  # the current solve's choices with a design -> its objective
        self._names: list[str] = []  # the integer variables a choice gives, in order
        self.known = known or {}  # choices known to have no design before the loop starts -> why (a start-up
        # sweep's point: those the papers' sizing there finds infeasible, ``start_up_sweep.sized_out``)

    def found(self, combo, violation: float) -> None:
        """A choice the current solve found infeasible by ``violation``; its error comes with :meth:`settle`."""
        self._pending[tuple(float(c) for c in combo)] = violation

    def designed(self, combo, objective: float, names: list[str]) -> None:
        """A choice (of the integer variables ``names``) a run of the current solve found a design for, of
        ``objective``. Found infeasible before (from another start, :func:`from_the_start`), its infeasibility was a
        local one of IPOPT's restoration, and it is not ruled out."""
        key = tuple(float(c) for c in combo)
        self._pending.pop(key, None)
        self.violations.pop(key, None)
        self._designed[key], self._names = objective, names

    def settle(self, error: float, design: dict[str, float], objective: float) -> None:
        """The current solve's collocation error, its kept ``design`` and its ``objective``: its infeasible
        choices, and those with a design heavier than it by more than RULED_MARGIN ``error``, are recorded."""
        self.violations.update({combo: (v, error) for combo, v in self._pending.items()})
        self._pending = {}
        kept = tuple(float(round(design[name])) for name in self._names)
        self.heavier.pop(kept, None)
        for combo, value in self._designed.items():
            if combo != kept and (value - objective) / abs(objective) > RULED_MARGIN * error:
                self.heavier[combo] = ((value - objective) / abs(objective), error, kept)
        self._designed = {}

    def reason(self, combo) -> list[str]:
        """Why ``combo`` is not solved again (empty: it is)."""
        key = tuple(float(c) for c in combo)
        if (known := self.known.get(key)) is not None:
            return [known]
        if (heavier := self.heavier.get(key)) is not None and heavier[2] in self._designed:
            return [f"heavier by {heavier[0]:.2g} than {dict(zip(self._names, heavier[2]))} at an earlier mesh of "
                    f"collocation error {heavier[1]:.2g}"]
        found = self.violations.get(key)
        if found is None or not found[0] > RULED_MARGIN * found[1]:
            return []
        return [f"infeasible by {found[0]:.2g} at an earlier mesh of collocation error {found[1]:.2g}"]


def least_violation(posed: Posed, values: np.ndarray) -> float:
    """The largest normalised constraint row left violated (inequalities above 0, equalities off 0) by the rows
    ``values`` (e.g. those a run's solver returned at its last point, ``g``)."""
    return float(max(np.max(values[: posed.n_ineq], initial=0.0), np.max(np.abs(values[posed.n_ineq:]), initial=0.0)))


def search_entry(posed: Posed, integer: list[int], combo, status: str, feasible: bool, objective: float) -> dict:
    """An ``integer_search`` entry: the integer choice ``combo`` by name, how its solve ended, its objective."""
    return {**{posed.names[i]: int(c) for i, c in zip(integer, combo)}, "status": status, "feasible": feasible,
            "objective": objective}


def excluded_entry(posed: Posed, integer: list[int], combo, violated: list[str]) -> dict:
    """The ``integer_search`` entry of a choice excluded without a solve: the constraints it breaks."""
    return search_entry(posed, integer, combo, f"{EXCLUDED}{', '.join(violated)}", False, math.nan)


def relaxation_seed(seed: dict, integer: list[int]) -> dict:
    """A warm start for the relaxation from a fixed-integer optimum: the same point, the integers' bound
    multipliers dropped (their bounds are opened)."""
    lam_x = seed["lam_x"].copy()
    lam_x[integer] = 0.0
    return {**seed, "lam_x": lam_x}


def violated_whatever_the_rest(posed: Posed, p, lbx, ubx, x0) -> list[str]:
    """Constraints that depend only on fixed variables (integers included) and are violated at ``x0`` (scaled;
    the fixed variables at their bounds)."""
    rows, values = posed.fixed_only(lbx == ubx)
    if not len(rows):
        return []
    g = posed.mapped(values, 1)(x0, p)[0].ravel()
    return list(dict.fromkeys(posed.row_names[k] for k, gk in zip(rows, g) if gk > 10 * FEASIBILITY_TOL))
