"""The review page's pieces as plain data, and the Jinja2 templates (clutchopt/report/templates/) that write them
as HTML. Autoescaping is on: every text a piece carries (a case's title, a quantity's description) is escaped
wherever a template puts it; only the SVG of a figure, which its own writer escaped, is marked safe."""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from functools import lru_cache

from markupsafe import Markup, escape

BREAKS = re.compile(r"(_|[./](?=[A-Za-z]))")  # where a column's name may wrap


@dataclass(frozen=True)
class Note:
    text: str
    kind: str = "note"


@dataclass(frozen=True)
class Heading:
    text: str
    kind: str = "heading"


@dataclass(frozen=True)
class Table:
    rows: list[dict]
    numeric: tuple[str, ...] = ()  # columns aligned right
    kind: str = "table"


@dataclass(frozen=True)
class Figure:
    svg: Markup
    caption: str
    kind: str = "figure"


@dataclass(frozen=True)
class Items:
    """A list of (name, text): the notes of a table's columns."""

    items: list[tuple[str, str]]
    kind: str = "items"


@dataclass(frozen=True)
class Bar:
    """A margin drawn as a bar: ``share`` of the full width (0 to 1), red where the constraint is active."""

    share: float
    active: bool


@dataclass
class Section:
    title: str
    anchor: str
    blocks: list = field(default_factory=list)


@lru_cache(maxsize=1)
def _environment():
    from jinja2 import Environment, PackageLoader, StrictUndefined

    environment = Environment(loader=PackageLoader("clutchopt.report", "templates"), autoescape=True,
                              undefined=StrictUndefined, trim_blocks=True, lstrip_blocks=True)
    environment.tests["bar"] = lambda value: isinstance(value, Bar)
    environment.filters["breakable"] = breakable
    return environment


def render(template: str, **context) -> str:
    return _environment().get_template(template).render(**context)


def breakable(text) -> Markup:
    """``text`` escaped, with a line-break opportunity after each underscore, and each dot or slash before a letter:
    a table of many columns named like ``paper_eq27_second_form`` wraps its head to the page's width instead of
    running past it."""
    return Markup(BREAKS.sub(r"\1<wbr>", str(escape(text))))


def safe_svg(svg: str) -> Markup:
    """SVG markup written by clutchopt's sketches or by matplotlib, both of which escape the text they draw."""
    return Markup(svg)
