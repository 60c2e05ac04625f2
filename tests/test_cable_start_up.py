"""The cable coupling's start-up (issue 11, point 4): the cables as a tension-stiffened link, by hand; its simulated
start against the rigid run-up's quadrature; the NLP's quasi-static start against both; the paper-sized design
overloading its cables on a real motor and the start-up design meeting the limit."""

import math
from dataclasses import replace
from types import SimpleNamespace

import pytest
from scipy.integrate import quad

import clutchopt.simulate.on_floats as on_floats
from clutchopt.cases import parse_case, read_toml
from clutchopt.errors import InputError
from clutchopt.formulations.cable.equations import cable_tension
from clutchopt.formulations.cable.speed_law import cable_pretension, link_stiffness, link_tension, link_torque
from clutchopt.start_up.equations import kloss_torque
from clutchopt.optimise import solve_case
from clutchopt.optimise.compare import compare_case
from clutchopt.start_up.simulation import run_start_up, start_up_model, until_lock_up
from tests.conftest import CASES

# cases/cable_pump.toml by hand: span l = 80 mm, finger circle D = 160 mm (psi = 0.5), c_k = 15 kN/m, c_kn = 1.3e7
# N/m, x_2 = 0.05 mm at 1460 rpm, z = 6 (eq. 18 rounded up)
L, PSI, Z = 0.08, 0.5, 6
PRETENSION = 15000.0 * L / 4  # N_0 = c_k l / 4 = 300 N: the pretension behind a mid-span stiffness 4 N_0 / l
WEIGHT_PULL = 1.3e7 * 0.05e-3  # c_kn x_2 = 650 N at the design speed, the travel eq. (9) sizes the weights for
STIFFNESS = Z * (PRETENSION + WEIGHT_PULL) * L / (4 * PSI**2)  # dT/dtheta at theta = 0: 456 N m/rad


def case(name="cable_motor_start.toml", **start_up):
    data = read_toml(CASES / name)
    data["start_up"].update(start_up)
    return parse_case(data, str(CASES / name))


@pytest.fixture(scope="module")
def paper():
    """The paper-sized design (no start-up) of the pump and its parameters."""
    c = case()
    sized = solve_case(parse_case({k: v for k, v in read_toml(CASES / "cable_motor_start.toml").items()
                                   if k != "start_up"}, "x"))
    return c, sized


def test_the_link_by_hand(paper):
    c, sized = paper
    x, p = SimpleNamespace(**sized.design), c.params()
    assert cable_pretension(p.transverse_stiffness, p.span) == pytest.approx(PRETENSION, rel=1e-12)
    assert link_tension(x, p, 0.0, 0.0) == pytest.approx(PRETENSION, rel=1e-12)  # the weights rest
    assert link_tension(x, p, p.speed, 0.0) == pytest.approx(PRETENSION + WEIGHT_PULL, rel=1e-9)
    assert link_stiffness(x, p, p.speed) == pytest.approx(STIFFNESS, rel=1e-9)
    theta = 0.05  # the twist lengthens each cable to (D/2) sqrt(4 psi^2 + theta^2)
    stretch = 1.3e7 * L * (math.sqrt(1 + theta**2 / (4 * PSI**2)) - 1)
    tension = PRETENSION + WEIGHT_PULL + stretch
    assert link_torque(x, p, p.speed, theta) == pytest.approx(Z * tension * L * theta / (4 * PSI**2 + theta**2),
                                                                    rel=1e-9)
    # eq. (18) both ways: the tension the design torque needs at a twist is what carries it there
    needed = cable_tension(108.0, PSI, theta, L, Z)
    assert Z * needed * L * theta / (4 * PSI**2 + theta**2) == pytest.approx(108.0, rel=1e-12)


def rigid_start_time(c) -> float:
    """Motor and pump as one: t = int_0^w_s (J + J_m) / (T_m(w) - T_c(w)) dw, by quadrature."""
    p, profile = c.params(), c.start_up.load_profile
    def integrand(w):
        return (p.driven_inertia + p.motor_inertia) / (
            kloss_torque(w, p.synchronous_speed, p.breakdown_torque, p.breakdown_slip) - profile.at(w, 0.0))
    knots = [w for w in profile.points if 0.0 < w < p.min_lock_up_speed]  # the load's kinks
    return quad(integrand, 0.0, p.min_lock_up_speed, points=knots, epsabs=0, epsrel=1e-10, limit=200)[0]


def test_a_stiff_link_starts_like_a_rigid_one(paper):
    """With a thousand times the pretension the link is nearly rigid: the simulated start approaches the quadrature
    of the rigid run-up, the elastic one lags it by little."""
    c, sized = paper
    stiff = c.with_values(transverse_stiffness=c.values["transverse_stiffness"] * 1000)
    head = run_start_up(start_up_model(stiff, "paper", sized.design)).headline
    assert head["locks_up"]
    assert head["start_time"] == pytest.approx(rigid_start_time(c), rel=2e-3)
    loose = run_start_up(start_up_model(c, "paper", sized.design)).headline
    assert loose["start_time"] == pytest.approx(rigid_start_time(c), rel=2e-2)  # the real link lags a little


def test_a_start_guess_and_the_check_of_a_design_share_one_trace(paper, monkeypatch):
    """The link's rates and stress rate are written out once for a design's start guess (cut at an end time) and
    its check: the run's end, integrator and reported effects enter no equation (a second trace was 8 ms of the
    cable's first solve)."""
    c, sized = paper
    monkeypatch.setattr(on_floats, "_FAMILIES", {})
    model = start_up_model(c, "paper", sized.design, rtol=1e-6)
    guess = run_start_up(until_lock_up(model, 6.0)).headline
    check = run_start_up(model).headline
    assert len(on_floats._FAMILIES) == 2  # link_rates and stress_rate, each once
    assert all(made is not None for made in on_floats._FAMILIES.values())  # written out, not the equations
    assert guess["start_time"] == check["start_time"] == pytest.approx(0.4, rel=0.1)


def test_a_check_locates_only_the_extremes_that_can_be_its_peaks(paper):
    """The twist's and the stress's extremes whose samples are below their largest so far by more than
    clutchopt.simulate.spans.PEAK_MARGIN are not located: every figure of the start the same to the bit as with every
    extreme located (36 fewer samples of 962); a start guess, whose samples are the NLP's initial states, has them
    all."""
    c, sized = paper
    model = start_up_model(c, "paper", sized.design)
    peaks, every = run_start_up(model), run_start_up(replace(model, all_extremes=True))
    assert peaks.headline["peak_stress"] == pytest.approx(423.8e6, rel=1e-3)  # (424 MPa: below)
    assert {k: v for k, v in peaks.headline.items() if v == v} == {k: v for k, v in every.headline.items() if v == v}
    assert len(peaks.columns["t"]) <= len(every.columns["t"]) - 30
    assert until_lock_up(model, 6.0).all_extremes and not model.all_extremes


def test_the_paper_design_overloads_its_cables_and_the_start_up_design_does_not(paper):
    c, sized = paper
    limit = c.values["max_link_stress"]
    head = run_start_up(start_up_model(c, "paper", sized.design)).headline
    assert head["peak_stress"] > 1.1 * limit  # 424 MPa against 350: the motor's breakdown torque passes the cables
    solution = solve_case(c)
    start = solution.start_up
    assert solution.status == "optimal"
    assert solution.design["cable_count"] > sized.design["cable_count"]
    assert start["peak_link_stress_simulated"] <= limit * (1 + c.start_up.tolerance)
    # the NLP's quasi-static run-up is the rigid one: its start time is the quadrature's, to the collocation's error
    assert start["start_time"] == pytest.approx(rigid_start_time(c), rel=1e-6)
    table = {row["quantity"]: row for row in compare_case(c).rows}
    assert table["link_stress_simulated"]["constant_acceleration"] > 1.1 * limit
    assert table["link_stress_simulated"]["nlp_start_up"] <= limit * (1 + c.start_up.tolerance)


def test_a_stress_limit_no_cable_count_meets_is_diagnosed():
    """At speed each cable carries N_0 + c_kn x_2 = 950 N on its 13.2 mm^2 whatever the count: 72 MPa; below it
    no design starts."""
    c = case(limits={"max_start_time": "2 s", "max_link_stress": "50 MPa"})
    solution = solve_case(c)
    assert solution.status == "not_found" and "link_stress" in solution.diagnosis


@pytest.mark.parametrize("edit, text", [
    ({"effects": ["slip_friction"], "driver": {}}, "needs the motor that drives it"),
    ({"effects": ["slip_friction", "motor_curve", "gravity"]}, "gravity does not apply to the cable coupling"),
    ({"limits": {"max_start_time": "2 s", "max_friction_work": "1 kJ"}}, "releases no friction heat"),
    ({"heat": {"capacity": "100 J/K"}}, "start_up.heat.capacity: does not apply to the cable coupling"),
    ({"wear": {"wear_rate": "1e-4 mm^3/J"}}, "start_up.wear.wear_rate: does not apply to the cable coupling"),
])
def test_what_a_cable_start_cannot_take(edit, text):
    with pytest.raises(InputError, match=text):
        case(**edit)
