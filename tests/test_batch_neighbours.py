"""A batched sweep whose integers' multipliers promise a neighbour at every point (clutchopt/optimise/batch.py): the
wedge in geometry mode over its inertia 1x-10x, the benchmark's user sweep of its other mode. From point 70 on the
weight count's bound multiplier promises a gain at a neighbouring count at every point; solved, it is heavier but at
74 (3 -> 4 weights), 86 (5) and 95 (6)."""

import numpy as np
import pytest

from clutchopt.bench.reference import bench_cases
from clutchopt.formulations import get_coupling
from clutchopt.optimise.batch import BATCHED, BatchSweep
from clutchopt.optimise.problem import Problem


@pytest.fixture(scope="module")
def swept():
    case = next(c for c in bench_cases() if c.coupling == "wedge")
    problem = Problem(get_coupling("wedge").formulation("geometry"))
    values = case.values["inertia"] * np.geomspace(1.0, 10.0, 100)
    sweep = BatchSweep(problem, case, {"inertia": values})
    return case, problem, values, sweep, [s for part in sweep.run() for s in part]


def test_no_chained_column_is_spent_past_a_point_the_search_decides(swept):
    # the count a change moves to promises the one it left at once (4 weights after 3 at 74: 3 again, heavier, at
    # each of 75 .. 82), so the chains after a change are probes of one point: each point from 70 on is its chained
    # column and the neighbour (2 calls) and the sweep spends no call beyond its points' (151 before, 131: chains of
    # 8, 11 and 4 points after the changes, aimed at the next change by the gaps between them, failed at their first
    # point and spent 7 + 10 + 3 solves on nothing)
    case, problem, values, sweep, solutions = swept
    assert [s.status for s in solutions] == ["optimal"] * 100
    counts = [int(s.design["weight_count"]) for s in solutions]
    changes = [k for k in range(1, 100) if counts[k] != counts[k - 1]]
    assert changes == [74, 86, 95] and counts[70] == 3 and counts[99] == 6
    for s in solutions[70:]:
        assert s.solver.status == BATCHED and s.solver.solves == 2
        assert [e["status"] for e in s.integer_search] == [BATCHED, BATCHED]
    assert sweep.solves == sum(s.solver.solves for s in solutions)


@pytest.mark.parametrize("k", [73, 74, 75, 86, 95, 99])
def test_each_count_is_the_one_solve_keeps(swept, k):
    case, problem, values, sweep, solutions = swept
    want = problem.solve(case.with_values(inertia=float(values[k])))
    assert want.status == "optimal" and want.design["weight_count"] == solutions[k].design["weight_count"]
    assert solutions[k].objective == pytest.approx(want.objective, rel=1e-9)


def test_a_neighbour_solved_at_the_point_before_starts_from_its_own_optimum_there(monkeypatch):
    # 4 weights, promised by 3's multipliers at each of 70 .. 74, start from their own optimum at the point before
    # (71 .. 74), not from 3's at the point (SQP 2.5 ms a point, 0.13 ms so); after the change 3 weights likewise
    # from 3's at the point before (75 .. 82: the chained column at 74, then the search's), and so on: every
    # neighbour but at 70, 83 and 93, the first points where it is promised
    case = next(c for c in bench_cases() if c.coupling == "wedge")
    values = case.values["inertia"] * np.geomspace(1.0, 10.0, 100)
    sweep = BatchSweep(Problem(get_coupling("wedge").formulation("geometry")), case, {"inertia": values})
    chained, columns = BatchSweep._chain, {}  # (point, weights) -> a one-point SQP's seed and optimum (SI)
    z = sweep.names.index("weight_count")

    def recorded(self, start, k, count, lower, upper, seed, method="sqp_chain", predict=True, changes=()):
        chain = chained(self, start, k, count, lower, upper, seed, method, predict, changes)
        if count == 1 and chain is not None:
            columns[k, lower[z]] = seed["x"] * start.scale, chain.x[:, 0] * start.scale
        return chain

    monkeypatch.setattr(BatchSweep, "_chain", recorded)
    solutions = [s for part in sweep.run() for s in part]
    own = []
    for k in range(70, 100):
        tried, neighbour = (e["weight_count"] for e in solutions[k].integer_search)  # (the chain's, the search's)
        seed, _ = columns[k, neighbour]
        if (k - 1, neighbour) in columns:
            assert np.array_equal(seed, columns[k - 1, neighbour][1]), k
            own.append(k)
    assert own == [k for k in range(71, 100) if k not in (83, 93)]
    assert [int(s.design["weight_count"]) for s in solutions[70::5]] == [3, 4, 4, 4, 5, 6]


def test_a_neighbour_whose_own_start_fails_is_solved_from_the_searchs_optimum_as_before(monkeypatch):
    # a one-point SQP from the combination's own optimum that does not pass its check (here: started from NaN) is
    # tried again from the optimum the search keeps at the point, before any least violation (which would decide
    # the combination by another path than main's): the same weights at every point
    case = next(c for c in bench_cases() if c.coupling == "wedge")
    values = case.values["inertia"] * np.geomspace(4.0, 6.0, 40)
    want = BatchSweep(Problem(get_coupling("wedge").formulation("geometry")), case, {"inertia": values})
    want = [s.design["weight_count"] for part in want.run() for s in part]
    own_start, failed = BatchSweep._own_start, []

    def nan_start(self, key, k, start, seed):
        own = own_start(self, key, k, start, seed)
        if own is seed:
            return seed
        failed.append(k)
        return {**own, "x": np.full_like(own["x"], np.nan)}

    def no_least_violation(*args):
        raise AssertionError("least violation")

    monkeypatch.setattr(BatchSweep, "_own_start", nan_start)
    monkeypatch.setattr(BatchSweep, "_least_violation", no_least_violation)
    sweep = BatchSweep(Problem(get_coupling("wedge").formulation("geometry")), case, {"inertia": values})
    solutions = [s for part in sweep.run() for s in part]
    assert len(failed) >= 10 and [s.design["weight_count"] for s in solutions] == want
    assert all(s.status == "optimal" for s in solutions)


def test_a_neighbour_heavier_at_an_earlier_point_than_the_chain_here_is_not_solved(monkeypatch):
    # 300 points over 6x-10x (steps of 0.17 %): a count the search solved heavier at an earlier point than the chain's
    # optimum here, the sweep having only tightened the constraints since (the inertia enters the torque's limit
    # alone), cannot be lighter here; the chain passes such points without the neighbour's solve (299 points with
    # the neighbour solved before, 119 now; 670 calls on main), each with the count solve keeps
    case = next(c for c in bench_cases() if c.coupling == "wedge")
    values = case.values["inertia"] * np.geomspace(6.0, 10.0, 300)
    problem = Problem(get_coupling("wedge").formulation("geometry"))
    sweep = BatchSweep(problem, case, {"inertia": values})
    heavier, bounded = BatchSweep._heavier, set()

    def recorded(self, combo, k, value):
        out = heavier(self, combo, k, value)
        if out:
            bounded.add(k)
        return out

    monkeypatch.setattr(BatchSweep, "_heavier", recorded)
    solutions = [s for part in sweep.run() for s in part]
    counts = [int(s.design["weight_count"]) for s in solutions]
    assert [k for k in range(1, 300) if counts[k] != counts[k - 1]] == [115, 243]
    searched = [k for k, s in enumerate(solutions) if s.solver.solves == 2]
    assert len(searched) < 150 and len(bounded - set(searched)) > 150
    for k in sorted(bounded - set(searched)):
        assert solutions[k].solver.solves == 1 and solutions[k].integer_search == []
        want = problem.solve(case.with_values(inertia=float(values[k])))
        assert want.design["weight_count"] == counts[k], k
        assert solutions[k].objective == pytest.approx(want.objective, rel=1e-9)
