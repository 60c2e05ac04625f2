"""Overload (docs/start_up.md, "Overload"): the largest torque the coupling passes - at the top speed, with worn
linings where they matter (the lever), with the highest friction of the pair or the scatter - against the motor's
breakdown torque and the driven machine's max_transmitted_torque; and the lever's start checked new and worn."""

import json
import math
from types import SimpleNamespace

import pytest

from clutchopt.cases import load_case, parse_case, read_toml
from clutchopt.errors import InputError
from clutchopt.optimise.problem import case_formulation, solve_case
from clutchopt.start_up.drive import Drive, Structure, named_constraints
from clutchopt.start_up.overload import overload_torque
from clutchopt.start_up.simulation import start_up_model, worn_start_up_model
from tests.conftest import CASES

RPM = math.pi / 30
G = 9.80665
# cases/lever_motor_start.toml, paper mode, by hand (docs/lever.md "Statics of the toggle", "Two states"):
G0, GPR = math.radians(15), math.radians(3)  # engagement and limit angles
DELTA, D_B, D_PHI, L_PR, Z, W_AX, I = 0.004, 0.042, 0.080, 0.040, 6, 20.0, 2
L2 = DELTA / (math.cos(GPR) - math.cos(G0))  # l_2 rule at its minimum: 0.004 / (0.998630 - 0.965926) = 122.310 mm
R_0 = D_B / 2 + (D_PHI - D_B) / 4 + L_PR  # 21 + 9.5 + 40 = 70.5 mm
D_CP = 2 * (L2 * math.sin(G0) + R_0)  # 2 (31.656 + 70.5) = 204.312 mm
TRAVEL = L2 * (math.sin(G0) - math.sin(GPR))  # dr = 25.255 mm, the spring's stretch when worn
W_S = 1500 * RPM  # 4 poles at 50 Hz: the top speed, 157.0796 rad/s


def lever_torques(m, preload, f, speed=W_S):
    """(new, worn) friction torque T = i f N d_cp / 2 of the paper's toggles at ``speed``, each weight's force less
    the spring preload (gravity sums to zero over the z weights):
    new  N = z (m w^2 R_0 - F_s) / (2 tan gamma_0);
    worn N = z (m w^2 (R_0 + dr) - c dr - F_s) / (2 tan gamma_pr), c dr = m g + 2 W_ax tan gamma_0 / z."""
    spring = m * G + 2 * W_AX * math.tan(G0) / Z
    new = Z * (m * speed**2 * R_0 - preload) / (2 * math.tan(G0))
    worn = Z * (m * speed**2 * (R_0 + TRAVEL) - spring - preload) / (2 * math.tan(GPR))
    return I * f * new * D_CP / 2, I * f * worn * D_CP / 2


def _lever_text(driver: str | None = None, pair: bool = True) -> str:
    """lever_motor_start.toml with the overload check on (its own [start_up.overload] left out), the linings from
    the library's organic_dry (f 0.3, f_max 0.45) and, if given, another [start_up.driver] table."""
    text = (CASES / "lever_motor_start.toml").read_text()
    text = text.replace("[start_up.overload]\ncheck = false", "")
    if pair:
        text = text.replace("friction_coefficient = 0.3\n", "").replace('allowable_pressure = "0.25 MPa"\n', "")
        if "[library]" not in text:  # the case's own library table (organic_dry) since the lining limits came
            text = text.replace("[material]", '[library]\nfriction_pair = "organic_dry"\n\n[material]')
    if driver:
        start = text.index("[start_up.driver]")
        text = text[:start] + driver + text[text.index("[start_up.heat]"):]
    return text


def test_hand_values():
    assert L2 == pytest.approx(0.1223103, rel=1e-6)
    assert D_CP == pytest.approx(0.2043124, rel=1e-6)
    assert TRAVEL == pytest.approx(0.0252550, rel=1e-5)
    new, worn = lever_torques(0.0791281, 11.612, 0.3)
    assert worn / new == pytest.approx(6.97, rel=1e-2)  # tan 15 / tan 3 = 5.11, times (R_0 + dr) / R_0 = 1.36 ...
    assert worn == pytest.approx(606.22, rel=1e-4)  # the case's optimum, worn: 2.3 times the motor's 265 N m


def test_the_overload_is_the_worn_lever_at_synchronous_speed_with_the_pairs_highest_friction(tmp_path):
    case = parse_case(read_toml_text(tmp_path, _lever_text()), "lever.toml")
    assert case.values["friction_coefficient"] == 0.3 and case.values["friction_max"] == 0.45  # organic_dry
    law, p = case_formulation(case).speed_law, case.params()
    x = SimpleNamespace(weight_mass=0.07, link_diameter=0.005, spring_preload=10.0)
    value = float(overload_torque(law, x, p, case.start_up.effects, motor=True))
    assert value == pytest.approx(lever_torques(0.07, 10.0, 0.45)[1], rel=1e-12)
    assert value == pytest.approx(max(lever_torques(0.07, 10.0, 0.45)), rel=1e-12)  # worn is the stronger


@pytest.mark.parametrize("driver, breakdown", [
    (None, 265.0),
    # a nameplate motor: 15 kW at 1460 rpm, T_k / T_n = 2.7: T_k = 2.7 * 15000 / (1460 pi / 30) = 264.89 N m
    ('[start_up.driver]\nrated_power = "15 kW"\nrated_speed = "1460 rpm"\npoles = 4\nfrequency = "50 Hz"\n'
     'breakdown_ratio = 2.7\ninertia = "0.09 kg*m^2"\n\n', 2.7 * 15000 / (1460 * RPM)),
])
def test_the_lever_on_its_drive_is_checked_worn_against_the_breakdown_torque(driver, breakdown, tmp_path, cli):
    """The done-when of issue 27: the worn lever passes more than twice the motor's breakdown torque, so no design
    of the paper's method both starts the basket in 30 s and slips under a jam; overload_torque says so, its value
    the worn torque at 1500 rpm with f_max = 0.45 at the design reported."""
    path = tmp_path / "lever.toml"
    path.write_text(_lever_text(driver))
    result = cli("solve", str(path), "--json", "--no-store")
    assert result.returncode == 0, result.stderr
    out = json.loads(result.stdout)
    assert out["status"] in ("infeasible", "not_found") and "overload_torque" in out["diagnosis"]
    check = next(c for c in out["constraints"] if c["name"] == "overload_torque")
    design = out["design"]
    new, worn = lever_torques(design["weight_mass"], design["spring_preload"], 0.45)
    assert check["value"] == pytest.approx(worn, rel=1e-9) and worn > new
    assert check["limit"] == pytest.approx(breakdown, rel=1e-12) and check["sense"] == "<=" and check["unit"] == "N*m"
    assert check["margin"] == pytest.approx((breakdown - worn) / breakdown, rel=1e-9, abs=1e-12)


def test_worn_linings_engage_first_so_the_new_start_is_the_slower():
    """T_w - T_n grows with the driving speed (docs/start_up.md "Overload"), so the worn toggles pass at least the
    new torque everywhere when they already push at the new engagement speed w_e^2 = (F_s + m g) / (m R_0)."""
    case = load_case(CASES / "lever_motor_start.toml")
    solution = solve_case(case)
    m, preload = solution.design["weight_mass"], solution.design["spring_preload"]
    engagement = math.sqrt((preload + m * G) / (m * R_0))
    assert engagement == pytest.approx(450 * RPM, rel=1e-6)  # min_engagement_speed binds
    _, worn = lever_torques(m, preload + m * G, 0.3, engagement)  # gravity too: the start model's worst position
    check = next(c for c in solution.constraints if c.name == "worn_engages_first")
    assert check.value == pytest.approx(worn, rel=1e-9) and worn > 0 and check.feasible
    # the worn start simulated (reported): K_w = i f z m (R_0 + dr) d_cp / (4 tan gamma_pr), and it engages at
    # w_e,worn^2 = (F_s + m g + c dr) / (m (R_0 + dr)), earlier than new; it locks up sooner
    worn_law = worn_start_up_model(case, "paper", solution.design, start_up_model(case, "paper", solution.design)).law
    spring = m * G + 2 * W_AX * math.tan(G0) / Z
    assert worn_law.torque_coefficient == pytest.approx(
        I * 0.3 * Z * m * (R_0 + TRAVEL) * D_CP / (4 * math.tan(GPR)), rel=1e-12)
    assert worn_law.engagement_squared == pytest.approx((preload + m * G + spring) / (m * (R_0 + TRAVEL)), rel=1e-12)
    assert worn_law.engagement_squared < engagement**2
    assert solution.start_up["worn"]["start_time"] < solution.start_up["start_time_simulated"]
    assert "overload_torque" not in {c.name for c in solution.constraints}  # the case turns the check off
    assert solution.start_up["overload"].startswith("overload not checked (start_up.overload.check = false)")


@pytest.mark.parametrize("machine, limit", [("10.8 N*m", 10.8), ("50 N*m", 37.0), (None, 37.0)])
def test_the_limit_is_the_lesser_of_the_breakdown_torque_and_the_machines(machine, limit, tmp_path):
    """wedge_motor_start (T_k = 37 N m) with a torque-limited machine or none: the overload's limit is the lesser;
    its value the wedge's slip torque at 1000 rpm with f_max = the nominal 0.15 (no pair, no scatter), by hand."""
    text = (CASES / "wedge_motor_start.toml").read_text()
    if machine:
        text = text.replace("[start_up.heat]", f'[start_up.driven]\nmax_transmitted_torque = "{machine}"\n\n'
                                               "[start_up.heat]")
    case = parse_case(read_toml_text(tmp_path, text), "limiter.toml")
    law, p = case_formulation(case).speed_law, case.params()
    x = SimpleNamespace(weight_mass=0.2, finger_diameter=0.007, spring_preload=12.0)
    structure = Structure.of(case)
    figures = SimpleNamespace(start_time=1.0, friction_work=1.0, temperatures=1.0, lock_up_speed=100.0)
    check = next(c for c in named_constraints(structure, Drive(structure, law, x, p), figures)
                 if c.name == "overload_torque")
    assert check.limit == limit and check.sense == "<="
    assert check.value == pytest.approx(wedge_overload(0.2, 12.0, 0.15), rel=1e-12)  # f_max: the nominal 0.15
    assert ("max_transmitted_torque" in check.description) == (machine is not None)


def wedge_overload(m, preload, f, speed=1000 * RPM):
    """cases/wedge_motor_start*.toml by hand (wedge eqs. 10-15): T = z f (m w^2 r_c - F_s) / sin(alpha) (r_1 + r_2) / 2,
    z = 4, alpha = 15 deg, r_1 = 50 mm, r_2 = 1.2 r_1 = 60 mm, r_c = r_2 - 2 h / 3 = 46.667 mm (h = 20 mm)."""
    r_c = 0.060 - 2 * 0.020 / 3
    return 4 * f * (m * speed**2 * r_c - preload) / math.sin(math.radians(15)) * (0.050 + 0.060) / 2


@pytest.mark.parametrize("corner", [0.12, 0.15, 0.18])
def test_under_scatter_the_overload_is_at_the_ranges_high_friction_at_every_corner(corner):
    """wedge_motor_start_scatter.toml, f 0.12 to 0.18: friction_max defaults to 0.18, and the overload seen at any
    corner of f (a robust design's view) is the wedge's slip torque at 1000 rpm with f = 0.18, by hand."""
    case = load_case(CASES / "wedge_motor_start_scatter.toml")
    law, p = case_formulation(case).speed_law, case.with_values(friction_coefficient=corner).params()
    x = SimpleNamespace(weight_mass=0.2, finger_diameter=0.007, spring_preload=12.0)
    value = float(overload_torque(law, x, p, case.start_up.effects, motor=True))
    assert p.friction_max == 0.18 and value == pytest.approx(wedge_overload(0.2, 12.0, 0.18), rel=1e-12)


def test_friction_max_defaults_to_the_scatter_high_end_and_a_given_one_stays(tmp_path):
    scattered = load_case(CASES / "wedge_motor_start_scatter.toml")
    assert scattered.values["friction_max"] == 0.18  # [scatter] friction_coefficient = [0.12, 0.18]
    assert load_case(CASES / "wedge_motor_start.toml").values["friction_max"] == 0.15  # nominal: no range given
    text = (CASES / "wedge_motor_start_scatter.toml").read_text().replace(
        "\n[scatter]", "\n[start_up.overload]\nfriction_max = 0.2\n\n[scatter]")
    assert parse_case(read_toml_text(tmp_path, text), "given.toml").values["friction_max"] == 0.2


def test_each_choice_of_friction_pair_brings_its_own_friction_max(tmp_path):
    """options.choose: organic_dry (f 0.3, f_max 0.45) and sintered_bronze_oiled (f 0.07, f_max 0.08), library."""
    from clutchopt.formulations import get_coupling
    from clutchopt.materials import variants

    text = _lever_text().replace('[library]\nfriction_pair = "organic_dry"\n', "").replace(
        "[options]", '[options]\nchoose = { friction_pair = ["organic_dry", "sintered_bronze_oiled"] }')
    case = parse_case(read_toml_text(tmp_path, text), "choose.toml")
    chosen = {choice["friction_pair"]: variant.values["friction_max"]
              for choice, variant in variants(case, get_coupling("lever"))}
    assert chosen == {"organic_dry": 0.45, "sintered_bronze_oiled": 0.08}


@pytest.mark.parametrize("table, text, field", [
    ("overload", "check = 1", "start_up.overload.check: must be true or false"),
    ("overload", "friction_max = 1.5", "start_up.overload.friction_max: must be <= 1"),
    ("overload", "friction = 0.4", "start_up.overload.friction: unknown key"),
    ("driven", 'max_transmitted_torque = "-3 N*m"', "start_up.driven.max_transmitted_torque: must be > 0"),
])
def test_bad_overload_fields_are_named(table, text, field, tmp_path):
    data = (CASES / "wedge_motor_start.toml").read_text().replace("[start_up.heat]",
                                                                  f"[start_up.{table}]\n{text}\n\n[start_up.heat]")
    with pytest.raises(InputError) as refused:
        parse_case(read_toml_text(tmp_path, data), "bad.toml")
    assert field in str(refused.value)


def test_an_elastic_link_limits_no_torque(tmp_path):
    text = (CASES / "cable_motor_start.toml").read_text()
    start = text.index("[start_up.driver]")
    text = text[:start] + '[start_up.overload]\nfriction_max = 0.3\n\n' + text[start:]
    with pytest.raises(InputError, match="start_up.overload.friction_max: does not apply to the cable coupling"):
        parse_case(read_toml_text(tmp_path, text), "cable.toml")


def read_toml_text(tmp_path, text: str) -> dict:
    path = tmp_path / "case.toml"
    path.write_text(text)
    return read_toml(path)

