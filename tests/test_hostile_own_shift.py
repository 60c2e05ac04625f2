"""Hostile start-up sweeps of an elastic link's integer choice (clutchopt.optimise.own_shift, Problem._own_loops):
a sweep point keeps `solve`'s design of the same values alone, the lightest verified one `solve` with each
cable_count fixed finds (docs/start_up.md, "A limit moved for another integer choice").

No hand calculation: the references are `solve` of the point alone and with cable_count fixed (each verified by the
independent simulation of its start)."""

from dataclasses import replace

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from tests.conftest import CASES

CABLE = load_case(CASES / "cable_motor_start.toml")
START_UP_RTOL = 1e-6  # the start-up contract: a sweep point's objective is solve's to 1e-6 relative


def fixed_count(case, count):
    return solve_case(replace(case, bounds={**case.bounds, "cable_count": (float(count),) * 2}))


def test_a_stress_sweep_s_third_point_keeps_12_cables_not_13():
    """allowable_cable_stress 350, 300, 250 MPa: at 250 MPa the point starts from 300's stress limit, moved by 10
    cables' start; the integer search there goes 10 -> 13 (infeasible) -> 14, 13's own loop ends optimal (6.277 kg)
    and 12 cables, never tried, are left, where `solve` of 250 MPa alone finds 12 (5.813 kg, the fixed solve's, its
    own start meeting the case's limit). Failed on main: 13 cables, optimal, exit 0."""
    twelve = fixed_count(CABLE.with_values(allowable_cable_stress=250e6), 12)
    assert twelve.status == "optimal" and twelve.limit_shift == {}
    assert twelve.objective == pytest.approx(5.8126027, rel=1e-7)
    vary = parse_vary("allowable_cable_stress=350,300,250", CABLE.coupling, CABLE.quantities)
    records = list(Sweep(CABLE, [vary]).run(progress=False).solutions)
    record = records[-1]
    assert record["status"] == "optimal" and record["design"]["cable_count"] == 12.0
    assert abs(record["objective"]["value"] - twelve.objective) <= START_UP_RTOL * twelve.objective
