"""Property tests over the case space of every coupling (hypothesis): scaled duties, speeds and allowables."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, reject, settings
from hypothesis import strategies as st

from clutchopt.bench.reference import bench_cases, closed_form, reference_mode
from clutchopt.bench.torture import judge, torque_quantities
from clutchopt.errors import InputError
from clutchopt.formulations import get_coupling
from clutchopt.formulations.wedge.closed_forms import closed_form_finger_diameter, closed_form_weight_mass
from clutchopt.optimise import problem_for
from clutchopt.units import ureg

BASE = {case.coupling: case for case in bench_cases()}
SETTINGS = settings(max_examples=60, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])


def _names(coupling, test):
    return [q.name for q in get_coupling(coupling).quantities if test(q) and q.name in BASE[coupling].values]


def _allowables(coupling):
    pressure = ureg.Quantity(1, "Pa").dimensionality
    names = _names(coupling, lambda q: q.name.startswith("allowable_")
                   and ureg.Quantity(1, q.unit).dimensionality == pressure)
    assert names, coupling
    return names


def scaled(coupling, torque=1.0, speed=1.0, allowable=None, factor=1.0):
    """The coupling's bench case with its duty torque, speed and one allowable stress scaled."""
    case = BASE[coupling]
    values = {name: case.values[name] * torque for name in torque_quantities(case)}
    values["speed"] = case.values["speed"] * speed
    if allowable:
        values[allowable] = case.values[allowable] * factor
    case = case.with_values(**values)
    get_coupling(coupling).check_case(case)
    return case


def _solve(case):
    return problem_for(get_coupling(case.coupling).formulation(reference_mode(case.coupling))).solve(case)


cases = st.builds(lambda coupling, torque, speed, which, factor: (coupling, torque, speed, which, factor),
                  st.sampled_from(sorted(BASE)), st.floats(0.2, 5.0), st.floats(0.5, 2.0), st.integers(0, 9),
                  st.floats(0.3, 3.0))


@SETTINGS
@given(cases)
def test_optimum_never_violates_a_constraint(draw):
    coupling, torque, speed, which, factor = draw
    allowables = _allowables(coupling)
    try:
        case = scaled(coupling, torque, speed, allowables[which % len(allowables)], factor)
    except InputError:
        reject()  # a contradictory case, refused naming its field (the bad-input suite's business)
    verdict = judge(case, reference_mode(coupling))
    assert verdict.passed, verdict.detail


@SETTINGS
@given(cases, st.floats(1.0, 4.0))
def test_raising_an_allowable_never_increases_the_minimum_mass(draw, raise_by):
    coupling, torque, speed, which, factor = draw
    allowable = _allowables(coupling)[which % len(_allowables(coupling))]
    try:
        lower, higher = (scaled(coupling, torque, speed, allowable, factor * r) for r in (1.0, raise_by))
    except InputError:
        reject()
    before, after = _solve(lower), _solve(higher)
    if before.status == "optimal":
        assert after.status == "optimal"
        assert after.objective <= before.objective * (1 + 1e-7)
    else:
        assert before.status in ("infeasible", "not_found")


WITH_CLOSED_FORM = sorted(name for name, case in BASE.items() if closed_form(case) is not None)


def test_closed_forms_exist():
    assert WITH_CLOSED_FORM == ["cable", "lever", "wedge"]


@SETTINGS
@given(st.sampled_from(WITH_CLOSED_FORM), st.floats(0.2, 5.0), st.floats(1.0, 3.0))
def test_closed_form_mass_grows_with_torque_and_falls_with_every_allowable(coupling, torque, more):
    try:
        cases_ = [scaled(coupling, torque), scaled(coupling, torque * more)]
    except InputError:
        reject()
    with np.errstate(invalid="ignore", divide="ignore"):
        light, heavy = (closed_form(c).objective for c in cases_)
    assert heavy >= light * (1 - 1e-12)
    for allowable in _allowables(coupling):
        try:
            strong = scaled(coupling, torque, allowable=allowable, factor=more)
        except InputError:
            continue
        with np.errstate(invalid="ignore", divide="ignore"):
            assert closed_form(strong).objective <= light * (1 + 1e-12)


@SETTINGS
@given(st.floats(0.1, 10.0), st.floats(0.3, 3.0), st.floats(0.05, 0.6))
def test_wedge_closed_forms_follow_the_physics(inertia, speed, friction):
    # m_r = 2 T sin(alpha) / (f z (r1 + r2) w^2 r_c): more inertia, more mass; more friction, less; faster, less
    # (T = I w / t_p + T_c grows as w, the centrifugal force as w^2); d_n shrinks as [sigma] grows
    base = BASE["wedge"]
    point = dict(inertia=inertia, speed=base.values["speed"] * speed, friction_coefficient=friction)
    p = base.with_values(**point).params()
    mass = closed_form_weight_mass(p)
    for name, sign in (("inertia", +1), ("friction_coefficient", -1), ("speed", -1)):
        other = closed_form_weight_mass(base.with_values(**{**point, name: point[name] * 1.1}).params())
        assert sign * (other - mass) > 0
    finger = closed_form_finger_diameter(p, mass)
    stronger = base.with_values(**point, allowable_bending_stress=p.allowable_bending_stress * 2).params()
    assert closed_form_finger_diameter(stronger, mass) == pytest.approx(finger / 2 ** (1 / 3), rel=1e-12)
    assert math.isfinite(finger)


@settings(max_examples=200, deadline=None)
@given(st.lists(st.lists(st.booleans(), min_size=4, max_size=4), max_size=30))
def test_active_names_join_each_points_active_constraints(columns):
    # one join per run of equal columns, spread back over the run: equal to joining each column on its own
    import numpy as np

    from clutchopt.optimise.table import active_names

    names = ["torque", "wear", "bending", "stress"]
    active = np.array(columns, dtype=bool).reshape(len(columns), 4).T
    expected = [" ".join(n for n, on in zip(names, column) if on) for column in columns]
    assert active_names(active, names).tolist() == expected
