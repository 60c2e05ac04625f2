"""A proof of infeasibility carried along a sweep that only tightens the limits it moves (Regions._tightened,
Tightening), or whose every moved row rises along the step for every design of the box (Slopes): each
point after the proven one gets the verdict `solve` alone gives it, without a search; nothing is carried where the
step may lower a row for some design, or moves a row's scale apart from its limit."""

from types import SimpleNamespace

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchopt.bench.reference import bench_cases, reference_mode
from clutchopt.backend import where
from clutchopt.model import at_least, at_most
from clutchopt.optimise import region_proof
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import Vary
from clutchopt.optimise.tightening import ProofCarry, Tightening

BALL = next(case for case in bench_cases() if case.coupling == "ball")
CABLE = next(case for case in bench_cases() if case.coupling == "cable")


def _swept(case, name, factors):
    quantity = next(q for q in case.quantities if q.name == name)
    values = case.values[name] * np.asarray(factors)
    return values, Sweep(case, [Vary(quantity, tuple(values.tolist()))], mode=reference_mode(case.coupling)).run(
        progress=False)


@pytest.fixture
def searched(monkeypatch):
    calls = []
    real = region_proof.searches
    monkeypatch.setattr(region_proof, "searches", lambda posed, problems, budgets=None: calls.append(len(problems))
                        or real(posed, problems, budgets))
    return calls


def test_the_ball_beyond_its_edge_is_proven_once_and_each_point_keeps_solve_s_verdict(searched):
    """The ball over 9.33x-18.7x its power (40 points, none with a design): point 0 proven by its own search; the
    power enters only the torque row's limit (k_s P / w, its scale), so each point after it is proven by that proof
    (had been four more region searches), no solver call, no search; `solve` alone proves each."""
    values, result = _swept(BALL, "power", np.geomspace(9.33, 18.7, 40))
    records = result.solutions
    assert [r["status"] for r in records] == ["infeasible"] * 40 and result.spent["solves"] == 1
    assert records[0]["diagnosis"].startswith("proven infeasible: no design within the bounds meets torque")
    body = records[0]["diagnosis"].split(": ", 1)[1]
    carried = (f"proven infeasible for power {values[1] / 1e3:.6g}-{values[-1] / 1e3:.6g} kW (39 points, by the "
               f"proof at power {values[0] / 1e3:.6g} kW; every limit the sweep moves at least as tight at each): "
               f"{body}")
    assert [r["diagnosis"] for r in records[1:]] == [carried] * 39
    assert all(r["solver"]["solves"] == 0 and r["solver"]["time_s"] == 0 for r in records[1:])
    assert searched == [1]  # (point 0's own search, its verdict's: no region searched)
    problem = case_problem(BALL, reference_mode("ball"))
    for k in (1, 20, 39):
        alone = problem.solve(BALL.with_values(power=float(values[k])))
        assert alone.status == "infeasible" and alone.diagnosis.startswith("proven infeasible")
        torque = next(c for c in records[k]["constraints"] if c["name"] == "torque")  # (at the point's own power)
        assert torque["limit"] == pytest.approx(next(c for c in alone.as_dict()["constraints"]
                                                     if c["name"] == "torque")["limit"], rel=1e-12)


def test_a_sweep_that_loosens_or_moves_a_value_carries_no_proof():
    """The ball's power downwards from beyond its edge (the limits loosen: its points searched as regions, as
    before), and the wedge over its friction coefficient (it enters the torque the design carries): no point
    carries another's proof."""
    _, down = _swept(BALL, "power", np.geomspace(18.7, 9.33, 20))  # (searched point by point, or as
    # regions: tests/test_region_search.py)
    assert [r["status"] for r in down.solutions] == ["infeasible"] * 20
    wedge = next(case for case in bench_cases() if case.coupling == "wedge")
    _, friction = _swept(wedge, "friction_coefficient", np.geomspace(2.0, 0.5, 40))
    statuses = [r["status"] for r in friction.solutions]
    assert "optimal" in statuses and "infeasible" in statuses
    assert not any("by the proof at" in (r["diagnosis"] or "") for r in (*down.solutions, *friction.solutions))


def _tightening(scale, varied=("a",), sense=at_most):
    """A design x under a limit a (a row scaled by ``scale`` of the parameters a, b)."""
    formulation = SimpleNamespace(
        variables=[SimpleNamespace(name="x")], quantities=[SimpleNamespace(name="a"), SimpleNamespace(name="b")],
        constraints=lambda x, p: [sense("row", x.x, p.a, equation="", scale=scale and scale(p))])
    return Tightening(SimpleNamespace(formulation=formulation), list(varied))


def test_a_proof_is_carried_only_where_each_moved_row_is_scaled_by_its_limit_or_a_scale_it_does_not_move():
    """x <= a over a sweep of a downwards: scaled by a itself (no scale given) or by b, what a proof rules out at a_j
    (x > a_j + tol s_j over the box) stays ruled out at every tighter a_k; scaled by 1000 (2 - a), a scale the step
    moves apart from its limit, it need not: with tol 0.01, x = 11.05 breaks x <= 1 by 10.05 / 1000 (ruled out) but
    x <= 0.99 by 10.06 / 1010, within the tolerance (not ruled out): no proof is carried there."""
    assert all(t.known and not t.sloped for t in (_tightening(None), _tightening(lambda p: p.b),
                                                  _tightening(None, sense=at_least)))
    moved = _tightening(lambda p: 1000 * (2 - p.a))
    assert moved.known and moved.sloped == [0]  # (its limits compared, its slope a proof's need)
    x, tol, (a_j, s_j), (a_k, s_k) = 11.05, 0.01, (1.0, 1000.0), (0.99, 1010.0)
    assert (x - a_j) / s_j > tol and (x - a_k) / s_k <= tol and moved.tightened(np.array([a_j, 0.0]),
                                                                                 np.array([a_k, 0.0]))
    unmoved = _tightening(None, varied=("b",))  # (b enters no row: the step moves nothing, what was ruled out stays)
    assert unmoved.known and not unmoved.sloped and unmoved.tightened(np.array([1.0, 0.0]), np.array([1.0, 5.0]))
    t = _tightening(None)
    limits, scales = t.limits(np.array([[1.0, 0.0], [0.9, 0.0], [1.1, 0.0], [0.8, 0.0]]))
    assert (t.held_from(limits, scales, 0, 1), t.held_from(limits, scales, 1, 2), t.held_from(limits, scales, 2, 3)
            ) == (2, 2, 4)  # (from 1: 0.9 tighter, 1.1 not; from 0.9: 1.1 not; from 1.1: 0.8)
    low = _tightening(None, sense=at_least)  # (x >= a: tighter upwards)
    limits, scales = low.limits(np.array([[1.0, 0.0], [1.2, 0.0], [1.1, 0.0], [0.9, 0.0]]))
    assert low.held_from(limits, scales, 0, 1) == 3


def test_a_list_up_and_down_carries_each_proof_to_the_points_it_holds_at():
    """cases/lever_centrifuge.toml in design mode at inertias 30, 60, 70, 65, 80, 62, 59, 75, 58.5, 45, 100 kg m^2:
    the proof at 60 carries to 62-80 (none below 60 among them), the one at 59 to 75 (a run searched from 59 had
    left it to be solved: review 21), and no point below the proof it would carry; each verdict `solve`'s."""
    from clutchopt.cases import load_case
    from clutchopt.optimise.sweep_grid import parse_vary
    from tests.conftest import CASES

    case = load_case(CASES / "lever_centrifuge.toml")
    values = [30, 60, 70, 65, 80, 62, 59, 75, 58.5, 45, 100]
    result = Sweep(case, [parse_vary("inertia=" + ",".join(map(str, values)), "lever")], mode="design").run(
        progress=False)
    diagnoses = [r["diagnosis"] or "" for r in result.solutions]
    carried = [(k, d.split(" (")[0], d.split("by the proof at ")[1].split(";")[0]) for k, d in enumerate(diagnoses)
               if "by the proof at" in d]
    assert carried == [(k, "proven infeasible for inertia 62-80 kg*m^2", "inertia 60 kg*m^2") for k in (2, 3, 4, 5)
                       ] + [(7, "proven infeasible for inertia 75 kg*m^2", "inertia 59 kg*m^2")]
    assert "(1 point, by the proof" in diagnoses[7]
    problem = case_problem(case, "design")
    for k in (7, 8):
        alone = problem.solve(case.with_values(inertia=float(values[k])))
        assert result.solutions[k]["status"] == alone.status == "infeasible"


def test_points_at_the_values_of_a_proven_one_say_so():
    """ball_crusher over its service factor 2, 2, 2 (a run of the same values: one proof, said so) and 1, 2, 2 (the
    last at the values of point 1, whose proof it carries); no empty list of quantities in the words (review 21c:
    "proven infeasible for  (2 points, one proof)")."""
    from clutchopt.cases import load_case
    from clutchopt.optimise.sweep_grid import parse_vary
    from tests.conftest import CASES

    crusher = load_case(CASES / "ball_crusher.toml")
    same = Sweep(crusher, [parse_vary("service_factor=2,2,2", "ball")]).run(progress=False).solutions
    assert [r["diagnosis"].split(":")[0] for r in same[1:]] == [
        "proven infeasible (2 points at the same values, one proof)"] * 2
    back = Sweep(crusher, [parse_vary("service_factor=1,2,2", "ball")]).run(progress=False).solutions
    assert [r["status"] for r in back] == ["optimal"] + ["infeasible"] * 2
    assert back[2]["diagnosis"].split(":")[0] == (
        "proven infeasible (1 point at the values of a point proven before, by its proof)")
    assert not any("for  (" in (r["diagnosis"] or "") for r in (*same, *back))


def test_the_cable_beyond_its_edge_carries_a_proof_through_rows_its_torque_enters_by_their_value(searched):
    """The cable over 10x-20x its torque (40 points, none with a design): the torque enters the stress of its cables,
    clamp screws and fingers (eqs. (18), (20), (22)), each sigma = c T / (design) under its allowable, whose slope in
    T, c / ([sigma] design), is positive over the whole design box: after point 0's own proof each point carries it,
    no solver call, no search; `solve` alone proves each. Downwards (the rows fall with T) nothing is carried."""
    values, result = _swept(CABLE, "torque", np.geomspace(10, 20, 40))
    records = result.solutions
    assert [r["status"] for r in records] == ["infeasible"] * 40 and result.spent["solves"] == 1
    body = records[0]["diagnosis"].split(": ", 1)[1]
    carried = (f"proven infeasible for torque {values[1]:.6g}-{values[-1]:.6g} N*m (39 points, by the proof at torque "
               f"{values[0]:.6g} N*m; each value the sweep moves going no further within its limit for every design "
               f"within the bounds): {body}")
    assert [r["diagnosis"] for r in records[1:]] == [carried] * 39
    assert all(r["solver"]["solves"] == 0 for r in records[1:]) and searched == [1]
    problem = case_problem(CABLE, reference_mode("cable"))
    for k in (1, 39):
        alone = problem.solve(CABLE.with_values(torque=float(values[k])))
        assert alone.status == "infeasible" and alone.diagnosis.startswith("proven infeasible")
    _, down = _swept(CABLE, "torque", np.geomspace(20, 10, 10))
    assert [r["status"] for r in down.solutions] == ["infeasible"] * 10
    assert not any("by the proof at" in r["diagnosis"] for r in down.solutions)


def _posed(*rows):
    """A posed problem's stand-in: one design x, quantities a and b, a constraint ``row(x, p) <= 1`` each."""
    formulation = SimpleNamespace(
        variables=[SimpleNamespace(name="x")], quantities=[SimpleNamespace(name="a"), SimpleNamespace(name="b")],
        constraints=lambda x, p: [at_most(f"row{i}", row(x.x, p), 1.0, equation="") for i, row in enumerate(rows)])
    return SimpleNamespace(formulation=formulation, built=lambda kind, key, build: build(0))


def _slopes(row, lower, upper, values, j=0, k=1):
    """:meth:`ProofCarry.held_from` for one design x in [lower, upper] under ``row(x, p)`` (p: quantities a, b), the
    sweep varying a (``values``: a column of a, b held at 1)."""
    points = np.column_stack([values, np.ones(len(values))])
    return ProofCarry(_posed(row), ["a"], points).held_from(np.array([lower]), np.array([upper]), j, k, len(values))


def test_a_proof_is_carried_through_a_value_only_where_every_design_s_row_rises_along_the_step():
    """x a <= 1 (normalised x a - 1, its slope in a is x): over x in [1, 2] every design's row rises with a, so from
    a = 1 a proof holds at 1.5 and 3 and not at 2.5 after them, a step down from 1 (all the points up to the first
    step down from point 0); over x in [-1, 2] a design's row falls with a (x < 0): nothing is carried; nor where the
    row jumps with a (a comparison: no slope sees a jump; atan2 across its cut), nor at a value left out (NaN)."""
    assert _slopes(lambda x, p: x * p.a, 1.0, 2.0, [1.0, 1.5, 3.0, 0.5, 4.0]) == 3
    assert _slopes(lambda x, p: x * p.a, 1.0, 2.0, [1.0, 1.5, 3.0, 2.5], j=2, k=3) == 3
    assert _slopes(lambda x, p: x * p.a, -1.0, 2.0, [1.0, 1.5]) == 1
    assert _slopes(lambda x, p: x * p.a + where(p.a > 2, 0.0, 1.0), 1.0, 2.0, [1.0, 1.5, 3.0]) == 1
    # -atan2(a, x) over x in [-2, -1]: its slope in a, -x / (a^2 + x^2), is positive, yet a crossing 0 takes it
    # across its cut from 3.08 to -3.08 (review 22): an operation outside the continuous ones concludes nothing
    assert _slopes(lambda x, p: -ca.atan2(p.a, x), -2.0, -1.0, [-0.1, 0.1]) == 1
    assert _slopes(lambda x, p: x * p.a, 1.0, 2.0, [1.0, np.nan, 3.0]) == 1
    assert _slopes(lambda x, p: x * p.b, -1.0, 2.0, [1.0, 0.5, 3.0]) == 3  # (a enters no row: nothing moves)


def test_each_moved_quantity_s_step_is_held_against_its_own_slopes():
    """Two rows x a + b <= 1 and -x b <= 1 over x in [1, 2], both a and b varied: the first's slope in b is 1, the
    second's -x, so b's slopes span [-2, 1] and no step of b holds; a's are x and 0, so a step of a upwards holds
    with b unmoved. (The Jacobian's columns, a moved quantity each, read apart from its rows: read across, a step of
    b downwards would have held.)"""
    posed = _posed(lambda x, p: x * p.a + p.b, lambda x, p: -x * p.b)
    box = np.array([1.0]), np.array([2.0])
    held = lambda *points: ProofCarry(posed, ["a", "b"], np.array(points)).held_from(  # noqa: E731
        *box, 0, 1, len(points))
    assert held([1.0, 1.0], [2.0, 1.0], [3.0, 1.0]) == 3
    assert held([1.0, 1.0], [2.0, 0.5]) == 1 and held([1.0, 1.0], [1.0, 1.5]) == 1


@settings(max_examples=60, deadline=None)
@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(-3, 3), st.floats(0.1, 3), st.floats(0.1, 3), st.floats(0.1, 3),
       st.floats(0.1, 3))
def test_where_the_slopes_carry_a_proof_every_design_s_row_rises(a, b, c, lower, width, p_j, p_k):
    """A row x^a p^b + c x p - p^2 / 4 <= 1 over x in [lower, lower + width], p stepped from p_j to p_k: wherever
    :class:`Slopes` says the step holds, the row rises (or stays) at every design sampled from the box (the mean
    value theorem's conclusion, checked at 201 designs in float64 to a relative 1e-12)."""
    upper = lower + width
    row = lambda x, p: x**a * p.a**b + c * x * p.a - p.a**2 / 4  # noqa: E731
    if _slopes(row, lower, upper, [p_j, p_k]) < 2:
        return
    xs = np.linspace(lower, upper, 201)
    before = xs**a * p_j**b + c * xs * p_j - p_j**2 / 4
    after = xs**a * p_k**b + c * xs * p_k - p_k**2 / 4
    assert np.all(after >= before - 1e-12 * np.maximum(np.abs(before), 1.0))


def test_a_proof_carried_on_names_the_point_whose_search_proved_it():
    """The cable over 10x-20x its torque in 300 points: point 0 proven by its own search (1 box); the points after it
    carry that proof LONGEST_RUN (256) at a time, and the run after the first names point 0's torque too, not the
    last point it had been carried to (review 22: "by the proof at torque 7965.09 N*m", itself carried), with its own
    count and values."""
    values, result = _swept(CABLE, "torque", np.geomspace(10, 20, 300))
    diagnoses = [r["diagnosis"] for r in result.solutions]
    assert [r["status"] for r in result.solutions] == ["infeasible"] * 300 and result.spent["solves"] == 1
    heads = [d.split(" (by")[0].split("; ")[0] for d in diagnoses[1:]]
    assert heads[0] == (f"proven infeasible for torque {values[1]:.6g}-{values[256]:.6g} N*m (256 points, by the "
                        f"proof at torque {values[0]:.6g} N*m")
    assert heads[256] == (f"proven infeasible for torque {values[257]:.6g}-{values[299]:.6g} N*m (43 points, by the "
                          f"proof at torque {values[0]:.6g} N*m")
    assert heads[1:256] == [heads[0]] * 255 and heads[257:] == [heads[256]] * 42


def test_a_carried_proof_s_words_count_only_the_points_that_take_it():
    """cases/wedge_paper.toml in paper mode, its guide length ratio and shell thickness raised together (zipped, 30
    points to 20x and 6x): point 9 proven by its own search, 10-22 carry its proof; from 23 on the outer diameter
    (which no design variable enters) is over its limit, each point's own verdict "infeasible whatever the design".
    The carried words name 13 points and their own values (review 22: "20 points" and values up to point 29's)."""
    from clutchopt.cases import load_case
    from tests.conftest import CASES

    case = load_case(CASES / "wedge_paper.toml")
    quantities = {q.name: q for q in case.quantities}
    ratio = case.values["guide_length_ratio"] * np.geomspace(1, 20, 30)
    shell = case.values["shell_thickness"] * np.geomspace(1, 6, 30)
    result = Sweep(case, [Vary(quantities["guide_length_ratio"], tuple(ratio.tolist())),
                          Vary(quantities["shell_thickness"], tuple(shell.tolist()))], mode="paper",
                   zipped=True).run(progress=False)
    diagnoses = [r["diagnosis"] or "" for r in result.solutions]
    assert [r["status"] for r in result.solutions] == ["optimal"] * 9 + ["infeasible"] * 21
    assert diagnoses[9].startswith("proven infeasible: no design within the bounds meets")
    carried = (f"proven infeasible for shell_thickness {1e3 * shell[10]:.6g}-{1e3 * shell[22]:.6g} mm, "
               f"guide_length_ratio {ratio[10]:.6g}-{ratio[22]:.6g} (13 points, by the proof at shell_thickness "
               f"{1e3 * shell[9]:.6g} mm, guide_length_ratio {ratio[9]:.6g};")
    assert all(d.startswith(carried) for d in diagnoses[10:23])
    assert all(d.startswith("infeasible whatever the design: outer_diameter") for d in diagnoses[23:])


def test_limits_compared_and_values_bounded_together_carry_a_proof():
    """The ball beyond its edge (9.33x-18.7x its power) with its shell 1x-1.5x as thick, both at each step (zipped,
    20 points): the power enters only the torque row's limit (compared: k_s P / w, higher), the shell thickness only
    the outer diameter's value (its slope 2 over the box: thicker, larger); together each point after the first carries
    its proof (the slopes of every row, the torque's in the power spanning zero by the dependency of its interval
    bound, 1 - T(x) / T_req(P), had carried none: eight-point region searches instead); `solve` alone proves them."""
    quantities = {q.name: q for q in BALL.quantities}
    power = BALL.values["power"] * np.geomspace(9.33, 18.7, 20)
    shell = BALL.values["shell_thickness"] * np.geomspace(1, 1.5, 20)
    result = Sweep(BALL, [Vary(quantities["power"], tuple(power.tolist())),
                          Vary(quantities["shell_thickness"], tuple(shell.tolist()))], mode=reference_mode("ball"),
                   zipped=True).run(progress=False)
    records = result.solutions
    assert [r["status"] for r in records] == ["infeasible"] * 20 and result.spent["solves"] == 1
    assert all(f"(19 points, by the proof at power {power[0] / 1e3:.6g} kW, shell_thickness 30 mm; every limit the "
               "sweep moves at least as tight at each, and each value it moves going no further within its limit "
               "for every design within the bounds)" in r["diagnosis"] for r in records[1:])
    problem = case_problem(BALL, reference_mode("ball"))
    for k in (1, 19):
        alone = problem.solve(BALL.with_values(power=float(power[k]), shell_thickness=float(shell[k])))
        assert alone.status == "infeasible" and alone.diagnosis.startswith("proven infeasible")


def test_points_carried_past_one_left_to_its_own_verdict_show_the_proven_point_s_design():
    """cases/wedge_paper.toml over its guide length ratio (1x three times, then 8x-12x) with its outer diameter's
    limit at 200 mm, then 0.9, 1.05, 0.8 and 1.02 times the coupling's own diameter: point 3 proven by its own
    search, 4-7 carry it; 8, 9 and 13 break the outer diameter whatever the design (their own verdicts, the start's
    design); 10-12 and 14-23 carry point 3's proof on, each run its own words, and show point 3's design, not the
    last of those points' (review 22c)."""
    from clutchopt.cases import load_case
    from tests.conftest import CASES

    case = load_case(CASES / "wedge_paper.toml")
    v, quantities = case.values, {q.name: q for q in case.quantities}
    own = 2 * (v["radius_ratio"] * v["flank_inner_radius"] + v["shell_thickness"])
    ratio = v["guide_length_ratio"] * np.concatenate([[1, 1, 1], np.geomspace(8, 12, 21)])
    limit = np.full(24, v["outer_diameter_max"])
    limit[8:10], limit[10:13], limit[13], limit[14:] = 0.9 * own, 1.05 * own, 0.8 * own, 1.02 * own
    result = Sweep(case, [Vary(quantities["guide_length_ratio"], tuple(ratio.tolist())),
                          Vary(quantities["outer_diameter_max"], tuple(limit.tolist()))], mode="paper",
                   zipped=True).run(progress=False)
    records = result.solutions
    assert [r["status"] for r in records] == ["optimal"] * 3 + ["infeasible"] * 21
    assert all(records[k]["diagnosis"].startswith("infeasible whatever the design: outer_diameter") for k in (8, 9, 13))
    runs = {4: (4, 8), 10: (10, 13), 14: (14, 24)}
    for a, (_, b) in runs.items():
        assert all(f"({b - a} points, by the proof at" in records[k]["diagnosis"] for k in range(a, b))
    shown = records[3]["design"]
    assert all(records[k]["design"] == shown for a, b in runs.values() for k in range(a, b))
    assert records[8]["design"] != shown


def test_a_proof_is_carried_no_further_than_its_window_s_stretch(monkeypatch):
    """The cable over 10x-20x its torque in 1,100 points, a window's stretch without designs cut at 1,024 points
    (STRETCH_WINDOWS 1; 8,192 points as shipped): the points carried in the first window name as many points as show
    the words, the first point of the next window is solved and proven afresh (review 22c: the last run's words had
    counted it, 256 points shown by 255)."""
    from collections import Counter

    from clutchopt.optimise import batch

    monkeypatch.setattr(batch, "STRETCH_WINDOWS", 1)
    _, result = _swept(CABLE, "torque", np.geomspace(10, 20, 1100))
    diagnoses = [r["diagnosis"] for r in result.solutions]
    assert all(d.startswith("proven infeasible") for d in diagnoses) and result.spent["solves"] == 2
    assert diagnoses[1024].startswith("proven infeasible: no design within the bounds meets")
    for text, shown in Counter(d for d in diagnoses if "by the proof at" in d).items():
        assert f"({shown} points, by the proof at" in text


@settings(max_examples=60, deadline=None)
@given(st.floats(-2, 2), st.floats(-2, 2), st.floats(-3, 3), st.floats(0.1, 3), st.floats(0.1, 3),
       st.floats(0.1, 3), st.floats(0.1, 3), st.floats(0.1, 3), st.floats(0.1, 3))
def test_where_a_value_s_slope_and_its_limit_carry_a_proof_every_design_broken_stays_broken(
        a, b, c, lower, width, p_j, p_k, l_j, l_k):
    """A row x^a p^b + c x p >= l (its scale its limit l, a quantity of its own) over x in [lower, lower + width],
    p and l stepped together: wherever the step holds (the value's slope and the limit compared: Tightening.valued),
    every design sampled from the box whose row was broken by more than the tolerance at the first point is broken
    so at the second (the row g = 1 - v / l: review 22's ball, its power in the limit, its friction in the value)."""
    upper = lower + width
    posed = _posed(lambda x, p: 0.0)  # (its quantities a and b: the row built below)
    posed.formulation.constraints = lambda x, p: [at_least("row", x.x**a * p.a**b + c * x.x * p.a, p.b, equation="")]
    points = np.array([[p_j, l_j], [p_k, l_k]])
    if ProofCarry(posed, ["a", "b"], points).held_from(np.array([lower]), np.array([upper]), 0, 1, 2) < 2:
        return
    xs = np.linspace(lower, upper, 201)
    broken = [1 - (xs**a * p**b + c * xs * p) / limit for p, limit in ((p_j, l_j), (p_k, l_k))]
    assert np.all(broken[1][broken[0] > 1e-6] > 1e-6)


def test_one_row_with_its_limit_and_its_value_moved_carries_a_proof():
    """The ball beyond its edge (9.33x-18.7x its power) with its friction coefficient lowered to 0.7x, both at each
    step (zipped, 20 points): both move the torque row, T(x, f) >= k_s P / w, the power its limit, the friction its
    value (the balls' friction torque: its slope in f positive over the box); the limit compared, higher, and the
    value's slope (T falls as f does) carry the first point's proof to the other 19 (its normalised row's slope in P,
    T(x) / T_req^2 dT_req/dP, had spanned zero by the dependency of the quotient's interval bound: region searches);
    `solve` alone proves them."""
    quantities = {q.name: q for q in BALL.quantities}
    power = BALL.values["power"] * np.geomspace(9.33, 18.7, 20)
    friction = BALL.values["friction_coefficient"] * np.geomspace(1, 0.7, 20)
    result = Sweep(BALL, [Vary(quantities["power"], tuple(power.tolist())),
                          Vary(quantities["friction_coefficient"], tuple(friction.tolist()))],
                   mode=reference_mode("ball"), zipped=True).run(progress=False)
    records = result.solutions
    assert [r["status"] for r in records] == ["infeasible"] * 20 and result.spent["solves"] == 1
    assert all("(19 points, by the proof at power" in r["diagnosis"] for r in records[1:])
    problem = case_problem(BALL, reference_mode("ball"))
    for k in (1, 19):
        alone = problem.solve(BALL.with_values(power=float(power[k]), friction_coefficient=float(friction[k])))
        assert alone.status == "infeasible" and alone.diagnosis.startswith("proven infeasible")
