"""The checks across fields run once for a sweep whose varied quantities none of them reads (clutchopt.fields_read),
and refuse exactly what the check at every point refuses."""

import math
from dataclasses import replace

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.errors import InputError
from clutchopt.fields_read import ReadRecorder, fields_read_across, followers
from clutchopt.optimise import sweep_grid
from clutchopt.optimise.sweep_grid import Vary, check_points, grid_points
from tests.conftest import CASES

WEDGE = load_case(CASES / "wedge_paper.toml")
MOTOR = load_case(CASES / "wedge_motor_start.toml")


def _vary(case, name, values):
    return Vary(next(q for q in case.quantities if q.name == name), tuple(values))


def _refusal(check, case, varies):
    """The message ``check`` refuses the sweep with (None if it passes)."""
    try:
        check(case, varies, grid_points(varies))
    except InputError as exc:
        return str(exc)
    return None


def _each(case, varies, points):
    sweep_grid._check_each(case, points)


def test_the_wedge_checks_read_the_geometry_and_the_shell_not_the_duty():
    # wedge check_case: r2 = K r1 and h_r for r_c > 0, z gamma <= 2 pi; check_shell_room: 2 s < D_max
    assert fields_read_across(WEDGE) == {"radius_ratio", "flank_inner_radius", "weight_height", "weight_count",
                                         "sector_angle", "shell_thickness", "outer_diameter_max"}


def test_a_check_that_reads_the_whole_mapping_or_refuses_the_case_decides_nothing():
    recorder = ReadRecorder({"a": 1.0, "b": 2.0})
    assert recorder["a"] == 1.0 and "c" not in recorder and recorder.get("b") == 2.0
    assert recorder.read == {"a", "b", "c"} and not recorder.everything
    dict(recorder)
    assert recorder.everything
    # z gamma = 9 x 0.785 rad = 7.07 rad > 2 pi: the case itself is refused, so no field set is known
    assert fields_read_across(WEDGE.with_values(weight_count=9.0)) is None
    # a field the case leaves out (a sweep may give it at each point): its check fails on the case itself
    without = {name: value for name, value in WEDGE.values.items() if name != "shell_thickness"}
    assert fields_read_across(replace(WEDGE, values=without)) is None


def test_a_start_up_default_follows_the_duty_so_a_duty_sweep_changes_it():
    # wedge_motor_start: the driven inertia follows duty.inertia (factor 1), and the simulator's range reads it
    assert MOTOR.follows["driven_inertia"][0] == "inertia"
    assert followers(MOTOR, ["inertia"]) >= {"inertia", "driven_inertia"}
    assert "driven_inertia" in fields_read_across(MOTOR)


@pytest.mark.parametrize("case, name, values", [
    (WEDGE, "inertia", [0.25, 0.5, 1.0]),  # unread: checked once
    (WEDGE, "inertia", [0.25, -0.5, 0.0, 1.0]),  # unread, out of range at point 1 (inertia > 0)
    (WEDGE, "sector_angle", [0.5, 0.785, 1.6, 1.7]),  # read: 4 x 1.6 rad = 6.4 rad > 2 pi at point 2
    (MOTOR, "inertia", [0.5, 1.0, 1e6]),  # a follower read: 1e6 kg m^2 beyond the simulator's inertia range
])
def test_the_sweep_is_refused_as_the_check_at_every_point_refuses_it(case, name, values):
    varies = [_vary(case, name, values)]
    assert _refusal(check_points, case, varies) == _refusal(_each, case, varies)


def test_an_unread_quantity_out_of_range_names_its_first_point_and_value():
    varies = [_vary(WEDGE, "inertia", [0.25, 0.5]), _vary(WEDGE, "speed", [100.0, -1.0, math.inf])]
    message = _refusal(check_points, WEDGE, varies)
    assert message == _refusal(_each, WEDGE, varies)
    assert "point 1" in message and "duty.speed" in message  # grid (0.25, -1): the second of 2 x 3 points


def test_no_case_is_built_per_point_when_no_check_reads_the_varied_quantity(monkeypatch):
    calls = []
    monkeypatch.setattr(sweep_grid, "check_across", lambda case: calls.append(case))
    varies = [_vary(WEDGE, "inertia", np.linspace(0.25, 1.0, 50))]
    check_points(WEDGE, varies, grid_points(varies))
    assert calls == []
