"""A limit that may be zero never divides by zero (issue 25): a constraint's margin is relative to its scale, the
limit unless the constraint says otherwise, so every scale must stay positive over the valid input. Each case's
posed NLP is evaluated with each quantity at the closed end of its valid range (0 for most: no load, no spring, no
shell) and with all of them there at once; where the case means nothing there, the whole-input check refuses it."""

import tomllib

import numpy as np
import pytest

from clutchopt.cases import check_across, load_case, parse_case
from clutchopt.cli import EXIT_BAD_INPUT, main
from clutchopt.errors import InputError
from clutchopt.optimise.problem import case_problem
from tests.conftest import CASES, COUPLING_CASES

NO_MOTOR = (CASES / "wedge_paper.toml").read_text() + '\n[start_up]\neffects = ["slip_friction", "lockup"]\n'


def cases():
    yield from ((path.name, load_case(path)) for path in COUPLING_CASES)
    yield "wedge without a motor", parse_case(tomllib.loads(NO_MOTOR))


@pytest.mark.parametrize("name, case", list(cases()), ids=lambda v: v if isinstance(v, str) else "")
def test_every_constraint_is_finite_at_the_closed_ends_of_the_ranges(name, case):
    posed = case_problem(case).posed
    ends = {q.name: q.at_least for q in case.quantities if q.name in case.values and q.at_least is not None}
    for values in [{q: end} for q, end in ends.items()] + [ends]:
        try:
            at = case.with_values(**values)
            check_across(at)
        except InputError:
            continue
        data = posed.scaled_data(at)
        rows = np.array(posed.constraint_values(data.x0, data.p)).ravel()
        bad = sorted({posed.row_names[i] for i in np.flatnonzero(~np.isfinite(rows))})
        assert not bad, f"{name} with {values}: {bad}"


def test_a_start_without_load_or_motor_is_solved(tmp_path, capsys):
    path = tmp_path / "case.toml"
    path.write_text(NO_MOTOR.replace('resisting_torque = "5 N*m"', 'resisting_torque = "0 N*m"'))
    assert main(["solve", str(path), "--no-store"]) == 0
    lock_up = next(line for line in capsys.readouterr().out.splitlines() if line.split()[:1] == ["lock_up"])
    assert "+1.00e+06" in lock_up  # measured against a millionth of the drive's torque scale


def test_no_lower_engagement_speed_is_left_out_not_zero(tmp_path, capsys):
    path = tmp_path / "case.toml"
    text = (CASES / "wedge_motor_start.toml").read_text()
    path.write_text(text.replace('min_engagement_speed = "350 rpm"', 'min_engagement_speed = "0 rpm"'))
    assert main(["solve", str(path), "--no-store"]) == EXIT_BAD_INPUT
    assert capsys.readouterr().err == "error: start_up.limits.min_engagement_speed: must be > 0 rpm, got 0 rpm\n"


def test_a_cable_hub_thread_with_nothing_to_push_is_refused():
    text = (CASES / "cable_pump.toml").read_text()
    data = tomllib.loads(text)
    data["cables"]["transverse_stiffness"] = 0
    data["spring"]["spring_compression"] = "0 mm"
    with pytest.raises(InputError, match=r"^cables.transverse_stiffness: is 0, and so is spring.spring_compression: "
                                         r"the hub thread pushes nothing"):
        parse_case(data)
