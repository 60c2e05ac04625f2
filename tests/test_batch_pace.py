"""The length of a batched sweep's next chain (clutchopt/optimise/batch_pace.py): doubling along smooth stretches,
aimed at the next expected integer break, a probe after an aimed chain passed."""

import casadi as ca
import numpy as np

from clutchopt.optimise.batch_pace import BatchPace, until_active
from clutchopt.optimise.batch_window import Block


def test_chains_double_while_they_pass_and_restart_after_a_point_solved_alone():
    pace = BatchPace(8, 256)
    sizes = [pace.size]
    for _ in range(6):
        pace.passed()
        sizes.append(pace.size)
    assert sizes == [8, 16, 32, 64, 128, 256, 256]
    pace.restart()
    assert pace.size == 8


def test_the_next_chain_ends_where_the_next_break_is_expected():
    # breaks of the ball clutch's sweep over its speed (100 points, 0.5x-2x): 23, 32, 41, 51, 62, 75, 89.
    # After 23 no gap is known: 8 points, then two probes of 1. After 32: one gap, 9, no growth known: 9 points less
    # the one short, 8 (33 .. 40; probe 41). After 41: gaps 9, 9 -> 9 * 9/9 = 9 - 1 = 8 (42 .. 49; probes 50, 51).
    # After 51: gaps 9, 10 -> 10 * 10/9 = 11.1 -> 11 - 1 = 10 (52 .. 61; probe 62). After 62: gaps 10, 11 -> 11 *
    # 11/10 = 12.1 -> 12 - 1 = 11. After 75: 11, 13 -> 13 * 13/11 = 15.4 -> 15 - 1 = 14 (76 .. 89, the break on the
    # last)
    pace = BatchPace(8, 256)
    pace.broke(23)
    assert pace.size == 8
    pace.passed()
    assert pace.size == 1
    pace.passed()
    assert pace.size == 1  # the second probe
    pace.passed()
    assert pace.size == 2  # doubling again after the probes
    expected = {32: 8, 41: 8, 51: 10, 62: 11, 75: 14}
    for k, size in expected.items():
        pace.broke(k)
        assert pace.size == size, k
    pace.restart()  # a point solved alone: no probes left
    pace.passed()
    assert pace.size == 16


def test_a_worse_neighbour_with_a_design_makes_the_next_chains_probes():
    # ball_crusher's rows: at one point one row more is promised a gain and, solved, does worse (kept: no change of
    # the integers, no break), at the next the rows carry no more. Breaks at 3 and 8 (gap 5: next aim 5 - 1 = 4);
    # near() then makes the next two chains one point long and records no break, so the gaps stay those between
    # changes: a break at 14 gives gaps 5, 6 -> 6 * 6/5 = 7.2 -> 7, one short: 6
    pace = BatchPace(8, 256)
    for k in (3, 8):
        pace.broke(k)
    assert pace.size == 4 and pace._aimed
    pace.near()
    assert pace.size == 1 and not pace._aimed
    pace.passed()
    assert pace.size == 1
    pace.passed()
    assert pace.size == 2
    pace.broke(14)
    assert pace.size == 6


def test_the_growth_of_the_gap_is_bounded():
    # gaps 2 then 20: growth 10 bounded to 2 -> 40 points, one short: 39; gaps 40 then 4: growth 0.1 bounded to 0.5
    # -> 2, one short: 1; gaps 1 then 1: 1, one short 0, at least 1; a prediction never exceeds the longest chain
    pace = BatchPace(8, 256)
    for k in (0, 2, 22):
        pace.broke(k)
    assert pace.size == 39
    pace = BatchPace(8, 256)
    for k in (0, 40, 44):
        pace.broke(k)
    assert pace.size == 1
    pace = BatchPace(8, 256)
    for k in (0, 1, 2):
        pace.broke(k)
    assert pace.size == 1
    pace = BatchPace(8, 64)
    for k in (0, 50, 150):
        pace.broke(k)
    assert pace.size == 64


class _Posed:
    """A posed problem's two members ``until_active`` reads: one inequality row g = x_0 + x_1 - 1 <= 0."""

    n_ineq = 1

    def __init__(self):
        x, p = ca.SX.sym("x", 2), ca.SX.sym("p", 1)
        self.constraint_values = ca.Function("g", [x, p], [x[0] + x[1] - 1])

    def mapped(self, function, count):  # as Posed.mapped's InPlace: the outputs as a list of arrays
        return lambda *args: [np.array(function.map(count)(*args))]


def _block(x0, x1, lam_g=0.0):
    x = np.array([x0, x1], dtype=float)
    return Block(np.array([4, 5]), x=x, lam_x=np.zeros((2, 2)), lam_g=np.full((1, 2), lam_g), p=np.zeros((1, 2)),
                 lbx=np.zeros((2, 2)), ubx=np.ones((2, 2)))


def test_a_chain_ends_where_a_slack_is_expected_to_close():
    # x_0 0.3 -> 0.4, x_1 0.2 -> 0.2: the row's slack 1 - x_0 - x_1 is 0.5 then 0.4 (step -0.1); at evenly spaced
    # points it is 0.3, 0.2, 0.1, 0.0 at the 1st .. 4th point ahead: active at the 4th. x_0's distance to its upper
    # bound 1 closes too (0.6 after 6 more), later. Where the case's steps double at each point (a geometric sweep,
    # ratio 2): 0.4 - 0.1 (2 + 4) < 0 at the 2nd point ahead
    posed, free = _Posed(), np.array([True, True])
    block = _block([0.3, 0.4], [0.2, 0.2])
    assert until_active(posed, block, np.ones(10), free, 1e-9) == 4
    assert until_active(posed, block, np.full(10, 2.0), free, 1e-9) == 2
    # a ratio of 0 (no step known) counts as 1
    assert until_active(posed, block, np.zeros(10), free, 1e-9) == 4
    # an active row (its multiplier non-zero) and opening slacks forecast nothing; nor does a single point
    assert until_active(posed, _block([0.3, 0.4], [0.2, 0.2], lam_g=1.0), np.ones(10), np.array([False, False]),
                        1e-9) is None
    assert until_active(posed, _block([0.4, 0.3], [0.2, 0.2]), np.ones(10), np.array([False, False]), 1e-9) is None
    # (x_0 falling 0.4 -> 0.3 towards its lower bound 0, a variable left free: 0.3 - 3 * 0.1 = 0 at the 3rd point)
    assert until_active(posed, _block([0.4, 0.3], [0.2, 0.2]), np.ones(10), free, 1e-9) == 3
    assert until_active(posed, Block(np.array([5]), **{k: v[:, 1:] for k, v in block.arrays.items()}), np.ones(10),
                        free, 1e-9) is None
    # beyond the ratios given (the sweep's end): None
    assert until_active(posed, block, np.ones(3), free, 1e-9) is None
