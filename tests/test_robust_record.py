"""How a design was made is recorded and shown (issue 25): the run store keeps the method (nominal, worst-case,
chance=P), the scatter and the robust result (corners, samples, simulated starts) of every solve, sweep point and
Pareto point; ``runs list`` and ``runs export`` show the method, a store of an older version still reads. ``solve
--robust --verify`` starts the robust design at every corner of its scatter; ``pareto --json`` shows the settings
that apply."""

import json
import sqlite3

import pandas as pd
import pytest

from clutchopt.cli import main
from clutchopt.store import RunStore
from tests.conftest import CASES

CENTRIFUGE = str(CASES / "wedge_centrifuge.toml")  # f 0.12-0.18, inertia 12 +- 0.6 kg m^2, load 15-25 N m


@pytest.fixture
def store(tmp_path, capsys) -> str:
    """A store with a worst-case solve, a chance solve, a nominal solve and a worst-case sweep of the centrifuge."""
    path = str(tmp_path / "runs.sqlite")
    for extra in (("--robust", "worst-case", "--samples", "200"), ("--robust", "chance=0.999", "--samples", "200"), ()):
        assert main(["solve", CENTRIFUGE, *extra, "--store", path]) == 0
    assert main(["sweep", CENTRIFUGE, "--vary", "density=7800,7900", "--robust", "worst-case", "--samples", "200",
                 "--quiet", "--store", path]) == 0
    capsys.readouterr()
    return path


def listed(path: str, capsys) -> list[dict]:
    assert main(["runs", "list", "--json", "--store", path]) == 0
    return json.loads(capsys.readouterr().out)["runs"]


def test_the_store_records_how_each_design_was_made(store, capsys):
    runs = {run["id"]: run for run in listed(store, capsys)}
    assert [runs[i]["method"] for i in (1, 2, 3, 4, 5)] == ["worst-case", "chance=0.999", "nominal", "worst-case",
                                                            "worst-case"]
    with RunStore(store, writable=False) as opened:
        worst, chance, nominal = (opened.run(i) for i in (1, 2, 3))
    assert worst["inputs"]["method"] == "worst-case" and nominal["inputs"]["method"] == "nominal"
    assert worst["inputs"]["scatter"]["friction_coefficient"] == {
        "kind": "range", "low": 0.12, "high": 0.18, "mean": pytest.approx(0.15), "sd": pytest.approx(0.06 / 12 ** 0.5)}
    assert worst["inputs"]["scatter"]["inertia"]["kind"] == "normal" and "scatter" not in nominal["inputs"]
    assert worst["inputs"]["values"]["friction_coefficient"] == 0.15  # the case's value, the corner beside it
    assert worst["outputs"]["robust"]["corners"]["torque"] == {"friction_coefficient": 0.12, "inertia": 13.8,
                                                                "resisting_torque": 25.0}
    assert chance["outputs"]["robust"]["target"] == 0.999 and chance["outputs"]["robust"]["samples"] == 200


def test_runs_list_and_export_show_the_method(store, tmp_path, capsys):
    assert main(["runs", "list", "--store", store]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].split()[:8] == ["id", "kind", "sweep", "point", "created", "(UTC)", "coupling", "mode"]
    assert lines[1].split()[8] == "method"
    methods = {int(line.split()[0]): line.split()[8] for line in lines[2:7]}
    assert methods == {1: "worst-case", 2: "chance=0.999", 3: "nominal", 4: "worst-case", 5: "worst-case"}
    out = tmp_path / "runs.csv"
    assert main(["runs", "export", "-o", str(out), "--store", store]) == 0
    table = pd.read_csv(out)
    assert table["method"].tolist() == ["worst-case", "chance=0.999", "nominal", "worst-case", "worst-case"]
    assert table.loc[0, "scatter"] == ("friction_coefficient range 0.12 to 0.18; inertia normal, mean 12 kg*m^2, "
                                       "sd 0.6 kg*m^2; resisting_torque range 15 N*m to 25 N*m")
    assert pd.isna(table.loc[2, "scatter"])


def test_a_store_of_an_older_version_still_reads(store, capsys):
    """Before the method column: a robust design's method read from its recorded robust result, the others' not
    known ('-'); recording into it adds the column."""
    with sqlite3.connect(store) as db:
        db.execute("ALTER TABLE runs DROP COLUMN method")
    assert [run["method"] for run in listed(store, capsys)] == ["worst-case", "worst-case", None, "chance=0.999",
                                                                "worst-case"]
    assert main(["solve", str(CASES / "wedge_paper.toml"), "--store", store]) == 0
    capsys.readouterr()
    assert listed(store, capsys)[0]["method"] == "nominal"


def test_a_robust_design_is_verified_at_every_corner(capsys):
    """The worst-case centrifuge started at constant driving speed at each of the 8 corners: at the slowest (low
    f, high inertia and load), in t_p = 30 s, as it was sized; the nominal design there takes longer."""
    assert main(["solve", CENTRIFUGE, "--robust", "worst-case", "--samples", "200", "--verify", "--json",
                 "--no-store"]) == 0
    check = json.loads(capsys.readouterr().out)["verify"]
    assert check["corners"] == 8 and check["corner"] == {"friction_coefficient": 0.12, "inertia": 13.8,
                                                         "resisting_torque": 25.0}
    assert check["verified"] and check["simulated_acceleration_time"] == pytest.approx(30.0, rel=1e-6)
    assert main(["solve", CENTRIFUGE, "--robust", "chance=0.999", "--samples", "200", "--verify", "--no-store"]) == 0
    assert "(the robust design at the slowest of 8 corners of the scatter: friction_coefficient 0.12002" in \
        capsys.readouterr().out


def test_verify_of_a_robust_start_up_uses_the_scattered_limit(tmp_path, capsys):
    data = (CASES / "wedge_motor_start.toml").read_text() + '\n[scatter]\nmax_start_time = ["8 s", "12 s"]\n'
    (tmp_path / "case.toml").write_text(data)
    assert main(["solve", str(tmp_path / "case.toml"), "--robust", "worst-case", "--starts", "10", "--samples",
                 "200", "--verify", "--json", "--no-store"]) == 0
    check = json.loads(capsys.readouterr().out)["verify"]
    assert check["max_start_time"] == 8.0 and check["corner"] == {"max_start_time": 8.0}
    assert check["verified"] and check["simulated_start_time"] <= 8.0 * (1 + 1e-6)


def test_pareto_json_shows_the_settings_that_apply(capsys):
    assert main(["pareto", CENTRIFUGE, "--points", "3", "--robust", "worst-case", "--samples", "200", "--json",
                 "--no-store"]) == 0
    assert json.loads(capsys.readouterr().out)["robust"] == {"method": "worst-case", "target": None, "samples": 200}
