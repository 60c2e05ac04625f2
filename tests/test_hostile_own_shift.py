"""Hostile start-up sweeps of an elastic link's integer choice (clutchopt.optimise.own_shift, Problem._own_loops):
a sweep point keeps `solve`'s design of the same values alone, the lightest verified one `solve` with each
cable_count fixed finds (docs/start_up.md, "A limit moved for another integer choice").

No hand calculation: the references are `solve` of the point alone and with cable_count fixed (each verified by the
independent simulation of its start)."""

from dataclasses import replace

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from tests.conftest import CASES

CABLE = load_case(CASES / "cable_motor_start.toml")
START_UP_RTOL = 1e-6  # the start-up contract: a sweep point's objective is solve's to 1e-6 relative


def fixed_count(case, count):
    return solve_case(replace(case, bounds={**case.bounds, "cable_count": (float(count),) * 2}))


def test_a_stress_sweep_s_third_point_keeps_12_cables_not_13():
    """allowable_cable_stress 350, 300, 250 MPa: at 250 MPa the point starts from 300's stress limit, moved by 10
    cables' start; the integer search there goes 10 -> 13 (infeasible) -> 14, 13's own loop ends optimal (6.277 kg)
    and 12 cables, never tried, are left, where `solve` of 250 MPa alone finds 12 (5.813 kg, the fixed solve's, its
    own start meeting the case's limit). Failed on main: 13 cables, optimal, exit 0."""
    twelve = fixed_count(CABLE.with_values(allowable_cable_stress=250e6), 12)
    assert twelve.status == "optimal" and twelve.limit_shift == {}
    assert twelve.objective == pytest.approx(5.8126027, rel=1e-7)
    vary = parse_vary("allowable_cable_stress=350,300,250", CABLE.coupling, CABLE.quantities)
    records = list(Sweep(CABLE, [vary]).run(progress=False).solutions)
    record = records[-1]
    assert record["status"] == "optimal" and record["design"]["cable_count"] == 12.0
    assert abs(record["objective"]["value"] - twelve.objective) <= START_UP_RTOL * twelve.objective


def test_the_cable_at_0_5_keeps_a_verified_count_not_an_unverified_8():
    """driven_inertia 0.5 kg m^2: 8 cables' simulated start carries 351.55 MPa in the cables, 0.44 % over the 350 MPa
    allowed, and the defect correction moves the NLP's limit by that 1.55 MPa a step (plus half the tolerance), where
    the NLP's quasi-static figure binds nowhere near: its seven steps leave the design unmoved and end `unverified`
    (3.953 kg, exit 0), though 9 cables fixed are verified (4.418 kg, their start at 321 MPa) and the sweep
    0.2, 0.5 keeps them. Failed on main: solve alone kept the 8 cables, unverified. (Since the correction moves the
    NLP's limit from its own figure, 335.996 MPa, it goes to 334.444 MPa in one step, where no 8-cable design of the
    NLP exists; modifier adaptation then verifies 8 cables with a heavier weight, 4.2568 kg, and solve keeps them:
    tests/test_defect_correction.py, tests/test_modifier.py.)"""
    case = CABLE.with_values(driven_inertia=0.5)
    nine = fixed_count(case, 9)
    assert nine.status == "optimal" and nine.objective == pytest.approx(4.4177854, rel=1e-7)
    eight = fixed_count(case, 8)
    assert eight.status == "optimal" and eight.objective < nine.objective
    alone = solve_case(case)
    assert alone.status == "optimal" and alone.design["cable_count"] == 8.0
    assert abs(alone.objective - eight.objective) <= START_UP_RTOL * eight.objective
    stress = next(c for c in alone.constraints if c.name == "link_stress")
    assert stress.feasible and stress.limit == 350e6


def test_the_counts_one_off_the_kept_design():
    """The record of the 250 MPa point's loop: 10 and 13 infeasible at a carried limit, 14 solved; 13 kept (its own
    loop): 12 is the untried count below, none above (13 is verified); 14 unverified would ask for 15 alone (16
    is past an upper bound of 15). At the lower bound 3 nothing is below."""
    from types import SimpleNamespace

    from clutchopt.optimise.own_shift import ForeignShifts, carried_by

    foreign = ForeignShifts(["cable_count"], carried_by(None))
    entries = [{"cable_count": n, "status": status, "objective": value} for n, status, value in
               [(10, "Infeasible_Problem_Detected", 4.906), (13, "Infeasible_Problem_Detected", 6.285),
                (14, "Solve_Succeeded", 6.742)]]
    foreign.seen(SimpleNamespace(integer_search=entries))
    assert foreign.found == {(10.0,): 4.906, (13.0,): 6.285} and foreign.looped == set()
    kept = SimpleNamespace(status="optimal", objective=6.277, design={"cable_count": 13.0})
    assert foreign.untried_below(kept, {"cable_count": 3.0}) == [(12.0,)]
    assert foreign.above_unverified(kept, {"cable_count": 15.0}) == []
    unverified = SimpleNamespace(status="unverified", objective=6.742, design={"cable_count": 14.0})
    assert foreign.above_unverified(unverified, {"cable_count": 15.0}) == [(15.0,)]
    assert foreign.above_unverified(SimpleNamespace(**{**vars(unverified), "design": {"cable_count": 15.0}}),
                                    {"cable_count": 15.0}) == []
    assert foreign.untried_below(SimpleNamespace(**{**vars(kept), "design": {"cable_count": 3.0}}),
                                 {"cable_count": 3.0}) == []
    assert foreign.untried_below(unverified, {"cable_count": 3.0}) == []  # no verified design kept: none below


def test_an_unverified_count_climbs_while_its_simulated_start_comes_nearer_to_its_limits():
    """``climbing``: 10 cables' start 30 % over the stress limit, 11's 10 % over: 0.20 nearer a count, so one more
    count (12) at that rate meets it, ceil(0.10 / 0.20) = 1 <= 15 - 11: climb to 12. 11's start 35 % over (further):
    none above; 29 % over: ceil(0.29 / 0.01) = 29 counts more, 40 > the bound 15: none; a loop that ended without a
    design: none. ``lighter_above``, once a count is verified (7.307 kg): on from a count kept lighter (6.276 kg) or
    unverified below it (5.35 kg), not from one heavier (7.5 kg), nor past the bound."""
    from types import SimpleNamespace

    from clutchopt.optimise.own_shift import climbing, lighter_above, stepped, worst_margin

    def loop(count, status, *margins, objective=5.0):
        checks = [SimpleNamespace(margin=m) for m in (*margins, float("nan"))]  # (an undefined margin: left out)
        return SimpleNamespace(status=status, design={"cable_count": count}, constraints=checks, objective=objective)

    names, ten, upper = ["cable_count"], loop(10.0, "unverified", 0.5, -0.30), {"cable_count": 15.0}
    assert worst_margin(ten) == -0.30 and stepped(names, ten.design, (11.0,)) == 0
    assert climbing(names, 0, ten, loop(11.0, "unverified", 0.4, -0.10), (11.0,), upper) == ((12.0,), "")
    ahead, reason = climbing(names, 0, ten, loop(11.0, "unverified", -0.35), (11.0,), upper)
    assert ahead is None and "0.35 (relative), no nearer than 10's 0.3" in reason
    ahead, reason = climbing(names, 0, ten, loop(11.0, "unverified", -0.29), (11.0,), upper)
    assert ahead is None and "40 would be needed, above the bound 15" in reason
    ahead, reason = climbing(names, 0, ten, loop(11.0, "not_found", -0.05), (11.0,), upper)
    assert ahead is None and reason == "no count of cable_count above 11 tried: its own accuracy loop ended not_found"
    verified = loop(10.0, "optimal", 0.1, objective=7.307)
    lighter = loop(11.0, "optimal", 0.1, objective=6.276)
    assert lighter_above(names, 0, lighter, lighter, (11.0,), upper) == (12.0,)  # (kept: it was lighter)
    assert lighter_above(names, 0, loop(11.0, "unverified", -0.1, objective=5.35), verified, (11.0,), upper) == (12.0,)
    assert lighter_above(names, 0, loop(11.0, "optimal", 0.1, objective=7.5), verified, (11.0,), upper) is None
    fifteen = loop(15.0, "optimal", 0.1, objective=6.0)
    assert lighter_above(names, 0, fifteen, fifteen, (15.0,), upper) is None  # (kept, lighter, at the bound)
