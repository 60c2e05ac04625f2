"""Every hostile input of tests/hostile_units.py through the CLI, in this process, as tests/test_hostile.py runs its
own: bad input ends in ``error:`` lines naming the field and exit code 2, a fine input in exit code 0, never a
traceback, exit code 3 or a hang. Then the values the fine inputs stand for, and the speed of a refusal."""

import time

import pytest

from clutchopt.cli import EXIT_BAD_INPUT, main
from clutchopt.cases import parse_case
from clutchopt.units import to_si
from hostile_units import HOSTILE, MOTOR
from test_hostile import run_in_process


def test_at_least_40_distinct_inputs_fine_and_refused():
    assert len(HOSTILE) >= 40 and len({h.name for h in HOSTILE}) == len(HOSTILE)
    assert sum(h.expect is None for h in HOSTILE) >= 10  # the rules refuse no more than they should


@pytest.mark.parametrize("hostile", HOSTILE, ids=lambda h: h.name)
def test_hostile_input_in_process(hostile, tmp_path, capsys, run_store):
    run_in_process(hostile, hostile.write(tmp_path / "input"), capsys, run_store)


@pytest.mark.parametrize("text, unit, si", [
    ("600 1/h", "1/hour", 600 / 3600), ("10 1/hour", "1/hour", 10 / 3600), ("0.1667 1/min", "1/hour", 0.1667 / 60),
    ("20 %", "", 0.2), ("0.2", "", 0.2), (0.2, "", 0.2),
])
def test_counts_per_time_and_ratios_take_their_own_units(text, unit, si):
    assert to_si("field", text, unit) == pytest.approx(si, rel=1e-15)


def test_a_case_reads_starts_per_hour_and_slip_as_meant():
    import tomllib

    text = MOTOR.replace('starts_per_hour = "10 1/hour"', 'starts_per_hour = "600 1/h"')
    values = parse_case(tomllib.loads(text.replace("breakdown_slip = 0.2", 'breakdown_slip = "20 %"'))).values
    assert values["starts_per_hour"] == pytest.approx(600 / 3600, rel=1e-15) and values["breakdown_slip"] == 0.2


def test_every_sweep_value_is_checked_before_the_first_solve(tmp_path, capsys):
    """The refused point comes last: before issue 25 the sweep solved 15 to 23 s before it."""
    path = tmp_path / "case.toml"
    path.write_text(MOTOR)
    started = time.perf_counter()
    code = main(["sweep", str(path), "--vary", "synchronous_speed=1000,1000,1000,1e9", "--quiet", "--no-store"])
    assert code == EXIT_BAD_INPUT and time.perf_counter() - started < 5.0
    assert capsys.readouterr().err.startswith("error: --vary (point 3): start_up.driver.synchronous_speed: ")
