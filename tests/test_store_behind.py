"""A sweep's windows committed by the store's writer thread (clutchopt.store_behind) while the sweep goes on."""

import threading

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise.sweep import Sweep, solve_points
from clutchopt.optimise.sweep_grid import parse_vary
from clutchopt.store import RunStore
from tests.conftest import CASES


@pytest.fixture(scope="module")
def solved():
    """A 40-point wedge sweep solved in windows of 10 (not yet stored)."""
    sweep = Sweep(load_case(CASES / "wedge_paper.toml"), [parse_vary("speed=500:3000:40", "wedge")])
    task = (sweep.case, sweep.formulation.mode, sweep.objective.name, sweep.tol, None)
    return sweep, [part for start in range(0, 40, 10) for part in solve_points(*task, sweep.grid[start:start + 10])]


def test_windows_handed_to_the_writer_are_committed_there_one_at_a_time(solved, tmp_path, monkeypatch):
    # each window's transaction runs in the writer thread, after the one before it has ended; settle() waits for the
    # last and says how many points it recorded; every point is then read back once
    sweep, parts = solved
    where, running = [], []
    transaction = RunStore._transaction

    def watched(store, execute, rows):
        running.append(rows)
        where.append((threading.current_thread().name, len(running)))
        try:
            return transaction(store, execute, rows)
        finally:
            running.pop()

    monkeypatch.setattr(RunStore, "_transaction", watched)
    with RunStore(tmp_path / "runs.sqlite") as store:
        sweep_id = store.new_sweep(sweep.spec, 40)
        for part in parts:
            assert store.record_points(sweep._inputs(), sweep._where(sweep_id), part.points.index,
                                       part.points.columns, *part.stored(), behind=True) is None
        assert store.settle() == 10 and store.settle() == 0
        assert sorted(store.sweep_outputs(sweep_id, sweep.points)) == list(range(40))
    assert where[0] == ("MainThread", 1)  # the sweep's row
    assert [name.startswith("clutchopt-store-writer") and depth == 1 for name, depth in where[1:]] == [True] * 4


def test_what_the_writer_raises_is_raised_where_the_sweep_settles(solved, tmp_path, monkeypatch):
    # a failing store is a warning and the run goes on (RunStore.failure); anything else the writer meets is raised
    # in the sweep's thread, by settle() or, at the latest, by close()
    sweep, parts = solved
    part = parts[0]
    store = RunStore(tmp_path / "runs.sqlite")
    sweep_id = store.new_sweep(sweep.spec, 40)
    monkeypatch.setattr(RunStore, "_transaction", lambda *args: 1 / 0)
    for settle in (store.settle, store.close):
        store.record_points(sweep._inputs(), sweep._where(sweep_id), part.points.index, part.points.columns,
                            *part.stored(), behind=True)
        with pytest.raises(ZeroDivisionError):
            settle()
