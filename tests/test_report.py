"""Design-review report: self-contained page with the key numbers, sketch or dimension table, checked in Chromium."""

import math
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


@pytest.fixture(scope="module")
def other_couplings(tmp_path_factory):
    """Design-review pages of the lever (design mode), the cable (threads mode) and the ball clutch (design mode)."""
    folder = tmp_path_factory.mktemp("sketches")
    pages = {}
    for name, mode in (("lever_centrifuge", "design"), ("cable_pump", "threads"), ("ball_crusher", "design")):
        case = load_case(CASES / f"{name}.toml")
        solution = solve_case(case, mode)
        page = folder / f"{name}.html"
        page.write_text(build_report(case, solution))
        pages[case.coupling] = (page, solution)
    return pages


def sketch_of(page) -> str:
    html = page.read_text()
    section = html[html.index('<section id="sketch">'):]
    return section[:section.index("</section>")]


def length(line: str) -> float:
    x1, y1, x2, y2 = (float(re.search(f' {a}="([-0-9.]+)"', line).group(1)) for a in ("x1", "y1", "x2", "y2"))
    return math.hypot(x2 - x1, y2 - y1)


def polygon_height(polygon: str) -> float:
    ys = [float(point.split(",")[1]) for point in re.search(r'points="([^"]+)"', polygon).group(1).split()]
    return max(ys) - min(ys)


def test_every_coupling_gets_a_sketch_with_its_optimised_dimensions_in_red(other_couplings):
    expected = {"lever": ("l_2 = {lever_length}", "b = {lining_width}", "D = {outer_diameter}"),
                "cable": ("D = 160 mm", "l = 80 mm", "R_rv = 100 mm"),
                "ball": ("R_a = {active_radius}", "l_a = {active_width}", "R_1 = {filling_radius}")}
    for coupling, (page, solution) in other_couplings.items():
        svg = sketch_of(page)
        assert "<svg" in svg and "Optimised (red)" in svg
        values = {**{k: o.value for k, o in solution.outputs.items()}, **solution.design}
        for label in expected[coupling]:
            text = label.format(**{k: f"{v * 1e3:.4g} mm" for k, v in values.items()})
            assert f">{text}</text>" in svg, (coupling, text)
    lever = sketch_of(other_couplings["lever"][0])
    assert re.search(r'class="dimtext opt"[^>]*>l_2 = ', lever)  # design mode chose the lever length
    cable = sketch_of(other_couplings["cable"][0])
    assert re.search(r'class="dimtext"[^>]*>D = 160 mm', cable)  # the finger circle is the case's: grey
    assert re.search(r'class="dimtext opt"[^>]*>lead angles', cable)  # threads mode chose them: red


def test_the_sketches_are_to_scale(other_couplings):
    """Ratios of drawn lengths equal ratios of the design's: link / lining width = l_2 / b (lever), finger /
    finger circle = d_n / D (cable), ball / layer depth = r_c / (R_a - R_1) (ball)."""
    page, solution = other_couplings["lever"]
    svg, out = sketch_of(page), {k: o.value for k, o in solution.outputs.items()}
    link = re.search(r'<line class="dark"[^>]*/>', svg).group(0)
    lining = re.search(r'<polygon class="lining"[^>]*/>', svg).group(0)
    assert length(link) / polygon_height(lining) == pytest.approx(out["lever_length"] / out["lining_width"], rel=1e-3)

    page, solution = other_couplings["cable"]
    svg = sketch_of(page)
    finger = float(re.search(r'<circle class="lining"[^>]* r="([0-9.]+)"', svg).group(1))
    circle = float(re.search(r'<circle class="ref"[^>]* r="([0-9.]+)"', svg).group(1))
    assert finger / circle == pytest.approx(solution.design["finger_diameter"] / 0.160, rel=1e-3)

    page, solution = other_couplings["ball"]
    svg, out = sketch_of(page), {k: o.value for k, o in solution.outputs.items()}
    ball = float(re.search(r'<circle class="ball"[^>]* r="([0-9.]+)"', svg).group(1))
    layer = re.findall(r'<polygon class="layer"[^>]*/>', svg)[-1]  # the section's layer, R_1 to R_a
    depth = solution.design["active_radius"] - out["filling_radius"]
    assert ball / polygon_height(layer) == pytest.approx(solution.design["ball_radius"] / depth, rel=1e-3)


@pytest.mark.skipif(find_chromium() is None, reason=NO_CHROMIUM)
def test_the_other_sketches_render_in_headless_chromium(other_couplings, tmp_path):
    for coupling, (page, solution) in other_couplings.items():
        rendered = render(page, tmp_path / f"{coupling}.png")
        assert rendered.errors == [], coupling
        assert "red, bold: chosen by the optimiser" in rendered.text
        assert f"{solution.objective:.6g}" in rendered.text


def test_a_design_without_a_needed_dimension_gets_a_dimension_table():
    """Paper mode of the wedge with no weight width still gets its front view; a sketch that cannot be drawn
    (here: a lever design with its lining width removed) falls back to the table."""
    from clutchopt.report.sketch import sketch

    case = load_case(CASES / "lever_centrifuge.toml")
    solution = solve_case(case)
    outputs = {k: o.value for k, o in solution.outputs.items() if k != "lining_width"}
    assert sketch("lever", {**case.values, **solution.design}, outputs, set()) is None


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
    plot = sweep_plot(frame)
    assert "allowable_pressure [MPa] = 2" in plot.svg and "allowable_pressure [MPa] = 4" in plot.svg
    assert plot.caption == "Sweep: 6 points, 5 optimal, 1 not (crosses at the bottom)"


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
