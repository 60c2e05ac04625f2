"""How many simulations a start-up solve runs (issue 26): the start guess's and the check's, the guess kept for a
re-solve of the same case; and what a kept guess must not be: another design's or another case's run."""

from dataclasses import replace

import pytest

import clutchopt.optimise.modifier as modifier
import clutchopt.start_up.simulation as simulation
from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from tests.conftest import CASES


@pytest.fixture
def counted(monkeypatch):
    """The runs of the simulator (a start guess's rtol 1e-6, a check's 1e-11 at the default tolerance 1e-6), none
    kept from before."""
    runs, run = [], simulation.run_start_up
    monkeypatch.setattr(simulation, "_GUESSES", {})
    monkeypatch.setattr(simulation, "run_start_up", lambda model: runs.append(model.rtol) or run(model))
    return runs


def test_a_re_solve_simulates_only_its_check(counted):
    """wedge_motor_start solves in one NLP solve (no mesh adaptation): its first solve simulates the start design's
    start up to lock-up (the guess, rtol 1e-6) and the optimum's (the check, 1e-11: check_rtol); a re-solve starts
    from the same design, so only the check runs, and the solution is the same to the last bit."""
    case = load_case(CASES / "wedge_motor_start.toml")
    first = solve_case(case)
    assert counted == [1e-6, 1e-11]
    again = solve_case(case)
    assert counted == [1e-6, 1e-11, 1e-11]
    assert again.objective == first.objective
    assert again.start_up["start_time_simulated"] == first.start_up["start_time_simulated"]
    assert again.start_up["start_time"] == first.start_up["start_time"]


def test_a_kept_guess_is_that_of_its_case_and_design(counted):
    """Another design, or the case with another value, is simulated afresh: a stronger spring preload engages the
    weights later, so its guess locks up later."""
    case = load_case(CASES / "wedge_motor_start.toml")
    solution = solve_case(case)
    design, mode = solution.design, solution.mode
    counted.clear()
    end = 30.0
    _, kept = simulation.start_guess(case, mode, design, 1e-6, end)
    assert counted == [1e-6]  # the solve's own guess started from its static optimum, not from this design
    stronger = {**design, "spring_preload": design["spring_preload"] * 1.5}
    _, other = simulation.start_guess(case, mode, stronger, 1e-6, end)
    heavier = case.with_values(driven_inertia=case.values["driven_inertia"] * 1.5)
    _, slower = simulation.start_guess(heavier, mode, design, 1e-6, end)
    assert counted == [1e-6, 1e-6, 1e-6]
    assert simulation.start_guess(case, mode, design, 1e-6, end)[1] is kept
    assert counted == [1e-6, 1e-6, 1e-6]
    assert other.headline["start_time"] > kept.headline["start_time"]
    assert slower.headline["start_time"] > kept.headline["start_time"]


def test_the_worn_start_is_simulated_once_a_solve(counted):
    """lever_motor_start at a tolerance of 3e-8 takes two NLP solves (the first mesh's error 8.2e-8, then one
    adaptation; at its own 1e-6 the first mesh, graded over the simulated knee, meets it in one): the guess, the
    check of each solve, and the worn linings' start of the returned design only (reported, never checked; it ran
    after every solve before), its figures those of the returned design."""
    case = load_case(CASES / "lever_motor_start.toml")
    case = replace(case, start_up=replace(case.start_up, tolerance=3e-8))  # (its checks' rtol 1e-11, as at 1e-6)
    solution = solve_case(case)
    assert solution.solver.solves == 2
    assert counted == [1e-6, 1e-11, 1e-11, 1e-11]  # guess, two checks, one worn start
    worn = solution.start_up["worn"]
    assert worn["locks_up"] and worn["start_time"] < solution.start_up["start_time_simulated"]
    model = simulation.start_up_model(case, solution.mode, solution.design, 1e-11)
    again = simulation.run_start_up(simulation.worn_start_up_model(case, solution.mode, solution.design, model))
    assert worn["start_time"] == again.headline["start_time"]
    assert worn["friction_work"] == again.headline["friction_work"]


def test_a_modifier_step_no_lighter_than_the_kept_design_is_not_simulated(counted, monkeypatch):
    """cable_motor_start: 8 cables are kept (refuted at the limit 7 cables' start moved, solved at the case's limit
    as their own loop would, 3.9526 kg); 7 cables' design (3.4872 kg) was kept ``unverified``
    (its simulated link stress 377 MPa against 350 MPa), so modifier adaptation goes on from it: one simulation for
    the stress's slope in the weight mass, then one corrected solve, whose design (5.826 kg) is no lighter than 8
    cables' and ends the adaptation whatever its start does (``first_order``'s bound): that start is not simulated.
    A re-solve (its start guess kept) simulates the checks of 7 and 8 cables' designs and the slope: three runs,
    not four (9 cables at the moved limit no longer solved: 8 are solved first, ``Problem._one_up_first``). (The step
    is now refuted before it is solved, ``modifier.no_lighter``: turned off here, so that the solved step is what is
    tested; the same four runs either way.)"""
    monkeypatch.setattr(modifier, "no_lighter", lambda *args: [])
    case = load_case(CASES / "cable_motor_start.toml")
    solve_case(case)
    counted.clear()
    solution = solve_case(case)
    assert solution.status == "optimal" and solution.design["cable_count"] == 8
    assert solution.objective == pytest.approx(3.952572919, rel=1e-9)
    assert [(e["cable_count"], e["status"]) for e in solution.integer_search][-3:] == \
        [(8, "own accuracy loop: optimal"), (7, "modifier adaptation: unverified"),
         (7, "simulated at the case's limits: unverified")]
    assert len(counted) == 3
