"""Infeasible regions of a sweep proven at once (issue 26 item 3): interval searches run in one array
(interval_proof.searches), a run of points without a design searched as one box with the varied quantity an interval
(region_proof), and every point keeps the verdict its own solve gives (issue 29: "infeasible" only when shown,
whatever the order of the points)."""

import time

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import interval_proof, region_proof, sweep, verdict
from clutchopt.optimise import problem as problem_module
from clutchopt.optimise.interval import IntervalFunction
from clutchopt.optimise.interval_proof import search, searches
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.solution import SolverInfo
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from clutchopt.optimise.verify import check_design
from tests.conftest import CASES

WEDGE = load_case(CASES / "wedge_paper.toml")


@pytest.fixture(autouse=True)
def _proofs_not_inherited(monkeypatch):
    """The regions' own searches, as a sweep meets them where its steps do not only tighten the limits (a speed, a
    friction coefficient, a sweep out of its region): a proof not carried along a tightening sweep
    (``Regions._tightened``: tests/test_region_tightened.py), which these sweeps of a duty upwards are."""
    monkeypatch.setattr(region_proof.Regions, "_tightened", lambda self, j, k, count=0: k)


def test_a_box_is_bounded_alike_whatever_boxes_are_evaluated_with_it():
    import casadi as ca

    x, y = ca.SX.sym("x"), ca.SX.sym("y")
    product = IntervalFunction(ca.Function("xy", [x, y], [x * y]))
    # box 0: x in [0, 0], y in [1, inf]: x y = 0 throughout (the corners 0 * 1 = 0; 0 * inf left out); box 1 has a
    # negative x, which once sent every box to the four-corner rule
    x_lo, x_hi, y_lo, y_hi = np.array([[0.0, -1.0]]), np.array([[0.0, 1.0]]), np.array([[1.0, 1.0]]), \
        np.array([[np.inf, 2.0]])
    (alone_lo, alone_hi), = product.bounds([(x_lo[:, :1], x_hi[:, :1]), (y_lo[:, :1], y_hi[:, :1])])
    (both_lo, both_hi), = product.bounds([(x_lo, x_hi), (y_lo, y_hi)])
    assert alone_hi[0, 0] == both_hi[0, 0] == 0.0 and alone_lo[0, 0] == both_lo[0, 0] == 0.0
    assert both_lo[0, 1] <= -2.0 and both_hi[0, 1] >= 2.0  # [-1, 1] x [1, 2] = [-2, 2], widened outwards


def test_searches_together_give_each_point_its_own_search():
    # the wedge paper case at resisting torques from 20 to 400 N m: a design met at the low ones (the search stops
    # there), emptiness proven at the high ones over 129 or 257 boxes (torque and flank pressure)
    posed = case_problem(WEDGE).posed
    problems = [interval_proof._search_problem(posed, WEDGE.with_values(resisting_torque=torque))
                for torque in (20.0, 140.0, 60.0, 400.0, 160.0)]
    together = searches(posed, problems)
    alone = [search(posed, *problem) for problem in problems]
    assert [e.proven for e in alone] == [False, True, False, True, True]
    assert [e.feasible is not None for e in alone] == [True, False, True, False, False]
    for a, b in zip(alone, together):
        assert (a.proven, a.boxes, list(a.decisive.items())) == (b.proven, b.boxes, list(b.decisive.items()))
        assert (a.feasible is None and b.feasible is None) or np.array_equal(a.feasible, b.feasible)


def test_a_search_past_its_budget_ends_before_the_splits_that_pass_it(monkeypatch):
    # The wedge paper case at 89.09 N m has a design (optimal alone); its search evaluates its first box (the design
    # box, not emptied), splits it into 128 and meets a design centre among them (129 boxes). With a budget of 64 it
    # ends after its first box, not proven, nothing met; 400 N m is proven in its first box whatever the budget. A
    # search without integers whose splits would pass its budget ends before them (a point searched alone past its
    # region's edge): no turn of bisection, not the 6 that pass it (64 boxes: 1 + 64 > 64) nor the 7 that make 128
    posed = case_problem(WEDGE).posed
    problems = [interval_proof._search_problem(posed, WEDGE.with_values(resisting_torque=t)) for t in (89.090909, 400.0)]
    turns = []
    real = interval_proof._bisected_where
    monkeypatch.setattr(interval_proof, "_bisected_where", lambda *a, **k: turns.append(1) or real(*a, **k))
    short, proven = searches(posed, problems, [64, 64])
    assert (short.proven, short.boxes, short.feasible, short.reached) == (False, 1, None, False)
    assert (proven.proven, proven.boxes) == (True, 1)
    assert len(turns) == 0
    met, = searches(posed, problems[:1])
    assert (met.proven, met.boxes, met.feasible is not None) == (False, 129, True) and len(turns) == 7



def test_boxes_bisected_where_chosen_keep_each_search_s_order():
    # two searches' boxes of one variable, the first's box 1 and none other left whole: each search's first halves
    # (a box left whole among them, in its place), then its second halves, search by search
    lo, hi = np.array([[0.0, 10.0, 20.0, 30.0]]), np.array([[2.0, 12.0, 24.0, 34.0]])
    owner, slope, width0 = np.array([0, 0, 1, 1]), np.ones((1, 4)), np.ones((1, 2))
    split = np.array([True, False, True, True])
    lo2, hi2, owner2, parents = interval_proof._bisected_where(lo, hi, owner, slope, (width0, width0), split)
    assert parents.tolist() == [0, 1, 0, 2, 3, 2, 3] and owner2.tolist() == [0, 0, 0, 1, 1, 1, 1]
    assert lo2.tolist() == [[0.0, 10.0, 1.0, 20.0, 30.0, 22.0, 32.0]]
    assert hi2.tolist() == [[1.0, 12.0, 2.0, 22.0, 32.0, 24.0, 34.0]]

def _wedge_into_its_region(monkeypatch, batched: bool):
    """The wedge paper case at 12 resisting torques from 20 to 400 N m (each solved alone: designs up to 89.09 N m,
    proven infeasible from 123.6 N m on), in batches or point by point: the varied torques, the sweep's result, and
    per call of ``searches`` its problems' lengths (3: a point's, 4: a region's, with a parameter interval)."""
    searched = []
    real = region_proof.searches
    monkeypatch.setattr(region_proof, "searches", lambda posed, problems, budgets=None: searched.append(
        [len(problem) for problem in problems]) or real(posed, problems, budgets))
    if not batched:
        monkeypatch.setattr(sweep, "batchable", lambda problem, names: False)
    vary = parse_vary("resisting_torque=20:400:12", "wedge", WEDGE.quantities)
    result = Sweep(WEDGE, [vary]).run(progress=False)
    assert [s["status"] for s in result.solutions] == ["optimal"] * 3 + ["infeasible"] * 9
    return vary, result, searched


@pytest.mark.parametrize("batched", [True, False])  # in batches, or point by point (start-ups, varied variables)
def test_a_sweep_into_an_infeasible_region_proves_each_point_alone_where_its_proof_takes_few_boxes(monkeypatch,
                                                                                                     batched):
    # The wedge paper case at 12 resisting torques from 20 to 400 N m (each solved alone: designs up to 89.09 N m,
    # proven infeasible from 123.6 N m on). Point 3 (123.6 N m), where the batch's chain from point 2 fails, is
    # searched alone before any solve and proven in 1 box (point by point: its full verdict, whose search proves it
    # in 1 box); the 8 points after it (158.2-400 N m) are searched each alone, in one call (8 boxes expected, where
    # their region's search takes 129: the next test): each proven, with the words of its own verdict (solve's),
    # without a solve.
    vary, result, searched = _wedge_into_its_region(monkeypatch, batched)
    frame = result.frame
    assert searched == [[3]] * batched + [[3] * 8]  # one call, 8 searches of one point each (no parameter interval)
    assert [s["solver"]["solves"] for s in result.solutions][4:] == [0] * 8
    assert [s["solver"]["name"] for s in result.solutions][3 + (not batched):] == ["interval"] * (8 + batched)
    if batched:  # point 3 shows point 2's design (its full verdict: its least relaxation's), at its own torque
        assert result.solutions[3]["solver"]["solves"] == 0
        assert result.solutions[3]["design"] == result.solutions[2]["design"]
        torque = next(c for c in result.solutions[3]["constraints"] if c["name"] == "torque")
        assert torque["margin"] < 0 and torque["limit"] == pytest.approx(vary.values[3] + 5.235987756, rel=1e-9)
    problem = case_problem(WEDGE)
    for point in (3, 4, 11):
        solution = problem.solve(WEDGE.with_values(resisting_torque=vary.values[point]))
        assert (frame["status"][point], frame["diagnosis"][point]) == (solution.status, solution.diagnosis)
    assert frame["diagnosis"][4] == ("proven infeasible: no design within the bounds meets torque, flank_pressure, "
                                     "finger_guide_length, finger_fits_chord together (interval branch and bound "
                                     "over 1 boxes of the design space)")  # (the rows that cut its box, all four)


@pytest.mark.parametrize("batched", [True, False])  # in batches, or point by point (start-ups, varied variables)
def test_a_sweep_into_an_infeasible_region_proves_it_once_and_keeps_each_point_s_verdict(monkeypatch, batched):
    # The sweep of the test above, its runs searched as regions (as where a point's own proof takes as many boxes as
    # its region's: the ball). Point 3 (123.6 N m) gets its full verdict (its own search); the 8 points after it
    # (158.2-400 N m) are searched as one box, the torque an interval: proven over 129 boxes, one proof for the 8
    # points, without a solve.
    monkeypatch.setattr(region_proof.Regions, "_one_by_one", lambda self, count: False)
    vary, result, regions = _wedge_into_its_region(monkeypatch, batched)
    frame = result.frame
    assert regions == [[3]] * batched + [[4]]  # (point 3 searched alone first where a chain failed there) one
    # search, over a parameter interval
    region = "proven infeasible for resisting_torque 158.182-400 N*m (8 points, one proof): no design within the " \
             "bounds meets torque, flank_pressure, finger_guide_length, finger_fits_chord together (interval branch " \
             "and bound over 129 boxes of the design space and the interval of resisting_torque)"
    assert list(frame["diagnosis"][4:]) == [region] * 8
    assert [s["solver"]["solves"] for s in result.solutions][4:] == [0] * 8
    problem = case_problem(WEDGE)
    for point in (2, 3):  # both sides of the region's edge: each point's own verdict
        solution = problem.solve(WEDGE.with_values(resisting_torque=vary.values[point]))
        assert (frame["status"][point], frame["diagnosis"][point]) == (solution.status, solution.diagnosis or "")
    for point in (4, 11):  # the region's ends: proven alone too
        solution = problem.solve(WEDGE.with_values(resisting_torque=vary.values[point]))
        assert solution.status == "infeasible" and solution.diagnosis.startswith("proven infeasible: no design")
    # a covered point shows point 3's design (its least relaxation) with every constraint re-evaluated in float64 at
    # its own torque: the torque row's limit is the resisting torque plus the same 5.236 N m at each point (the
    # wedge's limit for this case: 128.872 N m at 123.636 N m, read from point 3's own solve)
    torques = [next(c for c in result.solutions[k]["constraints"] if c["name"] == "torque") for k in (3, 4, 11)]
    assert [t["value"] for t in torques[1:]] == [torques[0]["value"]] * 2
    added = torques[0]["limit"] - vary.values[3]
    assert added == pytest.approx(5.235987756, rel=1e-9)
    assert [t["limit"] - vary.values[k] for t, k in zip(torques[1:], (4, 11))] == pytest.approx([added] * 2, rel=1e-12)
    assert result.solutions[4]["solver"]["name"] == "interval"


def test_a_region_proof_holds_only_where_no_design_exists():
    # the box over 89.09-158.2 N m holds the design of 89.09 N m (optimal alone): no proof there, however many boxes;
    # over 123.6-400 N m (each point proven alone) one proof
    posed = case_problem(WEDGE).posed
    points = {t: interval_proof._search_problem(posed, WEDGE.with_values(resisting_torque=t))
              for t in (89.090909, 123.63636, 158.18182, 400.0)}
    reaching, inside = (region_proof._region_problem([points[t] for t in ts])
                        for ts in ((89.090909, 123.63636, 158.18182), (123.63636, 158.18182, 400.0)))
    out, proven = searches(posed, [reaching, inside], [interval_proof.MAX_BOXES] * 2)
    assert not out.proven and proven.proven
    # the box reaching 89.09 N m stops where a centre meets every row at that end of the interval (no design meets
    # them over the whole interval: feasible is None), at its third evaluation (353 boxes; 289 at its second where
    # the rows were not carried back from the second on and the boxes split by their slopes): the finger's guide
    # length h_r >= 1.5 d_n (paper mode poses it too) keeps d_n below 13.3 mm, where its first (129 boxes) sufficed
    # when a 500 mm finger, the bound's, met every row; the point's own search meets a design at 129
    alone, = searches(posed, [points[89.090909]])
    assert (out.boxes, out.feasible, out.reached) == (353, None, True) and out.witness[1] <= 0.02 / 1.5
    assert alone.boxes == 129 and alone.feasible is not None
    assert case_problem(WEDGE).solve(WEDGE.with_values(resisting_torque=89.090909)).status == "optimal"


@pytest.mark.parametrize("order", [slice(None), slice(None, None, -1)])
def test_the_verdicts_do_not_depend_on_the_order_of_the_points(order):
    values = np.linspace(20.0, 400.0, 12)[order]
    vary = parse_vary("resisting_torque=" + ",".join(f"{v:.17g}" for v in values), "wedge", WEDGE.quantities)
    frame = Sweep(WEDGE, [vary]).run(progress=False).frame
    statuses = list(frame["status"])[order]
    assert statuses == ["optimal"] * 3 + ["infeasible"] * 9
    assert all(text.startswith("proven infeasible") for text in frame["diagnosis"][frame["status"] == "infeasible"])


def test_a_run_reaching_past_the_region_s_edge_searches_only_its_first_half_again(monkeypatch):
    # The wedge paper case from 300 down to 20 N m: designs up to 89.09 N m, proven infeasible from 123.6 N m on
    # (each point solved alone; the test above). Point 0 (300 N m), solved once, is proven by its own search
    # (Regions._first: solve's verdict); the run of the 8 points
    # after it (250-30 N m) meets a design at its 30 N m end, so no proof over it exists (the back-off rule): only
    # its first half (250-130 N m, all beyond 123.6 N m) is searched again and proven, and the other half's points
    # (80-30 N m, designs) are solved as usual, without a search of their own.
    # (Without the probes for the region's edge, which would find it first: the next test.)
    regions = []
    real = region_proof.searches
    monkeypatch.setattr(region_proof, "searches", lambda posed, problems, budgets=None: regions.append(
        [outcome for outcome in real(posed, problems, budgets)]) or regions[-1])
    monkeypatch.setattr(region_proof.Regions, "_edge", lambda self, k, end, points, witness=None: (end, k))
    monkeypatch.setattr(region_proof.Regions, "_one_by_one", lambda self, count: False)  # (its regions, as the ball's)
    torques = [300.0, 250.0, 200.0, 160.0, 130.0, 80.0, 60.0, 40.0, 30.0, 20.0]
    vary = parse_vary("resisting_torque=" + ",".join(f"{t:g}" for t in torques), "wedge", WEDGE.quantities)
    frame = Sweep(WEDGE, [vary]).run(progress=False).frame
    assert list(frame["status"]) == ["infeasible"] * 5 + ["optimal"] * 5
    assert [len(outcomes) for outcomes in regions] == [1, 1, 1]  # point 0, the run of 8, then its first half alone
    (own,), (run,), (half,) = regions
    assert own.proven and frame["diagnosis"][0] == "proven infeasible: " + verdict.emptied(own)
    assert run.reached and not run.proven and run.feasible is None
    assert half.proven
    assert list(frame["diagnosis"][1:5]) == [frame["diagnosis"][1]] * 4
    assert frame["diagnosis"][1].startswith("proven infeasible for resisting_torque 130-250 N*m (4 points, one proof)")


def _searches_and_probes(monkeypatch) -> tuple[list, list]:
    """The outcomes of a sweep's region searches (a list per call) and the points its probes tried, as they come."""
    regions, probed = [], []
    real, designed = region_proof.searches, region_proof.Regions._designed
    recorded = lambda posed, problems, budgets=None, **lead: regions.append(  # noqa: E731
        [outcome for outcome in real(posed, problems, budgets, **lead)]) or regions[-1]
    monkeypatch.setattr(region_proof, "searches", recorded)
    monkeypatch.setattr(interval_proof, "searches", recorded)  # (a point's own search with the runs after it:
    # interval_proof.searched_along)
    monkeypatch.setattr(region_proof.Regions, "_designed", lambda self, j, witness=None: probed.append(j) or designed(
        self, j, witness))
    return regions, probed


def test_probes_find_the_region_s_edge_before_its_search(monkeypatch):
    # The sweep of the test above. The search of the run of the 8 points after point 0 (250-30 N m) meets a design
    # at its 30 N m end; the run's last point (30 N m) has one without a solve (that design, within its bounds, meets
    # every constraint there in float64; a cold solve before), so the region's edge is looked
    # for from point 1 on in growing steps: points 2 (200 N m) and 4 (130 N m) without a design, then bisection
    # between 4 and 8: 6 (60 N m) and 5 (80 N m) with one. Points 1-4 (250-130 N m) are searched again, proven (here
    # the first half of the run too; the ball over its allowable contact stress: one search for the last 2 points of
    # its region, not three more halvings from 16, 7.7 s to 1.3 s). The 4 probes solved (IPOPT calls:
    # one each, two at 80 N m) are charged to point 1's verdict but the one at the edge (80 N m), which is that
    # point's own solve (cold, as next to a point without a design), not made again: the sweep's calls are its points'.
    regions, probed = _searches_and_probes(monkeypatch)
    monkeypatch.setattr(region_proof.Regions, "_one_by_one", lambda self, count: False)  # (its regions, as the ball's)
    torques = [300.0, 250.0, 200.0, 160.0, 130.0, 80.0, 60.0, 40.0, 30.0, 20.0]
    vary = parse_vary("resisting_torque=" + ",".join(f"{t:g}" for t in torques), "wedge", WEDGE.quantities)
    result = Sweep(WEDGE, [vary]).run(progress=False)
    frame = result.frame
    assert list(frame["status"]) == ["infeasible"] * 5 + ["optimal"] * 5
    assert probed == [8, 2, 4, 6, 5]
    assert [len(outcomes) for outcomes in regions] == [1, 1, 1, 1]  # (point 0's own search first: Regions._first)
    assert regions[0][0].proven and regions[1][0].reached and regions[3][0].proven
    # (before the probes, points 1-2's search (Regions._head), within 4 x the last proof's 1 box, at least 64: its
    # split of its first box to 128 passes that, and it ends unproven after 1 box)
    assert not regions[2][0].proven and regions[2][0].boxes == 1
    posed = case_problem(WEDGE).posed  # (the design met at 30 N m, the run's last point: no probe solved there)
    met = dict(zip(posed.names, regions[1][0].witness))
    assert all(c.feasible for c in check_design(posed.formulation, met, posed.params(WEDGE.with_values(
        resisting_torque=30.0))))
    assert frame["diagnosis"][1].startswith("proven infeasible for resisting_torque 130-250 N*m (4 points, one proof)")
    assert [s["solver"]["solves"] for s in result.solutions][1:6] == [3, 0, 0, 0, 2]  # (80 N m: 2 calls, a retry;
    # 4 at point 1 with the solve at 30 N m, 6 with the edge's solve made again before)
    assert result.spent["solves"] == sum(s["solver"]["solves"] for s in result.solutions)


def test_the_head_of_a_run_past_the_region_s_edge_proven_before_the_probes(monkeypatch):
    # The ball (design mode) over 20 points of the bench's sweep of its allowable contact stress (points 14-33 of 100
    # from 0.5x to 2x): no design up to 719.6 MPa (points 0-12), designs from 729.7 MPa. Point 0 proven by its own
    # search, points 1-8 by one region; the run from point 9 (searched with it) meets a design at its end (point 19,
    # whose design is that one: no solve). Points 9 and 10 searched as one region first (Regions._head): proven (249
    # boxes), so the probes start at 11: 11 without a design, 13 with one, then 12 without: the edge is 13, and
    # points 9-12 are
    # searched again (321 boxes), their proof the one the probes from 9 had led to (main: probes at 10 and 12
    # without, 16, 14 and 13 with a design, 45 solver calls in the sweep; here 39, and 37 since the first
    # design found, point 13, is polished onto its exact optimum: optimise/polish.py; point 16 then one solve fewer;
    # 36 since 6 rows at point 15, 750 MPa, are without a design by their least violation alone, its multipliers
    # taken again, not by IPOPT after it: optimise/feasibility.py; 32 since the chains after a change of the rows
    # whose new rows still promise a neighbour the next point's search would solve are probes of one point, not
    # chains aimed at the next change that failed at their first point: optimise/batch.py; 34 since the edge's
    # rounded rows are solved by SQP from its relaxation, integers.FROM_THE_RELAXATION, its design the same to 8e-14:
    # at point 16, 6 rows, the SQP from the least violation's design, a start that moves with those last bits, no
    # longer converges and IPOPT solves them, docs/tradeoffs.md). Every status and proof the same.
    regions, probed = _searches_and_probes(monkeypatch)
    from clutchopt.bench.reference import bench_cases, reference_mode
    from clutchopt.optimise.sweep_grid import Vary

    case = next(c for c in bench_cases() if c.coupling == "ball")
    values = case.values["allowable_contact_stress"] * np.geomspace(0.5, 2.0, 100)[14:34]
    quantity = next(q for q in case.quantities if q.name == "allowable_contact_stress")
    result = Sweep(case, [Vary(quantity, tuple(values.tolist()))], mode=reference_mode("ball")).run(progress=False)
    frame = result.frame
    assert list(frame["status"]) == ["infeasible"] * 13 + ["optimal"] * 7
    assert probed == [19, 11, 13, 12]
    assert [[(o.proven, o.reached, o.boxes) for o in outcomes] for outcomes in regions] == [
        [(True, False, 177), (True, False, 253), (False, True, 77)], [(True, False, 249)], [(True, False, 321)]]
    # (point 0's own search with points 1-8 and the run from point 9: interval_proof.searched_along,
    # Regions._next_runs, _runs_ahead; none after the run from 9, which meets a design)
    assert list(frame["diagnosis"][9:13]) == [frame["diagnosis"][9]] * 4
    assert frame["diagnosis"][9].startswith("proven infeasible for allowable_contact_stress 0.68999-0.719593 GPa "
                                            "(4 points, one proof)")
    assert result.spent["solves"] == 34


def test_a_point_its_own_search_does_not_prove_continues_its_verdict_from_its_first_solve(monkeypatch):
    # The wedge paper case at 12 resisting torques from 20 to 400 N m with every region search and quick search made
    # to fail (as where a point's bounds are too loose): each point after the first without a design (3) is solved
    # once (cold IPOPT, no design), then its verdict goes on from that solve (Problem.solve's first=), not from the
    # same solve again (4 calls a point before): its elastic relaxation finds the constraints apart, so the full
    # verdict's own interval search runs first and proves it, as solve's, without the retries (1 call a point; 3
    # before, with the retries from the least relaxation's design and from the last feasible point's, 89.09 N m).
    # With that search made to fail too, the retries follow from the same first solve: 3 calls a point, not_found
    monkeypatch.setattr(region_proof, "searches", lambda posed, problems, budgets=None: [None] * len(problems))
    vary = parse_vary("resisting_torque=20:400:12", "wedge", WEDGE.quantities)
    problem = case_problem(WEDGE)
    for proven, calls, starts in ((True, 1, ["the case's own start"]),
                                  (False, 3, ["the case's own start", "the least relaxation's design",
                                              "the neighbouring point's design"])):
        if not proven:
            monkeypatch.setattr(verdict, "empty_design_space", lambda posed, case, budget=None, resume=None: None)
        result = Sweep(WEDGE, [vary]).run(progress=False)
        status = "infeasible" if proven else "not_found"
        assert [s["status"] for s in result.solutions] == ["optimal"] * 3 + [status] * 9
        assert [s["solver"]["solves"] for s in result.solutions][4:] == [calls] * 8
        for point in (4, 11):
            alone = problem.solve(WEDGE.with_values(resisting_torque=vary.values[point]))
            record = result.solutions[point]
            assert (record["status"], record["diagnosis"]) == (alone.status, alone.diagnosis)
            assert record["starts"] == starts
        assert result.solutions[4]["diagnosis"].startswith(
            "proven infeasible: no design within the bounds meets" if proven
            else "no feasible design found (not proven infeasible): the least relaxation found")


def test_a_verdict_without_an_interval_search_leaves_the_boxes_of_a_point_s_own_proof():
    # Regions.point keeps the boxes of a point's own proof (its full verdict's or its own search's) for the budgets of
    # the searches after it (Regions._alone). A verdict that no interval search gave (here one "whatever the design",
    # a requirement no design variable enters broken; or a start-up's drive proofs) leaves them: the count of the last
    # search that proved, 500 boxes here, recorded before, is not this point's
    problem = case_problem(WEDGE)
    regions = region_proof.Regions(problem, lambda k: WEDGE, 2)  # (point 1: point 0 is solved by Regions._first)
    interval_proof.last_boxes(problem.posed, 500)
    design = dict(zip(problem.posed.names, problem.posed.bounds_and_start(WEDGE, None)[2].tolist()))
    whatever = verdict.infeasible_at(problem.posed, WEDGE, design, "infeasible whatever the design: ...",
                                     SolverInfo("ipopt", "Infeasible_Problem_Detected", 3, 0.0, 1))
    assert regions.point(1, lambda first: whatever).status == "infeasible"
    assert regions._alone == 0
    proven = verdict.infeasible_at(problem.posed, WEDGE, design, "proven infeasible: ...",
                                   SolverInfo("ipopt", "Infeasible_Problem_Detected", 3, 0.0, 1))
    regions = region_proof.Regions(problem, lambda k: WEDGE, 2)  # (a full verdict whose own search proved: 700)
    assert regions.point(1, lambda first: interval_proof.last_boxes(problem.posed, 700) and proven) is proven
    assert regions._alone == 700


def test_a_sweep_s_first_point_without_a_design_gets_solve_s_verdict_without_the_elastic_diagnosis(monkeypatch):
    # The wedge paper case at 300 N m: solve's first solve ends without a design, its elastic diagnosis finds the
    # constraints apart, so its own interval search goes before the retries and proves it; the verdict shows the
    # failed solve's design. As a sweep's first point (then 20 N m, a design) it is solved once, undiagnosed, and
    # searched (Regions._first): the same verdict, design and figures, no elastic problem solved
    calls = []
    real = problem_module.diagnose
    monkeypatch.setattr(problem_module, "diagnose", lambda *args: calls.append(1) or real(*args))
    alone = case_problem(WEDGE).solve(WEDGE.with_values(resisting_torque=300.0))
    assert len(calls) == 1 and alone.status == "infeasible" and alone.diagnosis.startswith("proven infeasible: ")
    vary = parse_vary("resisting_torque=300,20", "wedge", WEDGE.quantities)
    first, second = Sweep(WEDGE, [vary]).run(progress=False).solutions
    assert len(calls) == 1  # (none in the sweep)
    assert (first["status"], first["diagnosis"], first["design"]) == (alone.status, alone.diagnosis, alone.design)
    assert [c["value"] for c in first["constraints"]] == [c.value for c in alone.constraints]
    assert (first["solver"]["name"], first["solver"]["solves"]) == ("interval", 1) and second["status"] == "optimal"


def test_a_run_searched_ahead_keeps_its_share_of_the_call_that_searched_it(monkeypatch):
    # ball_crusher over 200 powers from 250 to 1000 kW: no design from point 84 (566.6 kW, its own proof). Points
    # 85-92 are searched as one region with the runs ahead 93-108, 109-140 and 141-199 (Regions._runs_ahead,
    # RUNS_AHEAD) in the call of point 84's own search in its verdict (Regions._along), 1 + 8 + 16 + 32 + 59 = 116
    # points: each point 1/116 of that call's seconds, taken from the kept searches later (main gave the ahead runs
    # the seconds of the later call that took them, which searched nothing, over its 16 and 32 points: 1/16 and
    # 1/32). With a clock that reads one second more at each reading, the call takes 1 s, and the seconds the proven
    # points after 84 carry add up to 115/116 s of it.
    import types

    from clutchopt.optimise.sweep_grid import Vary

    clock = iter(range(1, 1_000_000))
    ticking = types.SimpleNamespace(perf_counter=lambda: float(next(clock)))
    monkeypatch.setattr(region_proof, "time", ticking)
    monkeypatch.setattr(interval_proof, "time", ticking)
    proved, own = [], region_proof.Regions._proved
    monkeypatch.setattr(region_proof.Regions, "_proved",
                        lambda self, a, b, problem, outcome, seconds: (proved.append((a, b, seconds)),
                                                                       own(self, a, b, problem, outcome, seconds)))
    crusher = load_case(CASES / "ball_crusher.toml")
    quantity = next(q for q in crusher.quantities if q.name == "power")
    result = Sweep(crusher, [Vary(quantity, tuple(np.linspace(250e3, 1000e3, 200).tolist()))]).run(progress=False)
    assert list(result.frame["status"]) == ["optimal"] * 84 + ["infeasible"] * 116
    assert proved == [(85, 93, 1 / 116), (93, 109, 1 / 116), (109, 141, 1 / 116), (141, 200, 1 / 116)]
    assert sum((b - a) * seconds for a, b, seconds in proved) == pytest.approx(115 / 116, rel=1e-12)



def test_the_runs_searched_ahead_are_figured_in_one_evaluation_with_the_first(monkeypatch):
    # ball_crusher over 250-1000 kW (as above): the runs 85-92, 93-108, 109-140 and 141-199, proven in the call of
    # point 84's own search, share one design (point 84's); their float64 figures are one evaluation over the 115
    # points where each run had one (8, 16, 32, 59), each point's those of that design at its own values alone
    from clutchopt.optimise.sweep_grid import Vary

    evaluated, real, over = [], region_proof.figures_at, region_proof.figures_over
    monkeypatch.setattr(region_proof, "figures_at",
                        lambda posed, cases, design: evaluated.append(len(cases)) or real(posed, cases, design))
    monkeypatch.setattr(region_proof, "figures_over",
                        lambda posed, p, count, design: evaluated.append(count) or over(posed, p, count, design))
    crusher = load_case(CASES / "ball_crusher.toml")
    quantity = next(q for q in crusher.quantities if q.name == "power")
    powers = np.linspace(250e3, 1000e3, 200)
    result = Sweep(crusher, [Vary(quantity, tuple(powers.tolist()))]).run(progress=False)
    assert list(result.frame["status"]) == ["optimal"] * 84 + ["infeasible"] * 116
    assert evaluated[-1] == 115 and sum(evaluated) == 116  # (point 84's own verdict: its own figures)
    posed = case_problem(crusher).posed
    for k in (85, 100, 199):
        record = result.solutions[k]
        assert record["design"] == result.solutions[84]["design"]
        (checks, objective, _), = real(posed, [crusher.with_values(power=powers[k])], record["design"])
        assert [c["value"] for c in record["constraints"]] == [c.value for c in checks]
        assert [c["feasible"] for c in record["constraints"]] == [c.feasible for c in checks]
        assert record["objective"]["value"] == objective


def test_a_batched_sweep_reads_the_points_its_proofs_cover_from_its_arrays_without_a_case_each(monkeypatch):
    # ball_compressor (design mode) beyond the edge of its power, 9.33x-18.7x (bench.user_sweeps), 40 points, none with
    # a design: point 0 is solved and proven by its own search, the others by the runs searched in the same call. Their
    # search problems, float64 figures and conflicts are read from the batched sweep's arrays (region_proof.SharedBox):
    # a Case is built for point 0 alone (each point had built one, read its values twice more and its design box
    # again), and what the arrays give is what each point's Case gives, to the bit
    from clutchopt.optimise.batch import BatchSweep
    from clutchopt.optimise.interval_proof import _search_problem
    from clutchopt.optimise.sweep_grid import Vary

    built, real = [], BatchSweep.point_case
    monkeypatch.setattr(BatchSweep, "point_case", lambda self, k: built.append(k) or real(self, k))
    ball = load_case(CASES / "ball_compressor.toml")
    quantity = next(q for q in ball.quantities if q.name == "power")
    powers = ball.values["power"] * np.geomspace(9.33, 18.66, 40)
    result = Sweep(ball, [Vary(quantity, tuple(powers.tolist()))], mode="design").run(progress=False)
    assert list(result.frame["status"]) == ["infeasible"] * 40
    assert built == [0]
    problem = case_problem(ball, "design")
    posed, batch = problem.posed, BatchSweep(problem, ball, {"power": powers})
    shared, cases = batch._shared, [ball.with_values(power=float(power)) for power in powers]
    assert posed.sides.pairs  # (its width ratio held from both sides: the conflicts are evaluated)
    for j in (0, 17, 39):
        for given, own in zip(shared.problem(j), _search_problem(posed, cases[j])):
            assert given.tobytes() == own.tobytes()
    read, own = vars(shared.params_of(list(range(40)))), vars(posed.params_of(cases))
    assert list(read) == list(own) and all(read[n].tobytes() == own[n].tobytes() for n in own)
    conflicts = np.geomspace(0.5, 1.5, 40)  # (limits that leave room and limits that do not)
    apart = [ball.with_values(width_ratio_max=float(ball.values["width_ratio_min"] * c)) for c in conflicts]
    values = np.array([[getattr(posed.params(case), q.name) for q in posed.formulation.quantities] for case in apart])
    assert posed.conflicting_over(values) == [posed.conflicting(case) for case in apart] == [c < 1 for c in conflicts]
    design = result.solutions[0]["design"]
    for k in (1, 20, 39):
        record = result.solutions[k]
        assert record["design"] == design
        (checks, objective, _), = region_proof.figures_at(posed, [cases[k]], design)
        assert [c["value"] for c in record["constraints"]] == [c.value for c in checks]
        assert record["objective"]["value"] == objective


def _swept_counting_diagnoses(monkeypatch, case, vary, mode):
    """The sweep of ``case`` over ``vary`` in ``mode``, and a list that gets an entry at each elastic diagnosis (a
    full verdict's; none where a point is proven before any solve), later ones included."""
    calls = []
    real = problem_module.diagnose
    monkeypatch.setattr(problem_module, "diagnose", lambda *args: calls.append(1) or real(*args))
    return Sweep(case, [vary], mode=mode).run(progress=False), calls


def test_a_point_past_the_edge_of_the_ball_is_proven_by_its_own_search_before_any_solve(monkeypatch):
    # ball_compressor (design mode) at 11,040-11,400 kW, 4 points: 11,040 kW has a design, 11,160 kW none. The chain
    # from the design fails at 11,160 kW; with integer variables (ball_rows) its own search runs before its solve
    # (Regions._early): the search solve's verdict runs first (within SURE_BOXES, the run 11,280-11,400 kW searched in
    # the same call), so the words are solve's, the point needs no solver call, and no elastic problem is solved
    # (the failed solve, its integer search and its diagnosis had cost 24 of 82 ms over 1x-10x its power)
    ball = load_case(CASES / "ball_compressor.toml")
    vary = parse_vary("power=11040:11400:4", "ball", ball.quantities)
    result, calls = _swept_counting_diagnoses(monkeypatch, ball, vary, "design")
    assert [s["status"] for s in result.solutions] == ["optimal"] + ["infeasible"] * 3
    assert not calls
    record = result.solutions[1]
    assert (record["solver"]["name"], record["solver"]["solves"]) == ("interval", 0)
    alone = case_problem(ball, "design").solve(ball.with_values(power=vary.values[1]))
    assert calls and alone.status == "infeasible"  # (solve's verdict: the failed solve, then the same search)
    assert record["diagnosis"] == alone.diagnosis
    assert record["diagnosis"].startswith("proven infeasible: no design within the bounds meets torque")
    assert result.solutions[2]["diagnosis"].startswith("proven infeasible for power 11280-11400 kW (2 points")


def test_a_point_past_the_edge_whose_proof_takes_hundreds_of_boxes_is_proven_before_any_solve(monkeypatch):
    # The wedge centrifuge in paper mode over its speed, 1800-2000 rpm: designs up to 1885.7 rpm (its finger's
    # bending and its fit in the weight's width active); from about 1,905 rpm no weight carries its finger. The
    # chain from 1885.7 rpm fails at 1914.3 rpm, whose own interval search (Regions._early) is the one its full
    # verdict runs first (within SURE_BOXES) and proves it in hundreds of boxes: solve's words, no solver call, no
    # elastic problem solved. Within FEW_BOXES it had given up after its first box, and the full verdict followed
    # (warm SQP, warm and cold IPOPT, the elastic diagnosis, then that search: 3 calls, 14 of the 0.5x-2x speed
    # sweep's 44 ms of CPU). It shows the design of the point before, re-evaluated at its own speed.
    centrifuge = load_case(CASES / "wedge_centrifuge.toml")
    vary = parse_vary("speed=1800:2000:8", "wedge", centrifuge.quantities)
    result, calls = _swept_counting_diagnoses(monkeypatch, centrifuge, vary, "paper")
    assert [s["status"] for s in result.solutions] == ["optimal"] * 4 + ["infeasible"] * 4
    assert not calls
    record = result.solutions[4]
    assert (record["solver"]["name"], record["solver"]["solves"]) == ("interval", 0)
    assert result.spent["solves"] == 8  # (11 with the full verdict's 3)
    alone = case_problem(centrifuge, "paper").solve(centrifuge.with_values(speed=vary.values[4]))
    assert calls and alone.status == "infeasible"
    assert record["diagnosis"] == alone.diagnosis
    assert record["diagnosis"].startswith("proven infeasible: no design within the bounds meets finger_bending, "
                                          "finger_fits_width")
    boxes = int(record["diagnosis"].split("over ")[1].split(" boxes")[0])
    assert interval_proof.FEW_BOXES < boxes <= interval_proof.SURE_BOXES
    assert record["design"] == result.solutions[3]["design"]
    posed = case_problem(centrifuge, "paper").posed
    at_its_speed = posed.params(centrifuge.with_values(speed=vary.values[4]))
    checks = check_design(posed.formulation, record["design"], at_its_speed)
    assert [c["value"] for c in record["constraints"]] == [c.value for c in checks]
    assert not all(c.feasible for c in checks)  # (the design of 1885.7 rpm breaks a row at 1914.3 rpm)


def _searched_regions(monkeypatch) -> list:
    """region_proof's calls of ``searches`` recorded: per call, each problem's length (3: a point's, 4: a region's)
    and its outcome."""
    calls = []
    real = region_proof.searches

    def recorded(posed, problems, budgets=None):
        outcomes = real(posed, problems, budgets)
        calls.append([(len(problem), outcome) for problem, outcome in zip(problems, outcomes)])
        return outcomes

    monkeypatch.setattr(region_proof, "searches", recorded)
    return calls


def test_a_stretch_without_designs_is_searched_whole_before_its_runs(monkeypatch):
    # The wedge centrifuge in paper mode over its speed, 1800-2600 rpm in 20 points: designs up to 1884.2 rpm; point
    # 3 (1926.3 rpm) is proven by its own search (257 boxes, Regions._early). The 16 points after it are searched as
    # one region first (Regions._whole_stretch, within 4 x 257 boxes) and proven: one proof for all, where the runs
    # of 8 and 8 had taken two searches of about as many boxes each (a region's proof here costs about what its
    # point nearest the edge does, whatever its length)
    centrifuge = load_case(CASES / "wedge_centrifuge.toml")
    calls = _searched_regions(monkeypatch)
    vary = parse_vary("speed=1800:2600:20", "wedge", centrifuge.quantities)
    result = Sweep(centrifuge, [vary], mode="paper").run(progress=False)
    frame = result.frame
    assert list(frame["status"]) == ["optimal"] * 3 + ["infeasible"] * 17
    assert [[length for length, _ in call] for call in calls] == [[3], [4]]
    (_, own), = calls[0]
    (_, region), = calls[1]
    assert own.proven and region.proven and region.boxes <= region_proof.REGION_BUDGET * own.boxes
    assert list(frame["diagnosis"][4:]) == [frame["diagnosis"][4]] * 16
    assert frame["diagnosis"][4].startswith("proven infeasible for speed 1968.42-2600 rpm (16 points, one proof): "
                                            "no design within the bounds meets finger_bending")
    assert [s["solver"]["solves"] for s in result.solutions][3:] == [0] * 17
    problem = case_problem(centrifuge, "paper")
    for point in (4, 19):  # the region's ends: proven alone too
        alone = problem.solve(centrifuge.with_values(speed=vary.values[point]))
        assert alone.status == "infeasible" and alone.diagnosis.startswith("proven infeasible: no design")


def test_a_stretch_that_ends_within_its_whole_search_is_searched_by_its_runs_as_before(monkeypatch):
    # The wedge centrifuge's speed up from 1800 to 2300 rpm and back down to 1700 (24 points): no design from 1936.4
    # rpm up and back down to 1900. The whole stretch's search from point 4 (to the sweep's end, within 4 x 257
    # boxes) meets a design at the interval's low end (1700 rpm): no proof; the runs from point 4 then go on as
    # they did without it (8 points, then 16 reaching past the edge, its probes, the 8 up to it), nothing of that
    # search used: every record as without it
    centrifuge = load_case(CASES / "wedge_centrifuge.toml")
    speeds = [*np.linspace(1800.0, 2300.0, 12), *np.linspace(2250.0, 1700.0, 12)]
    vary = parse_vary("speed=" + ",".join(f"{v:.17g}" for v in speeds), "wedge", centrifuge.quantities)
    calls = _searched_regions(monkeypatch)
    result = Sweep(centrifuge, [vary], mode="paper").run(progress=False)
    whole = calls[1][0][1]
    assert len(calls[1]) == 1 and whole.reached and not whole.proven
    assert list(result.frame["status"]) == ["optimal"] * 3 + ["infeasible"] * 17 + ["optimal"] * 4
    assert result.frame["diagnosis"][4].startswith("proven infeasible for speed 1981.82-2300 rpm (8 points, one proof)")
    monkeypatch.setattr(region_proof.Regions, "_whole_stretch", lambda self, k, end: False)
    calls.clear()
    without = Sweep(centrifuge, [vary], mode="paper").run(progress=False)
    assert result.frame.equals(without.frame)
    assert [(s["design"], s["diagnosis"]) for s in result.solutions] == [(s["design"], s["diagnosis"])
                                                                         for s in without.solutions]


def test_points_next_to_one_that_breaks_a_requirement_no_design_enters_are_tested_against_it_first(monkeypatch):
    # The wedge centrifuge in paper mode over its friction coefficient, 0.2-0.3: from 0.2364 on its weights no longer
    # release (not_self_locking: tan(alpha) short of f, whatever the design). The first such point, where the chain
    # fails, is searched (1 box) before its verdict; each point after it is tested against that requirement first
    # (Problem._given, no solve), its verdict solve's, with no interval search of the runs after it nor of its own
    # (a proof covers no point that breaks it: 8 searches more, one box each, and the point's own, for nothing)
    centrifuge = load_case(CASES / "wedge_centrifuge.toml")
    calls = _searched_regions(monkeypatch)
    vary = parse_vary("friction_coefficient=0.2:0.3:12", "wedge", centrifuge.quantities)
    result = Sweep(centrifuge, [vary], mode="paper").run(progress=False)
    assert [s["status"] for s in result.solutions] == ["optimal"] * 4 + ["infeasible"] * 8
    assert [[length for length, _ in call] for call in calls] == [[3]]
    problem = case_problem(centrifuge, "paper")
    for point in range(4, 12):
        alone = problem.solve(centrifuge.with_values(friction_coefficient=vary.values[point]))
        record = result.solutions[point]
        assert (record["status"], record["diagnosis"]) == (alone.status, alone.diagnosis)
        assert record["diagnosis"].startswith("infeasible whatever the design: not_self_locking")
        assert record["design"] == alone.design and record["solver"]["solves"] == (2 if point == 4 else 0)


def test_a_point_s_verdict_counts_its_interval_searches_seconds_so_none_is_negative(monkeypatch):
    """A point's verdict counts its interval searches' seconds (``verdict._Searched``), of which a sweep's region
    proofs take the share of the runs a search proved along with it (``Regions._took``): that share had been taken
    from seconds that never counted the search, and a point's solver seconds came out negative (the lever in design
    mode over its inertia at f = 0.1: point 2, -0.015 s; 58 of 180 points over inertia and friction; review 20)."""
    case = load_case(CASES / "lever_centrifuge.toml")
    searched = []
    original = verdict._Searched.__call__

    def counted(self, budget=None, resume=None):  # (the verdict's searches ran: the share is taken from what
        searched.append(budget)  # they took)
        return original(self, budget, resume)

    monkeypatch.setattr(verdict._Searched, "__call__", counted)
    result = Sweep(case, [parse_vary("inertia=1:300:10", case.coupling), parse_vary("friction_coefficient=0.2",
                                                                                    case.coupling)],
                   mode="design").run(progress=False)  # (at f = 0.1 every point without a design is proven by the
    # sweep's region proofs now, its rows carried back through their expressions: no verdict's search runs)
    assert searched and result.frame["status"].value_counts().to_dict() == {"infeasible": 9, "optimal": 1}
    assert all(record["solver"]["time_s"] >= 0 for record in result.solutions)


def test_a_sweep_s_seconds_are_those_its_searches_and_solves_took(monkeypatch):
    """Every interval search's and solver run's seconds reach the sweep's records once: a run a search did not
    prove, a point's own search that did not prove it and the runs searched ahead and never used are charged to the
    next verdict (``Regions._unclaimed``; a window's to the next window's, the sweep's last to its last point solved
    alone). The lever in design mode over its inertia and friction coefficient: its records had reported a fifth of
    its searches' seconds (review 20b: 1.0 of 4.7 s). An accounting identity, not a timing: the records' sum against
    the seconds the same calls took, measured around them."""
    from clutchopt.optimise import attempts

    took = {"searches": 0.0, "runs": 0.0, "diagnoses": 0.0}
    search, run, diagnose = interval_proof.searches, attempts.run, problem_module.diagnose

    def timed(name, call):
        def spy(*args, **kwargs):
            began = time.perf_counter()
            try:
                return call(*args, **kwargs)
            finally:
                took[name] += time.perf_counter() - began
        return spy

    for module in (interval_proof, region_proof):
        monkeypatch.setattr(module, "searches", timed("searches", search))
    monkeypatch.setattr(attempts, "run", timed("runs", run))
    monkeypatch.setattr(problem_module, "diagnose", timed("diagnoses", diagnose))
    case = load_case(CASES / "lever_centrifuge.toml")
    result = Sweep(case, [parse_vary("inertia=1:300:10", case.coupling),
                          parse_vary("friction_coefficient=0.1,0.3", case.coupling)], mode="design").run(progress=False)
    recorded = sum(record["solver"]["time_s"] for record in result.solutions)
    assert result.frame["status"].value_counts().to_dict()["infeasible"] > 10 and took["searches"] > took["runs"]
    assert 0.9 * (took["searches"] + took["runs"]) <= recorded <= 1.1 * sum(took.values())
