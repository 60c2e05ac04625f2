"""The start-up's collocation (start_up/transcription.py): the slopes of a phase's Radau nodes, built for all its
intervals at once, and the start guess, whose values must land on the NLP's own variables."""

import casadi as ca
import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.posed import Posed
from clutchopt.start_up.drive import Structure, graded_part
from clutchopt.start_up.transcription import DEGREE
from tests.conftest import CASES


def _block(name: str):
    case = load_case(CASES / f"{name}_motor_start.toml")
    formulation = get_coupling(case.coupling).formulation(case.options.get("mode"))
    return Posed(formulation, case.options.get("objective", "mass"), start_up=Structure.of(case)).start_up


def _first_mesh(name: str):
    """The case's first mesh where no start is simulated (its motor's graded part)."""
    case = load_case(CASES / f"{name}_motor_start.toml")
    return _block(name).initial_mesh(graded_part(case.start_up, case.values))


def test_a_phase_s_slopes_differentiate_a_cubic_exactly():
    """Radau IIA of degree 3 differentiates a cubic exactly: on two intervals of lengths 0.3 and 0.7 (of a phase of
    unit duration), y(t) = 1 + 2 t - t^2 + 0.5 t^3 at the phase start and at each interval's nodes t = t_k + tau_j h_k
    gives the slopes dy/dtau = h_k y'(t) = h_k (2 - 2 t + 1.5 t^2) at the nodes j = 1..3 (e.g. at the first interval's
    end, t = 0.3: 0.3 (2 - 0.6 + 0.135) = 0.4605)."""
    block = _block("wedge")
    lengths, starts = [0.3, 0.7], [0.0, 0.3]
    y = lambda t: 1 + 2 * t - t**2 + 0.5 * t**3  # noqa: E731
    chain = [y(0.0)] + [y(starts[k] + block.tau[j] * lengths[k]) for k in range(2) for j in range(1, DEGREE + 1)]
    expected = [lengths[k] * (2 - 2 * t + 1.5 * t**2) for k in range(2)
                for t in (starts[k] + block.tau[j] * lengths[k] for j in range(1, DEGREE + 1))]
    slopes = np.array(ca.mtimes(block._phase_slopes(2), ca.DM(chain))).ravel()
    assert expected[2] == pytest.approx(0.4605, rel=1e-12)
    np.testing.assert_allclose(slopes, expected, rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("name, expected", [
    ("cable", {"duration": 2.0, "driver_speed": 3.0, "twist": 0.7}),  # the elastic link: its driven speed, twist
    ("wedge", {"driver_speed": 5.0, "slip": 2.0, "friction_work": 11.0, "temperature": 0.4}),
])
def test_the_start_guess_puts_each_state_on_its_own_variables(name, expected):
    """A simulated start with constant columns (driving speed 5, driven 3, friction work 11, temperature rise 0.4,
    twist 0.7, locked at 2 s; engaged and moving from the start): each internal variable of the guess (scales 1)
    takes its own state's value: slip 5 - 3 = 2; the cable's one (locked) phase follows the driven speed and the
    twist, in the NLP's order (an interval's speeds, then its twists); the wedge's run-up and breakaway last 0 s, its
    slip phase 2 s."""
    block = _block(name)
    t = np.array([0.0, 10.0])
    history = {"t": t, "w_driver": 5.0 + 0 * t, "w_driven": 3.0 + 0 * t, "friction_work": 11.0 + 0 * t,
               "temperature_rise": 0.4 + 0 * t, "twist": 0.7 + 0 * t}
    values = block.guess(history, {"locks_up": True, "start_time": 2.0}, 0.0, 30.0, np.ones(block.size),
                         _first_mesh(name))
    durations = {"run_up": 0.0, "breakaway": 0.0, "slip": 2.0, "locked": 2.0}
    assert len(values) == len(block.kinds) == block.size
    for value, (phase, kind) in zip(values, block.kinds):
        assert value == pytest.approx(durations[phase] if kind == "duration" else expected[kind], rel=1e-12), (phase,
                                                                                                            kind)


@pytest.mark.parametrize("name", ["cable", "wedge"])
def test_the_start_guess_samples_each_state_at_its_own_node_time(name):
    """A simulated start whose columns grow linearly in time (driving speed 1 + t, driven (1 + t) / 2, friction work
    2 t, temperature rise 3 t, twist 4 t; locked at 2 s, engaged and moving from the start): each state of the guess
    takes its column at its own node's time t_jk = begin + (start_k + tau_j h_k) (end - begin) of its phase, on the
    graded first mesh, in the NLP's order (per interval its nodes' states, then the locked phase's twists)."""
    block = _block(name)
    t = np.array([0.0, 10.0])
    history = {"t": t, "w_driver": 1.0 + t, "w_driven": 0.5 + 0.5 * t, "friction_work": 2.0 * t,
               "temperature_rise": 3.0 * t, "twist": 4.0 * t}
    of_time = {"driver_speed": (lambda s: 0.5 + 0.5 * s) if block.s.elastic else (lambda s: 1.0 + s),
               "slip": lambda s: 0.5 + 0.5 * s, "friction_work": lambda s: 2.0 * s, "temperature": lambda s: 3.0 * s,
               "twist": lambda s: 4.0 * s}
    mesh, n = _first_mesh(name), block.s.intervals
    expected = []
    for index, phase in enumerate(block.s.phases):
        begin, end = (0.0, 2.0) if phase in ("slip", "locked") else (0.0, 0.0)
        expected.append(end - begin)
        lengths = mesh[index * n:(index + 1) * n]
        starts = np.concatenate([[0.0], np.cumsum(lengths)[:-1]])
        names = list(block._states(phase))
        for k in range(n):
            times = [begin + (starts[k] + block.tau[j] * lengths[k]) * (end - begin) for j in range(1, DEGREE + 1)]
            expected += [of_time[state](time) for time in times for state in names]
            expected += [of_time["twist"](time) for time in times] if phase == "locked" else []
    values = block.guess(history, {"locks_up": True, "start_time": 2.0}, 0.0, 30.0, np.ones(block.size), mesh)
    assert len(expected) == block.size
    np.testing.assert_allclose(values, expected, rtol=1e-13, atol=1e-15)


def test_the_internal_bounds_are_built_once_and_read_only():
    """The internal variables' bounds (one pair per variable, scaled) are built once a problem and shared by its
    solves: the same arrays at the next call, read only; the lever's durations from 0, its speeds within [0, 1]."""
    block = _block("lever")
    lower, upper = block.bounds()
    assert block.bounds()[0] is lower and block.bounds()[1] is upper
    assert len(lower) == len(upper) == block.size
    with pytest.raises(ValueError):
        lower[0] = -1.0
    speeds = [i for i, (_, kind) in enumerate(block.kinds) if kind == "driver_speed"]
    assert speeds and np.all(lower[speeds] == 0.0) and np.all(upper[speeds] == 1.0)
