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


@pytest.mark.xfail(strict=True, reason="open (for the lead): a start-up limit's P(fail) counts failure beyond the "
                                       "start-up's tolerance (1e-6 relative), and FORM takes the performance point, "
                                       "met within it, for the limit state; read strictly (start time > 10 s) the "
                                       "one-in-a-billion design fails with 2.6e-7")
def test_the_system_probability_of_a_one_in_a_billion_design_is_the_designs(capsys):
    """--robust system_chance=0.999999999 (f uniform on 0.12 to 0.18): status optimal, the system's failure
    probability reported 1.5e-10 (at most 1e-9). The design reported, simulated independently (rtol 1e-11): its start
    time at f = 0.12 + 1e-8 is 10.0000016 s, beyond max_start_time = 10 s (by 1.6e-7, within the start-up's
    tolerance 1e-6), and the start time falls with f (torque ~ f), so every f below 0.12 + 1e-8 fails the limit:
    P(fail) >= 1e-8 / 0.06 = 1.67e-7, 170 times the 1e-9 promised (bisection puts the start time's 10 s at
    f = 0.12 + 1.56e-8: P = 2.6e-7). Read with the tolerance (failure: beyond 10 (1 + 1e-6) s), as the importance
    sampling counts it, no f fails and P = 0 <= 1.5e-10: the claim holds only so, and the verification's "every limit
    met" does not say it. The tolerance band itself (|start time - 10 s| <= 1e-5 s: f within about 1.2e-7 of the
    point) holds about 2e-6 of probability, so a 1 - P below that cannot be resolved by the start-up's accuracy;
    at system_chance=0.999999 the strict P is 5.8e-7 against 2.9e-7 reported (still below 1e-6)."""
    from clutchopt.cases import load_case
    from clutchopt.start_up.simulation import run_start_up, start_up_model

    assert main(["solve", SCATTER, "--robust", "system_chance=0.999999999", "--samples", "100", "--starts", "10",
                 "--no-store", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    claimed = out["robust"]["system_failure_probability"]
    assert out["status"] == "optimal" and claimed["high"] <= 1e-9
    case = load_case(CASES / "wedge_motor_start_scatter.toml")
    edge = 0.12 + 1e-8  # P(f < edge) = 1e-8 / 0.06
    start = run_start_up(start_up_model(case.with_values(friction_coefficient=edge), out["mode"], out["design"]))
    fails_below_edge = start.headline["start_time"] > case.values["max_start_time"]
    assert not fails_below_edge or 1e-8 / 0.06 <= claimed["high"]
