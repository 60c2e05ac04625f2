"""Every scattered quantity reaches the constraints it enters, the start-up's included, and a limit's worst end is
its strict one (issue 25): a preload the case fixes moves the engagement window, a geometry the case fixes moves
the static constraints, a scattered start time limit is designed for and checked at its low end."""

import math

import pytest

from clutchopt.cases import Case, parse_case, read_toml
from clutchopt.errors import InputError
from clutchopt.optimise.robust import CHANCE, WORST_CASE, solve_robust
from clutchopt.optimise.robust_start_up import quantile, start_up_corners
from clutchopt.start_up.simulation import run_start_up, start_up_model
from clutchopt.units import to_si
from tests.conftest import CASES

RPM = to_si("window", "1 rpm", "rad/s")


def motor_start(scatter: dict, free: tuple = ("spring_preload",), **limits) -> Case:
    """The paper's example on its motor (cases/wedge_motor_start.toml) with ``scatter``, ``options.free`` and
    start-up limits replaced."""
    data = read_toml(CASES / "wedge_motor_start.toml")
    data["start_up"]["limits"].update(limits)
    data["options"]["free"] = list(free)
    data["scatter"] = scatter
    return parse_case(data, str(CASES / "wedge_motor_start.toml"))


def engagement_speed(case, design: dict, preload: float) -> float:
    """The simulator's engagement speed (rpm) of a design whose springs are preloaded by ``preload`` N."""
    model = start_up_model(case.with_values(spring_preload=preload), "paper", {**design, "spring_preload": preload})
    return math.sqrt(model.law.engagement_squared) / RPM


def start_time(case, design: dict) -> float:
    return run_start_up(start_up_model(case, "paper", design)).headline["start_time"]


@pytest.fixture(scope="module")
def preload_window():
    """Springs preloaded 6 to 18 N (not a design variable), engagement between 250 and 420 rpm."""
    case = motor_start({"spring_preload": ["6 N", "18 N"]}, free=(), min_engagement_speed="250 rpm",
                       max_engagement_speed="420 rpm")
    return case, solve_robust(case, WORST_CASE, starts=10)


def test_a_scattered_preload_moves_the_engagement_window(preload_window):
    """w_e^2 = (F_s + m g) / (m r): the nominal design (375 rpm at 12 N) engages at 448 rpm with 18 N springs,
    above the window; the robust design's weights are heavier, so that it engages within the window at both ends,
    the simulator's engagement speed checked at 6 N and 18 N."""
    case, result = preload_window
    assert result.status == "optimal" and result.settled
    design, nominal = result.solution.design, result.nominal.design
    assert design["spring_preload"] == nominal["spring_preload"] == 12.0  # the case's value, not chosen
    assert engagement_speed(case, nominal, 18.0) > 440
    assert 250 <= engagement_speed(case, design, 6.0) and engagement_speed(case, design, 18.0) <= 420 * (1 + 1e-9)
    assert result.corners["min_engagement_speed"]["spring_preload"] == 6.0
    assert result.corners["max_engagement_speed"]["spring_preload"] == 18.0
    assert result.solution.objective > 1.1 * result.nominal.objective
    for preload in (6.0, 18.0):  # every start-up limit at both ends of the preload
        assert start_time(case.with_values(spring_preload=preload), {**design, "spring_preload": preload}) <= 10.0 * (
            1 + case.start_up.tolerance)


def test_a_window_no_design_meets_under_the_preload_scatter_is_not_optimal():
    """The example's window, 350 to 600 rpm: at 6 N the weights that start the machine in 10 s engage at 276 rpm,
    and lighter ones do not start it in time. The nominal design was called robust; now there is none."""
    case = motor_start({"spring_preload": ["6 N", "18 N"]}, free=())
    result = solve_robust(case, WORST_CASE, starts=10)
    assert result.status != "optimal"
    assert "min_engagement_speed" in result.solution.diagnosis


def test_a_scattered_fixed_geometry_reaches_the_static_constraints():
    """The flank angle the case fixes in geometry mode, scattering 13 to 17 deg: torque ~ 1 / tan(alpha + rho)
    falls at 17 deg, so the robust weights are heavier and the torque holds there."""
    data = read_toml(CASES / "wedge_paper.toml")
    data["scatter"] = {"flank_angle": ["13 deg", "17 deg"]}
    case = parse_case(data, str(CASES / "wedge_paper.toml"))
    for method, target in ((WORST_CASE, None), (CHANCE, 0.999)):
        result = solve_robust(case, method, target, mode="geometry")
        assert result.status == "optimal"
        assert result.solution.objective > 1.1 * result.nominal.objective
        assert result.nominal_failure["torque"][0] > 0.4
        torque = result.reliability.constraints["torque"].best  # importance sampling at the design point
        assert result.failure["torque"][0] == 0.0 if target is None else torque.high <= 2 * (1 - target)


def test_a_scattered_static_limit_is_held_at_its_strict_end():
    """The allowable bending stress 140 to 180 MPa: the fingers are sized for 140 MPa (the corner every constraint
    is evaluated at is its own worst, limits included)."""
    data = read_toml(CASES / "wedge_paper.toml")
    data["scatter"] = {"allowable_bending_stress": ["140 MPa", "180 MPa"]}
    case = parse_case(data, str(CASES / "wedge_paper.toml"))
    result = solve_robust(case, WORST_CASE, samples=1000)
    bending = next(c for c in result.checks if c.name == "finger_bending")
    assert result.status == "optimal" and bending.limit == 140e6 and bending.value <= 140e6 * (1 + 1e-8)
    assert result.corners["finger_bending"] == {"allowable_bending_stress": 140e6}
    assert result.nominal_failure["finger_bending"][0] > 0.4


@pytest.fixture(scope="module")
def start_time_limit():
    """max_start_time 8 to 12 s around the case's 10 s (the issue's example)."""
    case = motor_start({"max_start_time": ["8 s", "12 s"]})
    return case, solve_robust(case, WORST_CASE, starts=10)


def test_a_scattered_upper_limit_is_designed_at_its_low_end(start_time_limit):
    case, result = start_time_limit
    assert result.status == "optimal"
    assert result.corners["start_time"]["max_start_time"] == 8.0
    check = next(c for c in result.checks if c.name == "start_time")
    assert check.limit == 8.0 and check.value <= 8.0 * (1 + case.start_up.tolerance)
    assert start_time(case, result.solution.design) <= 8.0 * (1 + case.start_up.tolerance)
    nominal = next(c for c in result.nominal_checks if c.name == "start_time")
    assert nominal.limit == 8.0 and not nominal.feasible  # the nominal design takes 10 s


def test_a_scattered_lower_limit_is_checked_at_its_high_end():
    """min_lock_up_speed (900 rpm by default: 90 % of synchronous) scattering 850 to 950 rpm."""
    case = motor_start({"min_lock_up_speed": ["850 rpm", "950 rpm"]})
    design = solve_robust(case, WORST_CASE, starts=10).nominal.design
    corners = start_up_corners(case, "paper", design, case.scatter).corners
    assert corners["lock_up_speed"]["min_lock_up_speed"] == pytest.approx(950 * RPM)


def test_with_more_than_four_quantities_a_limit_is_still_at_its_strict_end():
    """Five quantities: each at its worse end, simulated alone, by the margin of each limit (a start that takes as
    long at either end of its limit is not the measure)."""
    case = motor_start({"friction_coefficient": [0.145, 0.155], "breakdown_torque": ["36 N*m", "38 N*m"],
                        "allowable_bending_stress": ["150 MPa", "170 MPa"],
                        "driven_inertia": {"normal": ["0.5 kg*m^2", "0.01 kg*m^2"]},
                        "max_start_time": ["9 s", "11 s"]})
    design = solve_robust(case, WORST_CASE, starts=10).nominal.design
    corners = start_up_corners(case, "paper", design, case.scatter).corners
    assert corners["start_time"]["max_start_time"] == 9.0
    assert corners["start_up"]["friction_coefficient"] == 0.145


def test_chance_counts_a_limit_among_the_quantities_that_move_the_start():
    """Sidak: f and the start time limit both move the start's margins, so each is taken at its quantile
    P^(1/2), not P."""
    case = motor_start({"friction_coefficient": [0.12, 0.18], "max_start_time": ["8 s", "12 s"]})
    design = solve_robust(case, WORST_CASE, starts=10).nominal.design
    ends = start_up_corners(case, "paper", design, case.scatter, 0.99).ends
    declared = {q.name: q for q in case.quantities}
    limit = case.scatter[1]
    assert ends["max_start_time"] == pytest.approx((quantile(limit, 1 - 0.99 ** 0.5, declared["max_start_time"]),
                                                    quantile(limit, 0.99 ** 0.5, declared["max_start_time"])))


@pytest.mark.parametrize("scatter, field", [
    ({"friction_coefficient": {"normal": [0.3, 0.01]}}, "scatter.friction_coefficient.normal: the mean 0.3 is not"),
    ({"driven_inertia": {"normal": ["0.6 kg*m^2", "0.01 kg*m^2"]}}, "scatter.driven_inertia.normal: the mean"),
    ({"friction_coefficient": {"uniform": [0.2, 0.3]}}, "scatter.friction_coefficient: the case's value 0.15"),
    ({"max_start_time": ["11 s", "12 s"]}, "scatter.max_start_time: the case's value 10 s"),
])
def test_a_scatter_must_spread_around_the_case_value(scatter, field):
    with pytest.raises(InputError) as error:
        motor_start(scatter)
    assert field in str(error.value) and ("set the case's value" in str(error.value))
