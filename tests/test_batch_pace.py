"""The length of a batched sweep's next chain (clutchopt/optimise/batch_pace.py): doubling along smooth stretches,
aimed at the next expected integer break, a probe after an aimed chain passed."""

from clutchopt.optimise.batch_pace import BatchPace


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
    # After 23 no gap is known: 8 points, then a probe of 1. After 32: one gap, 9, no growth known: 9 points
    # (33 .. 41, the break on the last). After 41: gaps 9, 9 -> 9 * 9/9 = 9 (42 .. 50 pass; probe 51). After 51:
    # gaps 9, 10 -> 10 * 10/9 = 11.1 -> 11 (52 .. 62, the break on the last). After 62: gaps 10, 11 -> 11 * 11/10 =
    # 12.1 -> 12. After 75: 11, 13 -> 13 * 13/11 = 15.4 -> 15.
    pace = BatchPace(8, 256)
    pace.broke(23)
    assert pace.size == 8
    pace.passed()
    assert pace.size == 1
    pace.passed()
    assert pace.size == 2  # doubling again after the probe
    expected = {32: 9, 41: 9, 51: 11, 62: 12, 75: 15}
    for k, size in expected.items():
        pace.broke(k)
        assert pace.size == size, k


def test_the_growth_of_the_gap_is_bounded():
    # gaps 2 then 20: growth 10 bounded to 2 -> 40 points; gaps 40 then 4: growth 0.1 bounded to 0.5 -> 2; a
    # prediction never exceeds the longest chain
    pace = BatchPace(8, 256)
    for k in (0, 2, 22):
        pace.broke(k)
    assert pace.size == 40
    pace = BatchPace(8, 256)
    for k in (0, 40, 44):
        pace.broke(k)
    assert pace.size == 2
    pace = BatchPace(8, 64)
    for k in (0, 50, 150):
        pace.broke(k)
    assert pace.size == 64
