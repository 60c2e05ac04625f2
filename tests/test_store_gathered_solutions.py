"""A window's points solved alone that share a template (a region proof's points without a design) reach the run
store as arrays read from their Solutions (``window_records.gathered_solutions``), without building each point's
record: the store gets the same rows, byte for byte, as when it gathered their records itself
(``window_records.gathered``, as before)."""

import copy
import dataclasses
import sqlite3
from contextlib import closing

import numpy as np
import pytest

from clutchopt.bench.reference import reference_mode
from clutchopt.cases import load_case
from clutchopt.optimise.solution import Solution
from clutchopt.output import to_json
from clutchopt.store import RunStore
from clutchopt.store_kept import close_kept
from clutchopt.window_records import gathered, gathered_solutions
from conftest import CASES

POINTS = 24  # the lever over 0.5x-2x its inertia: its last 6 points have no design, proven as one region


@pytest.fixture(scope="module")
def lever():
    """The lever's sweep over its inertia, solved once: the sweep and its results (one batched window)."""
    from clutchopt.optimise.sweep import Sweep, solve_points
    from clutchopt.optimise.sweep_grid import Vary

    case = load_case(CASES / "lever_centrifuge.toml")
    quantity = next(q for q in case.quantities if q.name == "inertia")
    values = case.values["inertia"] * np.geomspace(0.5, 2.0, POINTS)
    sweep = Sweep(case, [Vary(quantity, tuple(values.tolist()))], mode=reference_mode("lever"))
    return sweep, list(solve_points(sweep.case, sweep.formulation.mode, sweep.objective.name, sweep.tol, None,
                                    sweep.grid))


def _dump(path) -> tuple[list, list]:
    """Every stored row of a store (its creation time left out) and its templates."""
    close_kept()
    with closing(sqlite3.connect(path)) as db:
        return (db.execute("SELECT id, kind, sweep_id, point, case_path, title, coupling, mode, objective_name, "
                           "status, objective, objective_unit, method, inputs, outputs, versions, run_count, window "
                           "FROM runs ORDER BY id").fetchall(),
                db.execute("SELECT key, body FROM templates ORDER BY key").fetchall())


def test_a_lever_sweeps_proven_points_are_stored_from_their_solutions_as_the_store_gathered_them(lever, tmp_path,
                                                                                                monkeypatch):
    # the 6 points past the lining pressure's reach have no design, one region proof covers them: the store gets
    # them as one window's arrays read from their Solutions (no Solution.as_dict() for any of them), and stores the
    # same bytes as from their records gathered by the store itself (main's way); read back, the same records
    sweep, parts = lever
    assert len(parts) == 1
    held_alone, held_windows = parts[0].held()
    infeasible = [k for k, record in held_alone.items() if record["status"] == "infeasible"]
    assert infeasible == list(range(POINTS - 6, POINTS)) and len(held_alone) == 7  # (and the sweep's first point)
    built = []
    monkeypatch.setattr(Solution, "as_dict", lambda self, built_as=Solution.as_dict: built.append(self) or
                        built_as(self))
    alone, windows = parts[0].stored()
    solutions = parts[0]._solutions
    assert list(alone) == [0] and {id(s) for s in built} == {id(solutions[0]), id(solutions[infeasible[0]])}
    # (a run's first point's record alone: whether a run can start there, its template)
    assert [positions.tolist() for positions, _ in windows] == [infeasible, held_windows[0][0].tolist()]
    monkeypatch.undo()

    paths = {}
    for form in ("held", "stored"):
        paths[form] = tmp_path / f"{form}.sqlite"
        with RunStore(paths[form]) as store:
            sweep_id = store.new_sweep(sweep.spec, POINTS)
            assert store.record_points(sweep._inputs(), sweep._where(sweep_id), parts[0].points.index,
                                       parts[0].points.columns, *getattr(parts[0], form)()) == POINTS
    rows, templates = _dump(paths["stored"])
    assert (rows, templates) == _dump(paths["held"])
    assert [(row[3], row[16]) for row in rows] == [(0, None), (1, POINTS - 7), (POINTS - 6, 6)]
    with RunStore(paths["stored"], writable=False) as store:
        read = store.sweep_outputs(1, sweep.points)
    assert to_json([read[k] for k in range(POINTS)], None) == to_json(parts[0].records(), None)


def _covered(lever) -> list[Solution]:
    """The lever sweep's Solutions of its points a region proof covers."""
    solutions = lever[1][0]._solutions
    return [solutions[k] for k in range(POINTS - 6, POINTS)]


def _same(found: tuple, expected: tuple) -> None:
    """gathered_solutions' outcome (Solutions kept alone) is gathered's of their records: the same kept positions and
    windows, their templates and arrays bit for bit."""
    (kept, windows), (kept_records, record_windows) = found, expected
    assert {k: solution.as_dict() for k, solution in kept.items()} == kept_records
    assert len(windows) == len(record_windows)
    for (positions, window), (record_positions, record_window) in zip(windows, record_windows):
        assert positions.tolist() == record_positions.tolist() and window.key == record_window.key
        assert window.template == record_window.template and window.labels == record_window.labels
        assert window.arrays.keys() == record_window.arrays.keys()
        for name, array in window.arrays.items():
            assert array.dtype == record_window.arrays[name].dtype
            assert array.tobytes() == record_window.arrays[name].tobytes(), name


def test_gathered_solutions_keeps_what_gathered_keeps_of_their_records(lever):
    # the runs broken where a record's template differs (a constraint's unit, a bound), a record holds more than a
    # template expands (the starts a verdict tried), a number is not of its array's type (a whole number where a
    # float goes): the same runs, kept points and arrays as gathered's of the records
    covered = _covered(lever)
    alone = {10 + k: copy.deepcopy(solution) for k, solution in enumerate(covered)}
    assert len(gathered_solutions(alone)[1]) == 1
    _same(gathered_solutions(alone), gathered({k: s.as_dict() for k, s in alone.items()}))
    alone[11].constraints[0] = dataclasses.replace(alone[11].constraints[0], unit="kN*m")
    alone[13] = dataclasses.replace(alone[13], starts=("the case's start",))
    found = gathered_solutions(alone)
    assert sorted(found[0]) == [10, 11, 12, 13] and [p.tolist() for p, _ in found[1]] == [[14, 15]]
    _same(found, gathered({k: s.as_dict() for k, s in alone.items()}))
    bounded = {k: copy.deepcopy(solution) for k, solution in enumerate(covered)}
    name = next(iter(bounded[2].bounds))
    bounded[2].bounds[name] = (bounded[2].bounds[name][0] * 0.5, bounded[2].bounds[name][1])
    bounded[4].constraints[1] = dataclasses.replace(bounded[4].constraints[1], limit=3)
    found = gathered_solutions(bounded)
    assert [p.tolist() for p, _ in found[1]] == [[0, 1]] and sorted(found[0]) == [2, 3, 4, 5]
    _same(found, gathered({k: s.as_dict() for k, s in bounded.items()}))


def test_a_run_with_sensitivities_at_some_points_reads_back_each_points_own(lever):
    # sensitivities at some points of a run and none at others (a point without a design has none): each point's
    # read back as its JSON, -0.0 and NaN (null) kept; the same names in another order keep the run rows, as before
    records = [solution.as_dict() for solution in _covered(lever)[:4]]
    records[1]["sensitivities"] = {"inertia": 0.25, "speed": -0.0, "friction": float("nan")}
    records[3]["sensitivities"] = {"inertia": -1.5, "speed": 2.0, "friction": 1e-300}
    for make in (lambda: gathered(dict(enumerate(records))), lambda: _as_solutions(lever, records)):
        kept, windows = make()
        assert kept == {} and [positions.tolist() for positions, _ in windows] == [[0, 1, 2, 3]]
        back = windows[0][1].records(json_numbers=True)
        assert [to_json(record, None) for record in back] == [to_json(record, None) for record in records]
        assert windows[0][1].arrays["sensitive"].tolist() == [[False, True, False, True]] * 3
    records[3]["sensitivities"] = {"speed": 2.0, "inertia": -1.5, "friction": 1e-300}
    assert list(gathered(dict(enumerate(records)))[0]) == [0, 1, 2, 3]
    assert list(_as_solutions(lever, records)[0]) == [0, 1, 2, 3]


def _as_solutions(lever, records: list[dict]) -> tuple:
    """gathered_solutions of the lever's covered Solutions with these records' sensitivities."""
    solutions = _covered(lever)[:len(records)]
    return gathered_solutions({k: dataclasses.replace(solution, sensitivities=record["sensitivities"])
                               for k, (solution, record) in enumerate(zip(solutions, records))})


def test_a_check_holds_its_fields_only_so_gathered_solutions_cannot_drop_one(lever):
    # gathered_solutions compares a run's checks by their fields (the first point's record laid out), so a check
    # that held an attribute of its own would reach the store without it: a check refuses one, and its record's keys
    # are the record layout's
    from clutchopt.optimise.verify import ConstraintCheck
    from clutchopt.records import CONSTRAINT_KEYS

    check = _covered(lever)[0].constraints[0]
    with pytest.raises(AttributeError):
        check.note = "extra"
    assert tuple(check.as_dict()) == CONSTRAINT_KEYS
    assert check.as_dict()["display_unit"] == check.unit and dataclasses.asdict(check).keys() <= set(CONSTRAINT_KEYS)
    assert type(check) is ConstraintCheck


def test_a_run_whose_multipliers_are_all_none_holds_the_nans_numpy_reads_them_as(lever):
    # a point without a design has no multipliers nor elasticities: every point's None, read as NaN at once
    # (window_records._array), the bytes NumPy makes of the Nones; a float among them (a point of its own) kept
    # where it is, NaN about it; read back, None again
    covered = {k: copy.deepcopy(solution) for k, solution in enumerate(_covered(lever))}
    constraints = len(covered[0].constraints)
    window = gathered_solutions(covered)[1][0][1]
    for name in ("multiplier", "elasticity"):
        assert window.arrays[name].shape == (constraints, 6)
        assert window.arrays[name].tobytes() == np.array([None] * constraints * 6, dtype="<f8").tobytes()
    assert not window.arrays["priced"].any()
    covered[4].constraints[2].multiplier = 0.25
    window = gathered_solutions(covered)[1][0][1]
    multipliers = window.arrays["multiplier"]
    assert multipliers[2, 4] == 0.25 and np.isnan(np.delete(multipliers.ravel(), 2 * 6 + 4)).all()
    assert np.isnan(window.arrays["elasticity"]).all()
    back = window.records(json_numbers=True)
    assert back[4]["constraints"][2]["multiplier"] == 0.25 and back[3]["constraints"][2]["multiplier"] is None


def test_a_run_whose_sensitivities_are_all_none_keeps_a_row_a_point():
    # (found in review) records read back (not Solutions) whose every sensitivity is None: the all-None shortcut
    # (window_records._array) keeps the sensitivities' row a point (a name a column), every name read back, where
    # it had kept one row of the points (the lever's 31 names: 30 lost)
    from clutchopt.optimise import solve_case
    from clutchopt.window_records import WindowRecords

    record = solve_case(load_case(CASES / "lever_centrifuge.toml")).as_dict()
    records = [{**copy.deepcopy(record), "sensitivities": dict.fromkeys(record["sensitivities"])} for _ in range(3)]
    window = WindowRecords.of(records)
    assert window.arrays["sensitivity"].shape == (len(record["sensitivities"]), 3) == (31, 3)
    assert [back["sensitivities"] for back in window.records(json_numbers=True)] == [r["sensitivities"]
                                                                                      for r in records]
