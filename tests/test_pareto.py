"""Pareto front mass against cost: ends are the two optima, caps bind, no point dominates another."""

import json
import numpy as np
import pandas as pd
import pytest

from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.optimise.pareto import pareto_front
from conftest import CASES


@pytest.fixture(scope="module")
def centrifuge():
    return pareto_front(load_case(CASES / "wedge_centrifuge.toml"), "geometry", points=7)


def test_ends_are_the_mass_and_the_cost_optimum(centrifuge):
    case = load_case(CASES / "wedge_centrifuge.toml")
    frame = centrifuge.frame
    assert (frame["status"] == "optimal").all() and len(frame) == 7
    assert frame["mass [kg]"].iloc[0] == pytest.approx(solve_case(case, "geometry", "mass").objective, rel=1e-9)
    assert frame["cost [EUR]"].iloc[-1] == pytest.approx(solve_case(case, "geometry", "cost").objective, rel=1e-9)
    assert frame["mass [kg]"].iloc[0] == pytest.approx(0.684319, rel=1e-5)
    assert frame["cost [EUR]"].iloc[-1] == pytest.approx(39.18628, rel=1e-5)


def test_the_cap_binds_and_the_front_trades_mass_for_cost(centrifuge):
    frame = centrifuge.frame
    inner = frame.iloc[1:-1]
    assert inner["cost [EUR]"].to_numpy() == pytest.approx(inner["cost_cap [EUR]"].to_numpy(), rel=1e-8)
    assert (np.diff(frame["mass [kg]"]) > 0).all() and (np.diff(frame["cost [EUR]"]) < 0).all()
    caps = [c for s in centrifuge.solutions[1:-1] for c in s.constraints if c.name == "cost_cap"]
    assert all(c.active and c.elasticity < 0 for c in caps)  # a tighter cap costs mass


def test_a_coupling_whose_optima_coincide_has_no_front():
    front = pareto_front(load_case(CASES / "lever_centrifuge.toml"))
    assert front.note == "no trade-off: the mass optimum is also the cost optimum" and len(front.frame) == 1


def test_cli_table_plot_and_store(cli, tmp_path, run_store):
    plot, out = tmp_path / "front.png", tmp_path / "front.csv"
    result = cli("pareto", str(CASES / "wedge_centrifuge.toml"), "--mode", "geometry", "--points", "5",
                 "--plot", str(plot), "--out", str(out))
    assert result.returncode == 0, result.stderr
    assert "0.684319" in result.stdout and "39.1863" in result.stdout
    assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(pd.read_csv(out)) == 5
    listed = cli("runs", "list", "--kind", "pareto")
    assert listed.stdout.count(" pareto ") == 5
    bad = cli("pareto", str(CASES / "wedge_centrifuge.toml"), "--points", "1")
    assert bad.returncode == 2 and "--points: must be from 2 to 1000, got 1" in bad.stderr


def test_json_is_si(cli):
    result = cli("pareto", str(CASES / "lever_centrifuge.toml"), "--points", "2", "--json", "--no-store")
    assert result.returncode == 0, result.stderr
    front = json.loads(result.stdout)
    assert front["note"].startswith("no trade-off") and [row["cost_cap"] for row in front["rows"]] == [None]
    lightest = front["rows"][0]
    assert lightest["status"] == "optimal" and lightest["mass"] == pytest.approx(1.72653, rel=1e-5)  # kg
    assert 0.05 < lightest["design"]["weight_mass"] < 0.1  # kg, the closed form's 0.0724 kg per weight
