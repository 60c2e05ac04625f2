"""Sweeps: grids in display units, warm re-solves equal to cold solves, failed points kept, outputs, workers."""

import json
import math

import numpy as np
import pandas as pd
import pytest

from clutchopt.cases import load_case
from clutchopt.errors import InputError
from clutchopt.optimise import solve_case
from clutchopt.optimise.sweep import Sweep, dask_runner
from clutchopt.optimise.sweep_grid import Vary, grid_points, parse_vary
from clutchopt.store import RunStore
from conftest import CASES

RPM = 2 * math.pi / 60


def test_vary_reads_display_units_ranges_and_lists():
    speed = parse_vary("speed=500:3000:26", "wedge")
    assert len(speed.values) == 26
    assert speed.values[0] == pytest.approx(500 * RPM) and speed.values[-1] == pytest.approx(3000 * RPM)
    assert speed.values[1] == pytest.approx(600 * RPM)
    pressure = parse_vary("allowable_pressure=2,8", "wedge")
    assert pressure.values == pytest.approx((2e6, 8e6))
    assert parse_vary("friction_coefficient=0.1", "wedge").values == (0.1,)
    points = grid_points([speed, pressure]).values()
    assert len(points) == 52 and points[1] == {"speed": pytest.approx(500 * RPM), "allowable_pressure": 8e6}
    assert points[2] == {"speed": pytest.approx(600 * RPM), "allowable_pressure": 2e6}  # the last varies fastest


@pytest.mark.parametrize("text, message", [
    ("speed=abc:3000:4", "not a number"), ("sped=1,2", "unknown quantity 'sped'"), ("speed=1:2:0", "count >= 1"),
    ("speed=1:2:2.5", "count >= 1"), ("speed", "expected name="), ("speed=nan", "finite"),
    ("speed=1e308:-1e308:3", "span is beyond the float64 range"),
])
def test_bad_vary_is_named(text, message):
    with pytest.raises(InputError, match=message):
        parse_vary(text, "wedge")


def test_listed_sweep_pairs_values_and_needs_equal_lengths():
    speed, pressure = parse_vary("speed=500,1000", "wedge"), parse_vary("allowable_pressure=2,8", "wedge")
    assert [p["allowable_pressure"] for p in grid_points([speed, pressure], zipped=True).values()] == [2e6, 8e6]
    with pytest.raises(InputError, match="equally many"):
        grid_points([speed, parse_vary("allowable_pressure=2,4,8", "wedge")], zipped=True)


def test_warm_started_points_equal_cold_solves_and_failures_stay_rows():
    case = load_case(CASES / "wedge_paper.toml")
    sweep = Sweep(case, [parse_vary("outer_diameter_max=100,130,160,200", "wedge"),
                         parse_vary("speed=800,1000", "wedge")], mode="geometry")
    frame = sweep.run(progress=False).frame
    assert len(frame) == 8 and list(frame["point"]) == list(range(8))
    for row in frame.itertuples():
        cold = solve_case(case.with_values(outer_diameter_max=row[2] * 1e-3, speed=row[3] * RPM), "geometry")
        assert row.status == cold.status
        if cold.status == "optimal":
            assert row[5] == pytest.approx(cold.objective, rel=1e-7)
    failed = frame[frame["status"] != "optimal"]
    assert len(failed) >= 1 and (failed["outer_diameter_max [mm]"] == 100).all()
    assert failed["diagnosis"].str.startswith("no feasible design found (not proven infeasible)").all()
    best = frame[frame["status"] == "optimal"]
    assert (best["active"].str.contains("torque")).all()


def test_thousand_point_sweep_with_progress_bar_csv_and_runs_list(cli, tmp_path, run_store):
    out = tmp_path / "sweep.csv"
    result = cli("sweep", str(CASES / "wedge_paper.toml"), "--vary", "speed=500:3000:40",
                 "--vary", "allowable_pressure=2:8:25", "--out", str(out))
    assert result.returncode == 0, result.stderr
    assert "1000/1000" in result.stderr  # the progress bar
    # 4 points proven infeasible (2870 to 3000 rpm at [p] 2 to 2.25 MPa): the flank pressure caps m_r below the mass
    # whose real weight is wide enough for its finger (finger_fits_width at b(m_r); docs/errata.md)
    assert "1000 points, 996 optimal, 4 infeasible" in result.stdout
    assert out.read_text().startswith('# clutchopt_sweep {"coupling": "wedge", ')  # the sweep's identification
    frame = pd.read_csv(out, skiprows=1)
    assert len(frame) == 1000 and frame["point"].is_unique
    assert frame["speed [rpm]"].min() == pytest.approx(500) and frame["allowable_pressure [MPa]"].max() == pytest.approx(8)
    corner = frame.iloc[-25]  # the last speed (3000 rpm) at the first pressure (2 MPa)
    assert corner["speed [rpm]"] == 3000 and corner["allowable_pressure [MPa]"] == 2  # as given, not back from SI
    assert sorted(set(frame["speed [rpm]"])) == np.linspace(500, 3000, 40).tolist()
    cold = solve_case(load_case(CASES / "wedge_paper.toml").with_values(speed=3000 * RPM, allowable_pressure=2e6))
    assert corner["status"] == cold.status == "infeasible" and "finger_fits_width" in cold.diagnosis
    assert set(frame[frame["status"] != "optimal"]["speed [rpm]"]) <= {3000, np.linspace(500, 3000, 40)[-2],
                                                                        np.linspace(500, 3000, 40)[-3]}
    near = frame.iloc[-23]  # 3000 rpm at 2.5 MPa
    cold = solve_case(load_case(CASES / "wedge_paper.toml").with_values(speed=3000 * RPM, allowable_pressure=2.5e6))
    assert near["allowable_pressure [MPa]"] == 2.5 and near["mass [kg]"] == pytest.approx(cold.objective, rel=1e-7)
    listed = cli("runs", "list", "--kind", "sweep", "--limit", "3")
    assert listed.returncode == 0 and "sweep" in listed.stdout
    with RunStore(run_store) as store:
        assert store.sweeps()[0]["stored"] == 1000


@pytest.mark.parametrize("suffix", ["parquet", "md"])
def test_parquet_and_markdown_tables(cli, tmp_path, suffix):
    out = tmp_path / f"sweep.{suffix}"
    result = cli("sweep", str(CASES / "wedge_fan.toml"), "--vary", "speed=1000,2000", "--out", str(out), "--quiet",
                 "--no-store")
    assert result.returncode == 0, result.stderr
    if suffix == "parquet":
        assert list(pd.read_parquet(out)["speed [rpm]"]) == [1000, 2000]
    else:
        lines = out.read_text().splitlines()
        assert lines[0].startswith("| point | speed [rpm] |") and len(lines) == 4


def test_few_points_print_one_column_per_point(cli):
    result = cli("sweep", str(CASES / "wedge_paper.toml"), "--vary", "speed=1000,2000", "--quiet", "--no-store")
    assert result.returncode == 0, result.stderr
    lines = result.stdout.splitlines()
    assert any(line.split() == ["point", "0", "point", "1"] for line in lines)
    assert any(line.startswith("mass [kg]") and "0.667951" in line for line in lines)  # the worked example
    assert "active at points 0: torque finger_bending" in lines
    assert "active at points 1: finger_bending finger_fits_width" in lines  # 2000 rpm: a lighter weight, too thin
    # for its finger at the torque's m_r (b(m_r), docs/errata.md): its mass set by the finger's width


@pytest.mark.parametrize("args, message", [
    (["--vary", "speed=abc"], "--vary speed=abc: not a number"),
    (["--vary", "nonsense=1"], "unknown quantity 'nonsense'"),
    (["--vary", "speed=1", "--dask", "localhost"], "--dask: expected an address like tcp://host:8786"),
    (["--vary", "speed=1", "--out", "table.xlsx"], "--out: write .csv, .parquet or .md"),
    (["--vary", "speed=1", "--jobs", "0"], "argument --jobs: must be from 1"),
    (["--vary", "speed=1", "--resume", "--no-store"], "--resume: continues a sweep from the run store"),
    (["--vary", "speed=1000", "--out", "/nonexistent/dir/t.csv", "--quiet"], "--out: cannot write"),
])
def test_bad_sweep_arguments_end_in_one_line(cli, args, message):
    result = cli("sweep", str(CASES / "wedge_paper.toml"), *args)
    assert result.returncode == 2 and result.stderr.count("\n") == 1 and message in result.stderr, result.stderr


def test_unreachable_dask_scheduler_is_bad_input(cli):
    result = cli("sweep", str(CASES / "wedge_paper.toml"), "--vary", "speed=1000", "--dask", "tcp://127.0.0.1:9")
    assert result.returncode == 2 and "cannot reach a Dask scheduler at tcp://127.0.0.1:9" in result.stderr


def _sweep():
    case = load_case(CASES / "wedge_fan.toml")
    return Sweep(case, [parse_vary("speed=1500:3000:6", "wedge"), parse_vary("allowable_pressure=1,3", "wedge")],
                 mode="geometry")


def test_process_pool_gives_the_serial_table():
    serial = _sweep().run(progress=False).frame
    pooled = _sweep().run(jobs=2, progress=False, chunk_size=3).frame
    pd.testing.assert_frame_equal(serial.drop(columns="iterations"), pooled.drop(columns="iterations"), rtol=1e-7)


def test_dask_local_cluster_gives_the_serial_table(tmp_path):
    from distributed import LocalCluster

    serial = _sweep().run(progress=False).frame
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None) as cluster:
        with RunStore(tmp_path / "dask.sqlite") as store:
            result = _sweep().run(store, runner=dask_runner(cluster.scheduler_address), progress=False, chunk_size=4)
            assert len(store.runs(sweep_id=result.sweep_id)) == 12
    pd.testing.assert_frame_equal(serial.drop(columns="iterations"), result.frame.drop(columns="iterations"),
                                  rtol=1e-7)


def test_json_gives_every_point_in_si(cli, run_store):
    result = cli("sweep", str(CASES / "wedge_paper.toml"), "--vary", "speed=500,1000", "--json", "--quiet")
    assert result.returncode == 0, result.stderr
    sweep = json.loads(result.stdout)
    assert [p["values"]["speed"] for p in sweep["points"]] == pytest.approx([500 * math.pi / 30, 1000 * math.pi / 30])
    direct = solve_case(load_case(CASES / "wedge_paper.toml").with_values(speed=1000 * math.pi / 30))
    assert sweep["points"][1]["objective"]["value"] == pytest.approx(direct.objective, rel=1e-8)  # kg
    assert all(p["status"] == "optimal" and p["constraints"] for p in sweep["points"])
    listed = json.loads(cli("runs", "list", "--json", "--kind", "sweep").stdout)
    assert len(listed["runs"]) == 2 and listed["sweeps"][0]["id"] == sweep["sweep_id"]


@pytest.mark.parametrize("case_file, varies, mode", [
    ("wedge_paper.toml", ["outer_diameter_max=100,130,160,200", "speed=800:1000:8"], "geometry"),
    ("cable_conveyor.toml", ["torque=220:880:60"], None),
    ("ball_compressor.toml", ["power=600:2400:60"], None),
])
def test_the_table_read_from_a_window_is_the_table_of_its_records(case_file, varies, mode, tmp_path):
    # batched points are tabulated from their window's arrays, their records built only when read; both must give
    # the same table, cell for cell, next to points solved alone (the first, infeasible ones) and stored ones
    from clutchopt.optimise.batch import BATCHED
    from clutchopt.optimise.table import record_table
    from store_rows import forget_points

    case = load_case(CASES / case_file)
    sweep = Sweep(case, [parse_vary(text, case.coupling) for text in varies], mode=mode)
    names = [v.name for v in sweep.formulation.variables]
    with RunStore(tmp_path / "runs.sqlite") as store:
        result = sweep.run(store, progress=False)
    records = list(result.solutions)
    batched = [r["solver"]["status"] == BATCHED for r in records]
    assert any(batched) and not all(batched)
    pd.testing.assert_frame_equal(result.frame, sweep.frame(record_table(records, names)), check_exact=True)
    forget_points(tmp_path / "runs.sqlite", lambda point: point % 2 == 1)  # forget every other point, then resume
    with RunStore(tmp_path / "runs.sqlite") as store:
        resumed = sweep.run(store, resume=True, progress=False)
    assert resumed.reused == len(records) - len(records) // 2 and resumed.solved == len(records) // 2
    assert [r["status"] for r in resumed.solutions] == [r["status"] for r in records]
    shown = list(result.frame.columns[:len(varies) + 3])  # point, the varied inputs, status, objective (the ball's
    # design is not unique: 6 or 7 ball rows give the same mass to 1e-9 at some powers, and a resumed sweep that
    # starts cold at a point may take the other)
    pd.testing.assert_frame_equal(resumed.frame[shown], result.frame[shown], rtol=1e-7)
    assert resumed.frame.iloc[::2].equals(result.frame.iloc[::2])  # the stored points, as they were


def test_points_solved_alone_are_tabulated_from_their_solutions_as_from_their_records(monkeypatch):
    # a window without batched points (the lever past its edge: 1.5x-3x its inertia of 12 kg m^2, no design at any
    # point, each proven infeasible) is tabulated from its Solutions, without building a record (Solution.as_dict,
    # 0.02 ms a point, 8 % of such a sweep); the table is the one its records give, cell for cell: statuses,
    # diagnoses (the proof) and iterations (0: solver "interval", each proven without an IPOPT iteration shown)
    from clutchopt.optimise.solution import Solution
    from clutchopt.optimise.table import record_table

    case = load_case(CASES / "lever_centrifuge.toml")
    sweep = Sweep(case, [parse_vary("inertia=18:36:12", "lever")], mode="paper")
    built = []
    monkeypatch.setattr(Solution, "as_dict", lambda self, _as_dict=Solution.as_dict: built.append(1) or _as_dict(self))
    result = sweep.run(progress=False)
    assert not built  # (a table read from the solutions)
    records = list(result.solutions)
    assert len(built) == 12 and {r["solver"]["name"] for r in records} == {"interval"}
    assert list(result.frame["status"]) == ["infeasible"] * 12 and list(result.frame["iterations"]) == [0] * 12
    assert all(d.startswith("proven infeasible") and "no design within the bounds meets torque" in d
               for d in result.frame["diagnosis"])
    names = [v.name for v in sweep.formulation.variables]
    pd.testing.assert_frame_equal(result.frame, sweep.frame(record_table(records, names)), check_exact=True)


def test_a_bad_value_names_the_first_point_that_has_it():
    case = load_case(CASES / "wedge_paper.toml")
    varies = [parse_vary("speed=800,1000", "wedge"), parse_vary("allowable_pressure=2,-1,3", "wedge")]
    with pytest.raises(InputError, match=r"--vary \(point 1\): material.allowable_pressure: must be > 0"):
        Sweep(case, varies)


def test_a_varied_design_variable_keeps_its_input_column():
    # the cable's lead angle is a case value and a (fixed) design variable: the input column holds the values as
    # given at every point, infeasible ones too, and the design has its own column
    case = load_case(CASES / "cable_conveyor.toml")
    varies = [parse_vary("lead_angle=10.38,12.7", "cable"), parse_vary("torque=440,100000", "cable")]
    frame = Sweep(case, varies).run(progress=False).frame
    assert frame["lead_angle [deg]"].tolist() == [10.38, 10.38, 12.7, 12.7]
    assert frame["status"].tolist() == ["optimal", "infeasible", "optimal", "infeasible"]  # proven (interval search)
    assert frame["design.lead_angle [deg]"].iloc[[0, 2]].tolist() == pytest.approx([10.38, 12.7])
    assert frame["design.lead_angle [deg]"].iloc[[1, 3]].isna().all()


def test_points_where_the_integers_change_equal_individual_solves():
    # the cable over its allowable stress: the count falls as the stress allowed rises, each change found ahead, where
    # the exclusion table says the next count down, promised a gain, is no longer excluded by the cable stress (the
    # chain ends before that point and the batch's integer search starts there at the next count down: batch._opening);
    # at every change and the point before it, the sweep's design is the one `solve` finds alone (cold IPOPT: the same
    # count, the optimum to the solvers' tolerances). Solver calls: 40 + 2 (the first point, solved alone: relaxation,
    # then counts), one a point at each of the 7 changes; 49 when each change had the chained column at the count
    # before too, and chains that ran past the changes spent 81, then 63
    case = load_case(CASES / "cable_conveyor.toml")
    values = case.values["allowable_cable_stress"] * np.geomspace(0.5, 2.0, 40)
    stress = next(q for q in case.quantities if q.name == "allowable_cable_stress")
    sweep = Sweep(case, [Vary(stress, tuple(values.tolist()))], mode="paper")
    result = sweep.run(progress=False)
    counts = result.frame["cable_count"].tolist()
    changes = [j for j in range(1, len(counts)) if counts[j] != counts[j - 1]]
    assert len(changes) == 7 and counts == sorted(counts, reverse=True)
    assert result.spent["solves"] == 42
    for j in sorted({k for change in changes for k in (change - 1, change)}):
        alone = solve_case(case.with_values(allowable_cable_stress=float(values[j])), "paper")
        got = result.solutions[j]
        assert got["status"] == alone.status == "optimal"
        assert got["design"]["cable_count"] == alone.design["cable_count"], j
        assert got["objective"]["value"] == pytest.approx(alone.objective, rel=1e-9)
        for name, value in alone.design.items():
            assert got["design"][name] == pytest.approx(value, rel=1e-8, abs=1e-12), (j, name)
