"""The sweeps users run, not only the benchmark's own: for every coupling, ``clutchopt sweep``'s code (``Sweep.run``,
no store) over each of the speed, the duty's torque quantity, the friction coefficient and the allowable pressure
or stress (0.5x to 2x the case's value, or the widest of 0.7x-1.4x and 0.9x-1.1x whose every point its checks
accept), a sweep reaching into an infeasible region (the duty's quantity from 1x to 10x) and the two sides of the
edge it meets (from 1x to its last point with a design, and from its first point without one to twice that: what a
point without a design costs against one with a design, issue 26's "an infeasible point <= 20x a feasible one"),
each coupling's other modes over its duty from 1x into the infeasible region, ``ball_crusher`` over 250-1000 kW, and
for each start-up case a sweep of the driven inertia (0.6x to 1.4x, every
point simulated; once, with a fiftieth of the points, per state of the compiled-code cache: :func:`start_up_rows`;
wedge_motor_start's again over five times the points)
and one of the start-up limit nearest to binding its design (0.8x to 1.2x, as many points, once).
Per sweep: the points, how many have a design and how many a verdict without one, solver calls per point, points/s
(the median run of ``sweep_repeats``), and points/s against the wedge paper sweep of the duty's quantity measured in
the same run (its runs at the section's start and again after the static sweeps, REFERENCE_AGAIN times as many,
pooled: the median of all)."""

from __future__ import annotations

import math
import os
import tempfile
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.bench.throughput import sweep_quantity
from clutchopt.bench.timing import median_of, time_once
from clutchopt.cases import Case, load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.compiled import CACHE_ENV
from clutchopt.optimise.problem import problems_set_aside, start_up_key
from clutchopt.optimise.start_up_compiled import BUILD_LATER_ENV, compiled_now, wait_for_builds

CASES = Path(__file__).resolve().parents[2] / "cases"
SPANS = ((0.5, 2.0), (0.7, 1.4), (0.9, 1.1))  # factors on the case's value, the widest the case accepts
INTO_INFEASIBLE = (1.0, 10.0)  # factors on the duty's quantity: a sweep that reaches into its infeasible region
OTHER_MODES_SPANS = (INTO_INFEASIBLE, (1.0, 4.0), (1.0, 2.0))  # the same in each other mode, the widest its checks
# accept (the cable's threads mode refuses a thread no longer self-locking past about 6x its torque)
ALLOWABLE = {"wedge": "allowable_pressure", "lever": "allowable_pressure", "cable": "allowable_cable_stress",
             "ball": "allowable_contact_stress"}  # the allowable each coupling's main constraint is sized by
LIMIT_SPAN = (0.8, 1.2)  # factors on the start-up limit nearest to binding a start-up case's design (nearest_limit)
REFERENCE_AGAIN = 3  # the wedge paper sweep's runs after the static sweeps (times sweep_repeats), pooled with its first
IN_THE_CACHE, NO_LIBRARY = "in the cache", "none"  # the states of the compiled-code cache a start-up sweep is timed in
GOAL_CASE, LONGER = "wedge_motor_start", 5  # issue 26's start-up sweep goal names its case: its driven-inertia sweep
# again over five times the points (a user's longer sweep: the first point's cold solve spread over more)


def _run(case: Case, name: str, values: np.ndarray, mode: str | None, repeats: int,
         pooled: list | None = None) -> dict:
    """``Sweep(case, name=values).run()`` (SI values) timed ``repeats`` times: the tally of the median run, the
    values and which of them have a design (``values``, ``designed_at``: read by :func:`_edge_sides`, not shown).
    ``pooled``: the runs timed before of the same sweep, pooled with these (the median of all; the list grows)."""
    from clutchopt.optimise.sweep import Sweep
    from clutchopt.optimise.sweep_grid import Vary

    quantity = next(q for q in case.quantities if q.name == name)
    timed = [time_once(lambda: Sweep(case, [Vary(quantity, tuple(values.tolist()))], mode=mode).run(progress=False))
             for _ in range(repeats)]
    if pooled is not None:
        pooled += timed
    result, seconds = median_of(pooled if pooled is not None else timed)
    statuses = result.frame["status"].to_numpy()
    designed_at = np.isin(statuses, ("optimal", "unverified"))
    designed = int(designed_at.sum())
    return {"points": len(values), "designed": designed, "without_design": len(values) - designed,
            "solves_per_point": result.spent["solves"] / len(values), "wall_s": seconds,
            "points_per_s": len(values) / seconds, "values": values, "designed_at": designed_at}


def _widest(case: Case, name: str, spans, points: int, mode: str | None, repeats: int,
            pooled: list | None = None) -> dict:
    """The sweep over the widest span of factors whose every point the case's checks accept (a sweep with a point
    they refuse is refused whole: e.g. a cable thread no longer self-locking at a higher friction coefficient)."""
    from clutchopt.errors import InputError

    for low, high in spans:
        try:
            row = _run(case, name, case.values[name] * np.geomspace(low, high, points), mode, repeats, pooled)
        except InputError:
            continue
        return {"span": f"{low:g}x-{high:g}x", **row}
    raise InputError(name, f"no span of {spans} is accepted")


def _edge_sides(case: Case, name: str, swept: dict, mode: str | None, repeats: int) -> list[dict]:
    """The sweeps on either side of the edge the sweep ``swept`` (:func:`_run`'s row) over ``name`` met (none if it
    met none): from its first value to its last with a design, and from its first without one to twice that (as
    factors on the case's value), as many points each; the second's cost a point against the first's
    (``point_cost_vs_designed``)."""
    factors, designed_at = swept["values"] / case.values[name], swept["designed_at"]
    if designed_at.all() or not designed_at.any():
        return []
    last, first = factors[designed_at].max(), factors[~designed_at].min()
    sides = []
    for label, low, high in (("before the edge", factors[0], last), ("beyond the edge", first, 2 * first)):
        row = _run(case, name, case.values[name] * np.geomspace(low, high, len(factors)), mode, repeats)
        sides.append({"quantity": f"{name} ({label})", "span": f"{low:.3g}x-{high:.3g}x", **row})
    sides[1]["point_cost_vs_designed"] = sides[0]["points_per_s"] / sides[1]["points_per_s"]
    return sides


def user_sweep_rows(config) -> list[dict]:
    points = max(config.sweep_points // 10, 10)
    rows, reference, pooled = [], None, []
    for case in bench_cases():
        mode, duty = reference_mode(case.coupling), sweep_quantity(case)
        sweeps = [(q, SPANS) for q in dict.fromkeys((duty, "speed", "friction_coefficient", ALLOWABLE[case.coupling]))]
        label_case = f"{case.coupling} ({mode})"
        for label, spans in sweeps:
            name = label.split(" ")[0]
            is_reference = case.coupling == "wedge" and label == duty
            row = {"case": label_case, "quantity": label,
                   **_widest(case, name, spans, points, mode, config.sweep_repeats, pooled if is_reference else None)}
            if is_reference:
                reference = (case, name, mode, row)
            rows.append(row)
        into = _widest(case, duty, (INTO_INFEASIBLE,), points, mode, config.sweep_repeats)
        rows.append({"case": label_case, "quantity": f"{duty} (into infeasible)", **into})
        rows += [{"case": label_case, **side} for side in _edge_sides(case, duty, into, mode, config.sweep_repeats)]
        for other in (m for m in get_coupling(case.coupling).formulations if m != mode):  # (the coupling's other
            # modes: a user's too, the infeasible points of another formulation costing what its searches take)
            rows.append({"case": f"{case.coupling} ({other})", "quantity": f"{duty} (into infeasible)",
                         **_widest(case, duty, OTHER_MODES_SPANS, points, other, config.sweep_repeats)})
    crusher = load_case(CASES / "ball_crusher.toml")
    rows.append({"case": "ball_crusher", "quantity": "power", "span": "250-1000 kW",
                 **_run(crusher, "power", np.linspace(250e3, 1000e3, 2 * points), None, config.sweep_repeats)})
    case, name, mode, row = reference  # timed again after the static sweeps, pooled with its first runs (a moment of
    row.update(_run(case, name, row["values"], mode, REFERENCE_AGAIN * config.sweep_repeats, pooled))  # the machine's
    # noise at its first timing had moved every ratio: 02:22 UTC, 47 % slower than at 02:25)
    rows += start_up_rows(config)
    for row in rows:
        del row["values"], row["designed_at"]
        row["vs_wedge_paper"] = row["points_per_s"] / reference[3]["points_per_s"]
        row["point_cost_vs_designed"] = row.get("point_cost_vs_designed")
        row["compiled"], row["compiled_used"] = row.get("compiled"), row.get("compiled_used")
    return rows


def start_up_rows(config) -> list[dict]:
    """Each start-up case's sweep of the driven inertia (0.6x-1.4x), timed once in each state of the compiled-code
    cache of ``config.start_up_compiled`` (``compiled``): IN_THE_CACHE, the libraries of its NLPs built first, untimed
    and in the foreground (the problems posed by a sweep run once untimed: a user's second run), or NO_LIBRARY (an
    empty cache: a user's first run, less the build it starts beside itself). No build is started while a run is
    timed (``CLUTCHOPT_BUILD_LATER=0``) and none runs; each timed run builds its problems anew, as a new process does.
    ``compiled_used``: whether its solvers evaluated the compiled functions by its end (a sweep finds them at its first
    point by the link beside the library, :mod:`clutchopt.optimise.start_up_compiled`). GOAL_CASE's again over LONGER
    times the points, in the first state. Then a sweep of the start-up limit nearest to binding the case's design
    (:func:`nearest_limit`, over LIMIT_SPAN), as many points, in the first state only: a designer's other question of a
    start-up design."""
    rows = []
    for path in sorted(CASES.glob("*_motor_start.toml")):
        case = load_case(path)
        points = max(config.sweep_points // 50, 3)
        values = case.values["driven_inertia"] * np.linspace(0.6, 1.4, points)
        for state in config.start_up_compiled:
            with _compiled_state(state):
                if state == IN_THE_CACHE:
                    with problems_set_aside(start_up_key) as posed:
                        _run(case, "driven_inertia", values, None, 1)
                    for problem in posed:
                        if problem.posed.library is None:  # (one already compiled: its library in the cache)
                            compiled_now(problem.posed)  # (and its link: used from a sweep's first point)
                row = _timed(case, "driven_inertia", values, state)
            rows.append({"case": path.stem, "quantity": "driven_inertia", "span": "0.6x-1.4x", **row})
        if path.stem == GOAL_CASE:
            state = config.start_up_compiled[0]
            with _compiled_state(state):
                longer = case.values["driven_inertia"] * np.linspace(0.6, 1.4, LONGER * points)
                row = _timed(case, "driven_inertia", longer, state)
            rows.append({"case": path.stem, "quantity": "driven_inertia", "span": "0.6x-1.4x", **row})
        limit = nearest_limit(case)
        state = config.start_up_compiled[0]  # (the same NLP as the driven inertia's: its limits are parameters)
        with _compiled_state(state):
            row = _timed(case, limit, case.values[limit] * np.linspace(*LIMIT_SPAN, points), state)
        rows.append({"case": path.stem, "quantity": limit, "span": "{:g}x-{:g}x".format(*LIMIT_SPAN), **row})
    return rows


def _timed(case: Case, name: str, values: np.ndarray, state: str) -> dict:
    """A start-up sweep's :func:`_run`, timed once with its problems built anew (dropped after: their compiled state
    is the run's) in the compiled-code cache's ``state``, set by the caller: its row, with ``compiled`` and
    ``compiled_used``."""
    with problems_set_aside(start_up_key) as built:
        row = _run(case, name, values, None, 1)
    return {**row, "compiled": state, "compiled_used": any(p.posed.library is not None for p in built)}


def nearest_limit(case: Case) -> str:
    """The start-up limit (its case quantity) nearest to binding the case's own design: of the simulated checks of
    ``start_up_check.LIMIT_OF``, the one of the smallest relative margin (the start time of the wedge, lever and ball,
    which their designs bind; the cable's link stress, 4 % inside it with the 8 cables it set)."""
    from clutchopt.optimise.problem import solve_case
    from clutchopt.optimise.start_up_check import LIMIT_OF

    checks = [c for c in solve_case(case).constraints if c.name in LIMIT_OF and math.isfinite(c.margin)]
    return LIMIT_OF[min(checks, key=lambda c: c.margin).name]


@contextmanager
def _compiled_state(state: str):
    """The environment of a start-up sweep timed in ``state`` (IN_THE_CACHE: the caller's cache; NO_LIBRARY: an empty
    cache of its own), no build started in the background, and none running (one an earlier run started); the
    caller's environment restored after it."""
    kept = {name: os.environ.get(name) for name in (CACHE_ENV, BUILD_LATER_ENV)}
    wait_for_builds()
    with tempfile.TemporaryDirectory() as empty:
        os.environ.update({BUILD_LATER_ENV: "0", **({} if state == IN_THE_CACHE else {CACHE_ENV: empty})})
        try:
            yield
        finally:
            for name, value in kept.items():
                if value is None:
                    os.environ.pop(name, None)
                else:
                    os.environ[name] = value
