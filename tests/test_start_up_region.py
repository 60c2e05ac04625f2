"""A start-up sweep's point beyond a point without a design is tested against that point's reason first
(clutchopt/optimise/start_up_region.py): its first solve's own least relaxation, else one solve from the point
before's least relaxation, with its own elastic diagnosis.

lever_motor_start over the bench's driven inertias (0.6x-1.4x of 12 kg m^2, 20 points): 14.78 kg m^2 has a design,
15.28 and 15.79 none (lining_pressure and temperature_rise, docs/start_up.md). The first point past the design gets
``solve``'s verdict and the sweep's own starts; the next was given ``solve``'s too (4 solves, 340-400 IPOPT
iterations), then was solved from the papers' sizing (``solve``'s first solve) and from the first one's least
relaxation (2 solves), and is now decided by the first solve alone, whose least relaxation violates the constraints the
point before's did (1 solve)."""

from dataclasses import replace

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise.problem import Problem, case_problem, problems_set_aside
from clutchopt.optimise.sampled_start import SAMPLED
from clutchopt.optimise.start_up_region import REGION, TESTS, beyond, in_a_region, region_verdict, region_tested
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import Vary
from clutchopt.optimise.verdict import LEAST, NEXT, retried
from tests.conftest import CASES

REASON = ("lining_pressure", "temperature_rise")
SOLVE_STARTS = ("the papers' sizing", "the least relaxation's design", "a design the interval search met", SAMPLED)


def _lever():
    case = load_case(CASES / "lever_motor_start.toml")
    return case, case.values["driven_inertia"] * np.linspace(0.6, 1.4, 20)


def _swept(values) -> list[dict]:
    case, _ = _lever()
    quantity = next(q for q in case.quantities if q.name == "driven_inertia")
    return Sweep(case, [Vary(quantity, tuple(values))]).run(progress=False).solutions


def test_a_point_beyond_one_without_a_design_is_decided_by_its_first_solves_least_relaxation():
    case, inertias = _lever()
    designed, first, deeper = _swept(inertias[15:18])
    assert designed["status"] == "optimal"
    assert first["status"] == deeper["status"] == "not_found"
    assert tuple(first["starts"][:4]) == SOLVE_STARTS  # (then the sweep's own: the neighbour's design)
    assert tuple(deeper["starts"]) == TESTS[:1]  # was solve's four starts, 4 solves; then TESTS[:2], 2 solves
    assert deeper["solver"]["solves"] == 1
    assert deeper["diagnosis"].startswith("no feasible design found (not proven infeasible): the least relaxation "
                                          "found cannot satisfy lining_pressure")
    assert deeper["diagnosis"].endswith("the least relaxation from the papers' sizing violates what the point before's "
                                        "did (lining_pressure, temperature_rise): solve's other starts of this point "
                                        "alone were not tried, nor the sweep's (the neighbour's design, the "
                                        "continuation)")
    alone = case_problem(case).solve(case.with_values(driven_inertia=inertias[17]))  # solve of that point alone
    assert alone.status == "not_found" and alone.starts == SOLVE_STARTS and alone.diagnosed.violated == REASON
    assert alone.diagnosis.startswith("no feasible design found (not proven infeasible): the least relaxation found "
                                      "cannot satisfy lining_pressure")


def test_a_point_so_decided_before_a_later_design_gets_solves_verdict_after_all(monkeypatch):
    """Listed 14.78, 15.28, 15.79, then 14.27 kg m^2 (a design): the one its neighbour's reason decided, having no
    ``solve`` of it alone behind it, gets that verdict first, then (without a design) a retry from the later design,
    named among its starts as at the point before it. Where that retry reaches a design (a spy hands one back), the
    record says what ``solve`` alone ended with (review h18: it had kept the retry's design with no ``solve`` alone
    behind it, though a sweep's own starts come after ``solve``'s)."""
    case, inertias = _lever()
    solutions = _swept([*inertias[15:18], inertias[14]])
    assert [s["status"] for s in solutions] == ["optimal", "not_found", "not_found", "optimal"]
    retried = solutions[2]
    assert tuple(retried["starts"]) == (*SOLVE_STARTS, NEXT)  # (solve's alone, then the later design's; no start
    # from the neighbour's least relaxation, which its first solve's own reason made needless: named where solved)
    assert tuple(solutions[1]["starts"])[-1] == NEXT
    assert "were not tried" not in retried["diagnosis"]
    assert retried["solver"]["solves"] >= 3  # its first solve, solve's alone and the later design's retry at least
    # (solve's own starts fewer where this process already saw one fail there: failed_starts)
    solve = Problem.solve

    def spied(self, at, *args, start=None, **kwargs):  # a design from the later point's start at 15.79 kg m^2
        solved = solve(self, at, *args, start=start, **kwargs)
        reached = start is not None and at.values["driven_inertia"] == inertias[17]
        return replace(solved, status="optimal") if reached else solved

    monkeypatch.setattr(Problem, "solve", spied)
    with problems_set_aside():
        found = _swept([*inertias[15:18], inertias[14]])[2]
    assert found["status"] == "optimal" and found["solve_alone"] == {"status": "not_found", "objective": None}


def test_a_resumed_run_decides_no_point_by_a_pending_point_that_is_not_the_one_before(tmp_path):
    """Listed 14.27 (a design), 15.28, 14.78 (a design), 15.79, 16.29 kg m^2; a pool's run stopped after it stored
    14.78 alone (review h17): the resumed run's pending points are 14.27, 15.28, 15.79, 16.29, and 15.79 was decided
    beyond 15.28, which is not the point before it (14.78, a design, lies between): two starts and 2 solves where the
    uninterrupted run gives it the full verdict. Now only the grid's point before decides."""
    from clutchopt.optimise.sweep import solve_chunk
    from clutchopt.store import RunStore

    case, inertias = _lever()
    quantity = next(q for q in case.quantities if q.name == "driven_inertia")
    values = (inertias[14], inertias[16], inertias[15], inertias[17], inertias[18])

    class Stopped(Exception):
        pass

    def runner(task, pending, size):  # (a pool's run: the chunk of 14.78 finished first, then the run stopped)
        yield solve_chunk(*task, pending[2:3])
        raise Stopped

    path = tmp_path / "runs.sqlite"
    with RunStore(path) as store, pytest.raises(Stopped):
        Sweep(case, [Vary(quantity, values)]).run(store, runner=runner, progress=False)
    with RunStore(path) as store:
        resumed = Sweep(case, [Vary(quantity, values)]).run(store, resume=True, progress=False)
    assert (resumed.reused, resumed.solved) == (1, 4)
    assert [s["status"] for s in resumed.solutions] == ["optimal", "not_found", "optimal", "not_found", "not_found"]
    assert tuple(resumed.solutions[3]["starts"][:4]) == SOLVE_STARTS  # (was decided: beyond 15.28)
    assert tuple(resumed.solutions[4]["starts"]) == TESTS[:1]  # (beyond 15.79, the point before it)


def test_only_a_point_beyond_on_the_ray_and_only_a_shared_reason_decides():
    case, inertias = _lever()
    problem = case_problem(case)

    def values(j):
        return {"driven_inertia": float(inertias[j])}

    without = problem.solve(case.with_values(driven_inertia=inertias[16]))
    assert without.status == "not_found" and without.diagnosed.violated == REASON
    between = {"driven_inertia": float((inertias[15] + inertias[16]) / 2)}
    assert beyond(values(17), values(15), without, values(16))
    assert not beyond(between, values(15), without, values(16))  # (between the last design and the point before)
    assert not beyond(values(17), None, without, values(16))  # (no design before it in the run)
    assert not beyond(values(17), values(15), replace(without, diagnosed=without.diagnosed._replace(violated=())),
                      values(16))  # (an elastic problem stopped unconverged names no reason)
    point = case.with_values(driven_inertia=inertias[17])
    first = problem.refined(point)
    assert first.status == "infeasible" and first.diagnosed.violated == REASON  # (its elastic diagnosis, unproven)
    decided, made = region_tested(problem, point, first, without)  # (its own least relaxation: no second solve)
    assert made == [] and decided.status == "not_found" and decided.starts == TESTS[:1] and decided.solver.solves == 1
    assert decided.diagnosed.least == first.diagnosed.least
    assert decided.diagnosis.startswith("no feasible design found (not proven infeasible): the least relaxation found "
                                        "cannot satisfy lining_pressure")
    other = replace(without, diagnosed=without.diagnosed._replace(violated=("start_time",)))
    assert region_verdict(first, other) is None  # another reason: solve's verdict
    shared = replace(without, diagnosed=without.diagnosed._replace(violated=("lining_pressure", "start_time")))
    assert region_verdict(first, shared).starts == TESTS[:1]  # (one constraint shared: the same region)
    assert region_verdict(replace(first, diagnosed=None), without) is None  # (no diagnosis: a design)
    unconverged = replace(first, diagnosed=first.diagnosed._replace(violated=()))  # (names no reason: solved again)
    decided, made = region_tested(problem, point, unconverged, without)
    assert [label for label, _ in made] == [REGION]  # (from the point before's least relaxation, which decides)
    tested = made[0][1]
    assert tested.status == "infeasible" and tested.solver.solves == 1 and tested.diagnosed.violated == REASON
    assert decided.status == "not_found" and decided.starts == TESTS[:2] and decided.solver.solves == 2
    assert decided.diagnosed.least == min(first.diagnosed.least, tested.diagnosed.least)
    assert region_verdict(unconverged, other, made) is None
    blind = [(REGION, replace(tested, diagnosed=tested.diagnosed._replace(violated=())))]  # (names none either)
    assert region_verdict(unconverged, without, blind) is None
    own = retried(problem, point, first.diagnosed.nearest, diagnosed=True)  # (solve's own second start)
    third = region_verdict(unconverged, without, [*blind, (LEAST, own)])
    assert third.status == "not_found" and third.starts == TESTS and third.solver.solves == 3
    # which verdicts the test gave is marked, not read off the starts (review h18): where the REGION start's simulation
    # failed (not among the starts), the third decides, starts (SIZING, LEAST), and its later retry must still run
    # solve alone; a verdict of solve's whose starts happen to begin as the test's is not the test's
    skipped = region_verdict(unconverged, without, [(LEAST, own)])
    assert skipped.starts == (TESTS[0], LEAST) and in_a_region(skipped) and in_a_region(third)
    assert not in_a_region(replace(first, status="solver_failed", starts=TESTS[:1]))


def test_the_test_goes_on_from_the_first_solves_least_relaxation_where_the_point_befores_names_no_reason():
    """The solves from the starts given replayed (ball_motor_start at 446 kg m^2: the first solve's elastic problem and
    the one from the point before's least relaxation stop unconverged, the one from the first's least relaxation's
    design converges, contact_stress and start_time over their limits: 3 solves where the full verdict took 5)."""
    case, inertias = _lever()
    problem = case_problem(case)
    without = problem.solve(case.with_values(driven_inertia=inertias[16]))
    point = case.with_values(driven_inertia=inertias[17])
    first = problem.refined(point)
    unconverged = replace(first, diagnosed=first.diagnosed._replace(violated=()))
    blind = replace(first, diagnosed=first.diagnosed._replace(violated=(), least=2 * first.diagnosed.least))
    own = replace(first, diagnosed=first.diagnosed._replace(least=first.diagnosed.least / 2))

    class Replay:  # the problem's solves by their starts
        def __init__(self, solves: dict):
            self.solves = solves

        def refined(self, case, start, diagnosed):
            assert diagnosed
            return self.solves[id(start)]

    starts = {id(without.diagnosed.nearest): blind, id(first.diagnosed.nearest): own}
    decided, made = region_tested(Replay(starts), point, unconverged, without)
    assert [(label, id(s)) for label, s in made] == [(REGION, id(blind)), (LEAST, id(own))]
    assert decided.starts == TESTS and decided.solver.solves == 3 and decided.diagnosed.least == own.diagnosed.least
    assert decided.diagnosis.endswith("the least relaxation from the least relaxation's design violates what the point "
                                      "before's did (lining_pressure, temperature_rise): solve's other starts of this "
                                      "point alone were not tried, nor the sweep's (the neighbour's design, the "
                                      "continuation)")
    found = replace(first, status="optimal", diagnosed=None)  # (a design from the point before's least relaxation)
    decided, made = region_tested(Replay({**starts, id(without.diagnosed.nearest): found}), point, unconverged,
                                   without)
    assert decided is None and [(label, id(s)) for label, s in made] == [(REGION, id(found))]  # (no further start:
    # the full verdict keeps that design)
