"""A start-up sweep's points solved from the point before's optimum (clutchopt.optimise.start_up_sweep): each point's
design is the one ``clutchopt solve`` gives at its values, every solve still checked by the simulator."""

import numpy as np

from clutchopt.cases import load_case
from clutchopt.optimise import start_up_sweep, sweep
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from tests.conftest import CASES

MOTOR = load_case(CASES / "wedge_motor_start.toml")


def test_a_start_up_sweep_gives_each_point_solve_s_design_from_the_point_before(monkeypatch):
    along = []

    def spy(problem, case, previous):
        found = start_up_sweep.solved_along(problem, case, previous)
        along.append(found is not None)
        return found

    monkeypatch.setattr(sweep, "solved_along", spy)
    vary = parse_vary("driven_inertia=0.3,0.5,0.7", MOTOR.coupling, MOTOR.quantities)
    result = Sweep(MOTOR, [vary]).run(progress=False)
    assert along == [False, True, True]  # the first point cold (none before it), the others from the one before
    problem = case_problem(MOTOR)
    for point, inertia in enumerate(vary.values):
        alone = problem.solve(MOTOR.with_values(driven_inertia=inertia))
        record = result.solutions[point]
        assert record["status"] == alone.status == "optimal"
        swept = np.array([record["design"][name] for name in alone.design])
        assert np.allclose(swept, list(alone.design.values()), rtol=1e-6, atol=0)
        assert abs(record["objective"]["value"] - alone.objective) <= 1e-6 * abs(alone.objective)
        # verified by the simulator as solve verifies it: its start time beside the collocation's
        simulated = record["start_up"]["start_time_simulated"]
        assert abs(simulated - alone.start_up["start_time_simulated"]) <= 1e-6 * simulated
