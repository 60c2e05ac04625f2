"""The simulate command and solve --verify as users run them; bad scenes end in one line and exit code 2."""

import json
import math

import pytest

from clutchopt.cli import main
from clutchopt.errors import InputError
from clutchopt.simulate import load_scene
from tests.conftest import CASES

PAPER_SCENE = (CASES / "scenes" / "paper_transient.toml").read_text()


def test_simulate_paper_scene_json_reproduces_closed_forms(cli, tmp_path):
    png = tmp_path / "start.png"
    result = cli("simulate", "cases/scenes/paper_transient.toml", "--json", "--plot", str(png))
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    head, analytic = data["headline"], data["analytic"]
    # eq. (9) corrected, by hand: J = 2, k = 50, a = -0.01, M_r = 20, w0 = 1500 rpm
    w0, a = 50 * math.pi, -0.01
    t_c = 2.0 / (a * 30.0) * (a * w0 + math.log(80.0 / (50.0 * math.exp(a * w0) + 30.0)))
    assert analytic["start_time"] == pytest.approx(t_c, rel=1e-12)
    assert head["start_time"] == pytest.approx(t_c, rel=1e-9)
    assert head["friction_work"] == pytest.approx(analytic["friction_work"], rel=1e-9)
    assert head["source_work"] == pytest.approx(2.0 * w0**2 + 20.0 * w0 * t_c, rel=1e-9)  # (14) = J w0^2 + M_r w0 t_c
    assert head["temperature_rise"] == pytest.approx(head["friction_work"] / 2300.0, rel=1e-9)
    assert data["events"][0]["event"] == "lock-up"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_solve_verify_reports_acceleration_time_against_t_p(cli):
    result = cli("solve", "cases/wedge_paper.toml", "--verify", "--json")
    assert result.returncode == 0, result.stderr
    check = json.loads(result.stdout)["verify"]
    assert check["verified"] and check["sized_acceleration_time"] == 10.0
    assert check["simulated_acceleration_time"] == pytest.approx(10.0, rel=1e-8)


def test_solve_verify_text_and_simulate_text(capsys):
    assert main(["solve", "cases/wedge_paper.toml", "--verify"]) == 0
    assert "verify: start-up simulated at constant driving speed: acceleration time 10 s" in capsys.readouterr().out
    assert main(["simulate", "cases/scenes/wedge_motor_springs.toml"]) == 0
    out = capsys.readouterr().out
    assert "engagement speed 43.0037 rad/s" in out and "start time t_c" in out and "temperature rise" in out


def test_bad_scene_through_the_cli(cli, tmp_path):
    scene = tmp_path / "bad.toml"
    scene.write_text(PAPER_SCENE.replace('k = "50 N*m"', 'k = "50 kg"'))
    result = cli("simulate", str(scene))
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("error: coupling.k: expected ") and "a mass" in result.stderr


BAD = {
    "unknown effect": (lambda t: t.replace('"friction_heat"]', '"friction_heat", "wind"]'), "effects"),
    "no slip_friction": (lambda t: t.replace('"slip_friction", ', ""), "effects"),
    "springs on the paper law": (lambda t: t.replace('"lockup"', '"spring_preload"'), "effects"),
    "unknown law": (lambda t: t.replace('law = "paper"', 'law = "magnetic"'), "coupling.law"),
    "missing k": (lambda t: t.replace('k = "50 N*m"\n', ""), "coupling.k"),
    "unknown key": (lambda t: t.replace("[driven]", "[driven]\nmass = 3"), "driven.mass"),
    "negative inertia": (lambda t: t.replace('"2 kg*m^2"', '"-2 kg*m^2"'), "driven.inertia"),
    "heat without capacity": (lambda t: t.replace('capacity = "2300 J/K"', ""), "heat.capacity"),
    "speed as a torque": (lambda t: t.replace('"1500 rpm"', '"15 N*m"'), "driver.speed"),
    "motor without data": (lambda t: t.replace('"lockup"', '"motor_curve"'), "driver.breakdown_slip"),
    "profile not increasing": (lambda t: t.replace('resisting_torque = "20 N*m"',
                                                   '[driven.load_profile]\nover = "speed"\npoints = [2, 1]\n'
                                                   'torque = [1, 2]'), "driven.load_profile.points"),
}


@pytest.mark.parametrize("name", BAD)
def test_bad_scene_names_the_field(name, tmp_path):
    edit, field = BAD[name]
    scene = tmp_path / "scene.toml"
    scene.write_text(edit(PAPER_SCENE))
    with pytest.raises(InputError) as error:
        load_scene(scene)
    assert field in [problem.field for problem in error.value.problems]


def test_scene_with_a_design_of_another_coupling(tmp_path):
    (tmp_path / "design.json").write_text(json.dumps({"coupling": "lever", "status": "optimal", "outputs": {}}))
    scene = tmp_path / "scene.toml"
    scene.write_text(f'effects = ["slip_friction"]\n[coupling]\nlaw = "centrifugal"\n'
                     f'case = "{(CASES / "wedge_paper.toml").as_posix()}"\ndesign = "design.json"\n')
    with pytest.raises(InputError, match="not a solved wedge design") as error:
        load_scene(scene)
    assert error.value.field == "coupling.design"


def test_scene_with_a_design_solved_for_another_case(tmp_path):
    design = json.loads((CASES / "designs" / "wedge_paper.json").read_text()) | {"case": "cases/wedge_fan.toml"}
    (tmp_path / "design.json").write_text(json.dumps(design))
    scene = tmp_path / "scene.toml"
    scene.write_text(f'effects = ["slip_friction"]\n[coupling]\nlaw = "centrifugal"\n'
                     f'case = "{(CASES / "wedge_paper.toml").as_posix()}"\ndesign = "design.json"\n')
    with pytest.raises(InputError, match="solved for 'cases/wedge_fan.toml'"):
        load_scene(scene)


def test_scene_with_a_coupling_without_a_speed_law(tmp_path):
    scene = tmp_path / "scene.toml"
    scene.write_text(f'effects = ["slip_friction"]\n[coupling]\nlaw = "centrifugal"\n'
                     f'case = "{(CASES / "cable_pump.toml").as_posix()}"\n')
    with pytest.raises(InputError, match="cable coupling is an elastic link, not a slipping one") as error:
        load_scene(scene)
    assert error.value.field == "coupling.case"


def test_a_ball_scene_needs_the_driven_machine_and_no_springs(tmp_path):
    scene = tmp_path / "scene.toml"
    head = f'[coupling]\nlaw = "centrifugal"\ncase = "{(CASES / "ball_crusher.toml").as_posix()}"\n'
    scene.write_text('effects = ["slip_friction"]\n' + head)
    with pytest.raises(InputError, match="missing") as error:
        load_scene(scene)
    assert error.value.field == "driven.inertia"
    scene.write_text('effects = ["slip_friction", "gravity"]\n' + head)
    with pytest.raises(InputError, match="gravity does not apply to the ball coupling") as error:
        load_scene(scene)
    assert "effects" in [problem.field for problem in error.value.problems]


def test_a_plain_design_file_of_a_scatter_case_says_it_is_nominal(tmp_path):
    """review 34: a scene simulating a nominal design file of a [scatter] case said nothing of the scatter, where a
    scene that solves the case says its design is nominal."""
    from conftest import CASES, run_cli

    solved = run_cli("solve", str(CASES / "wedge_motor_start_scatter.toml"), "--json", "--no-store")
    assert solved.returncode == 0, solved.stderr
    (tmp_path / "design.json").write_text(solved.stdout)
    scene = tmp_path / "scene.toml"
    scene.write_text(f'title = "t"\neffects = ["slip_friction", "motor_curve", "spring_preload", "lockup"]\n'
                     f'[coupling]\nlaw = "centrifugal"\ncase = "{CASES / "wedge_motor_start_scatter.toml"}"\n'
                     f'design = "design.json"\n')
    run = run_cli("simulate", str(scene), "--no-store")
    assert run.returncode == 0, run.stderr
    assert "coupling: wedge design (design.json; nominal: the case's [scatter] is not designed for)" in run.stdout


def test_a_design_file_of_another_case_of_the_same_name_is_refused(tmp_path):
    """review 34: a design file was matched to the scene's case by its file name only: the worked example's design
    simulated with an edited copy of its case (friction 0.12, not 0.15) ran without a word."""
    from conftest import CASES, run_cli

    solved = run_cli("solve", str(CASES / "wedge_paper.toml"), "--json", "--no-store")
    (tmp_path / "design.json").write_text(solved.stdout)
    (tmp_path / "wedge_paper.toml").write_text((CASES / "wedge_paper.toml").read_text().replace(
        "friction_coefficient = 0.15", "friction_coefficient = 0.12"))
    scene = tmp_path / "scene.toml"
    scene.write_text('title = "t"\neffects = ["slip_friction", "lockup"]\n[coupling]\nlaw = "centrifugal"\n'
                     'case = "wedge_paper.toml"\ndesign = "design.json"\n')
    run = run_cli("simulate", str(scene), "--no-store")
    assert run.returncode == 2 and "error: coupling.design: design.json was solved for another case" in run.stderr
    (tmp_path / "wedge_paper.toml").write_text((CASES / "wedge_paper.toml").read_text())  # its own case: taken
    assert run_cli("simulate", str(scene), "--no-store").returncode == 0
