"""The simulation engine: effects evaluated only when listed, stick and slip, solved wedge designs on real drives."""

import json
import math

import pytest

from clutchopt.cases import load_case
from clutchopt.formulations.duty import GRAVITY
from clutchopt.simulate import effects as fx
from clutchopt.simulate import load_scene, report_figure, run_scene, verify
from clutchopt.simulate.engine import Model, simulate
from clutchopt.simulate.laws import ConstantFriction, Load
from tests.conftest import CASES

SCENES = CASES / "scenes"


@pytest.fixture(scope="module")
def wedge_paper():
    from clutchopt.optimise import solve_case

    case = load_case(CASES / "wedge_paper.toml")
    return case, solve_case(case)


def test_only_listed_effects_are_evaluated(monkeypatch):
    calls = {name: 0 for name in ("motor_curve", "spring_preload", "gravity", "friction_heat", "slip_friction")}
    for name in calls:
        original = getattr(fx, name)

        def counting(*args, _name=name, _original=original):
            calls[_name] += 1
            return _original(*args)

        monkeypatch.setattr(fx, name, counting)
    run_scene(load_scene(SCENES / "paper_transient.toml"))  # slip_friction, lockup, friction_heat
    assert calls["slip_friction"] > 0 and calls["friction_heat"] > 0
    assert calls["motor_curve"] == calls["spring_preload"] == calls["gravity"] == 0
    calls.update({name: 0 for name in calls})
    run_scene(load_scene(SCENES / "wedge_ideal.toml"))
    assert calls["slip_friction"] > 0 and sum(v for k, v in calls.items() if k != "slip_friction") == 0
    run_scene(load_scene(SCENES / "wedge_motor_springs.toml"))
    assert min(calls.values()) > 0


def test_lockup_then_break_loose_when_the_load_exceeds_the_capacity_then_lockup_again():
    # 10 N m clutch, J = 1 kg m^2, w0 = 10 rad/s; load 2 N m, a 15 N m peak between 3 and 4 s
    load = Load(over="time", points=(0.0, 2.9, 3.0, 4.0, 4.1), values=(2.0, 2.0, 15.0, 15.0, 2.0))
    result = simulate(Model(ConstantFriction(10.0), 1.0, load, ("slip_friction", "lockup"), driver_speed=10.0,
                            end_time=8.0))
    kinds = [e["event"] for e in result.events]
    assert kinds == ["lock-up", "break loose", "lock-up"]
    first, loose, again = (e["time"] for e in result.events)
    assert first == pytest.approx(10.0 / 8.0, rel=1e-9)  # (10 - 2) N m accelerate 1 kg m^2 to 10 rad/s
    assert loose == pytest.approx(2.9 + 0.1 * 8.0 / 13.0, rel=1e-9)  # the load ramp crosses 10 N m
    assert result.events[1]["torque"] == pytest.approx(10.0, rel=1e-9)
    # slipping, the driven half loses speed until the load falls again, then catches up at 8 N m net
    h = result.history
    slipping = h[(h.t > loose) & (h.t < again)]
    assert (slipping.slip > 0).all() and (slipping.friction_torque == 10.0).all()
    assert result.headline["final_driven_speed"] == pytest.approx(10.0)
    assert (h[h.t > again + 1e-9].slip == 0).all()


def test_without_lockup_the_run_ends_at_zero_slip():
    result = simulate(Model(ConstantFriction(10.0), 1.0, Load(2.0), ("slip_friction",), driver_speed=10.0))
    assert [e["event"] for e in result.events] == ["zero slip"]
    assert result.headline["end_time"] == pytest.approx(1.25, rel=1e-12)
    assert list(result.history.columns[:7]) == ["t", "w_driver", "w_driven", "slip", "friction_torque",
                                                "power_lost", "friction_work"]


def test_ideal_start_of_the_solved_wedge_design_takes_exactly_t_p(wedge_paper):
    case, solution = wedge_paper
    check = verify(case, solution)
    assert check["verified"]
    assert check["simulated_acceleration_time"] == pytest.approx(10.0, rel=1e-8)
    # constant acceleration: L = J w0^2 / 2 + T_c (w0 t_p - w0 t_p / 2)
    w0, inertia, t_c = 1000 * math.pi / 30, 0.5, 5.0
    assert check["friction_work"] == pytest.approx(inertia * w0**2 / 2 + t_c * w0 * 10.0 / 2, rel=1e-8)


def test_motor_and_springs_for_the_solved_wedge_design():
    scene = load_scene(SCENES / "wedge_motor_springs.toml")
    result = run_scene(scene)
    h, head = result.history, result.headline
    outputs = committed_outputs()
    mass_radius = outputs["weight_mass"] * outputs["centroid_radius"]
    engagement = math.sqrt((12.0 + outputs["weight_mass"] * GRAVITY) / mass_radius)
    assert head["source"]["engagement_speed"] == pytest.approx(engagement, rel=1e-12)
    # the driven machine rests until the motor passes the engagement speed
    assert (h[h.w_driver < engagement].w_driven == 0).all()
    assert h[h.w_driver > 1.01 * engagement].w_driven.iloc[-1] > 0
    assert head["locks_up"] and head["start_time"] > 10.0  # slower than the sized t_p = 10 s
    assert head["start_time"] == pytest.approx(16.7685, rel=1e-4)
    # locked, the motor carries the load at its Kloss slip: T = 5 N m
    motor = scene.model.motor
    assert motor(head["final_driver_speed"]) == pytest.approx(5.0, rel=1e-6)
    assert head["final_driven_speed"] == pytest.approx(head["final_driver_speed"])
    assert 0 < head["temperature_rise"] < head["friction_work"] / 1400.0


def test_load_profile_scene_is_faster_than_sized():
    head = run_scene(load_scene(SCENES / "wedge_fan_load.toml")).headline
    assert head["locks_up"] and 0 < head["start_time"] < 20.0


def test_report_figure(wedge_paper):
    case, solution = wedge_paper
    figure, caption = report_figure(case, solution)
    assert figure is not None and "t_p = 10 s" in caption and "10 s" in caption
    from clutchopt.optimise import solve_case

    cable = load_case(CASES / "cable_pump.toml")
    figure, reason = report_figure(cable, solve_case(cable))
    assert figure is None and "cable" in reason


def test_lever_design_verified_too():
    from clutchopt.optimise import solve_case

    case = load_case(CASES / "lever_wedge_duty.toml")  # the wedge paper's duty: 0.5 kg m^2, 1000 rpm, 10 s, 5 N m
    check = verify(case, solve_case(case))
    assert check["simulated_acceleration_time"] == pytest.approx(10.0, rel=1e-8)
    assert check["friction_work"] == pytest.approx(5359.5507, rel=1e-7)  # same duty, same L as the wedge


def test_springs_at_constant_speed_lengthen_t_p_as_the_torque_law_says():
    import copy

    from clutchopt.cases import read_toml
    from clutchopt.simulate.scene import parse_scene

    data = read_toml(SCENES / "wedge_motor_springs.toml")
    data = copy.deepcopy(data) | {"effects": ["slip_friction", "spring_preload", "lockup"]}
    head = run_scene(parse_scene(data, str(SCENES / "wedge_motor_springs.toml"))).headline
    outputs = committed_outputs()
    w0 = 1000 * math.pi / 30
    w_e2 = 12.0 / (outputs["weight_mass"] * outputs["centroid_radius"])
    torque = outputs["torque"] * (1 - w_e2 / w0**2)  # T = c_F m_r r_c (w^2 - w_e^2)
    assert head["start_time"] == pytest.approx(0.5 * w0 / (torque - 5.0), rel=1e-8)


def test_a_motor_below_the_engagement_speed_never_starts_the_machine():
    import copy

    from clutchopt.cases import read_toml
    from clutchopt.simulate.scene import parse_scene

    data = copy.deepcopy(read_toml(SCENES / "wedge_motor_springs.toml"))
    data["driver"]["synchronous_speed"] = "300 rpm"  # engagement is at 411 rpm
    del data["end_time"]
    head = run_scene(parse_scene(data, str(SCENES / "wedge_motor_springs.toml"))).headline
    assert not head["locks_up"] and head["reason"].startswith("no lock-up: the driven half stays at rest")
    assert head["final_driven_speed"] == 0.0
    assert head["final_driver_speed"] == pytest.approx(10 * math.pi, rel=1e-6)  # idles at synchronous speed


def test_an_infeasible_solution_is_not_started():
    from clutchopt.optimise import solve_case

    case = load_case(CASES / "wedge_paper.toml").with_values(outer_diameter_max=0.05)
    solution = solve_case(case, "geometry")
    assert solution.status == "infeasible"
    assert verify(case, solution) == {"verified": False,
                                      "reason": "the solution's status is infeasible, there is no design to start"}
    assert report_figure(case, solution)[0] is None


def committed_outputs() -> dict:
    """Outputs of the committed solved design (clutchopt solve cases/wedge_paper.toml --json)."""
    return json.loads((CASES / "designs" / "wedge_paper.json").read_text())["outputs"]


def test_a_start_up_case_s_design_is_simulated_with_its_own_spring_preload():
    """A scene whose coupling is a start-up case solved for its design (or that case's design file) simulates the
    design's own spring preload, one of its variables, as its start-up was solved: the engagement speed that preload
    gives (w_e^2 = F_s / (m_r r_c), the weights' own weight not listed), and a scene that gives another preload is
    refused by name (review 20: the scene's 12 N had replaced the design's 9.97 N silently)."""
    import copy

    from clutchopt.cases import read_toml
    from clutchopt.errors import InputError
    from clutchopt.optimise import solve_case
    from clutchopt.simulate.scene import parse_scene

    case = load_case(CASES / "wedge_motor_start.toml")
    solution = solve_case(case)
    data = copy.deepcopy(read_toml(SCENES / "wedge_motor_springs.toml"))
    data["effects"] = ["slip_friction", "motor_curve", "spring_preload", "lockup"]
    data["coupling"] = {"law": "centrifugal", "case": str(CASES / "wedge_motor_start.toml"), "spring_preload": "12 N"}
    with pytest.raises(InputError, match="coupling.spring_preload: the design sets the spring preload"):
        parse_scene(data, str(SCENES / "wedge_motor_springs.toml"))
    del data["coupling"]["spring_preload"]
    scene = parse_scene(data, str(SCENES / "wedge_motor_springs.toml"))
    outputs = {name: output.value for name, output in solution.outputs.items()}
    preload = solution.design["spring_preload"]
    assert preload != pytest.approx(12.0, rel=0.05)
    assert scene.source["engagement_speed"] == pytest.approx(
        math.sqrt(preload / (solution.design["weight_mass"] * outputs["centroid_radius"])), rel=1e-9)


def test_a_start_up_case_s_scene_takes_its_drive_from_the_case_and_says_what_it_took(tmp_path):
    """A scene naming a start-up case leaves out what the case gives: the start-up's own driven inertia (0.6 here,
    not the duty's 0.5: the duty's had been taken, silently), its load, its motor and its heat (had been refused as
    missing); the output names each field with the value it took (SI) and the fields the scene gives over the case's;
    the case's own design file (`solve --json`) carries its spring preload (had been refused as missing: review 21b)."""
    from clutchopt.cli.simulate import _text
    from clutchopt.optimise import solve_case
    from clutchopt.simulate.scene import parse_scene

    text = (CASES / "wedge_motor_start.toml").read_text()
    (tmp_path / "case.toml").write_text(text.replace("[start_up.heat]", "[start_up.driven]\ninertia = \"0.6 kg*m^2\""
                                                                        "\n\n[start_up.heat]"))
    case = load_case(tmp_path / "case.toml")
    assert (case.values["inertia"], case.values["driven_inertia"]) == (0.5, 0.6)
    solution = solve_case(case)
    (tmp_path / "design.json").write_text(json.dumps({**solution.as_dict(), "case": "case.toml"}))
    data = {"effects": ["slip_friction", "motor_curve", "spring_preload", "lockup", "friction_heat"],
            "coupling": {"law": "centrifugal", "case": "case.toml", "design": "design.json"}}
    scene = parse_scene(data, str(tmp_path / "scene.toml"))
    m = scene.model
    assert (m.inertia, m.load.torque, m.heat_capacity, m.conductance) == (0.6, 5.0, 1400.0, 4.0)
    motor = m.motor
    assert (motor.synchronous_speed, motor.breakdown_torque, motor.breakdown_slip, motor.inertia) == pytest.approx(
        (1000 * math.pi / 30, 37.0, 0.2, 0.012), rel=1e-15)
    radius = solution.outputs["centroid_radius"].value  # (the design's own preload: its engagement speed)
    assert scene.source["engagement_speed"] == pytest.approx(
        math.sqrt(solution.design["spring_preload"] / (solution.design["weight_mass"] * radius)), rel=1e-9)
    assert [(t["field"], t["value"], t["unit"]) for t in scene.source["from_the_case"]] == [
        ("driven.inertia", 0.6, "kg*m^2"), ("driven.resisting_torque", 5.0, "N*m"),
        ("driver.synchronous_speed", motor.synchronous_speed, "rad/s"), ("driver.breakdown_torque", 37.0, "N*m"),
        ("driver.breakdown_slip", 0.2, ""), ("driver.inertia", 0.012, "kg*m^2"), ("heat.capacity", 1400.0, "J/K"),
        ("heat.conductance", 4.0, "W/K")]
    assert scene.source["over_the_case"] == [] and scene.source["unread"] == []
    assert "from the case: driven.inertia 0.6 kg*m^2, driven.resisting_torque 5 N*m, driver.synchronous_speed " \
           "104.72 rad/s" in _text(scene, run_scene(scene), None)
    data["driver"] = {"breakdown_torque": "30 N*m"}
    data["heat"] = {"capacity": "1000 J/K"}
    data["effects"] = ["slip_friction", "motor_curve", "spring_preload", "lockup"]  # (the heat switched off)
    scene = parse_scene(data, str(tmp_path / "scene.toml"))
    assert scene.model.motor.breakdown_torque == 30.0 and scene.source["over_the_case"] == ["driver.breakdown_torque"]
    assert "driver.breakdown_torque" not in [t["field"] for t in scene.source["from_the_case"]]
    assert scene.source["unread"] == ["heat.capacity"]  # (given, its effect not listed: said, not refused)
    springs = load_scene(SCENES / "wedge_motor_springs.toml")
    assert [t["field"] for t in springs.source["from_the_case"]] == ["driven.inertia", "driven.resisting_torque"]


def test_a_scene_refuses_two_values_for_one_thing_and_names_only_real_problems(tmp_path):
    """A constant driving speed beside motor_curve, a constant load beside a load profile: refused by name (the first
    had been ignored without a word); a case that is refused leaves the fields it would give unnamed (seven
    "missing" lines had followed its own: review 21b)."""
    import copy

    from clutchopt.cases import read_toml
    from clutchopt.errors import InputError
    from clutchopt.simulate.scene import parse_scene

    data = copy.deepcopy(read_toml(SCENES / "wedge_motor_springs.toml"))
    data["driver"]["speed"] = "1000 rpm"
    data["driven"] = {"resisting_torque": "5 N*m", "load_profile": {"over": "speed", "points": [0, 100],
                                                                    "torque": [1, 2]}}
    with pytest.raises(InputError) as error:
        parse_scene(data, str(SCENES / "wedge_motor_springs.toml"))
    assert [p.field for p in error.value.problems] == ["driver.speed", "driven.resisting_torque"]
    paper = copy.deepcopy(read_toml(SCENES / "paper_transient.toml"))
    paper["coupling"] |= {"torque": "10 N*m", "case": "x.toml"}  # (another law's fields: had been ignored)
    with pytest.raises(InputError) as error:
        parse_scene(paper, str(SCENES / "paper_transient.toml"))
    assert [p.field for p in error.value.problems] == ["coupling.torque", "coupling.case"]
    fan = {"effects": ["slip_friction", "lockup"], "coupling": {"law": "centrifugal", "spring_preload": "500 N",
                                                               "case": str(CASES / "wedge_paper.toml")}}
    assert parse_scene(fan, str(tmp_path / "scene.toml")).source["unread"] == ["coupling.spring_preload"]
    for mode in (["paper"], 5):  # (a list had crashed: unhashable, exit 3)
        with pytest.raises(InputError) as error:
            parse_scene({"effects": ["slip_friction"], "coupling": {"law": "centrifugal", "mode": mode, "case": str(
                CASES / "wedge_paper.toml")}}, str(tmp_path / "scene.toml"))
        assert [(p.field, p.problem[:15]) for p in error.value.problems] == [("coupling.mode", "must be a name ")]
    start_up = {"effects": ["slip_friction", "spring_preload"], "coupling": {
        "law": "centrifugal", "case": str(CASES / "wedge_motor_start.toml"), "spring_preload": "12 N"}}
    for bad in ({"mode": 5}, {"design": str(tmp_path / "none.json")}):  # (each problem beside the preload the
        with pytest.raises(InputError) as error:  # start-up's design sets: named in one run, review 21c)
            parse_scene(start_up | {"coupling": start_up["coupling"] | bad}, str(tmp_path / "scene.toml"))
        assert [p.field for p in error.value.problems][-1] == "coupling.spring_preload"
        assert len(error.value.problems) == 2
    (tmp_path / "case.toml").write_text("coupling = \"wedge\"\n[duty]\nspeed = \"fast\"\n")
    lean = {"effects": ["slip_friction", "motor_curve", "friction_heat"],
            "coupling": {"law": "centrifugal", "case": "case.toml"}}
    with pytest.raises(InputError) as error:
        parse_scene(lean, str(tmp_path / "scene.toml"))
    assert {p.field.split(" ")[0] for p in error.value.problems} == {"coupling.case"}


def test_a_scene_solved_from_a_choosing_case_simulates_the_best_choice(tmp_path):
    """A scene whose coupling is a case with ``options.choose`` and no design simulates the design ``solve`` gives
    (every choice designed, the best kept) with that choice's case (its friction coefficient), and says which; a
    design file solved with one of its choices is simulated with that choice (review 20: the scene had solved the
    case's first choice, listed first, and simulated it without a word)."""
    import copy

    from clutchopt.cases import read_toml
    from clutchopt.optimise.design import design_case
    from clutchopt.simulate.scene import parse_scene
    from clutchopt.start_up.simulation import centrifugal_law
    from tests.conftest import choosing

    (tmp_path / "choosing.toml").write_text(choosing("wedge").replace('["steel_steel_dry", "steel_steel_oiled"]',
                                                                       '["steel_steel_oiled", "steel_steel_dry"]'))
    case = load_case(tmp_path / "choosing.toml")
    designed = design_case(case)
    best, first = designed[0], next(d for d in designed if d.choice == designed_first(case))
    assert best.choice != first.choice  # (the first listed is not the best: the case tells them apart)
    data = copy.deepcopy(read_toml(SCENES / "wedge_motor_springs.toml"))
    data["effects"] = ["slip_friction", "motor_curve"]
    data["coupling"] = {"law": "centrifugal", "case": "choosing.toml"}
    scene = parse_scene(data, str(tmp_path / "scene.toml"))
    law = centrifugal_law(best.case, best.solution.mode, best.solution.design, ("slip_friction",))
    assert best.choice_text in scene.source["design"]
    assert scene.source["design_torque"] == pytest.approx(law.capacity(best.case.params().speed), rel=1e-12)
    (tmp_path / "design.json").write_text(json.dumps({**first.as_dict(), "case": "choosing.toml"}))
    data["coupling"]["design"] = "design.json"
    chosen = parse_scene(data, str(tmp_path / "scene.toml"))
    law = centrifugal_law(first.case, first.solution.mode, first.solution.design, ("slip_friction",))
    assert chosen.source["design_torque"] == pytest.approx(law.capacity(first.case.params().speed), rel=1e-12)


def designed_first(case) -> dict:
    """The first choice ``options.choose`` lists."""
    from clutchopt.optimise.design import choices

    return next(iter(choices(case)))[0]


def test_a_scene_s_design_file_is_simulated_as_it_was_solved_and_says_what_it_is(tmp_path):
    """A design file's scene: a mode other than the file's, or an objective (neither solves anything there), refused
    by name; a choice the case does not offer named within a line's length (a million-character name had been echoed
    whole); a robust design said to be one, simulated at the case's nominal values (review 20b)."""
    import copy

    from clutchopt.cases import read_toml
    from clutchopt.errors import InputError
    from clutchopt.simulate.scene import parse_scene

    data = copy.deepcopy(read_toml(SCENES / "wedge_motor_springs.toml"))
    where = str(SCENES / "wedge_motor_springs.toml")
    for key, value in (("mode", "geometry"), ("objective", "cost")):
        with pytest.raises(InputError, match=f"coupling.{key}: '{value}' is for a case solved for its design"):
            parse_scene(copy.deepcopy(data) | {"coupling": {**data["coupling"], key: value}}, where)
    assert parse_scene(copy.deepcopy(data) | {"coupling": {**data["coupling"], "mode": "paper"}}, where)
    with pytest.raises(InputError) as error:  # (every problem in one run: a mode that is no name beside an objective)
        parse_scene(copy.deepcopy(data) | {"coupling": {**data["coupling"], "mode": 5, "objective": "cost"}}, where)
    assert [(p.field, p.problem[:16]) for p in error.value.problems] == [
        ("coupling.mode", "must be a name ("), ("coupling.objective", "'cost' is for a ")]
    design = json.loads((CASES / "designs" / "wedge_paper.json").read_text())
    (tmp_path / "chosen.json").write_text(json.dumps({**design, "choice": {"friction_pair": "x" * 1_000_000}}))
    (tmp_path / "robust.json").write_text(json.dumps({**design, "robust": {"method": "worst-case"}}))
    for name in ("chosen.json", "robust.json"):
        data["coupling"]["case"] = str(CASES / "wedge_paper.toml")
        data["coupling"]["design"] = str(tmp_path / name)
        if name == "chosen.json":
            with pytest.raises(InputError) as error:
                parse_scene(data, where)
            assert "names the choice" in str(error.value) and len(str(error.value)) < 300
        else:
            assert "a robust design" in parse_scene(data, where).source["design"]
