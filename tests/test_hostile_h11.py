"""A hostile user on this session's new surfaces (the run store's ``sweep_starts``, ``CLUTCHOPT_BUILD_LATER``, paper
modes): each test is one finding's repro, the command as a user types it and what it must answer. No hand
calculation where the reference is the same command on an undamaged store.

Finding 1: a ``sweep_starts`` row damaged inside valid JSON (an array cut short, a NaN, a zero scale, a string where a
count is meant, a start of another problem's length) made ``sweep --resume`` end in ``internal error:`` (exit 3,
a crash file) or print CasADi's NaN diagnostics; it is now an ``error: --store`` line naming the sweep and point,
exit 2, nothing recorded (batch_carried.Carried.from_dict).
"""

import json
import sqlite3
from contextlib import closing

import pytest

import clutchopt.optimise.batch as batch
from clutchopt.cases import load_case
from clutchopt.cli.main import main
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from clutchopt.store import RunStore
from conftest import CASES

# the ball over 1x-10x its power in design mode (test_resume_agrees.py's sweep): with a window's work cut to 64, its
# windows end at points 1, 40, 41, 49, ...; the store is cut at 49 as a kill inside the window from 49 leaves it
SWEEP = ("ball_compressor.toml", "power=1200:12000:100", "design")
CUT = 49


@pytest.fixture(scope="module")
def whole(tmp_path_factory):
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(batch, "WINDOW_WORK", 64)
        path = tmp_path_factory.mktemp("whole") / "runs.sqlite"
        file, text, mode = SWEEP
        case = load_case(CASES / file)
        with RunStore(path) as store:
            Sweep(case, [parse_vary(text, case.coupling)], mode=mode).run(store, progress=False)
    with closing(sqlite3.connect(path)) as db:
        assert CUT in [row[0] for row in db.execute("SELECT point FROM sweep_starts")]
    return path


def _cut(whole, tmp_path, damage) -> str:
    """The whole sweep's store as a kill inside the window from CUT leaves it, its start at CUT passed through
    ``damage`` (the JSON as a dict: changed in place)."""
    path = tmp_path / "cut.sqlite"
    with closing(sqlite3.connect(whole)) as source, closing(sqlite3.connect(path)) as db:
        source.backup(db)  # (with what the whole sweep's WAL holds)
        db.execute("DELETE FROM runs WHERE point >= ?", (CUT,))
        db.execute("DELETE FROM sweep_starts WHERE point > ?", (CUT,))
        body = json.loads(db.execute("SELECT body FROM sweep_starts WHERE point = ?", (CUT,)).fetchone()[0])
        damage(body)
        db.execute("UPDATE sweep_starts SET body = ? WHERE point = ?", (json.dumps(body), CUT))
        db.commit()
    return str(path)


def _runs(path) -> list:
    with closing(sqlite3.connect(path)) as db:
        return db.execute("SELECT * FROM runs ORDER BY id").fetchall()


def _set(where: str, value):
    def damage(body):
        *keys, last = where.split(".")
        for key in keys:
            body = body[key]
        body[last] = value(body[last]) if callable(value) else value
    return damage


DAMAGES = {
    "x_cut_short": _set("start.x", lambda x: x[:-1]),
    "x_nan": _set("start.x", lambda x: [float("nan")] * len(x)),
    "scale_inf": _set("start.scale", lambda s: [float("inf")] * len(s)),
    "scale_zero": _set("start.scale", lambda s: [0.0] * len(s)),
    "x_a_string": _set("start.x", "abc"),
    "start_without_arrays": _set("start", {}),
    "ahead_a_string": _set("ahead", "abc"),
    "ahead_negative": _set("ahead", -5),
    "pace_empty": _set("pace", {}),
    "pace_size_zero": _set("pace.size", 0),
    "feasible_a_string": _set("feasible", "x"),
    "feasible_other_names": _set("feasible", {"nonsense": 1.0}),
    # every array one shorter: internally consistent, another problem's start (4 variables, not the ball's 5)
    "another_problems_start": lambda body: body["start"].update(
        {key: value[:-1] for key, value in body["start"].items() if isinstance(value, list)}),
}


@pytest.mark.parametrize("name", DAMAGES)
def test_a_resume_from_a_damaged_stored_start_is_an_error_naming_the_store_and_point(whole, tmp_path, name, capsys):
    path = _cut(whole, tmp_path, DAMAGES[name])
    before = _runs(path)
    file, text, mode = SWEEP
    code = main(["sweep", str(CASES / file), "--vary", text, "--mode", mode, "--resume", "--store", path, "--quiet",
                 "--json"])
    err = capsys.readouterr().err
    assert code == 2, err
    assert err.startswith(f"error: --store: {path}: sweep 1's start at point {CUT} is damaged ("), err
    assert "Traceback" not in err and "internal error" not in err and "Input" not in err  # (CasADi's NaN report)
    assert _runs(path) == before  # nothing recorded


def test_a_resume_from_an_undamaged_cut_store_goes_on(whole, tmp_path, capsys):
    # the control of the test above: the same store, its start untouched, resumes to the 91 designs and 9 proofs
    path = _cut(whole, tmp_path, lambda body: None)
    file, text, mode = SWEEP
    code = main(["sweep", str(CASES / file), "--vary", text, "--mode", mode, "--resume", "--store", path, "--quiet",
                 "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0
    statuses = [point["status"] for point in out["points"]]
    assert (statuses.count("optimal"), statuses.count("infeasible")) == (91, 9)


# Finding 2: `pareto --json` on a case whose optimum is proven infeasible gave the row's status with the least-violation
# point's mass, cost and design but not why (the proof solve's JSON gives): ball_conveyor in paper mode (its 1.0 GPa
# contact stress cannot be met with the paper's width ratio, eqs. 4, 9: solve says "proven infeasible ... 129 boxes")
def test_pareto_json_of_a_proven_infeasible_case_gives_the_proof(cli):
    result = cli("pareto", "cases/ball_conveyor.toml", "--mode", "paper", "--points", "4", "--json", "--no-store",
                 "--quiet", timeout=300)
    assert result.returncode == 0, result.stderr
    rows = json.loads(result.stdout)["rows"]
    assert [row["status"] for row in rows] == ["infeasible"]
    assert rows[0]["diagnosis"].startswith("proven infeasible: no design within the bounds meets torque, "
                                           "contact_stress,")


def test_pareto_json_of_an_optimal_front_has_no_diagnosis(cli):
    result = cli("pareto", "cases/wedge_paper.toml", "--points", "3", "--json", "--no-store", "--quiet", timeout=300)
    assert result.returncode == 0, result.stderr
    rows = json.loads(result.stdout)["rows"]
    assert rows and all(row["status"] == "optimal" and row["diagnosis"] is None for row in rows)


# Finding 3: $CLUTCHOPT_BUILD_LATER of 5,000 characters was refused as "(5002 characters)": the count was of its repr
# (the quotes). Spaces and tabs around a word are ignored (documented); a look-alike word (full-width) is refused.
@pytest.mark.parametrize("value, code", [("\t1", 0), (" TRUE ", 0), ("1\n", 0), ("oN", 0), ("\uff4f\uff4e", 2),
                                         ("-1", 2), ("x" * 5000, 2)],
                         ids=["tab_1", "spaced_TRUE", "1_newline", "oN", "full_width_on", "minus_1", "5000_chars"])
def test_the_build_later_switch_reads_odd_values_one_way(value, code, monkeypatch, cli):
    monkeypatch.setenv("CLUTCHOPT_BUILD_LATER", value)
    result = cli("couplings", timeout=120)
    assert result.returncode == code, result.stderr
    if code:
        assert result.stderr.startswith("error: $CLUTCHOPT_BUILD_LATER: must be on (1, true, yes, on) or off"), \
            result.stderr
        assert "Traceback" not in result.stderr and not result.stdout
    if len(value) == 5000:
        assert result.stderr.rstrip().endswith("... (5000 characters)"), result.stderr
