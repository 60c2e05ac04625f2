"""A motor given by its nameplate (rated power and speed, poles, frequency, T_k/T_n) is the Kloss motor derived by
hand, solves as that motor written out, and every bad or doubled field is named."""

import math

import pytest

from clutchopt.cases import parse_case, read_toml
from clutchopt.errors import InputError
from clutchopt.optimise.problem import case_problem
from tests.conftest import CASES

RPM = math.pi / 30
NAMEPLATE = {"rated_power": "2.2 kW", "rated_speed": "940 rpm", "poles": 6, "frequency": "50 Hz",
             "breakdown_ratio": 2.0, "starting_ratio": 1.9, "inertia": "0.012 kg*m^2"}


def _case(driver: dict):
    data = read_toml(CASES / "wedge_motor_start.toml")
    data["start_up"]["driver"] = driver
    return parse_case(data, "nameplate.toml")


def test_nameplate_is_the_kloss_motor_by_hand():
    case = _case(NAMEPLATE)
    rated_torque = 2200 / (940 * RPM)  # 22.35 N m
    rated_slip = 1 - 940 / 1000  # 6 poles at 50 Hz: 1000 rpm
    assert case.values["synchronous_speed"] == pytest.approx(1000 * RPM, rel=1e-15)
    assert case.values["breakdown_torque"] == pytest.approx(2.0 * rated_torque, rel=1e-15)
    assert case.values["breakdown_slip"] == pytest.approx(rated_slip * (2 + math.sqrt(3)), rel=1e-14)
    # the curve through the rating: Kloss's torque at the rated slip is the rated torque
    s, s_k = rated_slip, case.values["breakdown_slip"]
    assert 2 * case.values["breakdown_torque"] / (s / s_k + s_k / s) == pytest.approx(rated_torque, rel=1e-13)
    assert "starting torque is 0.8" in case.start_up.motor_note and "catalogue's 1.9 T_n" in case.start_up.motor_note


def test_a_nameplate_motor_solves_as_the_same_motor_written_out():
    plate = _case(NAMEPLATE)
    written = _case({"synchronous_speed": "1000 rpm", "breakdown_torque": f"{plate.values['breakdown_torque']!r} N*m",
                     "breakdown_slip": plate.values["breakdown_slip"], "inertia": "0.012 kg*m^2"})
    a, b = (case_problem(c).solve(c) for c in (plate, written))
    # the two cases' values differ in the last bits (the synchronous speed from poles and frequency, or written):
    # IPOPT's tolerance 1e-10 on the start-up's NLP bounds how far two such optima may end apart (measured 1.7e-10
    # with the collocation's barrier from 1e-3, docs/start_up.md "IPOPT on the collocation"; 1e-15 from 0.1)
    assert a.status == b.status == "optimal" and a.objective == pytest.approx(b.objective, rel=1e-9)
    assert a.start_up["motor"].startswith("motor from its nameplate") and not b.start_up["motor"]


@pytest.mark.parametrize("change, fields", [
    ({"breakdown_slip": 0.2}, ["start_up.driver.breakdown_slip: given beside the nameplate"]),
    ({"poles": 5}, ["start_up.driver.poles: must be an even whole number"]),
    ({"poles": None, "frequency": None}, ["start_up.driver.poles: missing", "start_up.driver.frequency: missing"]),
    ({"rated_speed": "1000 rpm"}, ["start_up.driver.rated_speed: 1000 rpm is not below the synchronous speed"]),
    ({"breakdown_ratio": 1.0}, ["start_up.driver.breakdown_ratio: T_k/T_n must be above 1"]),
    ({"frequency": "3000 rpm"}, ["start_up.driver.frequency:"]),
    ({"rated_power": "2.2 kW*m"}, ["start_up.driver.rated_power: expected a power"]),
    ({"rated_power": "1e-10 W"}, ["start_up.driver.breakdown_torque: derived from the nameplate's start_up.driver."
                                  "rated_power, start_up.driver.rated_speed, start_up.driver.breakdown_ratio: must be "
                                  "from 1e-09 to 1e+09 N*m"]),
    ({"frequency": "1e-5 Hz", "rated_speed": "1.9e-4 rpm"}, [
        "start_up.driver.synchronous_speed: derived from the nameplate's start_up.driver.poles, "
        "start_up.driver.frequency: must be from 0.001 to 100000 rad/s"]),
])
def test_every_bad_nameplate_field_is_named(change, fields):
    driver = {k: v for k, v in {**NAMEPLATE, **change}.items() if v is not None}
    with pytest.raises(InputError) as refused:
        _case(driver)
    for text in fields:
        assert text in str(refused.value)
