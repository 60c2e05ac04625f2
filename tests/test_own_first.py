"""A start-up sweep's point whose elastic link's warm run at the point before's count fails at the limits carried from
it: that count's own loop first, from the case's limits (``Problem._own_first``; docs/start_up.md, "The kept count's
own loop first")."""

import numpy as np
import pytest

import clutchopt.optimise.attempts as attempts
import clutchopt.optimise.link_bound as link_bound
from clutchopt.cases import load_case
from clutchopt.optimise.problem import Problem, problems_set_aside
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import Vary
from clutchopt.optimise.verify import FEASIBILITY_TOL
from tests.conftest import CASES
from tests.test_one_up_first import recording

CABLE = load_case(CASES / "cable_motor_start.toml")
CASE_LIMIT = 350e6  # Pa: the case's max_link_stress


def swept(monkeypatch, name: str, values, own_first: bool = True, onto_the_drive: bool = True):
    """The sweep of ``CABLE`` over ``name`` at ``values`` (its records), with each start-up run's (value of ``name``,
    cable count fixed or None, the stress limit it solved with); ``own_first=False``: without the count's own loop
    first (main before it); ``onto_the_drive=False``: no least stress from a seed off the drive's rows, not brought
    onto them (main before ``link_bound.on_the_drive``)."""
    runs = []
    quantity = next(q for q in CABLE.quantities if q.name == name)
    with monkeypatch.context() as patched, problems_set_aside():  # (its own problems, as a new process builds them)
        patched.setattr(attempts, "run", recording(runs, name))
        if not own_first:
            patched.setattr(Problem, "_own_first", lambda *args: None)
        if not onto_the_drive:
            patched.setattr(link_bound, "on_the_drive", lambda posed, x0, p, *box: x0 if np.max(np.abs(
                link_bound.drive_rows(posed)(x0, p).full())) <= FEASIBILITY_TOL else None)
        records = Sweep(CABLE, [Vary(quantity, tuple(values))]).run(progress=False).solutions
    return records, runs


def searched(record) -> list[tuple]:
    return [(e["cable_count"], e["status"]) for e in record["integer_search"]]


def test_the_failed_count_verified_at_the_case_s_limits_first_the_search_at_the_carried_limit_not_solved(monkeypatch):
    """cable_motor_start over driven_inertia, 0.171 then 0.255 kg m^2 (the bench's points 2 and 10): the second point
    carries the stress limit 7 cables' start moved (313.9 MPa), where 8 cables' warm run ends infeasible. Before, the
    relaxation and 9 cables were solved there (9 kept, 4.418 kg), then 8 cables' own loop at 350 MPa kept 8 (3.953 kg)
    and 7's own loop ended unverified: 5 solver calls. Now 8 cables' own loop is solved first, from the point before,
    and verified: 3 calls, no run at the carried limit but the failed one, the same count, status and objective. The
    failed one, 19-20 IPOPT iterations from the point before's optimum, is refuted unsolved since by 8 cables' least
    stress at this drive's nodes (``link_bound.on_the_drive``: the seed brought onto them): 2 calls, the design the
    same to the last bit."""
    values = (CABLE.values["driven_inertia"] * np.linspace(0.6, 1.4, 20)[[2, 10]]).tolist()
    before, _ = swept(monkeypatch, "driven_inertia", values, own_first=False, onto_the_drive=False)
    own, own_runs = swept(monkeypatch, "driven_inertia", values, onto_the_drive=False)
    records, runs = swept(monkeypatch, "driven_inertia", values)
    own_point = [(count, limit) for inertia, count, limit in own_runs if inertia == values[1]]
    point = [(count, limit) for inertia, count, limit in runs if inertia == values[1]]
    assert [r["solver"]["solves"] for r in before] == [4, 5]
    assert [r["solver"]["solves"] for r in own] == [4, 3]
    assert [r["solver"]["solves"] for r in records] == [4, 2]
    assert sum(r["solver"]["solves"] for r in records) == len(runs)  # (every start-up run counted, once)
    assert [count for count, limit in own_point if limit < CASE_LIMIT] == [8.0]  # (the failed warm run alone)
    assert own_point[1:] == point == [(8.0, CASE_LIMIT), (7.0, CASE_LIMIT)]  # (now not even that one)
    assert records[1]["status"] == own[1]["status"] == before[1]["status"] == "optimal"
    assert records[1]["design"]["cable_count"] == before[1]["design"]["cable_count"] == 8.0
    assert records[1]["objective"]["value"] == pytest.approx(before[1]["objective"]["value"], rel=1e-12)
    assert records[1]["objective"]["value"] == pytest.approx(3.95257291915, rel=1e-10)
    assert records[1]["design"] == own[1]["design"] and records[0]["design"] == own[0]["design"]
    assert searched(own[1]) == [(8, "Infeasible_Problem_Detected"), (8, "own accuracy loop: optimal"),
                                (7, "own accuracy loop: unverified")]
    assert searched(records[1]) == [(8, "excluded: link_stress"), (8, "own accuracy loop: optimal"),
                                    (7, "own accuracy loop: unverified")]
    assert (9, "Solve_Succeeded") in searched(before[1])


def test_a_failed_count_not_verified_at_the_case_s_limits_the_search_goes_on_and_its_own_loop_from_that_solve(
        monkeypatch):
    """cable_motor_start over breakdown_torque, 223.2 then 259.4 N m: 7 cables' warm run fails at the limit carried
    from the first point; solved first at 350 MPa their simulated start misses the stress limit, so the search at the
    carried limit goes on (8 cables kept) and 7 cables' own loop goes on from that solve, not solving it again: the
    same 4 calls as before, 7 cables solved at the case's limit once, the same count, status and objective. The
    failed warm run (29 IPOPT iterations) is refuted unsolved since: 7 cables' least stress at this drive's nodes,
    337.2 MPa, is over the carried 326.4 (``link_bound.on_the_drive``); 3 calls, the design the same to the bit."""
    values = (CABLE.values["breakdown_torque"] * np.array([223.15789474, 259.42105263]) / 265.0).tolist()
    before, before_runs = swept(monkeypatch, "breakdown_torque", values, own_first=False, onto_the_drive=False)
    own, own_runs = swept(monkeypatch, "breakdown_torque", values, onto_the_drive=False)
    records, runs = swept(monkeypatch, "breakdown_torque", values)
    own_point = [(count, limit) for torque, count, limit in own_runs if torque == values[1]]
    point = [(count, limit) for torque, count, limit in runs if torque == values[1]]
    assert own_point[:3] == [(7.0, own_point[0][1]), (7.0, CASE_LIMIT), (None, own_point[0][1])]  # (the failed warm
    # run at the carried limit, 7 cables at the case's, then the relaxation at the carried limit)
    assert own_point[0][1] < CASE_LIMIT
    assert point == own_point[1:]  # (the failed warm run not solved)
    assert point.count((7.0, CASE_LIMIT)) == 1
    assert [r["solver"]["solves"] for r in own] == [r["solver"]["solves"] for r in before] == [4, 4]
    assert [r["solver"]["solves"] for r in records] == [4, 3]
    assert sum(r["solver"]["solves"] for r in records) == len(runs) and len(own_runs) == len(before_runs)
    assert records[1]["status"] == own[1]["status"] == before[1]["status"] == "optimal"
    assert records[1]["design"]["cable_count"] == before[1]["design"]["cable_count"] == 8.0
    assert records[1]["objective"]["value"] == pytest.approx(before[1]["objective"]["value"], rel=1e-12)
    assert records[1]["design"] == own[1]["design"] and records[0]["design"] == own[0]["design"]
    assert searched(own[1])[:3] == [(7, "Infeasible_Problem_Detected"), (8, "Solve_Succeeded"),
                                    (7, "own accuracy loop: unverified")]
    assert searched(records[1])[:3] == [(7, "excluded: link_stress"), (8, "Solve_Succeeded"),
                                        (7, "own accuracy loop: unverified")]
