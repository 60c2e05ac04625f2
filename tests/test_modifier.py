"""Modifier adaptation of a start-up limit (clutchopt.optimise.modifier; docs/start_up.md, "Modifier adaptation").

Hand calculation (cable_motor_start at driven_inertia 0.5 kg m^2, 8 cables, L = 350 MPa): the NLP solved at the
case's limit puts the weight mass on weight_turns_cable's bound, w_0 = 0.4545805 kg; its quasi-static stress peaks at
C_0 = 335.9957 MPa, the simulated start at S_0 = 351.5512 MPa. Along the weight mass the NLP's figure rises (dC/dw,
the NLP re-solved at w_0 + 1 g with the weight mass fixed) and the simulated one falls (dS/dw, simulations at w_0 +-
0.1 g), so the modifier of the stress is the slope lambda = dS/dw - dC/dw (about -49.9 - 32.8 = -82.6 MPa/kg) and the
offset S_0 - C_0 - lambda w_0: at w_0 the corrected figure C + offset + lambda w is S_0. With C linear the corrected
NLP's limit would bind at w_1 = w_0 + (S_0 - L) / |dS/dw| = 0.48567 kg; C's curvature adds 0.07 g (0.48574 kg).
"""

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.model import at_least, at_most
from clutchopt.optimise.modifier import first_order, modified, modifiers, offset_name, slope_name
from clutchopt.optimise.problem import case_problem
from clutchopt.start_up.simulation import run_start_up, start_up_model
from tests.conftest import CASES

CABLE = load_case(CASES / "cable_motor_start.toml")
L = 350e6  # Pa


def test_a_modified_figure_is_its_own_plus_the_offset_and_the_slopes():
    """link_stress's figure at two nodes [300, 310] with offset 10 and slopes 2 (a = 3) and -1 (b = 4): [312, 322];
    start_time with zero modifiers as it was; a lower limit (the motor's torque) not touched; a problem without the
    modifiers' parameters: the constraints as they are."""
    x = SimpleNamespace(a=3.0, b=4.0)
    zero = {name: 0.0 for limit in ("start_time", "link_stress")
            for name in (offset_name(limit), slope_name(limit, "a"), slope_name(limit, "b"))}
    p = SimpleNamespace(**{**zero, offset_name("link_stress"): 10.0, slope_name("link_stress", "a"): 2.0,
                           slope_name("link_stress", "b"): -1.0})
    torque = at_least("motor_starting_torque", 50.0, 40.0, equation="Kloss")
    constraints = [at_most("link_stress", np.array([300.0, 310.0]), 350.0, equation="(18)"),
                   at_most("start_time", 1.5, 2.0, equation="start-up"), torque]
    stress, time, kept = modified(constraints, x, p)
    assert stress.value.tolist() == [312.0, 322.0] and stress.limit == 350.0
    assert time.value == 1.5 and kept is torque
    assert modified(constraints, x, SimpleNamespace()) is constraints


@pytest.fixture(scope="module")
def at_the_bound():
    """8 cables at 0.5 kg m^2 solved once at the case's limit (its simulated start over it), and its problem."""
    case = CABLE.with_values(driven_inertia=0.5)
    case = replace(case, bounds={**case.bounds, "cable_count": (8.0, 8.0)})
    problem = case_problem(case)
    solution = problem.solve(case, refine=False)
    assert solution.status == "unverified"
    return case, problem, solution


def peak_stress(case, design):
    return run_start_up(start_up_model(case, "paper", design)).headline["peak_stress"]


def test_the_modifier_is_the_simulated_figure_and_its_slope_at_the_design(at_the_bound):
    case, problem, solution = at_the_bound
    w0 = solution.design["weight_mass"]
    assert w0 == pytest.approx(0.4545805, rel=1e-6)
    simulated, own = solution.start_up["peak_link_stress_simulated"], solution.collocated["link_stress"]
    assert (simulated, own) == (pytest.approx(351.5512e6, rel=1e-6), pytest.approx(335.9957e6, rel=1e-6))
    heavier = problem.solve(replace(case, bounds={**case.bounds, "weight_mass": (w0 + 1e-3, w0 + 1e-3)}),
                            refine=False)
    own_slope = (heavier.collocated["link_stress"] - own) / 1e-3  # the NLP re-solved: its states follow the design
    simulated_slope = (peak_stress(case, {**solution.design, "weight_mass": w0 + 1e-4})
                       - peak_stress(case, {**solution.design, "weight_mass": w0 - 1e-4})) / 2e-4
    assert own_slope == pytest.approx(32.8e6, rel=1e-2) and simulated_slope == pytest.approx(-49.9e6, rel=1e-2)
    counts = {}
    values = modifiers(problem, case, solution, {"link_stress"}, counts)
    assert counts == {"simulations": 1}  # of the free continuous variables only the weight mass enters the start
    slope = values[slope_name("link_stress", "weight_mass")]
    assert slope == pytest.approx(simulated_slope - own_slope, rel=2e-3)
    assert all(value == 0.0 for name, value in values.items()
               if name.startswith(slope_name("link_stress", "")) and not name.endswith("weight_mass"))
    assert own + values[offset_name("link_stress")] + slope * w0 == pytest.approx(simulated, rel=1e-12)
    assert values[offset_name("start_time")] == 0.0  # a limit met is not modified


def test_a_step_binds_the_corrected_figure_and_nears_the_limit(at_the_bound):
    """The corrected NLP (the case's limit) binds C(w_1) + offset + lambda w_1 = L; its weight mass near the hand
    calculation's 0.48567 kg (C's curvature); its simulated start 350.23 MPa, within a sixth of S_0's excess."""
    case, problem, solution = at_the_bound
    values = modifiers(problem, case, solution, {"link_stress"}, {})
    moved = replace(case, values={**case.values, **values})
    step = problem.modified_problem._solve(case, warm=solution, nlp_case=moved, cold=False)
    w1 = step.design["weight_mass"]
    w0 = solution.design["weight_mass"]
    hand = w0 + (solution.start_up["peak_link_stress_simulated"] - L) / 49.9e6
    assert hand == pytest.approx(0.48567, rel=1e-4) and w1 == pytest.approx(hand, rel=5e-4)
    corrected = (step.collocated["link_stress"] + values[offset_name("link_stress")]
                 + values[slope_name("link_stress", "weight_mass")] * w1)
    assert corrected == pytest.approx(L, rel=1e-8)
    simulated = step.start_up["peak_link_stress_simulated"]
    assert 0 < simulated - L < (solution.start_up["peak_link_stress_simulated"] - L) / 6


def test_only_an_unverified_design_goes_on():
    """A verified design (or one without a simulated miss) is returned as it is, no solve."""
    solves = []
    done = SimpleNamespace(status="optimal", constraints=[], internal=None)
    assert first_order(None, None, done, solves) is done and solves == []
