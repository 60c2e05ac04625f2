"""Every hostile input of tests/hostile_scatter.py through the CLI, in this process, judged as tests/test_hostile.py
judges its own: bad input ends in ``error:`` lines naming the field and exit code 2 with nothing on stdout and
nothing recorded; a fine input in exit code 0; never a traceback, never exit code 3, never a hang."""

import pytest

from hostile_scatter import HOSTILE, written
from test_hostile import run_in_process


def test_at_least_40_distinct_hostile_inputs():
    assert len(HOSTILE) >= 40 and len({h.name for h in HOSTILE}) == len(HOSTILE)
    assert {h.argv[0] for h in HOSTILE} >= {"solve", "pareto", "compare", "runs"}
    assert sum(h.expect is None for h in HOSTILE) >= 15 and sum(h.expect is not None for h in HOSTILE) >= 15


@pytest.fixture(scope="module")
def stores(tmp_path_factory):
    return tmp_path_factory.mktemp("robust-stores")


@pytest.mark.parametrize("hostile", HOSTILE, ids=lambda h: h.name)
def test_hostile_scatter_input(hostile, tmp_path, capsys, run_store, stores):
    run_in_process(hostile, written(hostile, tmp_path / "input", stores), capsys, run_store)
