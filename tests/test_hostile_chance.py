"""Hostile input and true numbers of the chance start-up (``--robust system_chance=P``, optimise/risk_allocation.py):
a refused target names its own method, and a reported failure probability is checked against an independent
simulation of the design reported."""

import json

import pytest

from clutchopt.cli import EXIT_BAD_INPUT, main
from conftest import CASES

SCATTER = str(CASES / "wedge_motor_start_scatter.toml")


@pytest.mark.parametrize("method", ["chance", "system_chance"])
def test_a_refused_target_shows_its_own_method(method, capsys):
    """--robust system_chance=0.5 was refused with "(e.g. chance=0.999)": the example named the other method."""
    assert main(["solve", SCATTER, "--robust", f"{method}=0.5", "--no-store"]) == EXIT_BAD_INPUT
    assert capsys.readouterr().err == (f"error: --robust: {method}=P needs 0.5 < P <= 1 - 1e-9 (e.g. {method}=0.999), "
                                       "got '0.5'\n")


def test_the_system_probability_of_a_one_in_a_billion_design_is_the_designs(capsys):
    """--robust system_chance=0.999999999 (f uniform on 0.12 to 0.18) was reported `optimal` with the system's failure
    probability 1.5e-10: the start time's share Phi(-beta) at its performance point, where the start is met only
    within the start-up's tolerance (1e-6). The design reported, simulated independently (rtol 1e-11): its start
    time at f = 0.12 + 1e-8 is 10.0000016 s, beyond max_start_time = 10 s, and the start time falls with f (torque
    ~ f), so every f below the crossing fails: P(fail) >= 1e-8 / 0.06 = 1.67e-7 by hand (bisection puts 10 s at
    f = 0.12 + 1.56e-8: P = 2.6e-7, 170 times the 1e-9 promised). Now the limit's probability is that of its strict
    crossing along the ray (one quantity: exact), the system misses its target and says so: `unverified`."""
    from clutchopt.cases import load_case
    from clutchopt.start_up.simulation import run_start_up, start_up_model

    assert main(["solve", SCATTER, "--robust", "system_chance=0.999999999", "--samples", "100", "--starts", "10",
                 "--no-store", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    claimed = out["robust"]["system_failure_probability"]
    case = load_case(CASES / "wedge_motor_start_scatter.toml")
    edge = 0.12 + 1e-8  # P(f < edge) = 1e-8 / 0.06
    start = run_start_up(start_up_model(case.with_values(friction_coefficient=edge), out["mode"], out["design"]))
    if start.headline["start_time"] > case.values["max_start_time"]:  # fails below the edge: P >= 1.67e-7
        assert claimed["probability"] >= 1e-8 / 0.06 and out["status"] == "unverified"
    crossing = 0.12 + 0.06 * out["robust"]["reliability"]["constraints"]["start_time"]["failure_probability"][
        "probability"]  # P(f < crossing): the strict crossing of 10 s, where the start time must be 10 s
    at_crossing = run_start_up(start_up_model(case.with_values(friction_coefficient=crossing), out["mode"],
                                              out["design"]))
    assert at_crossing.headline["start_time"] == pytest.approx(case.values["max_start_time"], rel=1e-9)
