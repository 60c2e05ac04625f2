"""Sweeps and solves agree: a sweep point's status and objective are `solve`'s of the same values, whichever path
solved it (batched SQP re-solve, warm SQP, IPOPT, a region proof) and whatever the order of the points.

No hand calculation here: the reference is `solve_case` of the point's case (``sweep.case.with_values``, as the
sweep builds it), the contract the sweep's speed paths promise (objective to 1e-9 relative on static points,
statuses identical).
"""

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from conftest import CASES

STATIC_RTOL = 1e-9


def swept_and_solved(case_file: str, text: str, solve=lambda record: True):
    """Each point of the sweep ``text`` of a case: its record and `solve`'s solution of the same values (None where
    ``solve(record)`` is false: a full verdict of a point without a design takes a second)."""
    case = load_case(CASES / case_file)
    sweep = Sweep(case, [parse_vary(text, case.coupling)])
    records = list(sweep.run(progress=False).solutions)
    return [(record, solve_case(sweep.case.with_values(**point)) if solve(record) else None)
            for record, point in zip(records, sweep.points)]


@pytest.mark.parametrize("text", [
    "power=440,403.8461538461538",  # the second point batched (SQP, from the first): groove_conformity at 1.005
    "speed=900,918.1818181818181",  # the second point a warm SQP re-solve
])
def test_a_point_solved_by_sqp_has_the_objective_solve_gives(text):
    # ball_crusher's optimum has groove_conformity on its lower bound 1.005; the contact stress goes with
    # (c - 1), so an IPOPT bound relaxed by 1e-10 (bound_relax_factor 1e-9) moved the mass by 2.3e-8 relative,
    # below the exact optimum SQP keeps: the same values swept after another point and solved alone differed
    for record, solved in swept_and_solved("ball_crusher.toml", text):
        assert record["status"] == solved.status == "optimal"
        assert record["objective"]["value"] == pytest.approx(solved.objective, rel=STATIC_RTOL, abs=0)
        assert solved.design["groove_conformity"] >= 1.005  # the declared bound, held exactly


def test_a_sweep_from_an_infeasible_region_gives_solves_verdicts_and_optimum():
    # ball_crusher at 600, 570 and 540 kW: no design from about 560 kW (contact stress, torque and the outer
    # diameter together), one at 540 kW. 600 kW is solve's full verdict, 570 kW the point after it (a region
    # proof's quick test), 540 kW solved from the infeasible side, cold; the same points forward:
    # test_a_point_solved_by_sqp_has_the_objective_solve_gives and the hypothesis test below
    designed = lambda record: record["status"] == "optimal"  # noqa: E731 (a full verdict of each point: seconds)
    points = swept_and_solved("ball_crusher.toml", "power=600,570,540", designed)
    assert [record["status"] for record, _ in points] == ["infeasible", "infeasible", "optimal"]
    assert points[1][0]["diagnosis"].startswith("proven infeasible")
    record, solved = points[2]
    assert solved.status == "optimal"
    assert record["objective"]["value"] == pytest.approx(solved.objective, rel=STATIC_RTOL, abs=0)


@settings(max_examples=12, deadline=None)
@given(st.lists(st.floats(0.25, 0.45), min_size=2, max_size=6))
def test_any_order_of_points_across_an_infeasible_edge_gives_solves_verdicts(pressures):
    # wedge_paper has no design at 0.30 MPa allowable pressure and one at 0.35 MPa (torque and the flank pressure,
    # eqs. (9), (12), (13), together; at 0.30 proven by interval branch and bound); points in any order, across the edge and back, repeated: each point's status and
    # objective are solve's (region proofs after an infeasible point, batches and warm starts after a design)
    text = "allowable_pressure=" + ",".join(map(repr, pressures))
    for record, solved in swept_and_solved("wedge_paper.toml", text):
        assert record["status"] == solved.status
        if solved.status == "optimal":
            assert record["objective"]["value"] == pytest.approx(solved.objective, rel=STATIC_RTOL, abs=0)
