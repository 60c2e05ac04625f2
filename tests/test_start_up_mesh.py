"""The collocation mesh adapted to a simulated start (clutchopt.start_up.mesh.adapted_mesh): each phase's intervals
equidistribute sqrt|x''| (each state scaled by its spread over the phase and the phase's duration) plus a fifth of
its mean (MONITOR_FLOOR); a state at rest in a phase shapes nothing there."""

from types import SimpleNamespace

import numpy as np
import pytest

from clutchopt.start_up.mesh import MONITOR_FLOOR, adapted_mesh

STRUCTURE = SimpleNamespace(phases=("breakaway", "slip"), intervals=4, motor=False, graded_part=0.05)
T = np.arange(4097) / 2048  # breakaway over [0, 1] s, slip over [1, 2] s, samples every 2^-11 s (exact in binary:
# a straight state's differences are exact, its second derivative exactly 0)


def history(w_driver, w_driven, work, rise):
    return {"t": T, "w_driver": w_driver, "w_driven": w_driven, "friction_work": work, "temperature_rise": rise}


def test_straight_states_give_a_uniform_mesh():
    # x'' = 0 everywhere: the monitor is 0, the weight is time itself, so 4 intervals of 1/4 of each phase
    mesh = adapted_mesh(STRUCTURE, history(3.0 * T, T, 0.5 * T, 2.0 - T), [1.0, 1.0])
    assert mesh == pytest.approx([0.25] * 8, abs=1e-12)


def test_a_corner_draws_the_intervals_and_a_resting_state_shapes_nothing():
    # the driving speed turns at t = 0.5 s (|t - 0.5|: x'' a spike of area 2 there), the friction work rests through
    # the breakaway (a state still there: its spread 0 would divide by 0) and rises in the slip phase.
    # Breakaway: sqrt|x''| integrates to W over the corner; the floor adds 0.2 W t, so the weight climbs 0.1 W up to
    # the corner, W at it, 0.1 W after: 1.2 W in all. The edges at 0.3 W, 0.6 W and 0.9 W all fall at the corner:
    # intervals 0.5, 0, 0, 0.5 (to the spike's width, a few samples of 2^-11 s). Slip: every state straight there, uniform.
    work = np.where(T <= 1.0, 0.0, T - 1.0)
    driver = np.abs(T - 0.5)
    mesh = adapted_mesh(STRUCTURE, history(driver, 0.125 * T, work, 0.0 * T), [1.0, 1.0])
    assert MONITOR_FLOOR == 0.2
    assert mesh[:4] == pytest.approx([0.5, 0.0, 0.0, 0.5], abs=2e-3)
    assert mesh[4:] == pytest.approx([0.25] * 4, abs=1e-12)
    assert np.all(np.isfinite(mesh)) and mesh.sum() == pytest.approx(2.0, rel=1e-15)


def test_a_phase_with_too_few_samples_keeps_its_first_mesh():
    # a breakaway of 1.6e-3 s holds 4 samples (< 5): its intervals stay uniform (first_mesh without a motor)
    mesh = adapted_mesh(STRUCTURE, history(np.abs(T - 0.5), T, T, T), [1.6e-3, 2.0 - 1.6e-3])
    assert mesh[:4] == pytest.approx([0.25] * 4, abs=0)
