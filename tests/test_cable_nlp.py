"""Cable coupling NLP: optima equal the consistent closed forms; self-locking threads are refused or diagnosed."""

import math
from dataclasses import replace

import pytest
from scipy.optimize import brentq

from clutchopt.cases import load_case
from clutchopt.errors import InputError
from clutchopt.formulations.cable.closed_forms import (
    closed_form,
    closed_form_threads,
    hub_lead_angle_optimum,
    weight_lead_angle_optimum,
)
from clutchopt.formulations.cable.equations import required_cable_count
from clutchopt.formulations.cable.quantities import check_threads
from clutchopt.optimise import solve_case
from tests.conftest import CASES

DEG = math.pi / 180
CABLE_CASES = ["cable_pump.toml", "cable_conveyor.toml"]
DESIGN = ("half_coupling_mass", "weight_mass", "cable_count", "finger_diameter", "screw_diameter", "lead_angle",
          "weight_lead_angle")


@pytest.fixture(scope="module", params=CABLE_CASES)
def case(request):
    return load_case(CASES / request.param)


def assert_design(solution, expected):
    assert solution.status == "optimal", solution.diagnosis
    for name in DESIGN:
        assert solution.design[name] == pytest.approx(expected[name], rel=1e-6), name


@pytest.mark.parametrize("objective", ["mass", "cost"])
def test_paper_mode_optimum_is_the_closed_form(case, objective):
    # with the threads given, both objectives rise with every size: all sizing constraints active
    solution = solve_case(case, "paper", objective)
    assert_design(solution, closed_form(case.params()))
    active = {c.name for c in solution.constraints if c.active}
    assert active == {"hub_thread_drive", "weight_turns_cable", "clamp_screw_stress", "finger_bending"}


def test_freed_hub_lead_angle_goes_to_the_self_locking_limit(case):
    p = case.params()
    solution = solve_case(replace(case, free=("lead_angle",)), "paper", "mass")
    assert_design(solution, closed_form(p, lead_angle=hub_lead_angle_optimum(p)))
    assert solution.design["lead_angle"] == pytest.approx(math.atan(p.friction_coefficient / math.cos(15 * DEG))
                                                          + 2 * DEG, rel=1e-6)
    assert next(c for c in solution.constraints if c.name == "hub_thread_not_self_locking").active


def test_threads_mode_optimum_is_its_closed_form(case):
    solution = solve_case(case, "threads", "mass")
    assert_design(solution, closed_form_threads(case.params()))
    assert solution.objective <= solve_case(case, "paper", "mass").objective


def test_threads_mode_pump_weight_thread_stops_at_its_smallest_diameter():
    solution = solve_case(load_case(CASES / "cable_pump.toml"), "threads", "mass")
    assert solution.design["weight_lead_angle"] == pytest.approx(math.atan(9 / (6 * math.pi)), rel=1e-6)
    assert solution.outputs["weight_thread_diameter"].value == pytest.approx(6e-3, rel=1e-6)


def test_threads_mode_conveyor_weight_thread_stops_at_its_wear_limit():
    # by hand: lead 2 pi x_2 / phi_1 = 9.6 mm, so d_2w = 9.6 mm / (pi tan beta); the thread carries the twist force
    # 2 c_kk phi_1 / (d_2w tan(beta - phi')) on pi d_2w (h/p) H_w; the optimum is where that reaches [q] = 6 MPa
    phi = math.atan(0.12 / math.cos(15 * DEG))
    twist = 1.5 * DEG

    def excess_pressure(beta):
        d = 2 * 0.04e-3 / (twist * math.tan(beta))
        return 2 * 28 * twist / (d * math.tan(beta - phi)) / (math.pi * d * 0.5 * 0.010) - 6e6

    beta_wear = brentq(excess_pressure, 20 * DEG, 27 * DEG, xtol=1e-14)
    solution = solve_case(load_case(CASES / "cable_conveyor.toml"), "threads", "mass")
    assert solution.status == "optimal"
    assert solution.design["weight_lead_angle"] == pytest.approx(beta_wear, rel=1e-6)
    assert math.degrees(beta_wear) == pytest.approx(21.3197, rel=1e-5)
    assert next(c for c in solution.constraints if c.name == "weight_thread_wear").active


def test_weight_thread_at_best_efficiency_when_nothing_stops_it():
    # a long weight nut and a small smallest diameter: beta_w = 45 deg + phi'/2 minimises tan(b) / tan(b - phi')
    case = load_case(CASES / "cable_pump.toml").with_values(weight_nut_height=0.1, min_weight_thread_diameter=1e-3)
    phi = math.atan(0.1 / math.cos(15 * DEG))
    solution = solve_case(case, "threads", "mass")
    assert solution.status == "optimal"
    assert solution.design["weight_lead_angle"] == pytest.approx(math.pi / 4 + phi / 2, rel=1e-6)


def test_cable_count_is_the_rounded_up_eq18(case):
    solution = solve_case(case, "paper", "mass")
    z = solution.design["cable_count"]
    assert z == math.ceil(required_cable_count(case.params()))
    tried = {entry["cable_count"]: entry["feasible"] for entry in solution.integer_search}
    assert tried[z] and not tried[z - 1]


def test_fixed_self_locking_lead_angle_is_an_input_error():
    base = load_case(CASES / "cable_pump.toml")
    with pytest.raises(InputError) as error:
        check_threads(replace(base, values={**base.values, "lead_angle": 7 * DEG}))
    assert error.value.field == "thread.lead_angle"
    assert "must exceed phi' = 5.911 deg" in str(error.value) and "\n" not in str(error.value)


def test_fixed_self_locking_weight_lead_angle_is_an_input_error(tmp_path):
    text = (CASES / "cable_conveyor.toml").read_text().replace('weight_lead_angle = "20 deg"', 'weight_lead_angle = "6 deg"')
    path = tmp_path / "locked.toml"
    path.write_text(text)
    with pytest.raises(InputError) as error:
        load_case(path)
    assert error.value.field == "thread.weight_lead_angle"
    assert "phi' = 7.082 deg" in str(error.value)


@pytest.mark.parametrize("mode", ["paper", "threads"])
def test_free_lead_angle_with_only_self_locking_bounds_is_diagnosed(mode):
    case = load_case(CASES / "cable_pump.toml")
    case = replace(case, free=("lead_angle",), bounds={"lead_angle": (1 * DEG, 5 * DEG)})
    solution = solve_case(case, mode, "mass")
    assert solution.status == "infeasible"  # proven: interval branch and bound
    assert "hub_thread_not_self_locking" in solution.diagnosis


def test_free_weight_lead_angle_with_only_self_locking_bounds_is_diagnosed():
    case = replace(load_case(CASES / "cable_pump.toml"), bounds={"weight_lead_angle": (1 * DEG, 6 * DEG)})
    solution = solve_case(case, "threads", "mass")
    assert solution.status == "infeasible"
    assert "weight_thread_not_self_locking" in solution.diagnosis


def test_too_weak_weight_thread_is_diagnosed():
    case = load_case(CASES / "cable_conveyor.toml").with_values(allowable_thread_pressure=4e6)
    solution = solve_case(case, "paper", "mass")
    assert solution.status == "infeasible"
    assert "weight_thread_wear" in solution.diagnosis
    assert weight_lead_angle_optimum(case.params()) is None  # no lead angle in the box helps either
    threads = solve_case(case, "threads", "mass")  # the lead angles free too: proven (mean-value contraction; an
    assert threads.status == "infeasible" and "weight_thread_wear" in threads.diagnosis  # interval search without
    # it gave up at its budget)


def test_an_optimum_off_its_scales_is_solved_again_warm_from_its_own_kkt_point(monkeypatch):
    """The cable pump's cold solve ends more than tenfold off its start's scales (the weight mass) and is solved
    again scaled by its optimum: from that optimum's primal-dual point carried into the new scales
    (``problem.rescaled_seed``: a KKT point there, as the multipliers carried unscaled are not), by warm IPOPT in
    fewer iterations than a cold solve (it had been cold from the same point: 42 iterations in all, now 31)."""
    import numpy as np

    from clutchopt.optimise import problem as problem_module
    from clutchopt.optimise.chain import first_order_optimal
    from clutchopt.optimise.problem import case_problem, problems_set_aside

    case = load_case(CASES / "cable_pump.toml")
    seen, runs, rescaled, attempt = {}, [], problem_module.rescaled_seed, problem_module.attempt

    def spy(run, before, after):
        seen.update(run=run, before=before, after=after)
        return rescaled(run, before, after)

    def attempted(posed, data, lbx, ubx, x0, seed, methods, *args):
        runs.append((methods, (solved := attempt(posed, data, lbx, ubx, x0, seed, methods, *args))["iterations"]))
        return solved

    monkeypatch.setattr(problem_module, "rescaled_seed", spy)
    monkeypatch.setattr(problem_module, "attempt", attempted)
    with problems_set_aside():
        problem = case_problem(case)
        solution = problem.solve(case)
    posed, run, before, after = problem.posed, seen["run"], seen["before"], seen["after"]
    assert solution.status == "optimal" and np.max(after.scale / before.scale) > 10
    assert [methods for methods, _ in runs[:2]] == [("ipopt",), ("warm",)] and runs[1][1] < runs[0][1] / 2

    def kkt(seed, data) -> bool:
        lam_g = posed.sides.posed(seed["lam_g"], data.p)
        return bool(first_order_optimal(posed, seed["x"], data.p, seed["lam_x"], lam_g,
                                        data.lbx, data.ubx)[0])
    assert kkt(run, before) and kkt(rescaled(run, before, after), after)
    assert not kkt({"x": after.x0, "lam_x": run["lam_x"], "lam_g": run["lam_g"]}, after)
