"""A chance design's start-up limits by the performance measure approach (docs/robust.md, "A start-up under a chance
target"): with two scattered quantities the performance point on the beta-sphere is lighter than the corner of the
quantiles, and importance sampling of simulated starts at its design point shows the target met."""

import math

import numpy as np
import pytest
from scipy.special import ndtri

from clutchopt.cases import parse_case, read_toml
from clutchopt.optimise import robust, solve_case
from clutchopt.optimise.robust import CHANCE, solve_robust
from clutchopt.optimise.start_up_reliability import SimulatedLimitStates, performance_point
from tests.conftest import CASES

BETA = -ndtri(0.001)  # 3.090232


@pytest.fixture(scope="module")
def two_quantities():
    """The worked example's drive (cases/wedge_motor_start.toml) without its heat (fewer limits to simulate), with f
    uniform over 0.12 to 0.18 and the driven inertia normal, 0.5 +- 0.025 kg m^2: the start is slowest at low f and
    high inertia, neither alone at its end."""
    data = read_toml(CASES / "wedge_motor_start.toml")
    data["start_up"]["effects"] = ["slip_friction", "motor_curve", "spring_preload", "gravity", "lockup"]
    del data["start_up"]["heat"]
    for limit in ("max_temperature_rise", "starts_per_hour", "heat_dissipation"):
        del data["start_up"]["limits"][limit]
    data["scatter"] = {"friction_coefficient": [0.12, 0.18],
                       "driven_inertia": {"normal": ["0.5 kg*m^2", "0.025 kg*m^2"]}}
    return parse_case(data, str(CASES / "wedge_motor_start.toml"))


def u_of(case, values: dict) -> np.ndarray:
    """The standard normal point of the scattered quantities' values (the inverse of the exact map)."""
    return np.array([float(s.to_standard(values[s.name])) for s in case.scatter])


def test_two_quantities_pma_is_lighter_than_the_quantile_corner_and_meets_the_target(two_quantities, monkeypatch):
    """The corner design (Sidak) puts f and the inertia each at its P^(1/2) = 0.9995 quantile: f 0.12003, inertia
    0.5 + 3.2905 x 0.025 = 0.58226 kg m^2, a point at ||u|| = 3.2905 sqrt 2 = 4.65 in standard normal space. PMA
    puts the start at the start time's performance point on ||u|| = beta = 3.0902, where the start time is longest
    on that sphere: a point of the same probability content to first order, closer to the means, so the weights
    need less mass. Verified: the start time's failure probability by importance sampling of simulated starts at
    its design point lies at or below 1 - P = 0.001 (the failure region curves away from the means here, so FORM's
    beta is conservative), and not above 2 x 0.001."""
    case = two_quantities
    result = solve_robust(case, CHANCE, 0.999, starts=40)
    assert result.status == "optimal" and result.settled and result.start_up_fallbacks == ()
    start = result.corners["start_up"]
    assert np.linalg.norm(u_of(case, start)) == pytest.approx(BETA, rel=1e-9)  # on the beta-sphere
    assert result.corners["start_time"] == start  # the start is simulated where its start time binds
    assert 0.12 < start["friction_coefficient"] < 0.125 and 0.53 < start["driven_inertia"] < 0.58  # both move it
    checks = {c.name: c for c in result.checks}
    assert checks["start_time"].active and checks["start_time"].feasible  # at its own performance point
    sampled = result.reliability.constraints["start_time"].best
    assert sampled.estimator == "importance sampling" and 0 < sampled.probability <= 0.001
    assert sampled.low <= 0.001 and sampled.high <= 0.002
    assert "start-up designed at its performance point" in result.verification

    monkeypatch.setattr(robust, "StartUpPerformancePoints", lambda *args: None)  # the corners of the quantiles
    corner = solve_robust(case, CHANCE, 0.999, starts=10)
    corner_u = u_of(case, corner.corners["start_up"])
    z = ndtri(0.999 ** 0.5)  # 3.2905
    assert corner_u == pytest.approx([-z, z], rel=1e-6)  # f at its low quantile, the inertia at its high one
    assert result.solution.objective < 0.98 * corner.solution.objective  # 1.053 kg against 1.088 kg


class UniformTail:
    """A limit state of a uniform quantity mapped exactly, Phi(u1), beside a normal one, u2: g = 3 Phi(u1) - 0.05 u2
    (a start that slows as f falls and as the inertia grows). The advanced mean value iteration u <- -beta grad g /
    |grad g| jumps for ever between u = (-3.086, 0.156) and (-0.619, 3.028): where f's tail is flat the gradient
    points along u2, and at u2's end along u1."""

    scatter = (None, None)

    def __call__(self, u):
        from scipy.special import ndtr

        u = np.atleast_2d(u)
        return (3 * ndtr(u[0]) - 0.05 * u[1])[None, :]

    value_gradient = SimulatedLimitStates.value_gradient


def test_the_performance_point_where_the_mean_value_iteration_fails():
    """The minimum of g on ||u|| = beta by brute force (10^6 angles) against the search's."""
    g = UniformTail()
    t = np.linspace(-math.pi, math.pi, 1_000_001)
    circle = BETA * np.array([np.cos(t), np.sin(t)])
    best = circle[:, int(np.argmin(g(circle)[0]))]
    u, settled = performance_point(g, 0, BETA)
    assert settled and np.linalg.norm(u) == pytest.approx(BETA, rel=1e-12)
    assert u == pytest.approx(best, abs=1e-3)
    assert g(u[:, None])[0, 0] == pytest.approx(g(best[:, None])[0, 0], abs=1e-6)
    assert g(u[:, None])[0, 0] < g(np.array([[-3.08628327], [0.15617714]]))[0, 0] - 0.01  # below the iteration's


def test_a_limit_whose_point_does_not_settle_falls_back_to_its_quantile_corner(monkeypatch):
    """Where the search does not settle (here made so for the start time), the limit is designed at its quantile
    corner (one uniform f: 0.12 + 0.06 x 0.001 = 0.12006) and named among the fallbacks; the others keep their
    performance points (the lock-up speed at 0.18 - 0.00006 = 0.17994). The quantile corners are simulated once per
    design: f alone at each end of its range (2 starts, which are also the tornado's bars) and at the 2 corners of
    its quantiles; the bars are read from those starts, and the corners found again at the same design (as the SORA
    loop does after its importance sampling) simulate nothing new."""
    from clutchopt.optimise import robust_start_up, start_up_reliability
    from clutchopt.optimise.robust_models import START_UP
    from clutchopt.optimise.robust_start_up import start_up_bars
    from clutchopt.optimise.start_up_reliability import StartUpPerformancePoints

    path = CASES / "wedge_motor_start_scatter.toml"
    case = parse_case(read_toml(path), str(path))
    searched = start_up_reliability.performance_point
    monkeypatch.setattr(start_up_reliability, "performance_point", lambda g, row, beta, start=None: (
        (np.zeros(1), False) if g.names[row] == "start_time" else searched(g, row, beta, start)))
    design = solve_case(case).design  # the nominal design
    started, simulated = [], robust_start_up.simulated_start_ups
    monkeypatch.setattr(robust_start_up, "simulated_start_ups", lambda *args: started.extend(args[3]) or simulated(
        *args))  # the quantile corners' and the bars' starts
    points = StartUpPerformancePoints(case, "paper", 0.999)
    at = points.at(design)
    corners = at.corners
    assert len(started) == 2 + 2  # f at 0.12 and 0.18 alone, then at 0.12006 and 0.17994
    assert dict(at.bars) == start_up_bars(case, "paper", design, case.scatter) and len(started) == 2 + 2 + 2
    searches = len(points.states.simulated)
    assert points.at(design).corners == corners and (len(started), len(points.states.simulated)) == (6, searches)
    assert points.fallbacks == {"start_time"} and "start_time" not in points.points
    assert corners["start_time"]["friction_coefficient"] == pytest.approx(0.12006, rel=1e-9)
    assert corners["lock_up_speed"]["friction_coefficient"] == pytest.approx(0.17994, rel=1e-9)
    assert corners[START_UP]["friction_coefficient"] == pytest.approx(0.12006, rel=1e-9)  # the figures bind at low f
    assert "start_time" not in {c.name for c in points.checks()}  # checked at its corner by the caller


def test_system_chance_gives_the_start_up_limits_their_shares_of_the_target(two_quantities):
    """system_chance=0.999 on a start-up: the design (any closed-form constraint or start-up limit) fails with at
    most 1 - P = 0.001. Each start-up limit the scatter moves takes an equal share s of 0.001 with the allocated
    constraints (k limits, n constraints: s = 0.001 / (k + n)), the NLP splits what is left, 0.001 - k s, between
    the constraints; the union bound of the system (the constraints' by importance sampling plus each limit's
    estimate) is shown within 1 - P."""
    from clutchopt.optimise.robust import SYSTEM_CHANCE

    result = solve_robust(two_quantities, SYSTEM_CHANCE, 0.999, starts=40)
    assert result.status == "optimal"
    share, allocated = result.start_up_share, len(result.allocation.names)
    k = round((0.001 - result.allocation.allowed) / share)
    assert k >= 1 and share == pytest.approx(0.001 / (k + allocated), rel=1e-12)
    assert result.allocation.allowed == pytest.approx(0.001 - k * share, rel=1e-12)
    start_time = result.reliability.constraints["start_time"].best
    assert start_time.probability <= share and start_time.high <= 2 * share  # designed for its share
    system = result.design_failure()
    assert system.probability == pytest.approx(result.reliability.system.probability + sum(
        c.best.probability for name, c in result.reliability.constraints.items() if name in result.start_up_failure))
    assert system.probability <= 0.001 and system.low <= 0.001
    data = result.as_dict()
    assert data["system_failure_probability"]["probability"] == system.probability
    assert data["start_up_verification"]["share_of_target"] == share
    assert "the system with the start-up limits" in result.verification


def test_the_shares_are_taken_from_the_gradients_at_the_means(two_quantities):
    """take_shares decides which start-up limits the scatter moves from g and its gradient at the means (n + 1 = 3
    simulated starts: the means and a step STEP along each u), not from each limit's search on the sphere: the
    search ends at the means only where |grad g| < NEGLIGIBLE there. The searches (about 100 simulated starts) find
    4 limits moved on this design: the start time, the lock-up speed, lock-up and stays-locked, which f or the
    inertia move; the engagement windows, the breakdown and overload torques are closed forms of the design that
    neither moves. With 2 other constraints the share is 0.001 / (4 + 2) and 0.001 - 4 x 0.001 / 6 is left."""
    from clutchopt.optimise.start_up_reliability import StartUpPerformancePoints

    case = two_quantities
    design = solve_case(case).design
    searched = StartUpPerformancePoints(case, "paper", 0.999)
    searched.at(design)
    moved = {name for name, u in searched.points.items() if np.any(u)} | searched.fallbacks
    assert moved == {"start_time", "lock_up_speed", "lock_up", "stays_locked"}
    assert len(searched.states.simulated) > 50
    points = StartUpPerformancePoints(case, "paper", 0.999)
    assert points.take_shares(design, 2, 0.001) == pytest.approx(0.001 - 4 * 0.001 / 6, rel=1e-12)
    assert points.share == pytest.approx(0.001 / 6, rel=1e-12) and points.target == 1 - points.share
    assert len(points.states.simulated) == 3  # the means and one step along each u


def test_a_limit_failing_at_its_point_is_crossed_between_the_means_and_that_point_itself():
    # strict_reach's bracket ends at u itself, not at radius * (u / radius), which differs from u = (0.213643,
    # 0.217322) in its last bits: a limit a hair below zero at u (g = -1e-12, its start simulated there) and a hair
    # above everywhere else on the ray from the means, g = 1 - t / |u| > 0 for t < |u|, would have had no sign change
    from clutchopt.optimise.start_up_reliability import strict_reach

    u = np.array([0.213643, 0.217322])
    radius = float(np.linalg.norm(u))
    assert (radius * (u / radius)).tobytes() != u.tobytes()

    def g(points):
        point = points[:, 0]
        if point.tobytes() == u.tobytes():
            return np.array([[-1e-12]])
        return np.array([[max(1.0 - float(np.linalg.norm(point)) / radius, 1e-12)]])

    reach = strict_reach(g, 0, u)
    assert 0.0 < reach <= radius
    assert reach == pytest.approx(radius, rel=1e-6)
