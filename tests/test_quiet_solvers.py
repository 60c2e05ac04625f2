"""A sweep's stderr carries clutchopt's own lines only: a NaN at a trial step of CasADi's SQP (the lever's design
mode over its speed: a row's square root of a negative number at a step the line search rejects) is the method's to
handle, and the point's status says what came of it; CasADi printed a 'NaN detected' WARNING line for each."""

from clutchopt.cli import main


def test_a_sweep_through_nan_trial_steps_prints_no_casadi_warning(capfd):
    assert main(["sweep", "cases/lever_centrifuge.toml", "--mode", "design", "--vary", "speed=300:6000:40",
                 "--no-store", "--json"]) == 0
    captured = capfd.readouterr()
    assert '"status": "optimal"' in captured.out
    assert "CasADi" not in captured.err and "NaN detected" not in captured.err
