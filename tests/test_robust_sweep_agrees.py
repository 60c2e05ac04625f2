"""`sweep --robust` and `solve --robust` ask the same question of a point and get the same answer: one solver
tolerance (clutchopt/solver_tolerance.py) for both, so the same design to round-off and the same Monte Carlo verdict,
even for a chance design whose estimate lies on its target (a design 1e-10 apart could put a sample on the other
side of a limit).

No hand calculation: the reference is `solve --robust` of the case at the point, as a user runs it.
"""

import json

import pytest

from clutchopt.cli.main import build_parser
from clutchopt.optimise.solution import SolverOptions
from clutchopt.optimise.sweep import Sweep
from clutchopt.solver_tolerance import SOLVER_TOL
from conftest import CASES
from tests.composition import run

CENTRIFUGE = CASES / "wedge_centrifuge.toml"  # [scatter]: f 0.12-0.18, inertia normal(12, 0.6), load 15-25 N m
DESIGN_RTOL = 1e-9


def test_solve_sweep_and_the_python_api_default_to_one_tolerance():
    assert SolverOptions().tol == SOLVER_TOL == 1e-10
    assert Sweep.__init__.__defaults__[2] == SOLVER_TOL  # (mode, objective, tol, ...)
    parser = build_parser()
    for command in (["solve"], ["sweep", "--vary", "density=7800"], ["pareto"], ["compare"],
                    ["report", "-o", "r.html"]):
        assert parser.parse_args([*command, str(CENTRIFUGE)]).tol == SOLVER_TOL, command


def test_a_robust_sweep_point_on_its_chance_target_is_solve_s_design_and_verdict():
    # density 7800 then 7850 kg/m^3 (the case's own), chance=0.999 with 2000 samples: the torque row fails in 2 of
    # the 2000 samples, an estimate of 0.001 = 1 - P exactly, its 95 % interval 1.2e-4 to 3.6e-3 containing the
    # target (not above it: the design is verified, status optimal); finger_bending is active too
    code, out, _ = run("sweep", CENTRIFUGE, "--vary", "density=7800,7850", "--robust", "chance=0.999",
                       "--samples", "2000", "--no-store", "--json", "--quiet")
    assert code == 0
    swept = json.loads(out)["points"][1]
    code, out, _ = run("solve", CENTRIFUGE, "--robust", "chance=0.999", "--samples", "2000", "--no-store",
                       "--json", "--quiet")
    assert code == 0
    solved = json.loads(out)
    assert swept["values"] == {"density": 7850.0}
    assert swept["status"] == solved["status"] == "optimal"
    assert swept["design"].keys() == solved["design"].keys()
    for name, value in solved["design"].items():
        assert swept["design"][name] == pytest.approx(value, rel=DESIGN_RTOL, abs=0)
    mine, theirs = swept["robust"], solved["robust"]
    assert mine["status"] == theirs["status"] == "optimal"
    assert mine["failure_probability"] == theirs["failure_probability"]  # each row: estimate, 95 % low, high
    assert mine["monte_carlo_above_target"] == theirs["monte_carlo_above_target"] == []
    assert mine["failure_probability_estimator"] == theirs["failure_probability_estimator"]
    assert theirs["failure_probability"]["torque"][0] == pytest.approx(1 - 0.999, rel=1e-12)  # 2 in 2000: on it
