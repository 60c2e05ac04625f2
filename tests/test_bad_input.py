"""Malformed input through the CLI: one line on stderr naming the field, exit code 2, nothing on stdout.

Most cases call ``clutchopt.cli.main`` in-process; a handful run ``python -m clutchopt`` as a user would."""

from pathlib import Path

import pytest

from clutchopt.cli import EXIT_BAD_INPUT, main

CASES = Path(__file__).resolve().parents[1] / "cases"
WEDGE = (CASES / "wedge_paper.toml").read_text()
LEVER = (CASES / "lever_centrifuge.toml").read_text()
CABLE = (CASES / "cable_pump.toml").read_text()


def edit(text: str, old: str, new: str) -> str:
    assert old in text, old  # the edit must change the case, or the test would test nothing
    return text.replace(old, new, 1)


# (id, case text, extra CLI arguments, the field the message must name)
BAD = [
    ("toml-syntax", edit(WEDGE, 'speed = "1000 rpm"', 'speed = "1000 rpm'), [], "not valid TOML"),
    ("toml-duplicate-key", edit(WEDGE, 'speed = "1000 rpm"', 'speed = "1000 rpm"\nspeed = "900 rpm"'), [],
     "not valid TOML"),
    ("unknown-section", edit(WEDGE, "[duty]", "[dutyy]"), [], "dutyy"),
    ("unknown-key", edit(WEDGE, 'inertia = "0.5 kg*m^2"', 'inertia = "0.5 kg*m^2"\ninertiaa = 1'), [],
     "duty.inertiaa"),
    ("unknown-top-level", "colour = 'red'\n" + WEDGE, [], "colour"),
    ("wrong-unit-speed", edit(WEDGE, '"1000 rpm"', '"1000 kg"'), [], "duty.speed"),
    ("wrong-unit-inertia", edit(WEDGE, '"0.5 kg*m^2"', '"0.5 N*m"'), [],
     "duty.inertia: expected a moment of inertia (e.g. in kg*m^2), got '0.5 N*m', which is a torque or energy"),
    ("wrong-unit-pressure", edit(WEDGE, '"4 MPa"', '"4 mm"'), [], "material.allowable_pressure"),
    ("not-a-quantity", edit(WEDGE, '"1000 rpm"', '"fast"'), [], "duty.speed"),
    ("boolean", edit(WEDGE, '"0.5 kg*m^2"', "true"), [], "duty.inertia"),
    ("array", edit(WEDGE, '"0.5 kg*m^2"', "[0.5, 1]"), [], "duty.inertia"),
    ("negative-inertia", edit(WEDGE, '"0.5 kg*m^2"', '"-0.5 kg*m^2"'), [], "duty.inertia"),
    ("zero-speed", edit(WEDGE, '"1000 rpm"', '"0 rpm"'), [], "duty.speed"),
    ("negative-time", edit(WEDGE, '"10 s"', '"-10 s"'), [], "duty.acceleration_time"),
    ("zero-density", edit(WEDGE, '"7850 kg/m^3"', "0"), [], "material.density"),
    ("nan", edit(WEDGE, '"1000 rpm"', "nan"), [], "duty.speed"),
    ("inf", edit(WEDGE, '"4 MPa"', "inf"), [], "material.allowable_pressure"),
    ("nan-with-unit", edit(WEDGE, '"160 MPa"', '"nan MPa"'), [], "material.allowable_bending_stress"),
    ("angle-over-90", edit(WEDGE, '"15 deg"', '"95 deg"'), [], "geometry.flank_angle"),
    ("angle-zero", edit(WEDGE, '"15 deg"', '"0 deg"'), [], "geometry.flank_angle"),
    ("lambda-below-1", edit(WEDGE, "radius_ratio = 1.2", "radius_ratio = 0.9"), [], "geometry.radius_ratio"),
    ("friction-over-1", edit(WEDGE, "friction_coefficient = 0.15", "friction_coefficient = 1.5"), [],
     "material.friction_coefficient"),
    ("fractional-count", edit(WEDGE, "weight_count = 4", "weight_count = 2.5"), [], "geometry.weight_count"),
    ("zero-count", edit(WEDGE, "weight_count = 4", "weight_count = 0"), [], "geometry.weight_count"),
    ("missing-required", edit(WEDGE, 'speed = "1000 rpm"\n', ""), [], "duty.speed"),
    ("missing-coupling", edit(WEDGE, 'coupling = "wedge"\n', ""), [], "coupling"),
    ("unknown-coupling", edit(WEDGE, 'coupling = "wedge"', 'coupling = "clutch"'), [], "coupling"),
    ("weight-taller-than-centroid", edit(WEDGE, 'weight_height = "20 mm"', 'weight_height = "100 mm"'), [],
     "geometry.weight_height"),
    ("sectors-overlap", edit(WEDGE, 'sector_angle = "0.785 rad"', 'sector_angle = "120 deg"'), [],
     "geometry.sector_angle"),
    ("shell-fills-housing", edit(WEDGE, 'shell_thickness = "10 mm"', 'shell_thickness = "100 mm"'), [],
     "limits.outer_diameter_max"),
    ("bounds-reversed", edit(WEDGE, '["5 mm", "40 mm"]', '["40 mm", "5 mm"]'), [], "bounds.weight_width"),
    ("bounds-not-a-pair", edit(WEDGE, '["5 mm", "40 mm"]', '"5 mm"'), [], "bounds.weight_width"),
    ("bounds-unknown", edit(WEDGE, "weight_width = [", "weight_depth = ["), [], "bounds.weight_depth"),
    ("bounds-wrong-unit", edit(WEDGE, '["5 mm", "40 mm"]', '["5 kg", "40 kg"]'), [], "bounds.weight_width"),
    ("option-unknown", WEDGE + '\n[options]\ncolour = "red"\n', [], "options.colour"),
    ("option-free-not-freeable", WEDGE + '\n[options]\nfree = ["speed"]\n', [], "options.free"),
    ("option-mode-unknown", WEDGE + '\n[options]\nmode = "fancy"\n', [], "mode"),
    ("cli-objective-unknown", WEDGE, ["--objective", "beauty"], "objective"),
    ("lever-limit-above-engagement", edit(LEVER, 'engagement_angle = "15 deg"', 'engagement_angle = "2 deg"'), [],
     "geometry.engagement_angle: must exceed the limit angle"),
    ("lever-engagement-over-15", edit(LEVER, 'engagement_angle = "15 deg"', 'engagement_angle = "20 deg"'), [],
     "geometry.engagement_angle"),
    ("lever-flange-inside-shaft", edit(LEVER, 'flange_diameter = "80 mm"', 'flange_diameter = "30 mm"'), [],
     "geometry.flange_diameter"),
    ("cable-self-locking", edit(CABLE, 'lead_angle = "11.18 deg"', 'lead_angle = "5 deg"'), [], "thread.lead_angle"),
    ("cable-too-slow", edit(CABLE, 'speed = "1460 rpm"', 'speed = "50 rpm"'), [], "geometry.mass_radius"),
]


@pytest.mark.parametrize("text, extra, field", [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_bad_case_file(tmp_path, capsys, text, extra, field):
    path = tmp_path / "case.toml"
    path.write_text(text)
    assert main(["solve", str(path), *extra]) == EXIT_BAD_INPUT
    out, err = capsys.readouterr()
    assert out == ""
    lines = err.splitlines()
    assert err.endswith("\n") and lines and all(line.startswith("error: ") for line in lines), err
    assert len(lines) == (5 if field == "dutyy" else 1), err  # [dutyy]: unknown, and its four duty fields missing
    assert field in err, err


def test_enough_distinct_cases():
    assert len(BAD) >= 30 and len({b[0] for b in BAD}) == len(BAD)


def test_missing_file(tmp_path, capsys):
    assert main(["solve", str(tmp_path / "nowhere.toml")]) == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "nowhere.toml: no such file" in err


@pytest.mark.parametrize("args, needle", [
    (["solve", "x.toml", "--tol", "-1"], "--tol"),
    (["solve", "x.toml", "--tol", "tight"], "--tol"),
    (["bench", "--fast"], "--fast"),
    (["benchmark"], "invalid choice"),
])
def test_bad_command_line(capsys, args, needle):
    try:
        code = main(args)
    except SystemExit as stop:  # argparse's own refusals; those our code checks are returned, all at once
        code = stop.code
    assert code == EXIT_BAD_INPUT
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err, err


@pytest.mark.parametrize("name", ["toml-syntax", "nan", "sectors-overlap", "cable-self-locking"])
def test_as_a_user_runs_it(tmp_path, cli, name):
    text, extra, field = next(b[1:] for b in BAD if b[0] == name)
    path = tmp_path / "case.toml"
    path.write_text(text)
    result = cli("solve", str(path), *extra)
    assert result.returncode == EXIT_BAD_INPUT and result.stdout == ""
    assert result.stderr.count("\n") == 1 and field in result.stderr, result.stderr


def test_bad_flag_as_a_user_runs_it(cli):
    result = cli("bench", "--quick", "--repeats", "3")
    assert result.returncode == EXIT_BAD_INPUT and result.stderr.count("\n") == 1 and "--repeats" in result.stderr
