"""Every hostile input of tests/hostile_surfaces.py through the CLI, in this process, as tests/test_hostile.py runs
its own: bad input ends in ``error:`` lines naming the field and exit code 2, a fine input in exit code 0, never a
traceback, exit code 3 or a hang."""

import pytest

from hostile_surfaces import HOSTILE
from test_hostile import run_in_process


def test_distinct_inputs_fine_and_refused():
    assert len({h.name for h in HOSTILE}) == len(HOSTILE)
    assert sum(h.expect is None for h in HOSTILE) >= 5 and sum(h.expect is not None for h in HOSTILE) >= 10


@pytest.mark.parametrize("hostile", HOSTILE, ids=lambda h: h.name)
def test_hostile_input_in_process(hostile, tmp_path, capsys, run_store):
    run_in_process(hostile, hostile.write(tmp_path / "input"), capsys, run_store)
