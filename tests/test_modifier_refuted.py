"""A modifier step refuted before its corrected NLP is solved (clutchopt.optimise.modifier.no_lighter;
docs/start_up.md, "A modifier step refuted unsolved")."""

import math
from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

import clutchopt.optimise.modifier as modifier
from clutchopt.cases import load_case
from clutchopt.formulations.cable.equations import reduced_friction_angle, weight_mass
from clutchopt.model import namespace
from clutchopt.optimise.problem import solve_case
from clutchopt.optimise.verify import evaluate_objective
from clutchopt.start_up.drive import Drive
from tests.conftest import CASES

CABLE = load_case(CASES / "cable_motor_start.toml")


def refuted_step(monkeypatch, refute: bool = True):
    """cable_motor_start solved; what its modifier step was asked (problem, case, unverified solution, modifiers,
    fixed integers, bound); ``refute=False``: the step solved, as before the bound."""
    asked = {}

    def spied(problem, case, solution, values, fixed, bound):
        asked.update(problem=problem, case=case, solution=solution, values=values, fixed=fixed, bound=bound)
        return no_lighter(problem, case, solution, values, fixed, bound) if refute else []

    no_lighter = modifier.no_lighter
    monkeypatch.setattr(modifier, "no_lighter", spied)
    return solve_case(CABLE), SimpleNamespace(**asked)


def test_7_cables_modifier_step_is_refuted_the_design_and_start_the_same(monkeypatch):
    """7 cables' design (3.4872 kg, its simulated stress 377 MPa against 350) goes on in modifier adaptation below 8
    cables' 3.9526 kg. The corrected row: 341.41 MPa (7 cables' least stress at the nodes) + 88.08 MPa - 115.06 MPa
    per kg of weight mass <= 350 MPa, so each weight has at least 0.6908 kg, the coupling at least 4.836 kg: the step
    is not solved (3 runs, not 4; 25 IPOPT iterations, not 35: 8 cables solved first, ``Problem._one_up_first``).
    Solved, it ends at 0.7887 kg, 5.826 kg, above that bound. The design, its objective and its simulated start are
    the solved step's to the last bit."""
    with monkeypatch.context() as patched:
        solved, _ = refuted_step(patched, refute=False)
    found, step = refuted_step(monkeypatch)
    assert (found.solver.solves, solved.solver.solves) == (3, 4)
    assert (found.solver.iterations, solved.solver.iterations) == (25, 35)
    assert found.status == solved.status == "optimal" and found.design == solved.design
    assert found.objective == solved.objective == pytest.approx(3.952572919154992, rel=1e-12)
    assert found.start_up["start_time_simulated"] == solved.start_up["start_time_simulated"]
    assert [(e["cable_count"], e["status"]) for e in found.integer_search][-2:] == [
        (7, "modifier adaptation: excluded: link_stress"), (7, "simulated at the case's limits: unverified")]
    assert [e["status"] for e in solved.integer_search][-2:] == ["modifier adaptation: unverified",
                                                                 "simulated at the case's limits: unverified"]
    values = step.values
    assert values["modifier_link_stress"] / 1e6 == pytest.approx(88.08, abs=0.01)
    assert values["modifier_link_stress_per_weight_mass"] / 1e6 == pytest.approx(-115.06, abs=0.01)
    assert [k for k, v in values.items() if v and "_per_" in k] == ["modifier_link_stress_per_weight_mass"]
    floor = modifier.least_objective(step.problem, step.case, step.solution, values, step.fixed)
    assert step.bound == found.objective and floor == pytest.approx(4.836, abs=1e-3)
    nlp_case = replace(step.case, values={**step.case.values, **values},
                       bounds={**step.case.bounds, **step.fixed})
    ran = step.problem.modified_problem._solve(step.case, warm=step.solution, nlp_case=nlp_case, cold=False)
    assert ran.design["cable_count"] == 7.0 and ran.design["weight_mass"] == pytest.approx(0.7887, abs=1e-4)
    assert ran.objective == pytest.approx(5.826, abs=1e-3) and ran.objective > floor


def test_no_sampled_design_meeting_the_corrected_row_is_below_the_bound(monkeypatch):
    """4,000 designs of 7 cables sampled (weight masses from eq. (9)'s, the least weight_turns_cable admits, to 3
    times it; the half-coupling, finger and screw over a tenth to 3 times the unverified design's): each one's
    quasi-static stress at the step's nodes (its twist bisected on eq. 18 read the other way for the locked drive's
    torque), corrected by the modifier, meets the limit only where the design weighs at least the bound (4.836 kg;
    the lightest that meets it 5.67 kg, its weights at the solved step's 0.7888 kg, above the 0.6908 kg the bound
    admits)."""
    _, step = refuted_step(monkeypatch)
    posed, solution, values = step.problem.posed, step.solution, step.values
    data = posed.scaled_data(step.case, solution.design, solution.scale, solution.internal, solution.mesh[0])
    p, law = data.params, posed.formulation.speed_law
    _, times, speeds, *_ = (path.full().ravel()[1:] for path in posed.start_up_figures(data.x0, data.p))
    at_seven = namespace({"cable_count": 7.0, "weight_lead_angle": p.weight_lead_angle})
    torque = Drive(posed.start_up.s, law, at_seven, p).carried(speeds, times)
    rng = np.random.default_rng(14)
    n = 4000
    least_mass = weight_mass(p, p.weight_lead_angle, reduced_friction_angle(p.friction_coefficient, p.flank_angle))
    designs = {name: solution.design[name] * rng.uniform(0.1, 3.0, n)
               for name in ("half_coupling_mass", "finger_diameter", "screw_diameter")}
    designs["weight_mass"] = least_mass * rng.uniform(1.0, 3.0, n)
    x = namespace({"cable_count": 7.0, "weight_lead_angle": p.weight_lead_angle,
                   "weight_mass": designs["weight_mass"][:, None]})
    low, high = np.zeros((n, len(speeds))), np.full((n, len(speeds)), law.largest_twist(x, p))
    assert np.all(law.torque(x, p, speeds, high) >= torque)  # (every design carries its torque)
    for _ in range(80):
        middle = 0.5 * (low + high)
        short = law.torque(x, p, speeds, middle) < torque
        low, high = np.where(short, middle, low), np.where(short, high, middle)
    stress = law.stress(x, p, speeds, high).max(axis=1)
    corrected = (stress + values["modifier_link_stress"]
                 + values["modifier_link_stress_per_weight_mass"] * designs["weight_mass"])
    meets = corrected <= p.max_link_stress
    floor = modifier.least_objective(step.problem, step.case, solution, values, step.fixed)
    weights = [evaluate_objective(posed.formulation, "mass",
                                  {**solution.design, **{k: v[i] for k, v in designs.items()}, "cable_count": 7.0}, p)
               for i in np.flatnonzero(meets)]
    assert 1000 < meets.sum() < n
    assert min(weights) >= floor > step.bound and not math.isinf(floor)
    lightest = designs["weight_mass"][meets].min()
    assert lightest > 0.6908 and lightest == pytest.approx(0.7888, abs=2e-3)  # (the solved step's weight: the
    # stress rises with the mass, and the least stress, taken at the least pull, bounds the weights below it)
    assert round(min(weights), 2) == 5.67


def test_a_row_no_design_meets_bounds_nothing_and_a_loose_one_refutes_nothing(monkeypatch):
    """The same step with its offset raised by 1000 GPa: the row admits no weight within its bounds (1 t: the box
    emptied), or, its slope dropped, raised by 1 GPa, no design at all: the bound is infinite. Lowered by 1 GPa, the
    row leaves every weight mass, and the objective's bound is the box's least (0.13 g): nothing refuted."""
    _, step = refuted_step(monkeypatch)
    values, offset = step.values, step.values["modifier_link_stress"]
    args = (step.problem, step.case, step.solution)
    assert modifier.least_objective(*args, {**values, "modifier_link_stress": offset + 1e12}, step.fixed) == math.inf
    flat = {**values, "modifier_link_stress": offset + 1e9, "modifier_link_stress_per_weight_mass": 0.0}
    assert modifier.least_objective(*args, flat, step.fixed) == math.inf
    loose = {**values, "modifier_link_stress": offset - 1e9}
    assert modifier.least_objective(*args, loose, step.fixed) == pytest.approx(1.288e-4, rel=1e-3)
    assert modifier.no_lighter(*args, loose, step.fixed, step.bound) == []
