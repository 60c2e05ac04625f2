"""Mean-value bounds and the contraction they give (clutchopt.optimise.interval_contract): every design a box holds
stays in it, and a search near a limit needs far fewer boxes."""

from functools import lru_cache

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from clutchopt.cases import load_case
from clutchopt.optimise.interval_contract import contracted
from clutchopt.optimise.interval_proof import _bounds, _search_problem, empty_design_space, \
    interval_functions
from clutchopt.optimise.problem import case_problem
from conftest import CASES

PATHS = ["wedge_paper.toml", "lever_centrifuge.toml", "cable_conveyor.toml", "ball_crusher.toml"]


@lru_cache(maxsize=None)
def _posed(path):
    case = load_case(CASES / path)
    posed = case_problem(case).posed
    p, lower, upper = _search_problem(posed, case)
    return posed, p, lower, upper


@pytest.mark.parametrize("path", PATHS)
@settings(max_examples=15, deadline=None)
@given(st.lists(st.floats(0, 1), min_size=16, max_size=16), st.floats(-6, -0.5), st.floats(0.05, 0.95))
def test_every_value_and_every_point_within_a_row_s_limit_stay_in_the_bounds(path, fractions, log_width, quantile):
    """Random boxes of the design box (a random centre, a relative width 10^-6 to 10^-0.5): the rows' values at 200
    random points lie within the mean-value bounds met with the natural ones (interval_proof._bounds), and
    contracting the box by one row at a limit (a quantile of its sampled values, so that some points are within it
    and some beyond) keeps every point where that row is within the limit (the contraction's promise)."""
    posed, p, lower, upper = _posed(path)
    functions = interval_functions(posed)
    n = len(lower)
    centre = lower + (upper - lower) * np.array(fractions[:n])
    half = (upper - lower) * 10 ** log_width * np.array(fractions[n:2 * n]) / 2 + 1e-300
    lo, hi = np.maximum(centre - half, lower), np.minimum(centre + half, upper)
    lo[posed.integer], hi[posed.integer] = np.round(lo[posed.integer]), np.round(lo[posed.integer])
    (g_lo, g_hi), (d_lo, d_hi), mid, (c_lo, _), _ = _bounds(functions, lo[:, None], hi[:, None], (p[:, None],) * 2)
    rng = np.random.default_rng(len(fractions) + int(1e6 * quantile))
    x = lo[:, None] + (hi - lo)[:, None] * rng.random((n, 200))
    g = np.array(functions[0].function.map(200)(x, np.repeat(p[:, None], 200, axis=1)))
    tolerance = 1e-12 * (1 + np.abs(g))  # the NLP's own rows in float64 against true bounds
    assert np.all(g >= g_lo - tolerance) and np.all(g <= g_hi + tolerance)
    for row in range(g.shape[0]):
        limit = float(np.quantile(g[row], quantile))
        new_lo, new_hi, empty, _ = contracted(lo[:, None], hi[:, None], mid, c_lo[[row]], d_lo[[row]], d_hi[[row]],
                                              limit)
        within = x[:, g[row] <= limit - 1e-12 * (1 + abs(limit))]
        if within.size:
            assert not empty[0]
            assert np.all(within >= new_lo) and np.all(within <= new_hi), (row, limit)


def test_a_linear_row_cuts_the_box_to_its_half_plane():
    """g = x0 + 2 x1 - 1 over [0, 1]^2 (centre 0.5, 0.5: g(c) = 0.5, J = (1, 2)): g <= 0 needs
    x0 <= 1 - 2 x1, least at x1 = 0: x0 <= 1 (no cut), and x1 <= (1 - x0)/2 <= 0.5: the box [0, 1] x [0, 0.5]; at
    limit -1.5 (x0 + 2 x1 <= -0.5) the box is empty, the row named."""
    lo, hi, centre = np.zeros((2, 1)), np.ones((2, 1)), np.full((2, 1), 0.5)
    d = np.array([[[1.0], [2.0]]])
    new_lo, new_hi, empty, _ = contracted(lo, hi, centre, np.array([[0.5]]), d, d, 0.0)
    assert not empty[0] and new_lo[:, 0].tolist() == [0.0, 0.0]
    assert new_hi[:, 0] == pytest.approx([1.0, 0.5], rel=1e-10) and new_hi[1, 0] >= 0.5
    _, _, empty, cutters = contracted(lo, hi, centre, np.array([[0.5]]), d, d, -1.5)
    assert empty[0] and cutters[0, 0]


def test_a_proof_near_the_contact_stress_limit_takes_far_fewer_boxes():
    """ball_crusher at 600 kW (just past 560 kW, its last design): the natural and mean-value bounds alone proved it
    over 24,811 boxes (main before the contraction and the curvatures written with each variable once); now 8,235."""
    case = load_case(CASES / "ball_crusher.toml").with_values(power=600e3)
    emptiness = empty_design_space(case_problem(case).posed, case)
    assert emptiness.proven and emptiness.feasible is None and "contact_stress" in emptiness.decisive
    assert emptiness.boxes < 12_000


def test_a_conflict_of_two_linear_rows_is_proven_in_one_box():
    """The wedge paper case at 1000x its resisting torque: torque and flank pressure conflict everywhere; the
    natural bounds needed 129 boxes (one, then 128 halves), the contraction empties the first box. The finger's
    guide and chord rows (paper mode poses them too) cut its d_n first (to 13.3 and 15.3 mm): named, as rows that
    cut are."""
    case = load_case(CASES / "wedge_paper.toml")
    case = case.with_values(resisting_torque=case.values["resisting_torque"] * 1000)
    emptiness = empty_design_space(case_problem(case).posed, case)
    assert emptiness.proven and emptiness.boxes == 1
    assert set(emptiness.decisive) == {"torque", "flank_pressure", "finger_guide_length", "finger_fits_chord"}


def test_a_run_over_the_lever_s_speed_is_proven_with_its_speed_split_where_it_spreads_the_rows():
    """The lever (paper mode) at 2131-2351 rpm (8 points of the bench's sweep over 0.5x-2x its speed, none with a
    design): the torque takes the speed squared, and at a fixed design the torque row over the whole interval was
    bounded by [-0.005, 0.258] where its values are 0.073 to 0.174 at the ends; no design variable's split narrows
    that, and the search gave up after 2,600-3,000 boxes (its boxes left doubling) whatever the budget. Split where
    the speed spreads the rows more than the design does, it is proven (2,101 boxes); a box's speeds are always
    within the run's."""
    from clutchopt.bench.reference import bench_cases, reference_mode
    from clutchopt.optimise.interval_proof import searches
    from clutchopt.optimise.region_proof import _region_problem

    case = next(c for c in bench_cases() if c.coupling == "lever")
    posed = case_problem(case, reference_mode("lever")).posed
    speeds = [v for v in case.values["speed"] * np.geomspace(0.5, 2.0, 100) if 223.1 <= v <= 246.2]
    problem = _region_problem([_search_problem(posed, case.with_values(speed=v)) for v in speeds])
    k = [q.name for q in posed.formulation.quantities].index("speed")
    assert len(speeds) == 8 and (problem[0][k], problem[3][k]) == (min(speeds), max(speeds))
    outcome, = searches(posed, [problem], [40_000])
    assert outcome.proven and outcome.boxes < 5_000
    assert {"torque", "lining_pressure"} <= set(outcome.decisive)


def test_the_compiled_contraction_gives_the_numpy_contraction_s_numbers():
    """Random boxes (1-7 rows, 1-10 variables, 1-49 boxes, every fourth draw one box; infinite ends and slopes, zero
    slopes, NaN and -inf at the centre): the compiled contraction's ends, empty boxes and cutters are the NumPy
    rule's, every number equal (a box's sweeps stop where it is empty or did not move, where the sweeps over all
    boxes leave it), and the NumPy rule gives a box alone what it gives it among others. One box and 8 or more
    variables is where NumPy's own sum over the variables would add them pairwise, not from the first on as over a
    batch (the axis then innermost). The draws cut and empty boxes: the rule's every branch is taken."""
    from clutchopt.optimise import interval_contract_compiled

    if interval_contract_compiled.library() is None:
        pytest.skip("no C compiler or cache folder")
    rng = np.random.default_rng(7)
    emptied = cut = alone = 0
    for trial in range(600):
        m, n, count = rng.integers(1, 8), rng.integers(1, 11), 1 if trial % 4 == 1 else rng.integers(1, 50)
        lo = rng.normal(size=(n, count))
        hi = lo + rng.random((n, count)) * rng.choice([0.0, 1e-3, 1.0, 10.0], size=(n, count))
        if trial % 3 == 0:
            lo[rng.random((n, count)) < 0.1], hi[rng.random((n, count)) < 0.1] = -np.inf, np.inf
        with np.errstate(invalid="ignore"):
            centre = np.nan_to_num(0.5 * (lo + hi), nan=0.0, posinf=1.0, neginf=-1.0)
        centre = np.clip(centre, lo, hi)
        c_lo = rng.normal(size=(m, count)) * rng.choice([0.01, 1.0, 100.0])
        c_lo[rng.random((m, count)) < 0.05], c_lo[rng.random((m, count)) < 0.05] = np.nan, -np.inf
        slope = rng.normal(size=(m, n, count)) * rng.choice([0.1, 1.0, 10.0])
        spread = rng.random((m, n, count)) * rng.choice([0.01, 1.0])
        d_lo, d_hi = slope - spread, slope + spread
        d_lo[rng.random((m, n, count)) < 0.05], d_hi[rng.random((m, n, count)) < 0.05] = -np.inf, np.inf
        flat = rng.random((m, n, count)) < 0.1
        d_lo[flat], d_hi[flat] = 0.0, 0.0
        limit = rng.choice([0.0, 1e-6, -0.5])
        with np.errstate(invalid="ignore"):
            numpy_rule = contracted(lo, hi, centre, c_lo, d_lo, d_hi, limit, compiled=False)
        compiled_rule = contracted(lo, hi, centre, c_lo, d_lo, d_hi, limit)
        for a, b in zip(compiled_rule, numpy_rule):
            assert a.shape == b.shape and a.dtype == b.dtype
            assert np.all((a == b) | (np.isnan(a) & np.isnan(b)) if a.dtype.kind == "f" else a == b), trial
        b = int(rng.integers(count))
        with np.errstate(invalid="ignore"):
            one_box = contracted(lo[:, [b]], hi[:, [b]], centre[:, [b]], c_lo[:, [b]], d_lo[..., [b]],
                                 d_hi[..., [b]], limit, compiled=False)
        for a, batched in zip(one_box, numpy_rule):
            a, batched = a[..., 0], batched[..., b]
            assert np.all((a == batched) | (np.isnan(a) & np.isnan(batched)) if a.dtype.kind == "f"
                          else a == batched), trial
        emptied, cut = emptied + int(numpy_rule[2].sum()), cut + int(numpy_rule[3].sum())
        alone += int(count == 1 and n >= 8)
    assert emptied > 1000 and cut > 3000 and alone > 20, (emptied, cut, alone)
