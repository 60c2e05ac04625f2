"""Input that had been read as something else (review 25): a nonzero number float64 reads as 0, an empty path read as
an option not given, a sweep id the store does not hold, a design file with a key twice or a variable of no design."""

import json
from pathlib import Path

import pytest

from clutchopt.cli import EXIT_BAD_INPUT, main

ROOT = Path(__file__).resolve().parents[1]
WEDGE = (ROOT / "cases" / "wedge_paper.toml").read_text()
LOAD = 'resisting_torque = "5 N*m"'


def _run(capsys, *args: str) -> tuple[int, str, str]:
    try:
        code = main(list(args))
    except SystemExit as stop:
        code = stop.code
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("load, expected", [
    ('resisting_torque = "1e-400 N*m"', "error: duty.resisting_torque: 1e-400 is below the float64 range: it would "
                                        "be read as 0"),
    ("resisting_torque = 1e-400", "line 14 (resisting_torque): 1e-400 is below the float64 range"),
    ('resisting_torque = "1e-320 nN*m"', "error: duty.resisting_torque: '1e-320 nN*m' is below the float64 range in "
                                         "SI: it would be read as 0"),  # (1e-329 N*m; 1e-300 nN*m, 1e-309 N*m: under
    # the 1e-18 clutchopt works with, refused as such)
])
def test_a_nonzero_number_float64_reads_as_zero_is_refused(tmp_path, capsys, load, expected):
    assert WEDGE.count(LOAD) == 1 and WEDGE.splitlines()[13] == LOAD  # (line 14)
    path = tmp_path / "case.toml"
    path.write_text(WEDGE.replace(LOAD, load))
    code, _, err = _run(capsys, "solve", str(path), "--no-store")
    assert code == EXIT_BAD_INPUT and expected in err and err.count("\n") == 1, err


def test_a_swept_value_float64_reads_as_zero_is_refused_and_zero_itself_is_not(tmp_path, capsys):
    path = tmp_path / "case.toml"
    path.write_text(WEDGE)
    code, _, err = _run(capsys, "sweep", str(path), "--vary", "resisting_torque=0,1e-400", "--no-store", "--quiet")
    assert code == EXIT_BAD_INPUT and "--vary resisting_torque=0,1e-400: 1e-400 is below the float64 range" in err
    code, out, _ = _run(capsys, "sweep", str(path), "--vary", "resisting_torque=0,0.0e-400", "--no-store", "--quiet",
                        "--json")
    assert code == 0 and [p["status"] for p in json.loads(out)["points"]] == ["optimal", "optimal"]


def test_an_empty_path_is_refused_before_any_work(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(WEDGE)
    code, _, err = _run(capsys, "sweep", "case.toml", "--vary", "speed=800", "--store", "", "--out", " ")
    assert code == EXIT_BAD_INPUT
    assert "error: argument --store: expected a file path, got ''" in err
    assert "error: argument --out: expected a file path, got ' '" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["case.toml"]  # (nothing recorded, nothing written)
    for args in (("init", "wedge", "-o", ""), ("pareto", "case.toml", "--plot", ""), ("report", "case.toml", "-o", ""),
                 ("runs", "export", "-o", "")):
        code, out, err = _run(capsys, *args)
        assert code == EXIT_BAD_INPUT and "expected a file path, got ''" in err and not out, (args, err)


def test_a_sweep_id_the_store_does_not_hold_is_refused(tmp_path, capsys):
    store, case = tmp_path / "runs.sqlite", tmp_path / "case.toml"
    case.write_text(WEDGE)
    assert _run(capsys, "sweep", str(case), "--vary", "speed=800,900", "--store", str(store), "--quiet")[0] == 0
    for action in (("list",), ("export", "-o", str(tmp_path / "points.csv"))):
        code, _, err = _run(capsys, "runs", *action, "--store", str(store), "--sweep", "42")
        assert code == EXIT_BAD_INPUT and f"error: --sweep: no sweep 42 in {store}" in err, err
    assert not (tmp_path / "points.csv").exists()
    code, out, _ = _run(capsys, "runs", "export", "-o", str(tmp_path / "points.csv"), "--store", str(store),
                        "--sweep", "1")
    assert code == 0 and out.startswith("2 runs written")


@pytest.mark.parametrize("text, expected", [
    ('"weight_mass": 0.2, "weight_mass": 0.1569', "'weight_mass' given twice in one object"),
    ('"bogus": 1.0', "coupling.design design.bogus: not a design variable of the wedge in paper mode"),
])
def test_a_design_file_with_a_key_twice_or_no_such_variable_is_refused(tmp_path, capsys, text, expected):
    design = (ROOT / "cases" / "designs" / "wedge_paper.json").read_text()
    assert design.count('"design": {') == 1
    (tmp_path / "designs").mkdir()
    (tmp_path / "designs" / "wedge_paper.json").write_text(design.replace('"design": {', '"design": {' + text + ", "))
    (tmp_path / "wedge_paper.toml").write_text(WEDGE)
    (tmp_path / "scenes").mkdir()
    scene = (ROOT / "cases" / "scenes" / "wedge_motor_springs.toml").read_text()
    assert 'case = "../wedge_paper.toml"' in scene and 'design = "../designs/wedge_paper.json"' in scene
    (tmp_path / "scenes" / "scene.toml").write_text(scene)
    code, _, err = _run(capsys, "simulate", str(tmp_path / "scenes" / "scene.toml"), "--no-store")
    assert code == EXIT_BAD_INPUT and expected in err, err


@pytest.mark.skipif(not Path("/dev/full").exists(), reason="no /dev/full (a device every write to fails)")
@pytest.mark.parametrize("args", [
    ("pareto", "case.toml", "--points", "2", "--out", "front.csv", "--plot", "full.png", "--quiet"),
    ("report", "case.toml", "-o", "full.html", "--quiet"),
    ("simulate", str(ROOT / "cases" / "scenes" / "paper_transient.toml"), "--plot", "full.png"),
])
def test_a_run_whose_output_fails_writes_and_records_nothing(tmp_path, capsys, monkeypatch, args):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(WEDGE)
    for name in ("full.png", "full.html"):
        (tmp_path / name).symlink_to("/dev/full")
    code, _, err = _run(capsys, *args, "--store", "runs.sqlite")
    assert code == EXIT_BAD_INPUT and "No space left on device" in err, err
    assert not (tmp_path / "front.csv").exists()  # (the table is written with the figure or not at all)
    code, out, _ = _run(capsys, "runs", "list", "--store", "runs.sqlite", "--json")
    assert code == 0 and json.loads(out)["runs"] == []


def test_a_normal_scatter_s_sd_beyond_the_magnitudes_clutchopt_works_with_is_refused(tmp_path, capsys):
    for sd, refused in (("1e300", True), ("1e19", True), ("0.02", False)):
        path = tmp_path / "case.toml"
        path.write_text(WEDGE + f"\n[scatter]\nfriction_coefficient = {{ normal = [0.15, {sd}] }}\n")
        code, _, err = _run(capsys, "solve", str(path), "--robust", "worst-case", "--no-store")
        if refused:
            assert code == EXIT_BAD_INPUT and err.count("\n") == 1, err
            assert err.startswith("error: scatter.friction_coefficient.normal: the standard deviation ") and \
                "is outside the magnitudes clutchopt works with, 1e-18 to 1e+18 in SI units" in err, err
        else:
            assert code == 0 and not err, err


def test_a_refused_law_or_choice_is_said_alone_not_with_the_fields_it_would_have_given(tmp_path, capsys):
    scene = (ROOT / "cases" / "scenes" / "wedge_motor_springs.toml").read_text()
    assert scene.count('law = "centrifugal"') == 1
    (tmp_path / "scenes").mkdir()
    (tmp_path / "scenes" / "scene.toml").write_text(scene.replace('law = "centrifugal"', 'law = "Centrifugal"')
                                                    .replace('"../', f'"{ROOT / "cases"}/'))
    code, _, err = _run(capsys, "simulate", str(tmp_path / "scenes" / "scene.toml"), "--no-store")
    assert code == EXIT_BAD_INPUT and err == ("error: coupling.law: must be one of paper, constant, centrifugal, got "
                                              "'Centrifugal'\n"), err
    path = tmp_path / "case.toml"  # (the wedge's friction pair's fields left to options.choose)
    chosen = "\n".join(line for line in WEDGE.splitlines()
                       if not line.startswith(("friction_coefficient", "allowable_pressure")))
    path.write_text(chosen + '\n[options]\nchoose = { friction_pair = ["organic_dry", "sintered_dry"] }\n')
    code, _, err = _run(capsys, "solve", str(path), "--no-store")
    assert code == EXIT_BAD_INPUT and err.count("\n") == 1, err
    assert err.startswith("error: options.choose.friction_pair: unknown friction pair 'sintered_dry'"), err


def test_choose_coupling_says_each_problem_every_coupling_shares_once(tmp_path, capsys):
    text = (ROOT / "cases" / "conveyor_drive.toml").read_text()
    assert text.count("poles = 4") == 1 and text.count('frequency = "50 Hz"') == 1
    path = tmp_path / "drive.toml"
    path.write_text(text.replace("poles = 4", "poles = 3").replace('frequency = "50 Hz"', 'frequency = "50 rpm"'))
    code, _, err = _run(capsys, "choose-coupling", str(path))
    assert code == EXIT_BAD_INPUT and err == (
        "error: start_up.driver.poles: must be an even whole number from 2 to 64, got 3\n"
        "error: start_up.driver.frequency: expected a count per time (e.g. in Hz), got '50 rpm', which is an angular "
        "speed\n"), err


def test_choose_coupling_says_a_bad_start_up_table_with_what_every_coupling_finds_in_one_run(tmp_path, capsys):
    text = (ROOT / "cases" / "conveyor_drive.toml").read_text()
    assert text.count('capacity = "3000 J/K"') == 1
    path = tmp_path / "drive.toml"
    path.write_text(text.replace("poles = 4", "poles = 3").replace('frequency = "50 Hz"', 'frequency = "50 rpm"')
                    .replace('capacity = "3000 J/K"', 'capacity = "3000 J"'))
    code, _, err = _run(capsys, "choose-coupling", str(path))
    assert code == EXIT_BAD_INPUT and err.splitlines() == [
        "error: start_up.heat.capacity: expected a heat capacity (e.g. in J/K), got '3000 J', which is a torque or "
        "energy",
        "error: start_up.driver.poles: must be an even whole number from 2 to 64, got 3",
        "error: start_up.driver.frequency: expected a count per time (e.g. in Hz), got '50 rpm', which is an angular "
        "speed"], err
