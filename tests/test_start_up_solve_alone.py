"""A start-up solved from a start its caller gives (a sweep's point retried from the next feasible point's design,
the robust loop's first solve) that ends without a verified design also tries what ``solve`` of the case alone tries
(``Problem.solve``: its own starts, the sampled design last), and a design kept where ``solve`` alone ends otherwise
says so (``Solution.beside_alone``: the record's ``solve_alone`` and its diagnosis)."""

import json
import sqlite3
from dataclasses import replace

import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import problem as problem_module
from clutchopt.optimise import start_up_sweep
from clutchopt.optimise import sweep as sweep_module
from clutchopt.optimise.problem import case_problem, verified_alone
from clutchopt.optimise.sampled_start import SAMPLED
from clutchopt.optimise.solution import Solution, SolverInfo
from clutchopt.optimise.start_up_sweep import as_solve_would, sized_out
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import Vary
from clutchopt.optimise.verdict import GIVEN, OWN
from clutchopt.output import solution_json
from clutchopt.store import RunStore
from conftest import BALL_PAPER_STRESS, CASES, Interrupted, resumed_sweep, stopped_sweep
from test_hostile_agree import START_UP_RTOL


def test_a_start_given_that_ends_without_a_design_gets_the_sampled_start_as_solve_alone_does():
    # ball_motor_start in paper mode at 1.5 GPa: 650 kW solved from the design at 507.9 kW (480.446 kg). From there,
    # from the papers' sizing, the least relaxation's design and the interval search's, it ended not_found (the
    # least relaxation 656.12 kg: start_time, lock_up_speed and overload_torque against stays_locked), where ``solve``
    # of 650 kW alone walks from its sampled design to 687.92 kg, the torque and the start time active
    case = load_case(CASES / "ball_motor_start.toml").with_values(**BALL_PAPER_STRESS)
    problem = case_problem(case, mode="paper")
    before = problem.solve(case.with_values(power=507.9e3))
    assert before.status == "optimal" and before.objective == pytest.approx(480.446152, rel=START_UP_RTOL)
    solved = problem.solve(case.with_values(power=650e3), start=before.design)
    assert solved.status == "optimal"
    assert solved.objective == pytest.approx(687.9175724, rel=START_UP_RTOL)
    assert {c.name for c in solved.constraints if c.active} == {"torque", "start_time"}
    assert solved.starts[0] == GIVEN and solved.starts[-1] == SAMPLED  # (its design from the last start named)
    assert solved.as_dict()["starts"] == list(solved.starts)


def test_an_unverified_design_from_a_start_given_gives_way_to_solve_s_verified_one(monkeypatch):
    # wedge_motor_start: a start that ends 'unverified' (a spy: 1 % under solve's optimum, its check failed) was
    # returned as it was; now ``solve`` of the case alone is solved beside it and its verified design kept, the
    # start given named first, every solve counted
    case = load_case(CASES / "wedge_motor_start.toml")
    problem = case_problem(case)
    alone = problem.solve(case)
    assert alone.status == "optimal" and not alone.starts
    unverified = replace(alone, status="unverified", objective=alone.objective * 0.99,
                         diagnosis="IPOPT reported success but the simulated start-up finds start_time violated")
    refined = problem.refined
    monkeypatch.setattr(problem, "refined", lambda case, start=None, *args, **kw:
                        unverified if start is not None else refined(case, start, *args, **kw))
    kept = problem.solve(case, start=alone.design)
    assert kept.status == "optimal" and kept.objective == alone.objective and kept.design == alone.design
    assert kept.starts == (GIVEN, OWN) and kept.solve_alone is None
    assert kept.solver.solves == unverified.solver.solves + alone.solver.solves


def test_a_design_kept_where_solve_alone_has_none_verified_says_so():
    # the start given's unverified design kept where ``solve`` alone has no verified design: the record names what
    # ``solve`` alone ended with, in ``solve_alone`` and the diagnosis (a sweep's table and the run store show it)
    case = load_case(CASES / "wedge_motor_start.toml")
    alone = case_problem(case).solve(case)
    unverified = replace(alone, status="unverified", diagnosis="IPOPT reported success but the simulated start-up "
                         "finds start_time violated by 0.002 (relative)")
    for status, objective, note in (("not_found", None, "solve alone: not_found"),
                                     ("unverified", alone.objective * 1.02,
                                      f"solve alone: unverified, {alone.objective * 1.02:.10g} kg")):
        other = replace(alone, status=status, objective=alone.objective * 1.02)
        kept = verified_alone(unverified, other)
        assert kept.status == "unverified" and kept.objective == unverified.objective
        assert kept.solve_alone == {"status": status, "objective": objective}
        assert kept.diagnosis == f"{unverified.diagnosis}; {note}"
        assert kept.as_dict()["solve_alone"] == {"status": status, "objective": objective}
        assert kept.solver.solves == 2 * alone.solver.solves


def test_a_warm_design_kept_over_solve_s_heavier_one_says_so(monkeypatch):
    # ball_motor_start (design mode) at a motor inertia of 12.26 kg m^2: a sweep point warm at 25 rows (1002.07 kg,
    # as the point before's integers left it) where the papers' sizing has 23 is also solved as ``solve`` solves it
    # alone (start_up_sweep.as_solve_would: 24 rows, 998.53 kg, kept: lighter). A spy makes that solve 2 % heavier:
    # the warm design is kept, and says what ``solve`` alone ended with (before: silently)
    case = load_case(CASES / "ball_motor_start.toml").with_values(motor_inertia=12.257623755009474)
    problem = case_problem(case, mode="design")
    warm = problem.solve(replace(case, bounds={**case.bounds, "ball_rows": (25, 25)}))
    assert warm.status == "optimal" and warm.objective == pytest.approx(1002.0703, rel=1e-6)
    solve, alone = problem.solve, []

    def heavier_alone(point, *args, **kw):  # (``solve`` of the point alone, as as_solve_would calls it)
        alone.append(solve(point, *args, **kw))
        return replace(alone[-1], objective=alone[-1].objective * 1.02)
    monkeypatch.setattr(problem, "solve", heavier_alone)
    kept = as_solve_would(problem, case, warm, sized_out(problem, case, None))
    [solved] = alone
    assert solved.design["ball_rows"] == 24 and solved.objective == pytest.approx(998.5306, rel=1e-6)
    assert kept.design == warm.design and kept.objective == warm.objective
    assert kept.solve_alone == {"status": "optimal", "objective": solved.objective * 1.02}
    assert kept.diagnosis == f"solve alone: optimal, {solved.objective * 1.02:.10g} kg"
    assert kept.solver.solves > warm.solver.solves + solved.solver.solves  # (the probe's too)


def test_a_sweep_record_that_says_so_shows_it_in_its_table_json_and_store(monkeypatch, tmp_path):
    # wedge_motor_start over its driven inertia: a point whose design is kept beside ``solve``'s (a spy in
    # start_up_sweep.as_solve_would's place: the point's own design, ``solve`` alone said to end not_found) has it in
    # its record (``solve_alone``), the table's diagnosis, the JSON's units, the run store and a resume that reads it
    case = load_case(CASES / "wedge_motor_start.toml")
    quantity = next(q for q in case.quantities if q.name == "driven_inertia")
    sweep = Sweep(case, [Vary(quantity, (0.5, 0.52, 0.54))])
    said = replace(case_problem(sweep.case).solve(sweep.case), status="not_found")
    monkeypatch.setattr(start_up_sweep, "as_solve_would", lambda problem, point, solution, sized:
                        solution.beside_alone(said) if point.values["driven_inertia"] == 0.54 else solution)
    with RunStore(tmp_path / "runs.sqlite") as store:
        result = sweep.run(store, progress=False)
        assert [r["status"] for r in result.solutions] == ["optimal"] * 3
        assert [r.get("solve_alone") for r in result.solutions] == [None, None, {"status": "not_found",
                                                                                 "objective": None}]
        assert list(result.frame["diagnosis"]) == ["", "", "solve alone: not_found"]
        resumed = sweep.run(store, resume=True, progress=False)
    assert resumed.reused == 3 and resumed.solved == 0
    assert resumed.solutions[2]["solve_alone"] == {"status": "not_found", "objective": None}
    assert list(resumed.frame["diagnosis"]) == ["", "", "solve alone: not_found"]
    assert solution_json(resumed.solutions[2])["units"]["solve_alone"] == {"objective": "kg"}


def _none_alone_at(monkeypatch, inertias: tuple[float, ...], at: float) -> tuple[Sweep, Solution]:
    """wedge_motor_start's sweep over ``inertias`` (driven inertia, kg m^2), a spy having the warm start and ``solve``
    alone at ``at`` end without a design; and ``solve``'s design there."""
    case = load_case(CASES / "wedge_motor_start.toml")
    quantity = next(q for q in case.quantities if q.name == "driven_inertia")
    sweep = Sweep(case, [Vary(quantity, inertias)])
    problem = case_problem(sweep.case)
    there = problem.solve(sweep.case.with_values(driven_inertia=at))
    solve, along = problem.solve, sweep_module.solved_along

    def none_alone(point, *args, **kw):
        solved = solve(point, *args, **kw)
        alone = point.values["driven_inertia"] == at and not args and set(kw) <= {"first"}
        return replace(solved, status="not_found", diagnosis="no feasible design found (a spy)") if alone else solved
    monkeypatch.setattr(problem, "solve", none_alone)
    monkeypatch.setattr(sweep_module, "solved_along", lambda problem, point, previous:
                        None if point.values["driven_inertia"] == at else along(problem, point, previous))
    return sweep, there


def test_a_sweep_point_a_start_of_the_sweep_s_own_designed_says_solve_alone_had_none(monkeypatch):
    # wedge_motor_start over its driven inertia, 0.5, 0.52, 0.54 kg m^2: at 0.52 a spy has the warm start and
    # ``solve`` alone end without a design; the neighbour's design (0.5's) reaches one, ``solve``'s of 0.52 (the
    # same optimum), and the record says ``solve`` alone had none, which it did not say before
    sweep, middle = _none_alone_at(monkeypatch, (0.5, 0.52, 0.54), 0.52)
    records = sweep.run(progress=False).solutions
    assert [r["status"] for r in records] == ["optimal"] * 3
    assert records[1]["objective"]["value"] == pytest.approx(middle.objective, rel=START_UP_RTOL)
    assert records[1]["solve_alone"] == {"status": "not_found", "objective": None}
    assert records[1]["diagnosis"] == "solve alone: not_found"
    assert "solve_alone" not in records[0] and "solve_alone" not in records[2]


def test_a_resumed_run_s_first_point_has_the_neighbour_and_continuation_of_the_uninterrupted_run(monkeypatch,
                                                                                                  tmp_path):
    # the same spy, over 0.5 then 0.52 kg m^2: uninterrupted, 0.52 takes 0.5's design as its neighbour's (solve
    # alone: none); stopped after 0.5 was stored and resumed, 0.52 had no point before it: not_found, where the
    # uninterrupted run has a design. Now the resumed run's first points see the last stored feasible point's design
    # as the uninterrupted run's do: the same record
    sweep, last = _none_alone_at(monkeypatch, (0.5, 0.52), 0.52)
    uninterrupted = sweep.run(progress=False).solutions
    original = RunStore.record_points

    def once(*args, **kwargs):  # 0.5 stored (a point with a design is stored as it is solved), then stopped
        original(*args, **kwargs)
        raise Interrupted
    resumed = resumed_sweep(stopped_sweep(tmp_path / "runs.sqlite", lambda: sweep, monkeypatch, RunStore,
                                          "record_points", once), lambda: sweep)
    assert (resumed.reused, resumed.solved) == (1, 1)
    again, once_run = resumed.solutions[1], uninterrupted[1]
    assert again["status"] == once_run["status"] == "optimal"  # (before: not_found resumed)
    assert again["objective"]["value"] == pytest.approx(last.objective, rel=START_UP_RTOL)
    assert again["design"] == pytest.approx(once_run["design"], rel=START_UP_RTOL)
    assert again["solve_alone"] == once_run["solve_alone"] == {"status": "not_found", "objective": None}


def _damaged(path, damage) -> None:
    """The run store at ``path`` with ``damage`` done to its first point's stored record (JSON, as a hand edit)."""
    with sqlite3.connect(path) as connection:
        for row, text in connection.execute("SELECT id, outputs FROM runs WHERE point = 0").fetchall():
            record = json.loads(text)
            damage(record["design"])
            connection.execute("UPDATE runs SET outputs = ? WHERE id = ?", (json.dumps(record, allow_nan=True), row))
    connection.close()


DAMAGE = {"null": lambda design: design.update({next(iter(design)): None}),
          "nan": lambda design: design.update({next(iter(design)): float("nan")}),
          "missing": lambda design: design.pop(next(iter(design))),
          "extra": lambda design: design.update({"bogus": 1.0})}


@pytest.mark.parametrize("damage", list(DAMAGE))
def test_a_resumed_run_whose_stored_design_is_not_the_problem_s_solves_its_first_point_cold(monkeypatch, tmp_path,
                                                                                            damage):
    # the spy of the test above, 0.5 stored then stopped, the stored design damaged (a value null or NaN, a variable
    # missing, one too many; text or true the store refuses itself): it is not a start (a null raised TypeError in the neighbour's retry: an
    # internal error); 0.52 is solved as the resumed run solved it before, cold: not_found under the spy
    sweep, _ = _none_alone_at(monkeypatch, (0.5, 0.52), 0.52)
    original = RunStore.record_points

    def once(*args, **kwargs):
        original(*args, **kwargs)
        raise Interrupted
    path = stopped_sweep(tmp_path / "runs.sqlite", lambda: sweep, monkeypatch, RunStore, "record_points", once)
    _damaged(path, DAMAGE[damage])
    resumed = resumed_sweep(path, lambda: sweep)
    assert (resumed.reused, resumed.solved) == (1, 1)
    assert resumed.solutions[1]["status"] == "not_found" and "solve_alone" not in resumed.solutions[1]


def test_a_start_given_that_misses_gets_the_walk_from_a_held_design_as_solve_alone_does(monkeypatch):
    # wedge_motor_start, every optimum "held" and its walk 1 % lighter (spies), the start given ending without a
    # design: solve alone walks from its held optimum; from the start given the own-start retry's design was kept
    # unwalked, 1 % heavier, saying nothing. Now the start given that misses is set beside solve alone
    case = load_case(CASES / "wedge_motor_start.toml")
    problem = case_problem(case)
    monkeypatch.setattr(problem_module, "from_the_held_design", lambda problem, case, held:
                        replace(held, objective=held.objective * 0.99))
    monkeypatch.setattr(problem, "_held", lambda solution: solution.status == "optimal")
    alone = problem.solve(case)
    refined = problem.refined

    def missed(point, start=None, *args, **kw):  # (the start given ends without a design)
        solved = refined(point, start, *args, **kw)
        return replace(solved, status="not_found", diagnosis="a spy") if start is not None and "coarser" in kw \
            else solved
    monkeypatch.setattr(problem, "refined", missed)
    given = problem.solve(case, start={name: value * 1.1 for name, value in alone.design.items()})
    assert given.status == "optimal" and given.objective == pytest.approx(alone.objective, rel=1e-12)
    assert given.starts[0] == GIVEN and given.solve_alone is None


def test_a_start_given_beside_solve_alone_reports_solve_s_solver_status():
    # verified_alone keeps solve alone's design with its solver's status, not the failed start's
    case = load_case(CASES / "wedge_motor_start.toml")
    alone = case_problem(case).solve(case)
    given = replace(alone, status="not_found", solver=SolverInfo("ipopt", "Restoration_Failed", 40, 0.1, 1))
    kept = verified_alone(given, alone)
    assert (kept.status, kept.solver.status, kept.solver.name) == ("optimal", alone.solver.status, alone.solver.name)
    assert kept.solver.solves == alone.solver.solves + 1 and kept.starts == (GIVEN, OWN)


def test_an_unverified_retry_of_a_waiting_point_is_set_beside_its_verdict_alone_once(monkeypatch):
    # the spy at 0.52 (0.5, 0.52, 0.54), no neighbour or continuation: 0.52 waits; the retry from 0.54's design ends
    # unverified (a spy): it was set beside a second solve alone of 0.52 and noted twice ("solve alone: not_found;
    # solve alone: not_found"); now beside the point's own verdict alone, noted once, 0.52 solved alone once
    sweep, _ = _none_alone_at(monkeypatch, (0.5, 0.52, 0.54), 0.52)
    problem = case_problem(sweep.case)
    refined, solve, alone_solves = problem.refined, problem.solve, []

    def unverified(point, start=None, *args, **kw):
        solved = refined(point, start, *args, **kw)
        at = point.values["driven_inertia"] == 0.52 and start is not None and "coarser" in kw
        return replace(solved, status="unverified") if at else solved

    def counted(point, *args, **kw):
        if point.values["driven_inertia"] == 0.52 and not args and set(kw) <= {"first"}:
            alone_solves.append(1)
        return solve(point, *args, **kw)
    monkeypatch.setattr(problem, "refined", unverified)
    monkeypatch.setattr(problem, "solve", counted)
    monkeypatch.setattr(sweep_module, "from_the_neighbour", lambda problem, case, verdict, design: verdict)
    monkeypatch.setattr(sweep_module, "continued", lambda *args, **kw: None)
    record = sweep.run(progress=False).solutions[1]
    assert record["status"] == "unverified" and record["solve_alone"] == {"status": "not_found", "objective": None}
    assert record["diagnosis"].count("solve alone: not_found") == 1 and len(alone_solves) == 1


def test_a_waiting_point_retried_from_the_next_design_counts_every_solve(monkeypatch):
    # the spy at 0.52, no neighbour or continuation: 0.52 waits (its solve alone), then is retried from 0.54's design,
    # which reaches solve's design: its record counted the retry's solves only (review: 1 where 2 were made); now
    # the solve alone's and the retry's
    sweep, _ = _none_alone_at(monkeypatch, (0.5, 0.52, 0.54), 0.52)
    problem = case_problem(sweep.case)
    solve, seen = problem.solve, []

    def spy(point, *args, **kw):
        solved = solve(point, *args, **kw)
        if kw.get("alone") is not None:
            seen.append((kw["alone"].solver.solves, solved.solver.solves, solved.status))
        return solved
    monkeypatch.setattr(problem, "solve", spy)
    monkeypatch.setattr(sweep_module, "from_the_neighbour", lambda problem, case, verdict, design: verdict)
    monkeypatch.setattr(sweep_module, "continued", lambda *args, **kw: None)
    record = sweep.run(progress=False).solutions[1]
    (waited, retry, status), = seen
    assert status == record["status"] == "optimal" and waited >= 1 and retry >= 1
    assert record["solver"]["solves"] == waited + retry


def test_a_sweep_keeps_no_simulation_of_its_points_behind_it(monkeypatch):
    # a check's suggested mesh is adapted where read (start_up.mesh.Meshes holds the simulation's columns, 50-90 kB,
    # until then): a sweep kept every feasible point's whole solution (its neighbours' designs), so a 40-point wedge
    # sweep held 39 unread columns (review: 3.3 MB; 10,000 points about 0.8 GB); now its designs alone
    import gc

    from clutchopt.start_up.mesh import Meshes

    unread, solved = [], sweep_module._solved
    before = [o for o in gc.get_objects() if isinstance(o, Meshes)]  # (other tests' in this process: held, not
    seen = set(map(id, before))  # counted)

    def counted(*args, **kw):
        gc.collect()  # (only what is still held)
        unread.append(sum(1 for o in gc.get_objects()
                          if isinstance(o, Meshes) and o._from is not None and id(o) not in seen))
        return solved(*args, **kw)
    monkeypatch.setattr(sweep_module, "_solved", counted)
    case = load_case(CASES / "wedge_motor_start.toml")
    quantity = next(q for q in case.quantities if q.name == "driven_inertia")
    Sweep(case, [Vary(quantity, (0.45, 0.47, 0.49, 0.51, 0.53, 0.55))]).run(progress=False)
    assert len(unread) == 6 and max(unread) <= 2  # (the point before's, kept as its warm start, and the last)




def test_a_waiting_point_whose_next_design_fails_its_first_simulation_is_not_solved_alone_again(monkeypatch):
    # the spy at 0.52, no neighbour or continuation: 0.52 waits; the retry from 0.54's design fails its first
    # simulation (InputError, a spy): it fell back to the papers' sizing and solved 0.52 alone again (review 2: its
    # starts and the sampled walk, the verdict the sweep already had); now the sweep's verdict alone is kept
    from clutchopt.errors import InputError

    sweep, _ = _none_alone_at(monkeypatch, (0.5, 0.52, 0.54), 0.52)
    problem = case_problem(sweep.case)
    refined, after = problem.refined, []  # (0.52's solves after its retry's start failed)

    def failing(point, start=None, *args, **kw):
        if point.values["driven_inertia"] == 0.52 and start is not None and "coarser" in kw and not after:
            after.append("failed")
            raise InputError("start", "its first simulation failed (a spy)")
        if point.values["driven_inertia"] == 0.52 and after:
            after.append(start)
        return refined(point, start, *args, **kw)
    monkeypatch.setattr(problem, "refined", failing)
    monkeypatch.setattr(sweep_module, "from_the_neighbour", lambda problem, case, verdict, design: verdict)
    monkeypatch.setattr(sweep_module, "continued", lambda *args, **kw: None)
    records = sweep.run(progress=False).solutions
    assert [r["status"] for r in records] == ["optimal", "not_found", "optimal"]
    assert after == ["failed"]  # (before: the papers' sizing's solve and the retries after it)
    assert "solve_alone" not in records[1] and records[1]["solver"]["solves"] >= 1
