"""Sweeps in batches (clutchopt/optimise/batch.py): the same verified optima as ``Problem.solve`` point by point, the
integer search's choices, one design solve per infeasible point, windows that change nothing, bad values refused."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchopt.bench.reference import closed_form
from clutchopt.cases import load_case
from clutchopt.errors import InputError
from clutchopt.formulations import get_coupling
from clutchopt.optimise.batch import BATCHED, BatchSweep, batchable
from clutchopt.optimise.feasibility import INFEASIBLE_MARGIN
from clutchopt.optimise.integers import downhill, violated_whatever_the_rest
from clutchopt.optimise.posed import Box, off_scale
from clutchopt.optimise.problem import Problem, case_problem
from clutchopt.optimise.solution import SolverOptions
from clutchopt.optimise.verify import evaluate_objective
from conftest import CASES

SWEEPS = {  # case, mode, swept quantity, factors: a smooth stretch, integer changes (by exclusion: cable; by the
    # search stepping to a better neighbour: ball over speed), an infeasible stretch (lever)
    "wedge": ("wedge_paper.toml", "paper", "inertia", np.geomspace(0.5, 2.0, 40)),
    "cable": ("cable_conveyor.toml", "paper", "torque", np.geomspace(0.5, 2.0, 60)),
    "ball": ("ball_compressor.toml", "design", "power", np.geomspace(0.5, 2.0, 30)),
    "ball_speed": ("ball_compressor.toml", "design", "speed", np.geomspace(0.5, 2.0, 25)),  # rows stepped downhill
    "lever": ("lever_centrifuge.toml", "paper", "inertia", np.geomspace(1.2, 2.0, 30)),
}
ROWS_UP = ("ball_compressor.toml", "design", "power", np.geomspace(4.7, 6.6, 16))  # one row fewer promised by the
# multipliers but infeasible (IPOPT), the rows rising where the rows before become infeasible


def _sweep(name, window=1024):
    file, mode, quantity, factors = SWEEPS[name] if name in SWEEPS else ROWS_UP
    case = load_case(CASES / file)
    problem = Problem(get_coupling(case.coupling).formulation(mode))
    values = case.values[quantity] * factors
    sweep = BatchSweep(problem, case, {quantity: values})
    return case, problem, quantity, values, sweep, [s for part in sweep.run(window) for s in part]


@pytest.fixture(scope="module", params=sorted(SWEEPS))
def swept(request):
    return (request.param, *_sweep(request.param))


def test_batched_points_equal_problem_solve_point_by_point(swept):
    # each point against Problem.solve warm from the previous optimum (the sweep before batches): status, optimum,
    # design, every constraint's value, margin and activity, outputs, sensitivities and multipliers (elasticities)
    # to the solver's tolerance
    name, case, problem, quantity, values, sweep, solutions = swept
    assert len(solutions) == len(values)
    batched, previous = 0, None
    for value, got in zip(values, solutions):
        want = problem.solve(case.with_values(**{quantity: float(value)}), warm=previous)
        previous = want if want.status == "optimal" else None
        assert got.status == want.status, value
        batched += got.solver.status == BATCHED
        if want.status != "optimal":  # a point a region's proof covers says the interval it holds for
            region = got.solver.name == "interval" and got.diagnosis.startswith(f"proven infeasible for {quantity} ")
            assert got.diagnosis == want.diagnosis or (region and want.diagnosis.startswith("proven infeasible: "))
            continue
        assert got.objective == pytest.approx(want.objective, rel=1e-8)
        unpriced = _unpriced(problem, got, want, case.with_values(**{quantity: float(value)}))
        assert {k: v for k, v in got.design.items() if k not in unpriced} == pytest.approx(
            {k: v for k, v in want.design.items() if k not in unpriced}, rel=1e-6, abs=1e-12)
        assert [c.name for c in got.constraints] == [c.name for c in want.constraints]
        for g, w in zip(got.constraints, want.constraints):
            assert g.feasible and g.elasticity == pytest.approx(w.elasticity, rel=1e-4, abs=1e-6)
            if not unpriced:
                assert g.value == pytest.approx(w.value, rel=1e-6, abs=1e-9 * abs(w.limit))
                assert g.margin == pytest.approx(w.margin, abs=1e-6) and g.active == w.active
        if not unpriced:
            assert {k: o.value for k, o in got.outputs.items()} == pytest.approx(
                {k: o.value for k, o in want.outputs.items()}, rel=1e-6)
        assert set(got.sensitivities) == set(want.sensitivities)
        assert got.sensitivities == pytest.approx(want.sensitivities, rel=1e-4, abs=1e-6)
    optimal = sum(s.status == "optimal" for s in solutions)
    assert optimal >= 9 and batched >= optimal // 2  # most optima came from batches, not one by one


def _unpriced(problem, got, want, case):
    """Design variables in which two optima differ although the objective does not price them (the ball clutch's
    groove conformity where the contact stress does not bind: any value that keeps it within its limit is optimal,
    and the integer search's re-solve by IPOPT, point by point, and by SQP, in a batch, leave it in different
    places). Each must leave the objective unchanged when set to the other optimum's value."""
    params = problem.posed.params(case)
    differ = [k for k in got.design if got.design[k] != pytest.approx(want.design[k], rel=1e-6, abs=1e-12)]
    for name in differ:
        moved = evaluate_objective(problem.formulation, problem.objective.name, {**got.design, name: want.design[name]},
                                   params)
        assert moved == pytest.approx(got.objective, rel=1e-12), name
    return differ


def test_every_point_is_verified_and_counted(swept):
    name, case, problem, quantity, values, sweep, solutions = swept
    for solution in solutions:
        if solution.solver.status == BATCHED:
            assert solution.status == "optimal" and solution.solver.iterations is None
            solved = sum(not e["status"].startswith("excluded") for e in solution.integer_search)
            assert solved <= solution.solver.solves <= max(1, solved + 1)  # a relaxation before its integers
            assert solution.worst_violation <= 1e-8 and solution.solver.time_s > 0
    solved = sum(s.solver.name != "interval" for s in solutions)  # (a point a region's proof covers: no solve)
    assert sweep.solves >= sum(s.solver.solves for s in solutions) >= solved
    assert sweep.check_s > 0 and sweep.solver_s > 0  # both measured (no timing is asserted)


def test_a_padded_chain_calls_no_solver():
    # the wedge's 40 smooth points: the first solved alone by one cold IPOPT call, then chains of 8, 16 and 15
    # points; the last runs on the chained function of 16 whose 16th column is padding (chain_length), which calls
    # no solver: 1 + 8 + 16 + 15 = 40 solver calls (41 when the padding re-solved the last point)
    case, problem, quantity, values, sweep, solutions = _sweep("wedge")
    assert [s.status for s in solutions] == ["optimal"] * 40
    assert [s.solver.solves for s in solutions] == [1] * 40
    assert sweep.solves == 40


def test_the_integer_search_along_a_batched_sweep():
    # cable count rises with the torque: a batch stops short of the point where its count breaks the cable
    # stress whatever the rest, the integer search chooses the next count there in a one-point SQP re-solve (the
    # one neighbour the exclusion leaves, one cable more: the count the relaxation would round to, without it); no
    # count within 1 of the one kept, fixed and solved on its own, does better
    case, problem, quantity, values, sweep, solutions = _sweep("cable")
    counts = [s.design["cable_count"] for s in solutions]
    assert counts == sorted(counts) and len(set(counts)) >= 3
    changes = [s for before, s in zip(solutions, solutions[1:])
               if s.design["cable_count"] != before.design["cable_count"]]
    for solution in changes:
        assert solution.solver.status == BATCHED and solution.solver.solves == 1
        assert [e["status"][:9] for e in solution.integer_search] == ["excluded:", BATCHED[:9]]
        assert solution.design["cable_count"] == solutions[solutions.index(solution) - 1].design["cable_count"] + 1
    assert sweep.solves / len(values) <= 1.5  # issue 14, goal 2
    # issue 26: 60 points, +2 for the first (solved alone: its relaxation, then the count); at each of the 7
    # changes the count one more, without the relaxation (69 calls before), none padded by a solve
    assert len(changes) == 7 and sweep.solves == 60 + 2
    for value, solution in list(zip(values, solutions))[::7]:
        point = case.with_values(**{quantity: float(value)})
        for n in (counts[0] - 1, solution.design["cable_count"] - 1, solution.design["cable_count"] + 1):
            if n >= 1:
                other = problem.solve(type(point)(point.coupling, "", point.values, {**point.bounds,
                                                                                     "cable_count": (n, n)}))
                assert other.status != "optimal" or other.objective >= solution.objective * (1 - 1e-9)


def test_a_count_that_opens_is_where_the_search_starts():
    # cable count falls as the allowable cable stress rises (cable_conveyor, 0.5x-2x over 40 points): the count one
    # fewer, promised a gain by the multipliers, is excluded by eq. (18)'s stress alone (no design variable enters it)
    # until the point where sigma_pk(n - 1) <= [sigma_pk]; the exclusion table finds that point ahead, the chain ends
    # before it and the search starts there at n - 1 (batch._opening): one solve, not the chained column at n and
    # then n - 1. Its record: n - 1 solved, n - 2 excluded. Under the convexity the search rests on, n could not win
    # where n - 1's multiplier promises a gain towards n - 2 (the tangent bounds f*(n) from below by more than
    # f*(n - 1)): each point equals Problem.solve's, which steps from n to n - 1
    file, mode, quantity = "cable_conveyor.toml", "paper", "allowable_cable_stress"
    case = load_case(CASES / file)
    problem = Problem(get_coupling(case.coupling).formulation(mode))
    values = case.values[quantity] * np.geomspace(0.5, 2.0, 40)
    sweep = BatchSweep(problem, case, {quantity: values})
    solutions = [s for part in sweep.run() for s in part]
    counts = [s.design["cable_count"] for s in solutions]
    changes = [k for k in range(1, len(counts)) if counts[k] != counts[k - 1]]
    assert counts == sorted(counts, reverse=True) and len(changes) >= 4
    for k in changes:
        n = counts[k - 1]
        assert counts[k] == n - 1 and solutions[k].solver.solves == 1
        assert [(e["cable_count"], e["status"][:9]) for e in solutions[k].integer_search] == [
            (n - 1, BATCHED[:9]), (n - 2, "excluded:")]
    previous = None
    for value, got in zip(values, solutions):
        want = problem.solve(case.with_values(**{quantity: float(value)}), warm=previous)
        previous = want
        assert got.status == want.status == "optimal" and got.design["cable_count"] == want.design["cable_count"]
        assert got.objective == pytest.approx(want.objective, rel=1e-9)
    assert sweep.solves <= len(values) + 3  # the first point's relaxation and count, no second solve at a change


def test_a_chain_ends_near_the_next_change_of_the_integers():
    # ball rows fall with the speed, the search stepping to a neighbour the multipliers promise (no exclusion to
    # foresee it): at each change the chained column of the rows before is the search's first attempt, the
    # neighbour its second (2 solves); the next chain ends where the next change is expected (batch_pace). At
    # least 25 + 1 (the first point: relaxation and rows) + 7 changes = 33 solves; chains that ran past the
    # changes spent 74 (41 on points after a change), now at most 9 more than the least
    case, problem, quantity, values, sweep, solutions = _sweep("ball_speed")
    changes = [s for before, s in zip(solutions, solutions[1:]) if s.design["ball_rows"] != before.design["ball_rows"]]
    assert len(changes) == 7
    for solution in changes:
        assert solution.solver.status == BATCHED and solution.solver.solves == 2
        assert [e["status"] for e in solution.integer_search] == [BATCHED, BATCHED]
    assert 33 <= sweep.solves <= 42


def test_a_neighbour_without_a_design_is_settled_in_the_batch():
    # ball rows rise with the power (4.7x-6.6x): at each point the multipliers promise a gain from one row fewer,
    # which IPOPT finds infeasible (as Problem.solve's search: the fixed-row problem solved cold). The first point
    # (solved alone) finds it so; from there the power only rises, and the power enters the torque row's limit alone
    # (k_s P / w, no design variable in it), so the row fewer stays ruled out (optimise/tightening.py) and the chain
    # runs on: 1 call a point. Where the rows before become infeasible (2 points) the chained column fails its KKT
    # test and the search finds them without a design by their least violation (optimise/feasibility.py: a verified
    # local minimum of the largest violation above 1e-6, where IPOPT had said Infeasible_Problem_Detected in 5-8 ms):
    # one row fewer than that is ruled out, so the search starts at one row more, without the relaxation: 2 calls (and
    # the failed column). The records' calls: 3 (the first point) + 13 * 1 + 2 * 2 = 20; the sweep's 27: the failed
    # columns at the 2 changes, and the points chained past them (the chains of 8 from points 1 and 7 break at 6 and
    # 11: 2 + 3); 51 before the ruling out, 142 before the batch's own search (chains of 8 failing at their first
    # point, then Problem.solve at each point)
    case, problem, quantity, values, sweep, solutions = _sweep("ball_rows_up")
    rows = [s.design["ball_rows"] for s in solutions]
    assert rows == sorted(rows) and rows[0] == 6 and rows[-1] == 8
    assert all(s.solver.status == BATCHED for s in solutions[1:])
    for before, s in zip(solutions, solutions[1:]):
        n = s.design["ball_rows"]
        if n == before.design["ball_rows"]:
            assert s.integer_search == [] and s.solver.solves == 1
        else:
            assert [(e["ball_rows"], e["status"][:28]) for e in s.integer_search] == [
                (n - 1, "infeasible (least violation "), (n, BATCHED)] and s.solver.solves == 2
            assert float(s.integer_search[0]["status"][28:].split(",")[0]) > INFEASIBLE_MARGIN
    assert not any(e["feasible"] for s in solutions for e in s.integer_search if e["status"] != BATCHED
                   and not e["status"].startswith("Solve"))
    assert sum(s.solver.solves for s in solutions) == 20 and sweep.solves <= 27
    previous = None
    for value, got in zip(values, solutions):  # Problem.solve's designs, point by point
        want = problem.solve(case.with_values(**{quantity: float(value)}), warm=previous)
        previous = want
        assert got.status == want.status == "optimal" and got.design["ball_rows"] == want.design["ball_rows"]
        assert got.objective == pytest.approx(want.objective, rel=1e-9)


def test_an_infeasible_stretch_is_proven_once_after_its_first_point():
    case, problem, quantity, values, sweep, solutions = _sweep("lever")
    statuses = [s.status for s in solutions]
    first = statuses.index("infeasible")
    assert "optimal" not in statuses[first:] and first > 3  # the lining pressure ends the feasible stretch
    # the first point without a design gets its full verdict (retried from at most three more starts:
    # optimise/verdict.py), the points after it one proof for them all, without a solve (optimise/region_proof.py):
    # no design within the bounds meets the torque and the lining pressure together
    assert all(s.solver.solves == 0 and s.solver.name == "interval" for s in solutions[first + 1:])
    assert all(s.diagnosis.startswith("proven infeasible") and
               "no design within the bounds meets torque, lining_pressure" in s.diagnosis for s in solutions[first:])
    assert solutions[first].solver.time_s > 0  # the diagnosis's IPOPT call is solver time; the points after it carry
    # its proof (the sweep only tightens their limits: Regions._tightened), no search: none
    assert all(s.solver.time_s == 0 and "by the proof at inertia" in s.diagnosis for s in solutions[first + 1:])


def test_windows_change_nothing():
    *_, whole = _sweep("ball")
    *_, windowed = _sweep("ball", window=7)
    assert [s.status for s in windowed] == [s.status for s in whole]
    assert [s.objective for s in windowed] == pytest.approx([s.objective for s in whole], rel=1e-8)
    assert [s.design["ball_rows"] for s in windowed] == [s.design["ball_rows"] for s in whole]


@settings(max_examples=12, deadline=None)
@given(st.lists(st.floats(0.3, 3.0), min_size=1, max_size=25))
def test_any_order_of_points_meets_the_closed_form(factors):
    # points in any order, with repeats and jumps: each batched optimum is the closed form of the same model (the
    # wedge paper mode's), to the solver's tolerance
    case = load_case(CASES / "wedge_paper.toml")
    problem = case_problem(case, "paper")
    values = case.values["inertia"] * np.array(factors)
    solutions = [s for part in BatchSweep(problem, case, {"inertia": values}).run(window=10) for s in part]
    assert len(solutions) == len(values)
    for value, solution in zip(values, solutions):
        reference = closed_form(case.with_values(inertia=float(value)))
        assert solution.status == "optimal"
        assert solution.objective == pytest.approx(reference.objective, rel=1e-8)


@pytest.mark.parametrize("bad, field", [(-1.0, "duty.inertia"), (math.nan, "duty.inertia"), (1e300, "duty.inertia")])
def test_bad_values_are_refused_before_any_solve(bad, field):
    case = load_case(CASES / "wedge_paper.toml")
    values = np.array([case.values["inertia"], bad])
    with pytest.raises(InputError) as error:
        BatchSweep(case_problem(case, "paper"), case, {"inertia": values})
    assert error.value.field == field


def test_start_ups_and_fixed_variables_go_point_by_point():
    start_up = load_case(CASES / "wedge_motor_start.toml")
    assert not batchable(case_problem(start_up), ["inertia"])
    case = load_case(CASES / "cable_conveyor.toml")
    assert batchable(case_problem(case, "paper"), ["torque"])
    fixed = next(v.name for v in case_problem(case, "paper").formulation.variables if v.fixed_unless_freed)
    assert not batchable(case_problem(case, "paper"), [fixed])


def test_an_error_inside_the_chained_call_sends_the_points_to_problem_solve(monkeypatch):
    import clutchopt.optimise.batch as batch

    case = load_case(CASES / "wedge_paper.toml")
    problem = Problem(get_coupling("wedge").formulation("paper"))
    values = case.values["inertia"] * np.geomspace(0.8, 1.2, 12)

    def failing(posed, count, method="sqp_chain"):
        raise RuntimeError("Error in Function::call for 'sqp_chain': NaN detected")

    monkeypatch.setattr(batch, "chained_sqp", failing)
    sweep = BatchSweep(problem, case, {"inertia": values})
    solutions = [s for part in sweep.run() for s in part]
    assert [s.status for s in solutions] == ["optimal"] * 12
    assert all(s.solver.status != BATCHED for s in solutions)
    for value, solution in zip(values, solutions):
        assert solution.objective == pytest.approx(closed_form(case.with_values(inertia=float(value))).objective,
                                                   rel=1e-8)


def test_a_point_that_fails_the_float64_check_is_solved_again(monkeypatch):
    # a batched point whose float64 re-evaluation finds a constraint violated is not reported as optimal: the
    # window solves it again by Problem.solve, warm from the point before (here every batched point fails the check)
    import clutchopt.optimise.batch_window as batch_window

    case = load_case(CASES / "wedge_paper.toml")
    problem = Problem(get_coupling("wedge").formulation("paper"))
    values = case.values["inertia"] * np.geomspace(0.8, 1.2, 20)
    monkeypatch.setattr(batch_window, "FEASIBILITY_TOL", -1.0)
    sweep = BatchSweep(problem, case, {"inertia": values})
    windows = list(sweep.run(window=8))
    assert [len(w) for w in windows] == [8, 8, 4]
    assert all(status == "optimal" for w in windows for status in w.statuses)
    solutions = [s for w in windows for s in w]
    assert all(s.solver.status != BATCHED for s in solutions)
    assert sweep.solves >= 2 * len(values) - 1  # all but the first point batched, then solved again
    for value, solution in zip(values, solutions):
        assert solution.objective == pytest.approx(closed_form(case.with_values(inertia=float(value))).objective,
                                                   rel=1e-8)


def test_a_sweep_table_says_where_a_point_was_batched():
    from clutchopt.optimise.sweep import Sweep
    from clutchopt.optimise.sweep_grid import parse_vary
    from clutchopt.optimise.sweep_table import markdown_table

    case = load_case(CASES / "wedge_paper.toml")
    frame = Sweep(case, [parse_vary("speed=800:1200:12", "wedge")]).run(progress=False).frame
    assert str(frame["iterations"].dtype) == "Int64"
    assert frame["iterations"][0] > 0 and frame["iterations"][1:].isna().all()  # the first point starts cold
    assert markdown_table(frame).splitlines()[3].endswith("| - |")


def test_the_predictor_ratio_of_each_point():
    # a point's step in the case against the step before it: 1 along a geometric sweep, -1 where it turns back,
    # 0 where there is no step before it, after a repeated point, and where the steps differ more than fourfold
    case = load_case(CASES / "wedge_paper.toml")
    problem = Problem(get_coupling("wedge").formulation("paper"))
    base = case.values["inertia"]
    factors = np.array([1.0, 1.01, 1.0201, 1.030301, 1.0201, 1.0201, 1.01, 1.5, 1.515])
    sweep = BatchSweep(problem, case, {"inertia": base * factors})
    moves = np.diff(factors) / factors[1:]
    expected = [0.0, 0.0, 1.0, 1.0, moves[3] / moves[2], 0.0, 0.0, 0.0, moves[7] / moves[6]]
    assert expected[4] == pytest.approx(-1.0, rel=0.03) and abs(moves[6] / moves[5]) > 4  # turns back; a jump
    assert sweep._ratio == pytest.approx(expected, rel=1e-12, abs=1e-12)
    assert sweep._ratios(np.array([6, 7, 8, 8, 8])) == pytest.approx([0.0, 0.0, expected[8], 0.0, 0.0])


@pytest.mark.parametrize("name, cases", [("cable", {"all excluded"}), ("ball_speed", {"none", "open"}),
                                         ("wedge", {"on scale"})])
def test_the_compiled_verdict_says_what_the_warm_search_would_do(name, cases, monkeypatch):
    # chain.chain_verdict's `moves` at every chained point against Problem.solve's own rule in Python: a neighbour
    # that integers.downhill steps to and that breaks no constraint of fixed variables alone; without integers, an
    # optimum off its scales (posed.off_scale). Along the cable's sweep every neighbour the multipliers point to is
    # excluded (its count breaks the cable stress; no relaxation is chained there, whose free count would point
    # nowhere: "none"); along the ball's speed sweep the search steps to a neighbour.
    import clutchopt.optimise.batch as batch

    chains = []
    chain = batch.BatchSweep._chain

    def kept(self, *args, **kwargs):
        result = chain(self, *args, **kwargs)
        chains.append((self, result))
        return result

    monkeypatch.setattr(batch.BatchSweep, "_chain", kept)
    case, problem, quantity, values, sweep, solutions = _sweep(name)
    seen = set()
    for sweep, result in chains:
        m, n = len(sweep.values), len(sweep.names)
        for j in range(len(result.index)):
            x, scale = result.x[:, j], result.p[m:m + n, j]
            if not sweep.integer:
                assert result.moves[j] == bool(off_scale(x))
                seen.add("off scale" if result.moves[j] else "on scale")
                continue
            run = {"x": x, "lam_x": result.lam_x[:, j], "f": float(result.f[0, j])}
            box = Box(scale, sweep.lower, sweep.upper)
            p = np.concatenate([result.p[:m, j], np.ones(n + 1)])  # unit scales: x in SI
            neighbours, open_neighbours = downhill(problem.posed, run, box, sweep.integer), []
            for combo in neighbours:
                lower, upper = sweep.lower.copy(), sweep.upper.copy()
                lower[sweep.integer] = upper[sweep.integer] = combo
                if not violated_whatever_the_rest(problem.posed, p, lower, upper, np.clip(x * scale, lower, upper)):
                    open_neighbours.append(combo)
            assert bool(result.moves[j]) == bool(open_neighbours), (sweep.integer, x * scale, open_neighbours)
            seen.add("open" if open_neighbours else "all excluded" if neighbours else "none")
    assert seen == cases


@pytest.mark.parametrize("name", sorted(SWEEPS))
def test_a_windows_records_are_its_solutions_as_dicts(name):
    # the records built column-wise (what clutchopt sweep stores and tabulates) are each point's Solution.as_dict(),
    # the same JSON text, key order and floats included; batched points, points solved alone (the first, the
    # lever's infeasible ones) and integer searches among them; the ball's window's sensitivities by compiled code,
    # a point's alone on CasADi's virtual machine
    import json

    file, mode, quantity, factors = SWEEPS[name]
    case = load_case(CASES / file)
    problem = Problem(get_coupling(case.coupling).formulation(mode))
    sweep = BatchSweep(problem, case, {quantity: case.values[quantity] * factors})
    kinds = set()
    for window in sweep.run(window=16):
        records = window.records()
        solutions = list(window)
        assert len(records) == len(solutions)
        for record, solution in zip(records, solutions):
            assert json.dumps(record) == json.dumps(solution.as_dict())
            kinds.add((solution.solver.status == BATCHED, solution.status, bool(solution.integer_search)))
    assert (True, "optimal", False) in kinds and (False, "optimal", bool(problem.posed.integer)) in kinds


def test_the_first_re_solve_after_a_cold_ipopt_optimum_goes_by_sqp():
    # IPOPT leaves about 1e-11 on inactive bounds; CasADi's SQP (qrqp) would read them as active bounds and stop
    # where it started. attempts.warm_multipliers drops them: the next point is one SQP re-solve, point by point and
    # in a batch (whose first point used to fail its KKT test and go to Problem.solve). IPOPT's optimum as it ends,
    # not polished (SolverOptions.polish: a polished one's multipliers on inactive bounds are 0 exactly)
    case = load_case(CASES / "wedge_centrifuge.toml")
    problem = Problem(get_coupling("wedge").formulation("paper"), options=SolverOptions(polish=False))
    values = case.values["inertia"] * np.geomspace(0.5, 2.0, 1000)[:3]
    first = problem.solve(case.with_values(inertia=float(values[0])))
    assert first.solver.name == "ipopt" and np.any((np.abs(first.multipliers[0]) > 0)
                                                  & (np.abs(first.multipliers[0]) < 1e-9))
    second = problem.solve(case.with_values(inertia=float(values[1])), warm=first)
    assert (second.status, second.solver.name, second.solver.solves) == ("optimal", "sqpmethod", 1)
    solutions = [s for part in BatchSweep(problem, case, {"inertia": values}).run() for s in part]
    assert [s.solver.status for s in solutions[1:]] == [BATCHED, BATCHED]


def test_a_chain_goes_on_where_its_count_is_excluded(monkeypatch):
    # the cable count rises with the torque (7 changes over 0.5x-2x, 60 points): at each change the count before
    # breaks the cable stress whatever the rest and one cable more is the one neighbour left, so a chain goes on
    # there with one cable more (its column the search's only attempt): after point 0 (solved alone) a chain of 8
    # points taken on to the change at point 10 (within the 16 it may reach), then 16 and 32 points doubling as they
    # pass, and the last point: 4 chained calls, where a chain that ended at each change and the one-point re-solve
    # there had made 15
    chains = []
    monkeypatch.setattr(BatchSweep, "_chain", lambda self, *a, _chain=BatchSweep._chain, **k: chains.append(
        a[2]) or _chain(self, *a, **k))
    *_, sweep, solutions = _sweep("cable")
    counts = [s.design["cable_count"] for s in solutions]
    assert sum(a != b for a, b in zip(counts, counts[1:])) == 7
    assert chains == [10, 16, 32, 1] and sweep.solves == 62
    assert all(s.solver.status == BATCHED for s in solutions[1:])


def test_a_change_settled_from_its_column_is_what_the_search_records(monkeypatch):
    # BatchSweep._changed gives a change's outcome without running the search, where it is certain: the same
    # designs, records (the count before excluded, then the column kept) and calls as the search run at each change
    # (_settle from the column), which then ends the kept points after it (more chained calls)
    def solved():
        chains = []
        monkeypatch.setattr(BatchSweep, "_chain", lambda self, *a, _chain=BatchSweep._chain, **k: chains.append(
            a[2]) or _chain(self, *a, **k))
        *_, sweep, solutions = _sweep("cable")
        monkeypatch.undo()
        return len(chains), solutions

    calls, direct = solved()
    monkeypatch.setattr(BatchSweep, "_changed", lambda *a: None)
    searched_calls, searched = solved()
    assert calls == 4 and searched_calls > calls
    for s, t in zip(direct, searched):  # (the chains end elsewhere: the objective normalised by another point's)
        assert s.objective == pytest.approx(t.objective, rel=1e-12) and s.design["cable_count"] == t.design[
            "cable_count"] and s.solver.solves == t.solver.solves and s.solver.status == t.solver.status
        assert [(e["cable_count"], e["status"]) for e in s.integer_search] == [
            (e["cable_count"], e["status"]) for e in t.integer_search]


def test_the_ball_past_4_5x_its_power_spends_one_call_a_point_between_changes_of_its_rows():
    # ball_compressor over 1x-10x its power (100 points, the benchmark's sweep into the infeasible): 7 rows up to
    # 4.5x, where the contact stress becomes active and one row fewer pays (6 rows from point 65); from point 66 on
    # the multipliers promise one row fewer at every point, which IPOPT finds infeasible at 66 and which stays ruled
    # out (the power enters the torque row's limit alone, so the constraints only tighten: optimise/tightening.py);
    # the rows rise by one at 72, 77, 82, 86, 90, 93, where the rows before become infeasible (IPOPT) and one more is
    # the only neighbour left; no design from 96 on. The records' calls: 2 (point 0: the relaxation, its rows) +
    # 64 (1 .. 64, chained) + 2 (65: 7 rows' column, 6 rows) + 2 (66: 5 rows by IPOPT) + 23 (chained between the
    # changes) + 6 * 2 (each change: the rows before by IPOPT, one more by SQP) + 0 (96: the chain from 95 fails there,
    # and with integer variables the point's own interval search, the one its verdict runs first, goes before its
    # solve and proves it, region_proof.Regions._early; 1 before, solve's from the case's own start, its relaxation
    # and elastic diagnosis, then that proof; 3 before that, with two retries) + 0 (97 .. 99: one region proof)
    # = 105. The sweep's 123 add the chained columns that failed at the changes and at 96, the batch's own search at
    # 96 (the 12 rows and the 13 by IPOPT) and points chained past a change; 192 before (the first chain past 4.5x ran
    # to the sweep's end, the row fewer was solved by IPOPT at every point)
    case = load_case(CASES / "ball_compressor.toml")
    problem = Problem(get_coupling("ball").formulation("design"))
    values = case.values["power"] * np.geomspace(1.0, 10.0, 100)
    sweep = BatchSweep(problem, case, {"power": values})
    solutions = [s for part in sweep.run() for s in part]
    assert [s.status for s in solutions] == ["optimal"] * 96 + ["infeasible"] * 4
    rows = [int(s.design["ball_rows"]) for s in solutions[:96]]
    changes = [k for k in range(1, 96) if rows[k] != rows[k - 1]]
    assert changes == [65, 72, 77, 82, 86, 90, 93] and rows[0] == 7 and rows[65] == 6 and rows[95] == 12
    calls = [s.solver.solves for s in solutions]
    assert calls[0] == 2 and calls[65] == calls[66] == 2 and all(calls[k] == 2 for k in changes[1:])
    assert sum(calls) == 105 and sweep.solves <= 123
    for k in (65, 66, 72, 95):  # Problem.solve's designs, warm from the point before (as the sweep before batches)
        want = problem.solve(case.with_values(power=float(values[k])), warm=solutions[k - 1])
        assert want.status == "optimal" and want.design["ball_rows"] == rows[k]
        assert solutions[k].objective == pytest.approx(want.objective, rel=1e-9)
