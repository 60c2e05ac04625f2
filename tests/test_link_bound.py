"""An elastic link's integer choice refuted before its start-up NLP is solved (clutchopt.optimise.link_bound;
docs/start_up.md, "An elastic link's count refuted by its least stress")."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

import clutchopt.optimise.attempts as attempts
import clutchopt.optimise.integers as integers
import clutchopt.optimise.modifier as modifier
from clutchopt.cases import load_case
from clutchopt.formulations.cable.equations import reduced_friction_angle, weight_mass
from clutchopt.formulations.cable.speed_law import weight_stiffness
from clutchopt.model import namespace
from clutchopt.optimise.link_bound import drive_rows, least_stress, on_the_drive, refuted
from clutchopt.optimise.own_shift import ForeignShifts
from clutchopt.optimise.posed import scaled_box
from clutchopt.optimise.problem import Problem, solve_case
from clutchopt.optimise.verify import FEASIBILITY_TOL
from clutchopt.start_up.drive import Drive
from tests.conftest import CASES

CABLE = load_case(CASES / "cable_motor_start.toml")
RUN = attempts.run
MAIN_RUNS = [11, 9, 35, 19, 12, 21, 9, 4, 10]  # the start-up IPOPT runs' iterations when every count was solved


def solved(monkeypatch, bound: bool = True, mode: str | None = None, case=CABLE):
    """cable_motor_start (``case``) solved, with its start-up runs (posed, data, run) recorded, its correction's search
    at the moved limit solved as before ``Problem._one_up_first``; ``bound=False``: unrefuted (no count by its least
    stress, no modifier step by its corrected row)."""
    runs, run = [], RUN

    def recorded(posed, data, *args, **kwargs):
        result = run(posed, data, *args, **kwargs)
        if posed.start_up is not None:
            runs.append((posed, data, result))
        return result

    monkeypatch.setattr(attempts, "run", recorded)
    monkeypatch.setattr(Problem, "_one_up_first", lambda *args: None)  # (the search at 7 cables' moved limit, which
    # 8 cables solved first at the case's limit skips: tests/test_one_up_first.py)
    if not bound:
        monkeypatch.setattr(integers, "refuted", lambda *args: [])
        monkeypatch.setattr(modifier, "no_lighter", lambda *args: [])
    return solve_case(case, mode=mode), runs


def test_6_cables_7_at_their_own_limit_and_8_at_7_s_are_refuted_unsolved_the_design_the_same(monkeypatch):
    """cable_motor_start's first NLP: the relaxation (11 iterations), 7 cables (9), then 6 cables from 7's optimum ran
    35 iterations to Infeasible_Problem_Detected; at the stress limit 7 cables' start moved in (to 314.22 MPa), 7
    cables 19 to the same and 8 cables 21 (infeasible by 7.5e-5). Their least stress at the nodes, 376.0, 341.4 and
    314.24 MPa with the least pull of weights of eq. (9)'s mass, refutes the three: 6 runs (9), the design, its
    simulated start and every run that ends with a design the same to the last bit, in the same order (8 cables'
    own loop before 7 cables' modifier step: ``lighter`` takes an exclusion at another's shift whatever its end).
    The modifier step (10 iterations) is refuted unsolved too (tests/test_modifier_refuted.py): 5 runs."""
    with monkeypatch.context() as patched:
        unbounded, before = solved(patched, bound=False)
    solution, runs = solved(monkeypatch)
    assert [r["iterations"] for *_, r in before] == MAIN_RUNS
    assert (solution.solver.solves, unbounded.solver.solves) == (5, 9)
    assert solution.status == "optimal" and solution.design["cable_count"] == 8.0
    assert solution.objective == unbounded.objective == 3.952572919154992
    assert solution.design == unbounded.design
    assert solution.start_up["start_time_simulated"] == unbounded.start_up["start_time_simulated"]
    kept = [before[i][2] for i in (0, 1, 4, 6, 7)]  # (not 6 cables, 7 at their own limit, 8 at 7's, 7's modifier)
    assert [r["design"]["cable_count"] for *_, r in runs][3:] == [9.0, 8.0]
    assert all(np.array_equal(a["x"], b["x"]) and a["status"] == b["status"]
               for a, b in zip(kept, (r for *_, r in runs)))


def fixed_at(posed, data, count):
    lower, upper = data.lower.copy(), data.upper.copy()
    i = posed.names.index("cable_count")
    lower[i] = upper[i] = count
    return scaled_box(lower, upper, data.scale, (data.internal_lower, data.internal_upper))


def test_the_least_stress_is_below_each_design_s_and_refutes_6_cables_only(monkeypatch):
    """At the relaxation's nodes (the first NLP's: the drive's rows met), the locked drive carries up to 207.4 N m;
    6 cables carry it at no less than 375.99 MPa (over 350: refuted), 7, 8 and 9 at 341.41, 314.24 and 292.25 MPa
    (without the weights' least pull 361.9, 327.1, 299.9 and 277.7): 8 cables are refuted at 7 cables' moved limit,
    314.22 MPa. The bound lies below the quasi-static stress of every design the NLP found (7, 8 and 9 cables, the
    relaxation), node by node."""
    _, runs = solved(monkeypatch)
    posed, data, relaxed = runs[0]
    law = posed.formulation.speed_law
    least = {}
    for count in (6, 7, 8, 9):
        lbx, ubx = fixed_at(posed, data, count)
        x0 = np.clip(relaxed["x"], lbx, ubx)
        assert refuted(posed, data, x0, lbx, ubx) == (["link_stress"] if count == 6 else [])
        _, times, speeds, *_ = (path.full().ravel()[1:] for path in posed.start_up_figures(x0, data.p))
        x = namespace({"cable_count": float(count), "weight_lead_angle": data.params.weight_lead_angle})
        torque = Drive(posed.start_up.s, law, x, data.params).carried(speeds, times)
        least[count] = law.least_stress(x, data.params, speeds, torque)
    assert torque.max() == pytest.approx(207.43, abs=0.01)
    assert [round(least[c].max() / 1e6, 2) for c in (6, 7, 8, 9)] == [375.99, 341.41, 314.24, 292.25]
    posed, data, relaxed = runs[2]  # the relaxation at the limit 7 cables' start moved
    assert data.params.max_link_stress / 1e6 == pytest.approx(314.22, abs=0.005)
    for count in (8, 9):
        lbx, ubx = fixed_at(posed, data, count)
        refutes = refuted(posed, data, np.clip(relaxed["x"], lbx, ubx), lbx, ubx)
        assert refutes == (["link_stress"] if count == 8 else [])
    designs = [(p, d, r) for p, d, r in runs if r["status"] == "Solve_Succeeded"]
    assert {r["design"]["cable_count"] for *_, r in designs} >= {7.0, 8.0, 9.0}
    for p, d, r in designs:
        _, times, speeds, _, _, _, twist = (path.full().ravel()[1:] for path in p.start_up_figures(r["x"], r["p"]))
        design = namespace(p.design(r["x"], d.scale))  # (the relaxation's 6.73 cables too, not rounded)
        stress = law.stress(design, d.params, speeds, twist)
        x = namespace({"cable_count": design.cable_count, "weight_lead_angle": design.weight_lead_angle})
        bound = law.least_stress(x, d.params, speeds, Drive(p.start_up.s, law, x, d.params).carried(speeds, times))
        assert np.all(bound <= stress * (1 + 1e-9))
        if design.weight_mass < 0.46:  # (at eq. (9)'s mass, weight_turns_cable active: the bound is the stress)
            assert np.all(bound >= stress * (1 - 1e-9))


def test_a_seed_of_another_drive_is_brought_onto_this_one_s_rows_and_refutes_at_its_nodes(monkeypatch):
    """A seed whose speeds and times are another drive's (a sweep's point before: here the relaxation's states
    0.1 % off) does not meet the drive's rows; Newton's steps on those rows alone (``on_the_drive``) bring it onto them,
    moving no design variable, to the relaxation's nodes: the same least stress (375.99 MPa for 6 cables, refuted),
    where main took no bound from it. A box that fixes the drive's own variables leaves nothing to move: no bound."""
    _, runs = solved(monkeypatch)
    posed, data, relaxed = runs[0]
    n = len(data.scale)
    lbx, ubx = fixed_at(posed, data, 6)
    own = np.clip(relaxed["x"], lbx, ubx)
    other = own.copy()
    other[n:] *= 1.001  # the speeds and times of another drive (a sweep's neighbour)
    rows = drive_rows(posed)
    assert np.max(np.abs(rows(other, data.p).full())) > 1e3 * FEASIBILITY_TOL
    on = on_the_drive(posed, other, data.p, lbx, ubx)
    assert np.max(np.abs(rows(on, data.p).full())) <= FEASIBILITY_TOL / 10
    assert np.array_equal(on[:n], other[:n])  # (no design variable moved)
    _, times, speeds, *_ = (path.full().ravel() for path in posed.start_up_figures(on, data.p))
    _, own_times, own_speeds, *_ = (path.full().ravel() for path in posed.start_up_figures(own, data.p))
    assert np.allclose(speeds, own_speeds, rtol=1e-9, atol=0) and np.allclose(times, own_times, rtol=1e-9, atol=0)
    least = least_stress(posed, data, other, lbx, ubx)
    assert least == pytest.approx(least_stress(posed, data, own, lbx, ubx), rel=1e-9)
    assert least / 1e6 == pytest.approx(375.99, abs=0.005)
    assert refuted(posed, data, other, lbx, ubx) == ["link_stress"]
    lbx[n:], ubx[n:] = np.maximum(lbx[n:], other[n:]), np.minimum(ubx[n:], other[n:])  # (the drive's own fixed)
    assert on_the_drive(posed, other, data.p, lbx, ubx) is None and refuted(posed, data, other, lbx, ubx) == []


def test_threads_mode_its_weight_thread_free_refutes_the_same_counts(monkeypatch):
    """In threads mode the weight's lead angle is free; the least pull does not depend on it (the weights reach the
    design travel e at the duty speed whatever beta_w in (phi', 90 deg), which weight_thread_not_self_locking keeps),
    so the bound holds: 6 cables (43 iterations), 7 at their own moved limit (34) and 8 there too refuted, and 7
    cables' modifier step (its slopes in the weight mass and its lead angle): 9 runs to 5, the design the same to the
    last bit (3.6547255064507436 kg)."""
    with monkeypatch.context() as patched:
        unbounded, before = solved(patched, bound=False, mode="threads")
    solution, runs = solved(monkeypatch, mode="threads")
    assert [r["iterations"] for *_, r in before][2:4] == [43, 34] and len(runs) == len(before) - 4
    assert [e["status"] for e in solution.integer_search].count("excluded: link_stress") == 2  # (7 and 8 at the limit
    # 7 cables moved: the search kept)
    assert solution.objective == unbounded.objective == 3.6547255064507436 and solution.design == unbounded.design


def test_a_count_excluded_at_its_own_limit_is_its_own_verdict():
    """An exclusion at the limits the choice's own start moved (or the case's) is recorded as its own verdict, like
    an infeasible run there: no own loop solves it again (``untried_below``); one at another's shift is not, and no
    run's end bounds its objective: it is solved through its own loop whatever the kept design weighs (``lighter``;
    reached only one count below the kept design before, it was skipped where that count's own loop failed)."""
    foreign = ForeignShifts(["cable_count"])
    foreign.corrected(SimpleNamespace(design={"cable_count": 7.0}))
    search = [{"cable_count": c, "status": s, "feasible": False, "objective": math.nan}
              for c, s in ((7, "excluded: link_stress"), (6, "excluded: link_stress"))]
    foreign.seen(SimpleNamespace(integer_search=search))
    assert foreign.own == {(7.0,)} and foreign.found == {(6.0,): -math.inf}
    kept = SimpleNamespace(status="optimal", objective=3.95, design={"cable_count": 8.0})
    assert foreign.untried_below(kept, {"cable_count": 1.0}) == [] and foreign.lighter(kept) == [(6.0,)]
    two_below = ForeignShifts(["cable_count"])  # 8 and 9 excluded at 7's limit, 10 kept: both their own loops
    two_below.corrected(SimpleNamespace(design={"cable_count": 7.0}))
    two_below.seen(SimpleNamespace(integer_search=[{"cable_count": c, "status": "excluded: link_stress",
                                                    "feasible": False, "objective": math.nan} for c in (8, 9)]))
    heavier = SimpleNamespace(status="optimal", objective=4.5, design={"cable_count": 10.0})
    assert set(two_below.lighter(heavier)) == {(8.0,), (9.0,)}


def test_no_sampled_design_carries_its_torque_below_the_least_stress(monkeypatch):
    """3,000 designs sampled (2-16 cables, weight masses from eq. (9)'s, the least weight_turns_cable admits at the
    case's weight lead angle, to 3 times it, driving speeds 0-1650 rpm, torques 0-300 N m): the twist at which each
    carries its torque (bisected on eq. 18 read the other way) gives a stress never below the least stress; at eq.
    (9)'s mass the two meet. That mass is where the row weight_turns_cable is met with no margin (below it the row
    is broken), and its travel at the duty speed is the elongation e at any lead angle: the least pull's."""
    _, runs = solved(monkeypatch)
    posed, data, _ = runs[0]
    law, p = posed.formulation.speed_law, data.params
    phi = reduced_friction_angle(p.friction_coefficient, p.flank_angle)
    least_mass = weight_mass(p, p.weight_lead_angle, phi)
    for scale, met in ((1.0, True), (1 - 1e-6, False)):
        x = namespace({**{n: 1.0 for n in ("half_coupling_mass", "finger_diameter", "screw_diameter", "lead_angle")},
                       "cable_count": 8.0, "weight_mass": least_mass * scale, "weight_lead_angle": p.weight_lead_angle})
        row = next(c for c in posed.formulation.constraints(x, p) if c.name == "weight_turns_cable")
        margin = (row.value - row.limit) / row.limit
        assert (abs(margin) < 1e-12) if met else (margin < -1e-7)
    rng = np.random.default_rng(26)
    n = 3000
    count = rng.integers(2, 17, n).astype(float)
    mass = least_mass * np.where(rng.random(n) < 0.2, 1.0, 1.0 + 2.0 * rng.random(n))
    speed = rng.uniform(0.0, 1650 * np.pi / 30, n)
    torque = rng.uniform(0.0, 300.0, n)
    design = namespace({"cable_count": count, "weight_mass": mass, "weight_lead_angle": p.weight_lead_angle})
    low, high = np.zeros(n), np.full(n, law.largest_twist(design, p))
    carried = law.torque(design, p, speed, high) >= torque
    for _ in range(80):
        middle = 0.5 * (low + high)
        short = law.torque(design, p, speed, middle) < torque
        low, high = np.where(short, middle, low), np.where(short, high, middle)
    stress = law.stress(design, p, speed, high)[carried]
    bound = law.least_stress(namespace({"cable_count": count, "weight_lead_angle": p.weight_lead_angle}), p, speed,
                             torque)[carried]
    assert carried.sum() > 2000
    assert np.all(bound <= stress * (1 + 1e-12))
    for angle in np.radians([6.0, 10.0, 15.0, 30.0, 59.0]):  # (phi' = 5.9 deg)
        duty = p.weight_radius * p.speed**2 - p.gravity
        travel = weight_mass(p, angle, phi) * duty / weight_stiffness(p, angle, phi)
        assert travel == pytest.approx(p.elongation, rel=1e-12)
    at_least_mass = (mass == least_mass)[carried]
    assert np.max(np.abs(stress / bound - 1)[at_least_mass]) < 1e-9 and np.max(stress / bound) > 1.01


def test_a_fixed_count_s_correction_refuted_unsolved_the_design_the_same(monkeypatch):
    """cable_motor_start at 0.6 times its driven inertia (the bench's sweep's first point): 7 cables' own loop (its
    integers fixed) solves at the case's limits, their simulated start moves the stress limit in to 314.667 MPa, and
    its defect correction's solve there ran a warm and a cold IPOPT run to Infeasible_Problem_Detected (10 and 33
    iterations, then the elastic diagnosis). Their least stress at the warm point's nodes is over that limit: the
    correction is refuted unsolved (``Problem._link_refuted``: infeasible at that moved limit, no solve; no proof
    about the case, whose own limit is looser), modifier adaptation
    goes on from the same unverified design, and the kept design is the same to the last bit: 8 solves, were 10."""
    case = CABLE.with_values(driven_inertia=CABLE.values["driven_inertia"] * 0.6)
    verdicts, refute = [], Problem._link_refuted

    def recorded(self, case, data):
        verdict = refute(self, case, data)
        verdicts.append((data.params.max_link_stress, verdict))
        return verdict

    with monkeypatch.context() as patched:
        patched.setattr(Problem, "_link_refuted", lambda self, case, data: None)
        unrefuted, unrefuted_runs = solved(patched, case=case)
    monkeypatch.setattr(Problem, "_link_refuted", recorded)
    solution, runs = solved(monkeypatch, case=case)
    assert (solution.solver.solves, unrefuted.solver.solves) == (8, 10)
    assert solution.status == unrefuted.status == "optimal" and solution.design["cable_count"] == 7.0
    assert solution.design == unrefuted.design and solution.objective == unrefuted.objective
    assert solution.start_up["start_time_simulated"] == unrefuted.start_up["start_time_simulated"]
    assert [e["status"] for e in solution.integer_search] == [e["status"] for e in unrefuted.integer_search]
    moved = [(d.params.max_link_stress, r["status"]) for posed, d, r in unrefuted_runs
             if d.lower[posed.names.index("cable_count")] == d.upper[posed.names.index("cable_count")] == 7.0
             and d.params.max_link_stress < 350e6]
    assert [s for _, s in moved] == ["Infeasible_Problem_Detected"] * 2
    assert not [r for posed, d, r in runs if d.params.max_link_stress == moved[0][0]
                and d.lower[posed.names.index("cable_count")] == 7.0]
    refuted_here = [(limit, v) for limit, v in verdicts if v is not None]
    assert len(refuted_here) == 1
    limit, verdict = refuted_here[0]
    assert limit == pytest.approx(moved[0][0], rel=1e-12) and limit < 350e6
    assert verdict.status == "infeasible" and not verdict.diagnosed.proven and verdict.solver.solves == 0
    assert verdict.diagnosis.startswith("infeasible at the moved limit: link_stress: ")  # (not "proven": the case's
    assert verdict.design["cable_count"] == 7.0  # limit, 350 MPa, is not the one refuted)
    least = float(verdict.diagnosis.split("design at these integers, ")[1].split(" MPa")[0])
    assert least * 1e6 > limit * (1 + 1e-6) and f"{limit / 1e6:.6g} MPa (the case's 350 MPa)" in verdict.diagnosis
