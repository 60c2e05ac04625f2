"""A start-up sweep's points solved from the point before's optimum (clutchopt.optimise.start_up_sweep): each point's
design is the one ``clutchopt solve`` gives at its values, every solve still checked by the simulator."""

from dataclasses import replace

import numpy as np
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import start_up_sweep, sweep
from clutchopt.optimise.problem import Problem, case_problem
from clutchopt.optimise.start_up_check import CENTRE
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


def test_the_limits_a_point_starts_with_follow_the_secant_through_the_two_points_before():
    """predicted_shift by hand: the two points before at J = 0.60 and 0.61 kg m^2 ended with the temperature limit's
    share (centred) 1 - 1.9765e-4 and 1 - 1.9470e-4 on the same mesh. At 0.62 (one step on, t = 1) the secant gives
    2 (1 - 1.9470e-4) - (1 - 1.9765e-4) = 1 - 1.9175e-4; at 0.625 (t = 1.5) 1 - 1.9470e-4 + 1.5 x 2.95e-6
    = 1 - 1.90275e-4. Beyond FURTHEST steps, off the line through the two points, or across a mesh change the point
    before's centred share is carried as it is; without points before, its limit_shift."""
    from types import SimpleNamespace

    from clutchopt.optimise.start_up_sweep import Along, predicted_shift, secant_step

    mesh = np.full(16, 1 / 16)
    before = Along({"driven_inertia": 0.60, "speed": 100.0}, {"max_temperature_rise": 1 - 1.9765e-4}, mesh)
    last = Along({"driven_inertia": 0.61, "speed": 100.0}, {"max_temperature_rise": 1 - 1.9470e-4}, mesh, before)
    previous = SimpleNamespace(along=last, limit_shift={"max_temperature_rise": 1 - 1.9400e-4})  # as its last NLP

    def at(inertia, speed=100.0, point_before=previous):
        step = secant_step(point_before.along, {"driven_inertia": inertia, "speed": speed})
        return predicted_shift(point_before, step, 1e-6)

    assert at(0.62)["max_temperature_rise"] == pytest.approx(1 - 1.9175e-4, rel=0, abs=1e-15)
    assert at(0.625)["max_temperature_rise"] == pytest.approx(1 - 1.90275e-4, rel=0, abs=1e-15)
    assert at(0.65) == last.shift  # t = 4 > FURTHEST
    assert at(0.62, speed=101.0) == last.shift  # not on the line through the points before
    adapted = SimpleNamespace(along=Along(last.values, last.shift, mesh * 1.0 + [0.01, -0.01] * 8, before),
                              limit_shift=previous.limit_shift)
    assert at(0.62, point_before=adapted) == last.shift  # a mesh adaptation between them
    cold = SimpleNamespace(along=None, limit_shift=previous.limit_shift)  # the sweep's first point: solve's
    assert at(0.62, point_before=cold) == previous.limit_shift


def test_a_binding_limit_is_centred_on_the_simulated_figure():
    """centred_shift by hand: the NLP saw max_temperature_rise 4 K x 0.9998 = 3.9992 K; the simulated peak is
    4 K + 2e-6 K, the check active: centred on the simulator, the NLP's limit would be 3.9992 - 2e-6 K, a share of
    0.9998 - 5e-7. An active limit never moved (max_friction_work 8 kJ, the simulated 8000.004 J) from the case's:
    a share of 1 - 0.004 / 8000 = 1 - 5e-7. An inactive check whose NLP figure is known (the start time, simulated
    9.0 s where the collocation gave 9.0 s - 3e-6 s, the case's limit 10 s) is centred on what the simulator adds to it,
    L - (S - C): a share of 1 - 3e-7, whatever share the NLP saw (0.99), so that the point where it first binds meets
    it; one without the NLP's figure (the heat per hour) is left as it is."""
    from types import SimpleNamespace

    from clutchopt.optimise.start_up_sweep import centred_shift

    check = SimpleNamespace(name="temperature_rise", active=True, sense="<=", value=4.0 + 2e-6, limit=4.0)
    work = SimpleNamespace(name="friction_work", active=True, sense="<=", value=8000.004, limit=8000.0)
    loose = SimpleNamespace(name="start_time", active=False, sense="<=", value=9.0, limit=10.0)
    heat = SimpleNamespace(name="heat_per_hour", active=False, sense="<=", value=50.0, limit=60.0)
    solution = SimpleNamespace(constraints=[check, work, loose, heat], collocated={"start_time": 9.0 - 3e-6},
                               limit_shift={"max_temperature_rise": 0.9998, "max_start_time": 0.99,
                                            "heat_dissipation": 0.999})
    case = SimpleNamespace(values={"max_temperature_rise": 4.0, "max_start_time": 10.0, "max_friction_work": 8000.0,
                                   "heat_dissipation": 60.0})
    shares = centred_shift(solution, case)
    assert shares["max_temperature_rise"] == pytest.approx(0.9998 - 5e-7, rel=0, abs=1e-15)
    assert shares["max_friction_work"] == pytest.approx(1 - 5e-7, rel=0, abs=1e-15)
    assert shares["max_start_time"] == pytest.approx(1 - 3e-7, rel=0, abs=1e-15)
    assert shares["heat_dissipation"] == 0.999


def test_an_elastic_link_s_sweep_carries_its_limits_as_they_are(monkeypatch):
    """The cable's loop moves the stress limit only where the simulated start misses it, never centres it (its NLP
    is another model than the simulated dynamics): its points record nothing for a secant, and each starts from the
    limit share the point before ended with (the same at every point: the stress limit moved by the same share)."""
    cable = load_case(CASES / "cable_motor_start.toml")
    seen = []

    def spy(problem, case, previous):
        found = start_up_sweep.solved_along(problem, case, previous)
        step = start_up_sweep.secant_step(previous.along, start_up_sweep._numbers(case)) if found else None
        predicted = start_up_sweep.predicted_shift(previous, step, 1e-6) if found is not None else None
        seen.append((found, predicted,
                     previous.limit_shift if previous is not None else None))
        return found

    monkeypatch.setattr(sweep, "solved_along", spy)
    vary = parse_vary("driven_inertia=0.2,0.21,0.22", cable.coupling, cable.quantities)
    Sweep(cable, [vary]).run(progress=False)
    along = [(found, shift, before) for found, shift, before in seen if found is not None]
    assert len(along) == 2
    for found, shift, before in along:
        assert found.along is None and shift == before and set(shift) == {"max_link_stress"}


def test_an_elastic_link_s_sweep_solves_the_papers_sizing_once_for_its_probes(monkeypatch):
    """cable_motor_start over driven_inertia (0.6x-1.4x, five of the bench's points): its designs leave the papers'
    sizing's integers (6 cables; 7 and 8 kept), so every point solved along reads the sizing to decide whether it is
    probed as ``solve`` would (:func:`~clutchopt.optimise.start_up_sweep.as_solve_would`; none is since its lighter
    counts are settled there, ``Problem.lighter_settled``: 3, 5, 5, 4 solver calls to 1, 3, 3, 2), and the sizing was
    solved again at each (3 static IPOPT runs). The driven inertia enters no row of the sizing: it is solved once
    more after the first point's cold solve, at the first point solved along the sweep, and carried (its loop takes
    none of it, as before): 5 static solves to 2 (3 where the first point solved along solved it for its probe and
    the next once more), every point's status, design and solver calls the same to the last bit."""
    cable = load_case(CASES / "cable_motor_start.toml")
    points = ",".join(str(0.25 * factor) for factor in np.linspace(0.6, 1.4, 20)[[0, 1, 2, 3, 4]])
    vary = parse_vary(f"driven_inertia={points}", cable.coupling, cable.quantities)
    static, solve = [], Problem.solve

    def counted(self, case, *args, **kwargs):
        static.append(self.start_up is None)
        return solve(self, case, *args, **kwargs)

    def run():
        static.clear()
        records = Sweep(cable, [vary]).run(progress=False).solutions
        rows = [(r["status"], r["objective"]["value"], r["design"], r["solver"]["solves"]) for r in records]
        return rows, sum(static)

    monkeypatch.setattr(Problem, "solve", counted)
    with monkeypatch.context() as patched:
        sized_out = start_up_sweep.sized_out
        patched.setattr(start_up_sweep, "sized_out", lambda problem, case, before: sized_out(problem, case, None))
        each, solved_each = run()
    carried, solved_carried = run()
    assert (solved_carried, solved_each) == (2, 5)
    assert carried == each and [c for *_, c in carried] == [8, 1, 3, 3, 2]
    assert [r[2]["cable_count"] for r in carried] == [7.0, 7.0, 8.0, 8.0, 8.0]


def test_a_dense_sweep_where_the_temperature_rise_binds_needs_no_correction_a_point():
    """wedge_motor_start at 0.6192-0.6394 kg m^2 (steps of about 0.004): the temperature rise binds, and the limit
    share the simulator needs moves by about 2.9e-6 a point, with a second difference of about 3e-8 (docs/start_up.md,
    "A sweep's limits carried on by a secant"): carried as it was, each point missed the centring (1.6e-7) and took a
    correction, two solves; from the fourth point on (two points before it solved along the sweep on one mesh) the
    secant meets it: one solve. Each design is solve's within the contract (a quarter of the tolerance, 1e-6, on the
    objective)."""
    vary = parse_vary("driven_inertia=0.6192,0.6232,0.6273,0.6313,0.6354,0.6394", MOTOR.coupling, MOTOR.quantities)
    records = list(Sweep(MOTOR, [vary]).run(progress=False).solutions)
    assert [r["status"] for r in records] == ["optimal"] * 6
    assert [r["solver"]["solves"] for r in records][3:] == [1, 1, 1]
    alone = case_problem(MOTOR).solve(MOTOR.with_values(driven_inertia=0.6394))
    assert abs(records[-1]["objective"]["value"] - alone.objective) <= 0.25e-6 * abs(alone.objective)


def test_a_point_whose_error_the_secant_puts_beyond_the_tolerance_starts_on_the_adapted_mesh():
    """first_mesh by hand: the two points before at J = 0.616 and 0.637 kg m^2 ended on one mesh with collocation
    errors -5.93e-7 and -8.97e-7 (wedge_motor_start's 20-point sweep). At 0.658 (t = 1) the secant gives
    -8.97e-7 + (-8.97e-7 + 5.93e-7) = -1.201e-6, beyond the tolerance 1e-6: the mesh the point before's simulated
    start suggests (its ``mesh[1]``). At 0.6475 (t = 0.5) -1.049e-6: adapted too; with errors -5.93e-7 and -7.0e-7
    the secant's -8.07e-7 at t = 1 is within: the mesh the point before ended on. Across a mesh change, or off the
    line, no secant, or where the point before binds at a limit its loop left uncorrected (its design carries the
    collocation's error there: the mesh decides it): the mesh the point before ended on."""
    from types import SimpleNamespace

    from clutchopt.optimise.start_up_sweep import Along, first_mesh, secant_step

    mesh, suggested = np.full(16, 1 / 16), np.linspace(1, 2, 16) / 24
    before = Along({"driven_inertia": 0.616}, {}, mesh, error=-5.93e-7)

    def at(inertia, last_error=-8.97e-7, before=before):
        last = Along({"driven_inertia": 0.637}, {}, mesh, before, error=last_error)
        step = secant_step(last, {"driven_inertia": inertia})
        return first_mesh(SimpleNamespace(along=last, mesh=(mesh, suggested)), step, 1e-6)

    assert at(0.658) is suggested and at(0.6475) is suggested
    assert at(0.658, last_error=-7.0e-7) is mesh
    assert at(0.658, before=Along(before.values, {}, mesh * 1.01, error=-5.93e-7)) is mesh  # a mesh change
    assert at(0.637 + 2 * 0.021) is mesh  # t = 2 > FURTHEST
    held = Along({"driven_inertia": 0.637}, {}, mesh, before, error=-8.97e-7, held={"max_start_time": 1e-7})
    step = secant_step(held, {"driven_inertia": 0.658})
    assert step == pytest.approx(1.0) and first_mesh(SimpleNamespace(along=held, mesh=(mesh, suggested)), step,
                                                     1e-6) is mesh


def test_an_active_limit_left_at_the_case_s_is_moved_where_the_correction_would_move_it():
    """predicted_shift with held_limits by hand: the start time binds at the two points before (J = 0.553 and 0.574
    kg m^2), its loop never moved it; the objective's error from the simulated start off the limit, |elasticity x
    gap / limit|, was 2.07e-7 and 2.47e-7 (0.55 x 3.75e-7, 0.56 x 4.40e-7), within CENTRE x tolerance = 2.5e-7, and
    its centred share 1 - 4.40e-7 at 0.574. At 0.595 (t = 1) the secant puts the error at 2.87e-7, beyond: the
    point starts at the centred share moved on by the secant, 1 - 4.40e-7 - 0.65e-7 = 1 - 5.05e-7. At 0.5845
    (t = 0.5) 2.67e-7: moved too; were the error 1.8e-7 and 2.0e-7 (2.2e-7 at t = 1), it stays at the case's."""
    from types import SimpleNamespace

    from clutchopt.optimise.start_up_sweep import Along, predicted_shift, secant_step

    mesh = np.full(16, 1 / 16)

    def at(inertia, errors=(2.07e-7, 2.47e-7)):
        before = Along({"driven_inertia": 0.553}, {"max_start_time": 1 - 3.75e-7}, mesh, held={"max_start_time":
                                                                                                errors[0]})
        last = Along({"driven_inertia": 0.574}, {"max_start_time": 1 - 4.40e-7}, mesh, before,
                     held={"max_start_time": errors[1]})
        previous = SimpleNamespace(along=last, limit_shift={})
        return predicted_shift(previous, secant_step(last, {"driven_inertia": inertia}), 1e-6)

    assert at(0.595)["max_start_time"] == pytest.approx(1 - 5.05e-7, rel=0, abs=1e-15)
    assert at(0.5845)["max_start_time"] == pytest.approx(1 - 4.725e-7, rel=0, abs=1e-15)
    assert "max_start_time" not in at(0.595, errors=(1.8e-7, 2.0e-7))


def test_where_an_adaptation_is_ahead_only_the_limits_the_loop_moved_are_carried():
    """predicted_shift: the two points before on one mesh, collocation errors -5.93e-7 and -8.97e-7, the secant's
    -1.201e-6 at t = 1 beyond the tolerance 1e-6 (an adaptation ahead): the temperature limit the point before's loop
    moved is carried on (1 - 1.9470e-4 + (1.9765e-4 - 1.9470e-4) = 1 - 1.9175e-4), the start time it binds at but left
    at the case's (held, its objective error 2.87e-7 ahead, past CENTRE x tolerance = 2.5e-7) is not; with the
    errors -5.93e-7 and -7.0e-7 (-8.07e-7 ahead, within) it is moved, to 1 - 4.40e-7 - 0.65e-7 = 1 - 5.05e-7. The heat
    per hour, slack at both points and centred on the old mesh's figures (1 - 3e-7, 1 - 2e-7), is carried on the
    secant (1 - 1e-7) without the adaptation, and not into it."""
    from types import SimpleNamespace

    from clutchopt.optimise.start_up_sweep import Along, predicted_shift, secant_step

    mesh = np.full(16, 1 / 16)

    def at(last_error):
        before = Along({"driven_inertia": 0.553}, {"max_temperature_rise": 1 - 1.9765e-4,
                                                   "max_start_time": 1 - 3.75e-7, "heat_dissipation": 1 - 3e-7},
                       mesh, error=-5.93e-7, held={"max_start_time": 2.07e-7})
        last = Along({"driven_inertia": 0.574}, {"max_temperature_rise": 1 - 1.9470e-4,
                                                 "max_start_time": 1 - 4.40e-7, "heat_dissipation": 1 - 2e-7},
                     mesh, before, error=last_error, held={"max_start_time": 2.47e-7})
        previous = SimpleNamespace(along=last, limit_shift={"max_temperature_rise": 1 - 1.9400e-4})
        return predicted_shift(previous, secant_step(last, {"driven_inertia": 0.595}), 1e-6)

    adapting = at(-8.97e-7)
    assert set(adapting) == {"max_temperature_rise"}
    assert adapting["max_temperature_rise"] == pytest.approx(1 - 1.9175e-4, rel=0, abs=1e-15)
    assert at(-7.0e-7)["max_start_time"] == pytest.approx(1 - 5.05e-7, rel=0, abs=1e-15)
    assert at(-7.0e-7)["heat_dissipation"] == pytest.approx(1 - 1e-7, rel=0, abs=1e-15)


def test_where_the_mesh_must_adapt_a_point_starts_on_the_adapted_mesh():
    """first_mesh: where the secant through the collocation errors of the two points before on one mesh (-5.9e-7,
    -9.0e-7: an earlier wedge sweep's at 0.6158 and 0.6368 kg m^2) puts a point's error beyond the tolerance (-1.21e-6
    at 0.6579, against 1e-6) after a point resolved on it, the point's first solve is on the mesh the point before's
    simulated start suggests; within it, on the old one. wedge_motor_start's sweep today at 0.5947-0.6579 kg m^2 (the
    20-point sweep's): at 0.6368 the temperature rise first binds (2 solves: the first meets the limit centred on what
    the simulator added to the NLP's figure at the point before, where it was slack, then one centring; 3 while it was
    carried at the case's: unverified, two corrections); at 0.6579 the secant puts -5.2e-8 (h15-wedgepy): its first
    solve on the old mesh, then one correction. Its design is solve's within the contract."""
    from types import SimpleNamespace

    from clutchopt.optimise.start_up_sweep import Along, first_mesh, secant_step

    mesh, suggested = np.full(16, 1 / 16), np.linspace(1, 2, 16) / 24
    for errors, expected in (((-5.9e-7, -9.0e-7), suggested), ((-4.0e-8, -4.6e-8), mesh)):
        before = Along({"driven_inertia": 0.6158}, {}, mesh, error=errors[0])
        last = Along({"driven_inertia": 0.6368}, {}, mesh, before, error=errors[1])
        step = secant_step(last, {"driven_inertia": 0.6579})
        assert step == pytest.approx(1.0047, abs=1e-4)
        assert first_mesh(SimpleNamespace(along=last, mesh=(mesh, suggested)), step, 1e-6) is expected
    vary = parse_vary("driven_inertia=0.5947,0.6158,0.6368,0.6579", MOTOR.coupling, MOTOR.quantities)
    records = list(Sweep(MOTOR, [vary]).run(progress=False).solutions)
    assert [r["status"] for r in records] == ["optimal"] * 4
    assert [r["solver"]["solves"] for r in records][1:] == [1, 2, 2]
    alone = case_problem(MOTOR).solve(MOTOR.with_values(driven_inertia=0.6579))
    for rise in (next(c for c in records[-1]["constraints"] if c["name"] == "temperature_rise"),
                 next(c.as_dict() for c in alone.constraints if c.name == "temperature_rise")):  # each the simulator's
        # optimum to CENTRE of the tolerance (its loop's test): the sweep's 1.5e-8 off the limit, solve's 1.6e-7 inside
        # (its one correction, aimed at the limit, lands within CENTRE), so the two up to twice that apart
        assert abs(rise["elasticity"] * (rise["value"] - rise["limit"]) / rise["limit"]) <= CENTRE * 1e-6
    assert abs(records[-1]["objective"]["value"] - alone.objective) <= 2 * CENTRE * 1e-6 * abs(alone.objective)


def test_a_sweep_adapts_no_mesh_its_points_do_not_solve_on(monkeypatch):
    """The same four points: the mesh a check's simulated start suggests is adapted only where a solve reads it
    (``clutchopt.start_up.mesh.Meshes``; 0.4 ms a check, each of the seven checks' adapted at once before). Every
    point's error is within the tolerance on the mesh it starts on (0.6579: -5.2e-8 ahead by the secant): no solve
    reads a suggestion, none is adapted."""
    import clutchopt.start_up.mesh as mesh_module

    adapted = []  # a phase's weights, each adaptation's (its own module's function: whoever imported adapted_mesh)
    monkeypatch.setattr(mesh_module, "_cumulative",
                        lambda *a, weights=mesh_module._cumulative: adapted.append(weights(*a)) or adapted[-1])
    vary = parse_vary("driven_inertia=0.5947,0.6158,0.6368,0.6579", MOTOR.coupling, MOTOR.quantities)
    sweep = Sweep(MOTOR, [vary])
    records = list(sweep.run(progress=False).solutions)
    assert [r["solver"]["solves"] for r in records] == [1, 1, 2, 2]
    assert adapted == []
    suggested = case_problem(MOTOR).solve(MOTOR.with_values(driven_inertia=0.6579)).mesh[1]  # read: adapted
    assert len(adapted) == 3 and len(suggested) == 3 * MOTOR.start_up.intervals  # (its three phases)


def test_a_point_after_a_coarse_mesh_the_loop_kept_stays_on_it():
    """first_mesh: where the point before's loop kept a mesh whose error is beyond the tolerance (it stopped for
    another reason: no start-up limit shapes the design, ``shapes_nothing``; ball_motor_start at 0.6-0.9 times its
    driven inertia, errors -1.0e-3 and 1.6e-3), the secant's 4.1e-3 starts no adaptation: the point before's mesh."""
    from types import SimpleNamespace

    from clutchopt.optimise.start_up_sweep import Along, first_mesh, secant_step

    mesh, suggested = np.full(16, 1 / 16), np.linspace(1, 2, 16) / 24
    before = Along({"driven_inertia": 240.8}, {}, mesh, error=-1.02e-3)
    last = Along({"driven_inertia": 256.6}, {}, mesh, before, error=1.55e-3)
    step = secant_step(last, {"driven_inertia": 272.4})
    assert first_mesh(SimpleNamespace(along=last, mesh=(mesh, suggested)), step, 1e-6) is mesh


def test_an_integer_choice_the_papers_sizing_finds_infeasible_is_not_solved_along_the_sweep():
    """ball_motor_start over driven_inertia (225-336 kg m^2 in the 20-point sweep): the design is the papers'
    sizing, 23 ball rows, and the row fewer its multiplier promises, 22, is infeasible in the sizing (the static
    problem, least violation 2.72e-3) and in the start-up problem, which keeps every row of the sizing (the ball has
    no constant-acceleration row): each point solved it (26-33 IPOPT iterations). The driven inertia enters no row
    of the sizing, so its verdict holds at every point: at the second point (the first solved along the sweep, its
    sizing solved before its loop, where ``as_solve_would`` solved it after: main solved the 22 rows there) and on,
    carried, 22 rows are excluded without a solve, and the design is solve's; so are they at the first point, solved
    as ``solve`` solves it (cold, from its sizing, whose own search found them infeasible: ``sized_choices``). The
    wedge's sizing has a row the start-up model replaces (the torque for T_max): nothing is ruled out by it."""
    from clutchopt.optimise.start_up_sweep import SizedOut, sized_out

    ball = load_case(CASES / "ball_motor_start.toml")
    points = ",".join(str(375.0 * factor) for factor in np.linspace(0.6, 1.4, 20)[[1, 2, 4]])  # the sweep's
    vary = parse_vary(f"driven_inertia={points}", ball.coupling, ball.quantities)
    records = list(Sweep(ball, [vary]).run(progress=False).solutions)
    assert [r["status"] for r in records] == ["optimal"] * 3
    rows = [{e["ball_rows"]: e["status"] for e in r["integer_search"]} for r in records]
    assert rows[0][23] == rows[1][23] == "Solve_Succeeded"
    for point in rows:
        assert point[22].startswith("excluded: infeasible in the papers' sizing at this point")
    alone = case_problem(ball).solve(ball.with_values(driven_inertia=vary.values[2]))
    assert alone.design["ball_rows"] == records[2]["design"]["ball_rows"] == 23
    # (the sweep reaches it warm, solve cold: equal to the start-up contract, 1e-6 relative; 3.6e-9 apart on one
    # machine, within 1e-9 on the one the test was written on: the linear algebra's rounding differs between CPUs)
    assert records[2]["objective"]["value"] == pytest.approx(alone.objective, rel=1e-6, abs=0)
    problem = case_problem(MOTOR)
    key = sized_out(problem, MOTOR, None).key
    assert sized_out(problem, MOTOR, SizedOut(key)).choices == {}


def test_a_point_whose_integers_moved_off_the_sizing_s_is_also_solved_as_solve_would(monkeypatch):
    # ball_motor_start over driven_inertia = 100,375 on NumPy's AVX2 loops (NPY_DISABLE_CPU_FEATURES="X86_V4
    # AVX512_ICL"; the native AVX-512 ones take another path): warm from 100's 23 rows, the loop's first solve at 375
    # kept 25 rows (1023.25 kg), its second, on the adapted mesh, found 25 rows infeasible from that optimum and kept
    # 26: "optimal" at 1029.52 kg, where solve ends at 25 rows, 1026.07 kg. The integers had moved off the point
    # before's, so the point was not solved as solve would. That warm solve's 26 rows made here on any CPU (the rows
    # fixed by the bounds): the point is solve's, 25 rows, every solve counted
    warm_solves = []

    def at_26_rows(self, case, *args, **kwargs):
        if self.start_up is None or kwargs.get("cold") is not False:  # (solved_along's warm solve only)
            return refined(self, case, *args, **kwargs)
        warm_solves.append(refined(self, replace(case, bounds={**case.bounds, "ball_rows": (26.0, 26.0)}),
                                   diagnosed=False))
        return warm_solves[-1]

    refined = Problem.refined
    monkeypatch.setattr(Problem, "refined", at_26_rows)
    case = load_case(CASES / "ball_motor_start.toml")
    record = Sweep(case, [parse_vary("driven_inertia=100,375", "ball", case.quantities)]).run(
        progress=False).solutions[1]
    [heavier] = warm_solves
    assert heavier.status == "optimal" and heavier.design["ball_rows"] == 26
    assert heavier.objective == pytest.approx(1029.52, abs=0.01)
    monkeypatch.undo()
    alone = case_problem(case).solve(case.with_values(driven_inertia=375.0))
    assert record["status"] == alone.status == "optimal"
    assert record["design"]["ball_rows"] == alone.design["ball_rows"] == 25
    assert record["objective"]["value"] == pytest.approx(alone.objective, rel=1e-6)
    assert record["objective"]["value"] == pytest.approx(1026.07, abs=0.005)
    assert record["solver"]["solves"] > heavier.solver.solves + alone.solver.solves  # (the probe's too)
    assert record["solver"]["iterations"] > heavier.solver.iterations + alone.solver.iterations  # (summed as its
    # solves are: the kept solve's alone were counted, review h17)


def test_a_point_proven_infeasible_is_recorded_before_the_next_point_is_solved(monkeypatch):
    """A sweep solved point by point hands on a point proven infeasible at once (a store records it, a kill loses
    nothing before it), not held with the points without a design until the next feasible point: no design is
    tried from there at a proven point (review 20: a run through a region proven point by point recorded nothing
    until its next feasible point). wedge_motor_start's motor cannot reach its speed in 0.5 or 0.6 s whatever the
    coupling (the drive's proofs); at its 10 s a design."""
    case = load_case(CASES / "wedge_motor_start.toml")
    solved, solve = [], sweep._solved

    def counted(problem, case, point_case, values, *args):
        solved.append(values["acceleration_time"])
        return solve(problem, case, point_case, values, *args)

    monkeypatch.setattr(sweep, "_solved", counted)
    grid = Sweep(case, [parse_vary("acceleration_time=0.5,0.6,10", case.coupling, case.quantities)]).grid
    handed = []
    for part in sweep.solve_points(case, None, "mass", 1e-8, None, grid):
        handed.append((part.points.index.tolist(), list(solved), [record["status"] for record in part.records()]))
    assert handed == [([0], [0.5], ["infeasible"]), ([1], [0.5, 0.6], ["infeasible"]),
                      ([2], [0.5, 0.6, 10.0], ["optimal"])]
