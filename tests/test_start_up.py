"""The start-up inside the NLP (issue 11): hand calculations of constant-speed starts, the NLP against the
independent simulator on real drives, infeasible drives diagnosed, the constant-acceleration design shown missing."""

import json
import math
import re

import pytest

from clutchopt.cases import parse_case, read_toml
from clutchopt.optimise import solve_case
from clutchopt.optimise.compare import compare_case
from tests.conftest import CASES

# The paper's worked example (wedge_paper.toml), started at its constant driving speed, by hand.
W0 = 1000 * 2 * math.pi / 60  # 104.7197551 rad/s
J, T_C, T_P = 0.5, 5.0, 10.0
T_NEEDED = J * W0 / T_P + T_C  # 10.2359878 N m: constant torque T reaches w0 in J w0 / (T - T_c) = t_p
R1, R2, H_R, Z, F, ALPHA = 0.05, 0.06, 0.02, 4, 0.15, math.radians(15)
R_C = R2 - 2 / 3 * H_R  # 0.0466667 m, eq. (11)
C_F = Z * F / math.sin(ALPHA) * (R1 + R2) / 2  # 0.1275 N m of torque per N of net radial force, eqs. (12)-(15)
G = 9.80665
F_S = 12.0  # spring preload per weight, N
# With springs and gravity the net radial force is m r_c w0^2 - F_s - m g, so T = c_F (m (r_c w0^2 - g) - F_s):
M_SPRINGS = (T_NEEDED / C_F + F_S) / (R_C * W0**2 - G)  # (80.28 + 12) N / 501.95 m/s^2 = 0.18384 kg per weight
# Constant torque, slip falling linearly from w0 to 0 in t_p: friction work L = T w0 t_p / 2 (a constant T)
L_CONSTANT = T_NEEDED * W0 * T_P / 2  # 5359.55 J; with C = 1400 J/K and no conductance, the rise is L / C
HEAT_CAPACITY = 1400.0


def case_from(name: str, **edits):
    """A case file with its [start_up] section edited: ``section__key=value`` sets, ``section__key=None`` drops."""
    data = read_toml(CASES / name)
    for path, value in edits.items():
        *tables, key = path.split("__")
        table = data
        for part in tables:
            table = table.setdefault(part, {})
        if value is None:
            table.pop(key, None)
        else:
            table[key] = value
    return parse_case(data, str(CASES / name))


def constant_speed(effects, **edits):
    """The paper's example with a [start_up] at its constant driving speed (no motor), preload 12 N if listed."""
    section = {"effects": effects}
    if "spring_preload" in effects:
        section["spring_preload"] = f"{F_S} N"
    if "friction_heat" in effects:
        section["heat"] = {"capacity": f"{HEAT_CAPACITY} J/K"}
    return case_from("wedge_motor_start.toml", **{"start_up": section, "options": {},
                                                  "bounds": {"weight_width": ["5 mm", "40 mm"]}, **edits})


def test_hand_numbers():
    assert T_NEEDED == pytest.approx(10.2359878, rel=1e-8)
    assert C_F == pytest.approx(0.12750, rel=1e-4)
    assert M_SPRINGS == pytest.approx(0.18384, rel=1e-4)


def test_constant_speed_without_springs_is_todays_optimum():
    """Issue 11, point 8: constant driving speed, no springs, no gravity: the start-up optimum is the papers'."""
    case = constant_speed(["slip_friction", "lockup", "friction_heat"])
    solution = solve_case(case)
    sized = solve_case(case_from("wedge_paper.toml"))
    assert solution.status == "optimal"
    assert solution.objective == pytest.approx(sized.objective, rel=1e-8)  # 0.667951 kg
    assert solution.design["weight_mass"] == pytest.approx(2 * T_NEEDED * math.sin(ALPHA)
                                                           / (Z * F * W0**2 * R_C * (R1 + R2)), rel=1e-8)
    start = solution.start_up
    assert start["start_time"] == pytest.approx(T_P, rel=1e-8)
    assert start["start_time_simulated"] == pytest.approx(T_P, rel=1e-8)
    assert start["friction_work"] == pytest.approx(L_CONSTANT, rel=1e-8)
    assert start["temperature_rise"] == pytest.approx(L_CONSTANT / HEAT_CAPACITY, rel=1e-8)
    assert start["phases"] == ["slip"] and start["engagement_speed"] == 0.0


def test_springs_and_gravity_at_constant_speed_by_hand():
    """The spring preload and the weight's own weight take force from each weight: m = (T / c_F + F_s) / (r_c w0^2 - g)."""
    case = constant_speed(["slip_friction", "spring_preload", "gravity", "lockup"])
    solution = solve_case(case)
    assert solution.status == "optimal" and solution.design["spring_preload"] == F_S
    assert solution.design["weight_mass"] == pytest.approx(M_SPRINGS, rel=1e-8)
    assert solution.start_up["engagement_speed"] == pytest.approx(
        math.sqrt((F_S + M_SPRINGS * G) / (M_SPRINGS * R_C)), rel=1e-8)
    assert solution.start_up["start_time_simulated"] == pytest.approx(T_P, rel=1e-8)


def test_a_binding_heat_limit_at_constant_speed():
    """At constant speed L = T w0 t_c / 2 with t_c = J w0 / (T - T_c): less heat needs more torque, so a heat
    limit binds: T = T_c w0 ... solved here by hand from L(T) = L_max."""
    limit = 5000.0  # J, below the 5359.55 J of the sized design
    # L(T) = T w0 (J w0 / (T - T_c)) / 2 = L_max  =>  T (J w0^2 / 2) = L_max (T - T_c)  =>  T = L_max T_c / (L_max - J w0^2 / 2)
    torque = limit * T_C / (limit - J * W0**2 / 2)
    case = constant_speed(["slip_friction", "lockup"], start_up__limits={"max_friction_work": f"{limit} J"})
    solution = solve_case(case)
    assert solution.status == "optimal"
    assert solution.outputs["torque"].value == pytest.approx(torque, rel=1e-7)
    assert solution.start_up["friction_work_simulated"] == pytest.approx(limit, rel=1e-7)
    assert solution.start_up["start_time_simulated"] < T_P  # the heat limit, not the start time, binds
    work = next(c for c in solution.constraints if c.name == "friction_work")
    assert work.active and work.multiplier > 0


@pytest.fixture(scope="module", params=["wedge_motor_start.toml", "lever_motor_start.toml", "ball_motor_start.toml"])
def motor_case(request):
    case = case_from(request.param)
    return case, solve_case(case), compare_case(case)


def test_real_drives_are_met_and_verified_by_the_simulator(motor_case):
    case, solution, _ = motor_case
    start = solution.start_up
    tolerance = case.start_up.tolerance
    assert solution.status == "optimal", solution.diagnosis
    assert start["locks_up"]
    assert start["start_time_simulated"] <= case.values["max_start_time"] * (1 + tolerance)
    assert abs(start["discretisation_error"]["start_time"]) <= tolerance
    assert start["friction_work"] == pytest.approx(start["friction_work_simulated"], rel=1e-4)
    for check in solution.constraints:
        assert check.feasible, check.name
    active = [c.name for c in solution.constraints if c.active]
    assert "start_time" in active  # the limit binds


def test_the_constant_acceleration_design_misses_the_start(motor_case):
    case, solution, table = motor_case
    rows = {row["quantity"]: row for row in table.rows}
    limit = case.values["max_start_time"]
    assert rows["start_time_simulated"]["constant_acceleration"] > 1.05 * limit
    assert rows["start_time_simulated"]["nlp_start_up"] <= limit * (1 + case.start_up.tolerance)
    assert table.solutions["nlp_start_up"].objective > table.solutions["constant_acceleration"].objective


def test_a_motor_too_weak_for_the_load_is_diagnosed():
    case = case_from("wedge_motor_start.toml", start_up__driver__breakdown_torque="4 N*m")
    solution = solve_case(case)
    assert solution.status == "infeasible"
    # proven before any start-up solve (clutchopt/optimise/proofs.py): above its breakdown speed (800 rpm) the Kloss
    # torque falls, so at or above the lock-up speed 900 rpm (s = 0.1, s_k = 0.2) the motor gives at most
    # 2 * 4 * 0.1 * 0.2 / (0.1^2 + 0.2^2) = 3.2 N m, less than the load's 5 N m
    assert solution.diagnosis.startswith("proven infeasible: the motor gives at most 3.2 N*m (breakdown_torque 4 N*m) "
                                         "at or above min_lock_up_speed 900 rpm, less than the machine's load_torque "
                                         "5 N*m")


def test_an_engagement_window_the_springs_cannot_meet_is_diagnosed():
    """Preload fixed at 12 N: the weights engage near 380 rpm, outside a 600-700 rpm window."""
    case = case_from("wedge_motor_start.toml", options={},
                     start_up__limits={"min_engagement_speed": "600 rpm", "max_engagement_speed": "700 rpm"})
    solution = solve_case(case)
    assert solution.status == "not_found"
    assert "min_engagement_speed" in solution.diagnosis


def test_a_narrow_engagement_window_stays_stable():
    case = case_from("wedge_motor_start.toml", start_up__limits__min_engagement_speed="400 rpm",
                     start_up__limits__max_engagement_speed="400.5 rpm")
    solution = solve_case(case)
    assert solution.status == "optimal"
    assert 400 * (1 - 1e-9) <= solution.start_up["engagement_speed"] * 30 / math.pi <= 400.5


def test_solve_json_has_the_start_up(cli):
    result = cli("solve", "cases/wedge_motor_start.toml", "--json", "--no-store")
    assert result.returncode == 0, result.stderr
    data = json.loads(result.stdout)
    start = data["start_up"]
    assert data["status"] == "optimal"
    for key in ("start_time", "start_time_simulated", "friction_work", "friction_work_simulated",
                "temperature_rise", "engagement_speed", "lock_up_time", "intervals"):
        assert key in start
    assert start["units"]["friction_work"] == "J" and start["friction_work"] > 1000  # joules, not kJ
    assert len(start["trajectory"]["t"]) == len(start["trajectory"]["w_driven"]) > 3 * start["intervals"]
    names = {c["name"] for c in data["constraints"]}
    assert {"start_time", "temperature_rise", "min_engagement_speed", "lock_up"} <= names
    assert "torque" not in names  # the papers' constant-acceleration requirement gives way to the start-up


@pytest.mark.parametrize("edit, field", [
    ({"start_up__effects": ["slip_friction", "motor"]}, "start_up.effects"),
    ({"start_up__effects": ["lockup"]}, "start_up.effects"),
    ({"start_up__driver__breakdown_slip": 1.5}, "start_up.driver.breakdown_slip"),
    ({"start_up__driver__inertia": None}, "start_up.driver.inertia"),
    ({"start_up__effects": ["slip_friction", "lockup", "friction_heat"]}, "start_up.driver.synchronous_speed"),
    ({"start_up__heat": None}, "start_up.heat.capacity"),
    ({"start_up__limits__max_engagement_speed": "300 rpm"}, "start_up.limits.min_engagement_speed"),
    ({"start_up__limits__starts_per_hour": None}, "start_up.limits.starts_per_hour"),  # heat_dissipation needs it
    ({"start_up__intervals": 1000}, "start_up.intervals"),
    ({"start_up__driven__load_profile": {"over": "speed", "points": ["0 rpm"], "torque": ["1 N*m"]}},
     "start_up.driven.load_profile"),
    ({"start_up__limits__max_start_time": "-3 s"}, "start_up.limits.max_start_time"),
    ({"start_up__surprise": 1}, "start_up.surprise"),
])
def test_bad_start_up_sections_name_the_field(edit, field):
    from clutchopt.errors import InputError

    with pytest.raises(InputError) as error:
        case_from("wedge_motor_start.toml", **edit)
    assert error.value.field.startswith(field.rsplit(".", 1)[0]), (error.value.field, field)
    assert re.search(field.rsplit(".", 1)[-1], str(error.value))


def test_a_ball_case_refuses_springs():
    from clutchopt.errors import InputError

    with pytest.raises(InputError, match="spring_preload does not apply to the ball coupling"):
        case_from("ball_motor_start.toml",
                  start_up__effects=["slip_friction", "motor_curve", "spring_preload", "friction_heat"])


def test_sweep_pareto_and_report_take_start_up_cases():
    from clutchopt.optimise.pareto import pareto_front
    from clutchopt.optimise.sweep import Sweep
    from clutchopt.optimise.sweep_grid import parse_vary
    from clutchopt.report import build_report

    case = case_from("wedge_motor_start.toml")
    sweep = Sweep(case, [parse_vary("max_start_time=10,12", case.coupling, case.quantities)])
    result = sweep.run(progress=False)
    frame = result.frame
    assert list(frame["status"]) == ["optimal", "optimal"]
    mass = frame[[c for c in frame.columns if c.startswith("mass")][0]].tolist()
    assert mass[1] < mass[0]  # a longer start allowed, a lighter coupling
    assert "spring_preload [N]" in frame.columns
    front = pareto_front(case, points=3)
    assert all(s.status == "optimal" for s in front.solutions)
    page = build_report(case, solve_case(case))
    assert "Radau collocation" in page and "start_time" in page and "simulated" in page
