"""Design-review report: self-contained page with the key numbers, sketch or dimension table, checked in Chromium."""

import re

import pandas as pd
import pytest

from chromium import find_chromium, render
from clutchopt.cases import load_case
from clutchopt.optimise import solve_case
from clutchopt.report import build_report, sweep_plot
from conftest import CASES

NO_CHROMIUM = "no Chromium on this machine (.ci/run installs the Debian chromium package when it runs as root)"


@pytest.fixture(scope="module")
def review(tmp_path_factory):
    """The worked example in geometry mode with a small sweep, written by the CLI."""
    from conftest import run_cli

    folder = tmp_path_factory.mktemp("review")
    sweep = folder / "sweep.csv"
    assert run_cli("sweep", str(CASES / "wedge_paper.toml"), "--mode", "geometry", "--vary", "speed=600:1800:7",
                   "--vary", "allowable_pressure=2,4", "--out", str(sweep), "--quiet", "--no-store").returncode == 0
    page = folder / "review.html"
    result = run_cli("report", str(CASES / "wedge_paper.toml"), "--mode", "geometry", "-o", str(page),
                     "--sweep", str(sweep), "--no-store")
    assert result.returncode == 0, result.stderr
    assert "(optimal, mass 0.282095 kg)" in result.stdout
    return page


def test_page_is_self_contained_with_every_section(review):
    html = review.read_text()
    for section in ("requirements", "design", "sketch", "margins", "sensitivities", "comparison", "simulation",
                    "sweep"):
        assert f'<section id="{section}">' in html
    assert "<script" not in html and not re.search(r'(src|href)="(https?:|//)', html)
    assert "0.282095" in html and "r2 = 90 mm" in html and "b = 40 mm" in html  # the optimum, dimensioned
    assert "Sweep: 14 points, 14 optimal" in html
    simulation = html[html.index('<section id="simulation">'):]
    assert simulation.index("<svg") < simulation.index("</section>")  # the start-up plot
    assert "Start-up of the optimised wedge design" in simulation and "reaches speed in 10 s" in simulation
    assert "outer_diameter_max" in html and "-1.5308" in html  # the largest elasticity of the worked example


def test_a_coupling_without_a_sketch_gets_a_dimension_table():
    case = load_case(CASES / "lever_centrifuge.toml")
    html = build_report(case, solve_case(case))
    assert "No sketch is drawn for the lever coupling" in html and "<th>dimension</th>" in html


@pytest.mark.skipif(find_chromium() is None, reason=NO_CHROMIUM)
def test_page_renders_in_headless_chromium_without_console_errors(review, tmp_path):
    shot = tmp_path / "review.png"
    page = render(review, shot)
    assert page.errors == []
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and shot.stat().st_size > 50_000
    for number in ("0.282095", "81.8182", "5.46156", "-1.5308", "Comparison with the paper's method"):
        assert number in page.text


@pytest.mark.skipif(find_chromium() is None, reason=NO_CHROMIUM)
def test_the_browser_check_sees_console_errors_and_failed_loads(tmp_path):
    broken = tmp_path / "broken.html"
    broken.write_text('<!DOCTYPE html><html><body><p>x</p><img src="missing.png">'
                      '<script>console.error("boom"); notDefined();</script></body></html>')
    errors = render(broken, tmp_path / "broken.png").errors
    assert "boom" in errors and any("notDefined" in e for e in errors) and any("missing" in e or "ERR_FILE" in e
                                                                                 for e in errors)


def test_sweep_plot_has_a_line_per_level_and_marks_failed_points():
    frame = pd.DataFrame({"point": range(6), "speed [rpm]": [500, 1000, 1500] * 2,
                          "allowable_pressure [MPa]": [2] * 3 + [4] * 3,
                          "status": ["optimal"] * 5 + ["infeasible"], "mass [kg]": [3, 2, 1, 3, 2, float("nan")]})
    svg = sweep_plot(frame)
    assert "allowable_pressure [MPa] = 2" in svg and "allowable_pressure [MPa] = 4" in svg
    assert "Sweep: 6 points, 5 optimal, 1 not (crosses at the bottom)" in svg


def test_bad_report_input(cli, tmp_path):
    missing = cli("report", str(CASES / "wedge_paper.toml"), "-o", str(tmp_path / "r.html"), "--sweep",
                  str(tmp_path / "none.csv"))
    assert missing.returncode == 2 and "none.csv: no such file" in missing.stderr
    other = tmp_path / "other.csv"
    other.write_text("a,b\n1,2\n")
    wrong = cli("report", str(CASES / "wedge_paper.toml"), "-o", str(tmp_path / "r.html"), "--sweep", str(other))
    assert wrong.returncode == 2 and "not a sweep table" in wrong.stderr
    unwritable = cli("report", str(CASES / "wedge_paper.toml"), "-o", str(tmp_path / "no" / "r.html"))
    assert unwritable.returncode == 2 and "--out: cannot write" in unwritable.stderr
