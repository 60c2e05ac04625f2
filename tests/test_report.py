"""Design-review report: self-contained page with the key numbers, what was verified, sketch or dimension table,
laid out in Chromium with no label over a part or another label and no table wider than the page; and the PDF."""

import html
import json
import math
import re
import unicodedata
from pathlib import Path
from types import SimpleNamespace

import pandas as pd
import pytest

from chromium import find_chromium, render
from clutchopt.cases import load_case
from clutchopt.errors import InputError
from clutchopt.optimise import solve_case
from clutchopt.report import build_report, sweep_plot
from clutchopt.report.sketch.svg import PARTS
from conftest import CASES

NO_CHROMIUM = "no Chromium on this machine (.ci/run installs the Debian chromium package when it runs as root)"
PRINTED = 703  # px: the width of an A4 page's text at 96 px per inch (210 mm less the print stylesheet's margins)
LAYOUT = f"({Path(__file__).with_name('layout.js').read_text()})({json.dumps(', '.join('.' + c for c in PARTS))})"


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


def verification_rows(html: str) -> dict[str, list[str]]:
    """The verification block as {check: [how, found, verdict]}."""
    block = html[html.index('<section id="verification">'):]
    block = block[:block.index("</section>")]
    cells = [re.findall(r"<td[^>]*>(.*?)</td>", row) for row in re.findall(r"<tr>(.*?)</tr>", block, re.S)[1:]]
    return {row[0]: row[1:] for row in cells}


def test_the_page_opens_with_what_was_verified(review):
    html = review.read_text()
    assert html.index('<section id="verification">') < html.index('<section id="requirements">')
    checks = verification_rows(html)
    assert list(checks) == ["solver", "float64 re-check", "independent simulation", "corners and Monte Carlo"]
    assert checks["solver"][0].startswith("IPOPT returned Solve_Succeeded") and checks["solver"][2] == "passed"
    how, found, verdict = checks["float64 re-check"]
    count = html[html.index('<section id="margins">'):html.index('<section id="sensitivities">')].count("<tr>") - 1
    assert f"all {count} constraints re-evaluated in float64" in how and found.startswith(f"all {count} met")
    assert verdict == "passed"
    how, found, verdict = checks["independent simulation"]
    assert "constant driving speed" in how and found.startswith("reaches speed in 10 s against t_p = 10 s")
    assert checks["corners and Monte Carlo"] == ["the case has no [scatter]", "-", "not done"]


@pytest.fixture(scope="module")
def other_couplings(tmp_path_factory):
    """Design-review pages of the lever (design mode), the cable (threads mode), the ball clutch (design mode) and the
    wedge on a motor with return springs (paper mode)."""
    folder = tmp_path_factory.mktemp("sketches")
    pages = {}
    for name, mode in (("lever_centrifuge", "design"), ("cable_pump", "threads"), ("ball_crusher", "design"),
                       ("wedge_motor_start", "paper")):
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
                "ball": ("R_a = {active_radius}", "l_a = {active_width}", "R_1 = {filling_radius}"),
                "wedge": ("r2 = 60 mm", "h_r = 20 mm", "b = 25 mm", "D = 2 (r2 + s) = 140 mm", "s = 10 mm")}
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


def test_the_wedge_sketch_has_its_housing_springs_and_flank_angle(other_couplings):
    page, solution = other_couplings["wedge"]
    svg = sketch_of(page)
    assert svg.count('<path class="part" fill-rule="evenodd"') == 1  # the driven half-coupling's rim, a ring
    assert svg.count('<polyline class="spring"') == 4  # a return spring under each of the z = 4 weights
    preload = solution.design["spring_preload"]
    assert re.search(rf'class="dimtext opt"[^>]*>return springs: preload F_s = {preload:.4g} N on each weight', svg)
    assert re.search(r'<path class="dim"[^>]*marker-start[^>]*/>', svg)  # the angle dimensions' arcs
    assert ">alpha = 15 deg</text>" in svg and ">gamma = 44.98 deg</text>" in svg
    assert "Section of a weight in its groove" in svg
    assert svg.count('<polygon class="dark"') == 1  # the groove's walls and the rim, in section


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


def check_layout(rendered, page: str) -> None:
    """No label over a part or another label; no table or figure wider than its room, none scrolled; the page no
    wider than the window."""
    layout = rendered.probed
    assert layout["overlaps"] == [], (page, layout["overlaps"])
    for box in layout["boxes"]:
        assert box["width"] <= box["room"] + 0.5 and not box["scrolls"], (page, box)
    assert layout["page"]["width"] <= layout["page"]["room"], page


@pytest.mark.skipif(find_chromium() is None, reason=NO_CHROMIUM)
def test_the_other_sketches_render_in_headless_chromium(other_couplings, tmp_path):
    for coupling, (page, solution) in other_couplings.items():
        rendered = render(page, tmp_path / f"{coupling}.png", probe=LAYOUT)
        assert rendered.errors == [], coupling
        assert "red, bold: chosen by the optimiser" in rendered.text
        assert f"{solution.objective:.6g}" in rendered.text
        check_layout(rendered, coupling)
        check_layout(render(page, tmp_path / f"{coupling}-printed.png", PRINTED, "print", LAYOUT), coupling)


@pytest.mark.skipif(find_chromium() is None, reason=NO_CHROMIUM)
def test_the_layout_check_sees_a_label_over_a_part_a_label_over_a_label_and_a_wide_table(tmp_path):
    from clutchopt.report.sketch.svg import STYLE

    crowded = tmp_path / "crowded.html"
    crowded.write_text(f'<!DOCTYPE html><html><body style="width:300px"><figure><svg xmlns="http://www.w3.org/2000/svg" '
                       f'width="200" height="100" aria-label="dimensioned sketch">{STYLE}'
                       '<circle class="part" cx="50" cy="50" r="30" fill-rule="evenodd"/>'
                       '<line class="dark" x1="120" y1="0" x2="120" y2="100" style="stroke-width:4"/>'
                       '<text class="dimtext" x="50" y="55" text-anchor="middle">on the disc</text>'
                       '<text class="dimtext" x="110" y="30" text-anchor="start">across the bar</text>'
                       '<text class="dimtext" x="110" y="34" text-anchor="start">and a label</text>'
                       '<text class="dimtext" x="4" y="96">clear</text></svg></figure>'
                       f'<table><tr>{"<td>wide_column_name_without_spaces</td>" * 8}</tr></table></body></html>')
    layout = render(crowded, tmp_path / "crowded.png", probe=LAYOUT).probed
    overlaps = {tuple(pair) for pair in layout["overlaps"]}
    assert ("on the disc", "circle.part") in overlaps and ("across the bar", "line.dark") in overlaps
    assert ("across the bar", "and a label") in overlaps and not any("clear" in pair for pair in overlaps)
    assert any(box["width"] > box["room"] for box in layout["boxes"]) and layout["page"]["width"] > 300


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
    page = render(review, shot, probe=LAYOUT)
    assert page.errors == []
    assert shot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and shot.stat().st_size > 50_000
    for number in ("0.282095", "81.8182", "5.46156", "-1.5308", "Comparison with the paper's method",
                   "paper_eq27_second_form"):
        assert number in page.text
    check_layout(page, "screen")
    check_layout(render(review, tmp_path / "printed.png", PRINTED, "print", LAYOUT), "print")


@pytest.mark.skipif(find_chromium() is None, reason=NO_CHROMIUM)
def test_report_writes_a_pdf_with_the_headline_design(tmp_path):
    from pypdf import PdfReader

    from conftest import run_cli

    pdf = tmp_path / "review.pdf"
    result = run_cli("report", str(CASES / "wedge_paper.toml"), "--mode", "geometry", "-o", str(pdf), "--no-store")
    assert result.returncode == 0, result.stderr
    assert f"written to {pdf}" in result.stdout
    reader = PdfReader(pdf)
    text = unicodedata.normalize("NFKC", " ".join(page.extract_text() for page in reader.pages))  # no ligatures
    assert len(reader.pages) >= 3 and round(float(reader.pages[0].mediabox.width)) == 595  # A4
    assert "Design review" in text and "objective (mass) 0.282095 kg" in text and "Verification" in text
    assert "r2 = 90 mm" in text  # the sketch, as text


def test_a_pdf_without_chromium_is_refused_before_any_work(tmp_path, monkeypatch, capsys):
    from clutchopt.cli import EXIT_BAD_INPUT, main

    monkeypatch.setenv("PATH", str(tmp_path))  # no Chromium on it
    pdf = tmp_path / "review.pdf"
    assert main(["report", str(CASES / "wedge_paper.toml"), "-o", str(pdf), "--no-store"]) == EXIT_BAD_INPUT
    out, err = capsys.readouterr()
    assert err == ("error: --out: writing a PDF needs headless Chromium, and none is on the PATH: install Chromium "
                   "(Debian and Ubuntu: apt-get install chromium) or write .html\n")
    assert out == "" and list(tmp_path.iterdir()) == []


def test_an_empty_tornado_chart_is_a_sentence_saying_why():
    from clutchopt.report.sections import tornado_chart

    case = load_case(CASES / "wedge_motor_start_scatter.toml")
    result = SimpleNamespace(start_up_points=[{}, {}], start_up_samples=200, samples=10000)
    note = tornado_chart(case, result, {"flank_pressure": {"friction_coefficient": 0.0},
                                        "finger_bending": {"friction_coefficient": 1e-12}})
    assert note.kind == "note" and note.text == (
        "No tornado chart: over its range, friction_coefficient moves none of the 2 constraints' margins "
        "(flank_pressure, finger_bending) at the nominal design; the start-up, which is simulated rather than "
        "evaluated, is checked at 2 corner(s) and by 200 simulated starts.")
    drawn = tornado_chart(case, result, {"flank_pressure": {"friction_coefficient": -0.2}})
    assert drawn.kind == "figure" and "<svg" in drawn.svg


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


def test_a_scatter_pages_designs_are_the_pages_own_and_made_once(monkeypatch):
    """report --mode geometry of a [scatter] case showed its geometry design (0.335 kg) over a Scatter section and
    comparison columns of the case's paper mode (nominal 0.800 kg, "fails with probability 0.504"), each solved once
    per section: now both sections show the worst-case and chance designs of the page's mode, made once (two robust
    solves, not four), their nominal design the page's to the bit."""
    import clutchopt.optimise.design as design_module
    import clutchopt.optimise.robust as robust_module

    case = load_case(CASES / "wedge_motor_start_scatter.toml")
    solution = solve_case(case, "geometry")
    solved = []
    original = robust_module.solve_robust

    def counted(*arguments, **keywords):
        solved.append(arguments[1:4])
        return original(*arguments, **keywords)

    monkeypatch.setattr(robust_module, "solve_robust", counted)
    monkeypatch.setattr(design_module, "solve_robust", counted)
    text = re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", build_report(case, solution)))
    assert solved == [("worst-case", None, "geometry"), ("chance", 0.999, "geometry")]
    shown = f"{solution.objective:.6g} kg"
    assert shown == "0.335452 kg" and f"nominal optimal {shown} +0.0%" in text  # the Scatter section's first row
    comparison = text[text.index("Comparison with the paper"):text.index("Start-up simulation")]
    total = comparison[comparison.index("total_mass kg"):].split()[2:12]  # the ten columns' total masses
    assert total[-3] == f"{solution.objective:.6g}"  # nominal, then worst_case and chance_0.999
    assert "nominal : the geometry mode optimised for mass at the nominal values" in comparison
    # review 29: the start-up columns too, the page's mode (they had been the case's paper mode: 0.799684 kg)
    assert total[-4] == f"{solution.objective:.6g}" and total[-5] == total[-6] == "0.282095"  # nlp_start_up, then
    assert "nlp_start_up : the geometry mode optimised for mass with the start-up" in comparison  # the static
    # geometry optimum, constant_acceleration beside nlp_geometry
    # review 29: the nominal design's failure leaves its start-up limits out, and says so (headline, verification,
    # table); the robust designs' systems have theirs (the chance design's 0.00193, not its constraints' 0.00102)
    assert "under the scatter (its constraints; its start-up limits not sampled" in text
    assert "(finger_bending); its start-up limits not sampled failed" in text
    scattered = text[text.index("Scatter design status"):]
    assert "importance sampling; the start-up limits apart)" in scattered[:scattered.index("worst case optimal")]
    assert "importance sampling plus each start-up limit" in scattered[scattered.index("chance 0.999 optimal"):]


def test_a_page_without_a_design_says_so_in_every_section():
    """review 29: an infeasible or not_found page was titled "Optimal design", its sketch "of the optimum", its
    margins with elasticities of -400 and its start "passed": now it names the last point as no design."""
    case = load_case(CASES / "wedge_paper.toml").with_values(outer_diameter_max=0.1)
    solution = solve_case(case, "geometry")
    assert solution.status == "not_found"
    text = html.unescape(re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", build_report(case, solution))))
    assert "objective (mass) none (no design" in text and "No design: the solver's last point" in text
    assert "Optimal design" not in text and "sketch of the optimum" not in text and "No sketch" in text
    assert "the point is no optimum, status not_found" in text
    assert "independent simulation not simulated no design to start (status not_found) not done" in text
    assert "nlp_paper : IPOPT, paper mode, minimum mass; no design, status infeasible: infeasible whatever" in text


def test_a_robust_start_up_page_starts_its_figure_where_its_table_does():
    """review 29: the robust design's start-up table was its start at the scatter's corner (f = 0.12, 10 s), its
    figure and caption the same design at the nominal f = 0.15 (6.84 s), the NLP's points drawn over the other
    start's lines, neither saying which f: now both at the corner, said."""
    from clutchopt.optimise.robust import WORST_CASE, solve_robust

    case = load_case(CASES / "wedge_motor_start_scatter.toml")
    robust = solve_robust(case, WORST_CASE, samples=100, starts=10)
    assert robust.corners["start_up"] == {"friction_coefficient": 0.12}
    text = html.unescape(re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", build_report(case, robust.solution,
                                                                                     robust=robust))))
    assert "The start at the scatter's friction_coefficient 0.12, where the robust design's start-up limits" in text
    caption = text[text.index("Start-up of the optimised wedge design"):]
    assert caption.startswith("Start-up of the optimised wedge design on the case's drive")
    assert "lock-up after 10 s" in caption[:300] and "(Simulated at the scatter's friction_coefficient 0.12" in caption


def test_a_robust_page_names_where_each_margin_is_taken():
    """review 29: wedge_centrifuge --robust worst-case showed the torque row 94.85 >= 94.85 N*m (at the corner
    f = 0.12, 13.8 kg m^2, 25 N*m) without its corner, under a derived torque of 118.56 N*m at the nominal values."""
    from clutchopt.optimise.robust import WORST_CASE, solve_robust

    case = load_case(CASES / "wedge_centrifuge.toml")
    robust = solve_robust(case, WORST_CASE, samples=100)
    text = html.unescape(re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", build_report(case, robust.solution,
                                                                                     robust=robust))))
    margins = text[text.index("Constraint margins"):text.index("Sensitivities")]
    assert "each constraint where the worst-case design holds it" in margins and " at margin bar " in margins
    torque = margins[margins.index("torque (15)-(16)"):margins.index("flank_pressure")]
    assert "friction_coefficient 0.12, inertia 13.8 kg*m^2, resisting_torque 25 N*m" in torque
    assert re.search(r"outer_diameter \S+ [\d.]+ <= [\d.]+ mm \S+ nominal ", margins)  # the scatter moves it not
    # and the scatter it was designed for, under Requirements (review 29: not on the page)
    assert "Scatter quantity scatter nominal friction_coefficient range 0.12 to 0.18 0.15 inertia normal" in text
    assert "one quantity at a time from the low to the high end of its range" in text  # the tornado: no Monte Carlo
    assert "friction_coefficient@torque -0.8789 friction_coefficient where torque is held (its corner" in text  # a
    # sensitivity to a corner's value, described (review 29: listed without a word)


def test_a_sweep_table_of_another_aspect_of_the_case_is_refused(tmp_path):
    """review 29: `report --sweep` took a table swept with other bounds, free variables, scatter, start-up effects or
    choices, its plot of another problem beside the page's design; each is now named."""
    from dataclasses import replace

    from clutchopt.optimise.sweep import Sweep, parse_vary
    from clutchopt.optimise.sweep_table import check_swept_from, read_frame, write_frame

    case = load_case(CASES / "wedge_paper.toml")
    sweep = Sweep(case, [parse_vary("speed=900,1000", case.coupling)])
    table = tmp_path / "sweep.csv"
    write_frame(sweep.run(progress=False).frame, str(table), identity=sweep.identity())
    frame, posed = read_frame(str(table)), ("paper", "mass", "")
    check_swept_from(frame, case, str(table), print, posed)  # its own case: taken
    for other, named in ((replace(case, bounds={**case.bounds, "weight_count": (4.0, 6.0)}), "bounds"),
                         (replace(case, free=("weight_width",)), "free")):
        with pytest.raises(InputError, match=f"whose {named} differ from this case's"):
            check_swept_from(frame, other, str(table), print, posed)


def test_a_scatter_page_without_a_design_quotes_no_failure_probability():
    """review 31: a [scatter] page whose solve found no design still said "the torque fails with probability 1 under
    the scatter", a failed verification row and a tornado chart of "the nominal design", all of its last point."""
    case = load_case(CASES / "wedge_centrifuge.toml").with_values(outer_diameter_max=0.15)
    solution = solve_case(case)
    assert solution.status == "infeasible"
    text = html.unescape(re.sub(r"\s+", " ", re.sub(r"<[^>]+>", " ", build_report(case, solution))))
    assert "under the scatter" not in text and "No tornado chart: the nominal solve found no design." in text
    assert "corners and Monte Carlo the nominal design under the case's [scatter] no design to check not done" in text


def test_an_undecided_start_is_not_called_no_lock_up():
    """review 31: a start that stopped without a verdict (locks_up None) read as 'no lock-up' in the page's
    verification and the worn linings' note."""
    from clutchopt.output import worn_note
    from clutchopt.report.verification import start_up_check

    assert worn_note({"locks_up": None}) == "worn linings (simulated): not decided"
    assert worn_note({"locks_up": False}) == "worn linings (simulated): no lock-up"
    undecided = SimpleNamespace(status="optimal", start_up={"effects": ["slip_friction"], "intervals": 8,
                                                             "locks_up": None, "reason": "stopped after 20000 steps"})
    check = start_up_check(None, undecided)
    assert check.found == "not decided: stopped after 20000 steps" and check.verdict == "failed"


def test_a_system_chance_page_says_what_its_start_up_limits_took_of_the_risk():
    """review 29: the risk allocation's table of a start-up case left out the start-up limits' shares (0.00125 each of
    0.01, the constraints' 0.0025 the rest)."""
    from clutchopt.optimise.robust import SYSTEM_CHANCE, solve_robust
    from clutchopt.report.sections import allocation_blocks

    case = load_case(CASES / "wedge_motor_start_scatter.toml")
    result = solve_robust(case, SYSTEM_CHANCE, 0.99, samples=200, starts=10)
    claim = allocation_blocks(result.allocation, result)[0].text
    assert "Each start-up limit the scatter moves took 0.00125 of 1 - P first (a union bound)" in claim
    assert "sum_i Phi(-beta_i) <= 0.0025" in claim
