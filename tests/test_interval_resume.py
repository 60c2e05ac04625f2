"""A search its budget ended, resumed (clutchopt.optimise.interval_proof: ``Emptiness.paused``, ``searches``'
``resumed``): the outcome of the search without that budget, its boxes before the pause evaluated once."""

import numpy as np
import pytest

from clutchopt.bench.reference import bench_cases
from clutchopt.optimise.interval_proof import (SURE_BOXES, _search_problem, boxes_evaluated, empty_design_space,
                                               keep_search, searches)
from clutchopt.optimise.problem import case_problem

LEVER = next(c for c in bench_cases() if c.coupling == "lever")
BALL = next(c for c in bench_cases() if c.coupling == "ball")


def _problem(case, mode, **factors):
    case = case.with_values(**{name: f * case.values[name] for name, f in factors.items()})
    posed = case_problem(case, mode).posed
    return posed, _search_problem(posed, case)


@pytest.mark.parametrize("case, mode, factors, proven, boxes", [
    (LEVER, "design", {"inertia": 3.6}, False, 3802),  # (next to its edge: given up by the growth rule)
    (LEVER, "design", {"inertia": 5.0}, True, 7139),
    (BALL, "design", {"allowable_contact_stress": 0.72}, True, 319),  # (integer rows: rounded boxes)
])
@pytest.mark.parametrize("budget", [64, 300, SURE_BOXES])
def test_a_search_resumed_where_its_budget_ended_it_is_the_search_without_that_budget(case, mode, factors, proven,
                                                                                         boxes, budget):
    """The lever in design mode at 3.6x its inertia (no design; its search gives up at 3,802 boxes, past SURE_BOXES
    as the boxes left grow) and at 5x (proven in 7,139), the ball at 0.72x its allowable contact stress (proven in
    319): each paused by a budget of 64, 300 or SURE_BOXES boxes and resumed gives the unbudgeted search's outcome
    (proven or not, boxes, the rows that emptied or cut them, a design met), and the boxes counted as evaluated are
    the unbudgeted search's alone (the paused part once)."""
    posed, problem = _problem(case, mode, **factors)
    fresh, = searches(posed, [problem])
    assert (fresh.proven, fresh.boxes) == (proven, boxes)
    early, = searches(posed, [problem], [budget], pause=True)
    if budget >= boxes:  # (ended by its outcome: nothing to resume)
        assert early.paused is None and early.boxes == boxes
        return
    assert not early.proven and early.paused is not None and early.paused.evaluated == early.boxes < boxes
    counted = boxes_evaluated(posed)
    resumed, = searches(posed, [problem], resumed=early.paused)
    assert (resumed.proven, resumed.boxes, resumed.decisive, resumed.reached) == (
        fresh.proven, fresh.boxes, fresh.decisive, fresh.reached)
    assert resumed.feasible is None and fresh.feasible is None
    assert boxes_evaluated(posed) - counted == boxes - early.boxes


def test_a_not_found_verdict_searches_its_design_space_once():
    """`solve` of the lever in design mode at 3.6x its inertia ends `not_found`: its early search (SURE_BOXES, before
    the retries) is resumed after them, not searched again from its first box: the boxes evaluated are the
    unbudgeted search's, 3,802 (had been 2,113 + 3,802), the verdict the same."""
    case = LEVER.with_values(inertia=3.6 * LEVER.values["inertia"])
    problem = case_problem(case, "design")
    before = boxes_evaluated(problem.posed)
    solution = problem.solve(case)
    assert solution.status == "not_found" and "not proven infeasible" in solution.diagnosis
    assert boxes_evaluated(problem.posed) - before == 3802
    assert np.isfinite(solution.objective)


def test_a_kept_search_its_budget_ended_serves_that_budget_and_is_resumed_without_one():
    """A sweep's point searched within SURE_BOXES before any solve (``Regions._early``, ``_first``) and kept for its
    verdict (the lever in design mode at 3.6x its inertia: paused at 2,113 boxes): the verdict's search within the
    same budget is that search (nothing evaluated), one within another budget searches afresh, and the search without
    a budget resumes it: 3,802 boxes, the 1,689 after the pause evaluated (review 22b: searched twice before)."""
    case = LEVER.with_values(inertia=3.6 * LEVER.values["inertia"])
    posed = case_problem(case, "design").posed
    problem = _search_problem(posed, case)
    early, = searches(posed, [problem], [SURE_BOXES], pause=True)
    keep_search(posed, problem, early)
    counted = boxes_evaluated(posed)
    assert empty_design_space(posed, case, SURE_BOXES) is early and boxes_evaluated(posed) == counted
    other = empty_design_space(posed, case, 300)
    assert other.paused.budget == 300 and boxes_evaluated(posed) == counted + other.boxes
    counted = boxes_evaluated(posed)
    resumed = empty_design_space(posed, case)
    assert (resumed.proven, resumed.boxes, early.boxes) == (False, 3802, 2113)
    assert boxes_evaluated(posed) - counted == 3802 - 2113
