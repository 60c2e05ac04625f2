"""The start-up plot speaks rpm like cases and sweeps, and simulate --plot says where it wrote."""

import numpy as np
import pytest

from clutchopt.simulate import load_scene, run_scene
from clutchopt.simulate.plot import history_figure
from tests.conftest import CASES


def test_speeds_are_drawn_in_rpm():
    """The paper's scene drives at w0 = 1500 rpm (50 pi rad/s): the driving half's line sits at 1500 on the axis."""
    result = run_scene(load_scene(CASES / "scenes" / "paper_transient.toml"))
    top = history_figure(result).axes[0]
    assert top.get_ylabel() == "speed, rpm"
    driver, driven = top.get_lines()[:2]
    assert np.allclose(driver.get_ydata(), 1500.0, rtol=1e-12)
    assert driven.get_ydata()[-1] == pytest.approx(result.history["w_driven"].iloc[-1] * 30 / np.pi, rel=1e-12)


def test_simulate_plot_says_where_it_wrote(cli, tmp_path):
    png = tmp_path / "start.png"
    result = cli("simulate", "cases/scenes/paper_transient.toml", "--plot", str(png), "--no-store")
    assert result.returncode == 0, result.stderr
    assert result.stdout.endswith(f"figure written to {png}\n") and png.read_bytes()[:4] == b"\x89PNG"


def test_the_nlp_start_is_marked_in_rpm_beside_the_simulated_one():
    """A solution's start-up summary (trajectory in rad/s at the collocation points) is drawn in rpm: 100 pi rad/s
    is 3000 rpm."""
    result = run_scene(load_scene(CASES / "scenes" / "paper_transient.toml"))
    nlp = {"trajectory": {"t": [0.0, 1.0], "w_driver": [100 * np.pi, 100 * np.pi], "w_driven": [0.0, 50 * np.pi]}}
    top = history_figure(result, nlp=nlp).axes[0]
    marked = {line.get_label(): line for line in top.get_lines()}
    driver = marked["NLP nodes, driving"]
    assert np.allclose(driver.get_ydata(), 3000.0) and driver.get_linestyle() == "None"
    assert np.allclose(marked["NLP nodes, driven"].get_ydata(), [0.0, 1500.0])
