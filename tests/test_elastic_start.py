"""The elastic problem's first slacks (``diagnosis._slacks``): each row's violation at the failed run's point, within
its bounds, plus SLACK_MARGIN, at most 1 (where every slack had started); 1 where the row is not a number there. A
start at a row's huge violation, or at NaN, had stopped IPOPT before its first iteration (review 19)."""

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import diagnosis
from clutchopt.optimise.problem import case_problem
from tests.conftest import CASES


def _fan():
    case = load_case(CASES / "wedge_fan.toml").with_values(speed=980 * 2.5 * np.pi / 30)  # (no design)
    posed = case_problem(case, "geometry").posed
    return posed, posed.scaled_data(case)


def test_a_row_violated_by_more_than_the_margin_allows_starts_its_slack_at_1():
    posed, data = _fan()
    x = data.x0.copy()
    x[4] = 1e200  # (weight_width far beyond its upper bound: clipped onto it, as IPOPT starts)
    g = np.array(posed.constraint_values(np.clip(x, data.lbx, data.ubx), data.p)).ravel()[: posed.n_ineq]
    slacks = diagnosis._slacks(posed, data.p, data.lbx, data.ubx, x)
    assert np.all(np.isfinite(slacks)) and slacks.max() <= 1.0
    assert slacks == pytest.approx(np.minimum(np.maximum(g, 0.0) + diagnosis.SLACK_MARGIN, 1.0))
    found = diagnosis.diagnose(posed, data.p, data.lbx, data.ubx, x, data.scale)
    assert found.least == pytest.approx(0.1607089, rel=1e-5)  # (as from the case's own start; was nan)
    assert found.violated == ("weight_covers_flank", "finger_guide_length")


def test_a_row_that_is_not_a_number_at_the_point_starts_its_slack_at_1():
    case = load_case(CASES / "wedge_motor_start.toml")
    posed = case_problem(case, "geometry").posed
    data = posed.scaled_data(case)
    x = data.x0.copy()
    x[2] = data.ubx[2]  # (weight_height at its upper bound: the engagement speeds' rows NaN, a root of a negative)
    g = np.array(posed.constraint_values(x, data.p)).ravel()[: posed.n_ineq]
    assert not np.all(np.isfinite(g))
    slacks = diagnosis._slacks(posed, data.p, data.lbx, data.ubx, x)
    assert np.all(slacks[~np.isfinite(g)] == 1.0) and np.all(np.isfinite(slacks))
