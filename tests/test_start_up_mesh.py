"""The collocation mesh adapted to a simulated start (clutchopt.start_up.mesh.adapted_mesh): each phase's intervals
equidistribute sqrt|x''| (each state scaled by its spread over the phase and the phase's duration) plus a fifth of
its mean (MONITOR_FLOOR); a state at rest in a phase shapes nothing there."""

import pickle
from types import SimpleNamespace

import numpy as np
import pytest

from clutchopt.start_up.mesh import MONITOR_FLOOR, adapted_mesh, graded_mesh

STRUCTURE = SimpleNamespace(phases=("breakaway", "slip"), intervals=4, motor=False)
T = np.arange(4097) / 2048  # breakaway over [0, 1] s, slip over [1, 2] s, samples every 2^-11 s (exact in binary:
# a straight state's differences are exact, its second derivative exactly 0)


def history(w_driver, w_driven, work, rise):
    return {"t": T, "w_driver": w_driver, "w_driven": w_driven, "friction_work": work, "temperature_rise": rise}


def test_straight_states_give_a_uniform_mesh():
    # x'' = 0 everywhere: the monitor is 0, the weight is time itself, so 4 intervals of 1/4 of each phase
    mesh = adapted_mesh(STRUCTURE, history(3.0 * T, T, 0.5 * T, 2.0 - T), [1.0, 1.0], 0.05)
    assert mesh == pytest.approx([0.25] * 8, abs=1e-12)


def test_a_corner_draws_the_intervals_and_a_resting_state_shapes_nothing():
    # the driving speed turns at t = 0.5 s (|t - 0.5|: x'' a spike of area 2 there), the friction work rests through
    # the breakaway (a state still there: its spread 0 would divide by 0) and rises in the slip phase.
    # Breakaway: sqrt|x''| integrates to W over the corner; the floor adds 0.2 W t, so the weight climbs 0.1 W up to
    # the corner, W at it, 0.1 W after: 1.2 W in all. The edges at 0.3 W, 0.6 W and 0.9 W all fall at the corner:
    # intervals 0.5, 0, 0, 0.5 (to the spike's width, a few samples of 2^-11 s). Slip: every state straight there, uniform.
    work = np.where(T <= 1.0, 0.0, T - 1.0)
    driver = np.abs(T - 0.5)
    mesh = adapted_mesh(STRUCTURE, history(driver, 0.125 * T, work, 0.0 * T), [1.0, 1.0], 0.05)
    assert MONITOR_FLOOR == 0.2
    assert mesh[:4] == pytest.approx([0.5, 0.0, 0.0, 0.5], abs=2e-3)
    assert mesh[4:] == pytest.approx([0.25] * 4, abs=1e-12)
    assert np.all(np.isfinite(mesh)) and mesh.sum() == pytest.approx(2.0, rel=1e-15)


def test_a_phase_with_too_few_samples_keeps_its_first_mesh():
    # a breakaway of 1.6e-3 s holds 4 samples (< 5): its intervals stay uniform (first_mesh without a motor)
    mesh = adapted_mesh(STRUCTURE, history(np.abs(T - 0.5), T, T, T), [1.6e-3, 2.0 - 1.6e-3], 0.05)
    assert mesh[:4] == pytest.approx([0.25] * 4, abs=0)


def knee_structure(motor: bool = True) -> SimpleNamespace:
    return SimpleNamespace(motor=motor, spec=SimpleNamespace(tolerance=1e-6))


@pytest.mark.parametrize(("knee", "graded_part", "part"), [
    (0.003, 0.4, 0.02),   # settled at 0.003 of the phase: 6 x 0.003 = 0.018, rounded up to 0.02
    (0.004, 0.4, 0.05),   # 0.024: the next of KNEE_PARTS
    (0.03, 0.05, 0.05),   # 0.18: never more than the structure's part (from the motor's run-up time)
    (0.1, 0.4, 0.4),      # 0.6: the largest part (ball_motor_start's knee, 0.10 of its slip phase)
])
def test_the_slip_phase_is_graded_over_the_knee_the_simulated_start_shows(knee, graded_part, part):
    # the driver's speed runs up linearly to its final speed at ``knee`` of the slip phase (2 s to 3 s) and stays
    from clutchopt.start_up.mesh import KNEE_COVER, KNEE_PARTS, knee_part

    assert KNEE_COVER == 6.0 and KNEE_PARTS == (0.01, 0.02, 0.05, 0.1, 0.2, 0.4)
    t = 2.0 + np.arange(2**14 + 1) / 2**14
    speed = 100.0 * np.minimum((t - 2.0) / knee, 1.0)
    history = {"t": np.concatenate([[0.0, 1.0], t]), "w_driver": np.concatenate([[0.0, 50.0], speed])}
    assert knee_part(knee_structure(), history, (2.0, 3.0), graded_part) == part


def test_a_knee_that_settles_within_the_tolerance_late_keeps_the_structures_part():
    # the speed creeps on by 1e-5 of itself over the whole phase: it settles within 1e-6 only at its end
    from clutchopt.start_up.mesh import knee_part

    t = np.arange(1025) / 1024
    history = {"t": t, "w_driver": 100.0 * (1.0 + 1e-5 * t)}
    assert knee_part(knee_structure(), history, (0.0, 1.0), 0.1) == 0.1
    assert knee_part(knee_structure(motor=False), history, (0.0, 1.0), 0.1) == 0.1  # no motor: no knee


def test_the_graded_mesh_is_found_once_and_read_only():
    """The graded first mesh (a root of its geometric series) is found once per arguments and shared: the same
    array at the next call, read only, so that no solve changes the next one's first mesh; 16 intervals graded over
    5 %: 8 growing from 1e-4 (relative) to sum 0.05, 8 uniform of 0.95 / 8."""
    mesh = graded_mesh(16, 0.05)
    assert graded_mesh(16, 0.05) is mesh
    with pytest.raises(ValueError):
        mesh[0] = 1.0
    assert mesh[:8].sum() == pytest.approx(0.05, rel=1e-12) and mesh.sum() == pytest.approx(1.0, rel=1e-12)
    np.testing.assert_array_equal(mesh[8:], np.full(8, 0.95 / 8))
    assert mesh[0] < mesh[1] < mesh[7]


@pytest.mark.parametrize("times", ["geometric", "uniform", "two spacings"])
def test_the_curvature_is_numpy_s_gradient_of_the_gradient_to_the_bit(times):
    # its difference weights over the samples' times formed once, not in each of np.gradient's two calls: the same
    # operations, so the meshes a simulated start suggests are the same to the last bit
    from clutchopt.start_up.mesh import _second_derivative

    t = {"geometric": 1e-3 * 1.02 ** np.arange(300), "uniform": 0.25 * np.arange(40.0),
         "two spacings": np.concatenate([np.arange(20.0), 20.0 + 3.0 * np.arange(1.0, 20.0)])}[times]
    values = np.vstack([np.sin(t), t**3, np.exp(-t), np.zeros_like(t)])
    exact = np.gradient(np.gradient(values, t, axis=1), t, axis=1)
    assert np.array_equal(_second_derivative(values, t), exact)
    assert _second_derivative(values[:0], t).shape == (0, len(t))


def test_the_suggested_mesh_is_adapted_where_first_read_and_to_the_bit(monkeypatch):
    # a solve's meshes (used, suggested): the used one read without adapting any; the suggestion adapted once, where
    # first read, from the simulated start's columns as they were (the same bits as adapted at once)
    import clutchopt.start_up.mesh as mesh_module
    from clutchopt.start_up.mesh import Meshes

    driver, work = np.abs(T - 0.5), np.where(T <= 1.0, 0.0, T - 1.0)
    columns = history(driver, 0.125 * T, work, T * T)
    expected = adapted_mesh(STRUCTURE, columns, [1.0, 1.0], 0.05)
    adapted = []
    monkeypatch.setattr(mesh_module, "adapted_mesh", lambda *a: adapted.append(a) or expected.copy())
    used = np.full(8, 0.25)
    meshes = Meshes(used, STRUCTURE, columns, [1.0, 1.0], 0.05)
    assert meshes[0] is used and meshes[-2] is used and len(meshes) == 2 and adapted == []
    assert np.array_equal(meshes[1], expected) and len(adapted) == 1
    first, again = meshes[1], meshes[-1]
    assert again is first and len(adapted) == 1
    monkeypatch.undo()
    unpacked_used, suggested = Meshes(used, STRUCTURE, columns, [1.0, 1.0], 0.05)
    assert unpacked_used is used and np.array_equal(suggested, expected)
    with pytest.raises(IndexError):
        meshes[2]
    sent = pickle.loads(pickle.dumps(Meshes(used, STRUCTURE, columns, [1.0, 1.0], 0.05)))  # (to another process:
    # adapted)
    assert np.array_equal(sent[0], used) and np.array_equal(sent[1], expected) and sent._from is None
