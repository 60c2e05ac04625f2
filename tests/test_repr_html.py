"""In Jupyter a Solution, a comparison and a sweep show themselves as tables with the CLI's columns and numbers."""

from html.parser import HTMLParser

import pytest

from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise import solve_case
from clutchopt.optimise.compare import compare_case
from clutchopt.optimise.sweep import Sweep
from clutchopt.optimise.sweep_grid import parse_vary
from clutchopt.output import comparison_text, solution_text
from tests.conftest import CASES


class Tables(HTMLParser):
    """Every <table> of a page as a list of rows of cell texts."""

    def __init__(self, html: str):
        super().__init__()
        self.tables: list[list[list[str]]] = []
        self._cell: list[str] | None = None
        self.feed(html)

    def handle_starttag(self, tag, attrs):
        if tag == "table":
            self.tables.append([])
        elif tag == "tr":
            self.tables[-1].append([])
        elif tag in ("td", "th"):
            self._cell = []

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self.tables[-1][-1].append("".join(self._cell).strip())
            self._cell = None

    def handle_data(self, data):
        if self._cell is not None:
            self._cell.append(data)


def text_table(text: str, title: str) -> list[list[str]]:
    """A table of the CLI text below its title: rows split on runs of two or more spaces or single spaces."""
    block = text.split(title + "\n", 1)[1].split("\n\n", 1)[0].splitlines()
    return [line.split() for line in block]


@pytest.fixture(scope="module")
def geometry():
    case = load_case(CASES / "wedge_paper.toml")
    return case, solve_case(case, mode="geometry")


def test_a_solution_shows_the_tables_of_solve(geometry):
    case, solution = geometry
    tables = Tables(solution._repr_html_()).tables
    assert [t[0] for t in tables] == [
        ["variable", "symbol", "value", "unit", "at bound", "description"],
        ["quantity", "value", "unit", "description"],
        ["constraint", "eq.", "value", "sense", "limit", "unit", "margin", "active", "elasticity"],
        ["parameter", "elasticity", "description"]]
    text = solution_text(solution, get_coupling("wedge").formulation("geometry"))
    design = text_table(text, "Design")[1:]
    assert [row[2] for row in tables[0][1:]] == [row[2] for row in design]  # the same values as printed
    assert tables[0][1][:4] == ["flank_inner_radius", "r_1", "81.8182", "mm"]
    torque = next(row for row in tables[2] if row[0] == "torque")
    assert torque[2:6] == ["10.236", ">=", "10.236", "N*m"] and torque[-2:] == ["yes", "+0.9408"]
    assert tables[3][1][:2] == ["outer_diameter_max", "-1.5308"]
    assert "status: optimal   objective (mass): 0.282095 kg" in solution._repr_html_()


def test_the_comparison_shows_the_tables_of_compare():
    table = compare_case(load_case(CASES / "wedge_paper.toml"))
    tables = Tables(table._repr_html_()).tables
    text = comparison_text(table.as_dict())
    assert tables[0][0] == ["quantity", "unit", *table.columns]
    assert tables[0][1] == text_table(text, "Comparison for the wedge coupling (values in the unit of each row)")[1]
    assert tables[1][0] == ["quantity", *[c for c in table.columns if c != "closed_form"]]
    mass = next(row for row in tables[1] if row[0] == "total_mass")
    assert mass[1] == "+42.68%" and mass[-1] == "-57.77%"  # 0.282095 / 0.667951 - 1


def test_a_sweep_shows_one_row_per_point():
    case = load_case(CASES / "wedge_paper.toml")
    result = Sweep(case, [parse_vary("speed=800,1000", "wedge")]).run(progress=False)
    html = result._repr_html_()
    assert "Sweep: 2 points, 2 optimal" in html
    tables = Tables(html).tables
    assert tables[0][0] == list(result.frame.columns)
    assert tables[0][2][:4] == ["1", "1000", "optimal", "0.667951"]  # the worked example's closed form at 1000 rpm
