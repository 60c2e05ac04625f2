"""The start-up's named constraints as the simulator's check evaluates them (clutchopt.start_up.drive.seen_constraints):
each with the design and case values its ``seen`` gives it, built once where those are the start's."""

from types import SimpleNamespace

from clutchopt.cases import load_case
from clutchopt.model import namespace
from clutchopt.optimise.problem import case_problem
from clutchopt.optimise.verify import check_constraints
from clutchopt.start_up import drive
from tests.conftest import CASES

MOTOR = load_case(CASES / "wedge_motor_start.toml")
# figures of a start, as the simulator reports them: 9 s to lock-up, 5 kJ, 3 K, lock-up at 950 rpm
FIGURES = SimpleNamespace(start_time=9.0, friction_work=5000.0, temperatures=3.0, lock_up_speed=99.48, stresses=0.0)


def test_each_constraint_is_checked_with_the_values_its_view_gives_it_built_once_where_they_are_the_start_s(
        monkeypatch):
    """By hand: wedge_motor_start allows max_start_time 10 s and max_temperature_rise 4 K. A view that moves only
    the start time's limit to 12 s (a scatter's corner) checks start_time 9 s against 12 s (margin 3/12 = 0.25) and
    temperature_rise 3 K against 4 K (0.25); the view of the case as it is checks 9 s against 10 s (0.1). Without a
    moved value the constraints are built once (one named_constraints call), with one moved twice."""
    problem = case_problem(MOTOR)
    law, structure = problem.formulation.speed_law, problem.start_up.s
    design = problem.solve(MOTOR).design
    plain = problem.posed.seen_by(MOTOR, design)
    assert plain("start_time") is plain(None)  # one pair for every name: each constraint is the start's at once

    def corner(name):
        x, p = plain(name)
        return (x, namespace({**vars(p), "max_start_time": 12.0})) if name == "start_time" else (x, p)

    calls = []
    built = drive.named_constraints
    monkeypatch.setattr(drive, "named_constraints", lambda *args: calls.append(1) or built(*args))

    def margins(seen):
        calls.clear()
        built_at_start = drive.Drive(structure, law, *seen(None))
        seen_checks = check_constraints(drive.seen_constraints(structure, law, FIGURES, seen, built_at_start), 1e-6)
        checks = {c.name: c for c in seen_checks}
        return checks["start_time"], checks["temperature_rise"], len(calls)

    start_time, temperature, built_times = margins(plain)
    assert (start_time.limit, start_time.margin, temperature.margin) == (10.0, 0.1, 0.25)
    assert built_times == 1
    start_time, temperature, built_times = margins(corner)
    assert (start_time.limit, start_time.margin, temperature.limit, temperature.margin) == (12.0, 0.25, 4.0, 0.25)
    assert built_times == 2
