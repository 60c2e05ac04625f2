"""What every sketch is drawn with: views to scale (model metres to px), parts, reference lines and dimensions.

A dimension of a variable the optimiser chose is drawn red and bold, one the case gives grey, so a reader sees
at a glance what the optimum changed. Coordinates of a view are model metres, x to the right and y up. Labels are
placed when the document is put together, clear of every part and of each other (labels.py); the document's size
follows from what it holds.
"""

from __future__ import annotations

import math
from html import escape
from itertools import count

from clutchopt.report.sketch.labels import (
    CLEAR,
    FAMILY,
    ROW,
    Label,
    Obstacles,
    Spot,
    beside,
    box_of,
    column,
    place,
)
from clutchopt.report.sketch.shapes import Bar, Box, Polygon, Ring, union

PARTS = ("part", "dark", "lining", "ball", "layer", "spring")  # classes of the drawn parts: no label covers one
STYLE = ("<style>.part{fill:#cfd8e3;stroke:#2b3a4a;stroke-width:1.2}.dark{fill:#8a99a8;stroke:#2b3a4a}"
         ".lining{fill:#c9a36a;stroke:#5a4320}.ball{fill:#e3e7eb;stroke:#2b3a4a;stroke-width:0.8}"
         ".layer{fill:#eef1f4;stroke:#2b3a4a;stroke-width:0.6}.spring{fill:none;stroke:#2b3a4a;stroke-width:1.2}"
         ".ref{fill:none;stroke:#6b7785;stroke-dasharray:5 4}.axis{stroke:#6b7785;stroke-dasharray:12 3 2 3}"
         ".dim{stroke:#6b7785;stroke-width:1;fill:none}.dim.opt{stroke:#b03a2e}.leader{stroke:#9aa5b1;stroke-width:0.7}"
         f".ext{{stroke:#9aa5b1;stroke-width:0.6}}text{{font-family:'{FAMILY}',sans-serif}}"
         ".dimtext{fill:#4a5562;font-size:12px;paint-order:stroke;stroke:#fff;stroke-width:3px;stroke-linejoin:round}"
         ".dimtext.opt{fill:#b03a2e;font-weight:bold}.title{font-size:13px;font-weight:bold;fill:#2b3a4a}"
         ".note{font-size:11px;fill:#55606b}</style>")
DEFS = ('<defs>' + "".join(
    f'<marker id="arrow{suffix}" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" '
    f'orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="{colour}"/></marker>'
    for suffix, colour in (("", "#6b7785"), ("-opt", "#b03a2e"))) + "</defs>")
LEGEND = "red, bold: chosen by the optimiser; grey: given by the case"
MARGIN = 8.0  # px round the document's content
OWNERS = count()  # tells a dimension's own lines from the others'
ALONG = (0.5, 0.35, 0.65, 0.2, 0.8)  # where along its dimension line a label may sit, in order of preference


def mm(value: float) -> str:
    return f"{value * 1e3:.4g} mm"


def deg(value: float) -> str:
    return f"{math.degrees(value):.4g} deg"


def text_element(text: str, cls: str, spot: Spot) -> str:
    return (f'<text class="{cls}" x="{spot.x:.1f}" y="{spot.y:.1f}" text-anchor="{spot.anchor}">'
            f"{escape(text)}</text>")


def line_element(cls: str, x1: float, y1: float, x2: float, y2: float, extra: str = "") -> str:
    return f'<line class="{cls}" x1="{x1:.2f}" y1="{y1:.2f}" x2="{x2:.2f}" y2="{y2:.2f}"{extra}/>'


def dimtext(chosen: bool) -> str:
    return "dimtext opt" if chosen else "dimtext"


class View:
    """One view: ``scale`` px per metre, the model origin at (``x0``, ``y0``) px; its title goes above it."""

    def __init__(self, title: str, x0: float, y0: float, scale: float):
        self.title, self.x0, self.y0, self.k = title, x0, y0, scale
        self.items: list[str] = []
        self.parts: list = []  # shapes (px) of the parts
        self.lines: list[tuple[int, object]] = []  # (owner, shape) of reference and dimension lines
        self.labels: list[Label] = []
        self.notes: list[tuple[str, str]] = []  # (text, class), in rows below the view

    def at(self, x: float, y: float) -> tuple[float, float]:
        return self.x0 + x * self.k, self.y0 - y * self.k

    def _draw(self, element: str, cls: str, shape, owner: int = -1) -> None:
        self.items.append(element)
        if cls in PARTS:
            self.parts.append(shape)
        else:
            self.lines.append((owner, shape))

    def polygon(self, points, cls: str = "part") -> None:
        drawn = [self.at(x, y) for x, y in points]
        self._draw(f'<polygon class="{cls}" points="{" ".join(f"{px:.2f},{py:.2f}" for px, py in drawn)}"/>', cls,
                   Polygon(tuple(drawn)))

    def rect(self, x1: float, y1: float, x2: float, y2: float, cls: str = "part") -> None:
        self.polygon([(x1, y1), (x2, y1), (x2, y2), (x1, y2)], cls)

    def circle(self, x: float, y: float, r: float, cls: str = "part") -> None:
        (cx, cy), radius = self.at(x, y), max(r * self.k, 0.4)
        shape = Ring(cx, cy, 0.0, radius) if cls in PARTS else Ring(cx, cy, radius - 0.5, radius + 0.5)
        self._draw(f'<circle class="{cls}" cx="{cx:.2f}" cy="{cy:.2f}" r="{radius:.2f}"/>', cls, shape)

    def ring(self, r_in: float, r_out: float, cls: str = "part") -> None:
        """An annulus about the origin from ``r_in`` to ``r_out``."""
        cx, cy = self.at(0, 0)
        path = "".join(f"M{cx + r:.2f},{cy:.2f} A{r:.2f},{r:.2f} 0 1 0 {cx - r:.2f},{cy:.2f} "
                       f"A{r:.2f},{r:.2f} 0 1 0 {cx + r:.2f},{cy:.2f} Z " for r in (r_out * self.k, r_in * self.k))
        self._draw(f'<path class="{cls}" fill-rule="evenodd" d="{path.strip()}"/>', cls,
                   Ring(cx, cy, r_in * self.k, r_out * self.k))

    def line(self, x1: float, y1: float, x2: float, y2: float, cls: str = "ref", width: float | None = None) -> None:
        """A line; ``width`` (metres) draws it as a bar of that thickness, to scale."""
        (a, b), (c, d) = self.at(x1, y1), self.at(x2, y2)
        px = max(width * self.k, 0.8) if width else 1.0
        self._draw(line_element(cls, a, b, c, d, f' style="stroke-width:{px:.2f}"' if width else ""), cls,
                   Bar(a, b, c, d, px / 2))

    def sector(self, r_in: float, r_out: float, start: float, stop: float, cls: str = "part") -> None:
        """Annular sector about the origin between angles start..stop (rad, counter-clockwise from +x)."""
        def point(r, a):
            px, py = self.at(r * math.cos(a), r * math.sin(a))
            return f"{px:.2f},{py:.2f}"
        large = 1 if stop - start > math.pi else 0
        ro, ri = r_out * self.k, r_in * self.k
        steps = [start + (stop - start) * i / 24 for i in range(25)]
        outline = [self.at(r_out * math.cos(a), r_out * math.sin(a)) for a in steps]
        outline += [self.at(r_in * math.cos(a), r_in * math.sin(a)) for a in reversed(steps)]
        self._draw(f'<path class="{cls}" d="M{point(r_in, start)} L{point(r_out, start)} '
                   f'A{ro:.2f},{ro:.2f} 0 {large} 0 {point(r_out, stop)} L{point(r_in, stop)} '
                   f'A{ri:.2f},{ri:.2f} 0 {large} 1 {point(r_in, start)} Z"/>', cls, Polygon(tuple(outline)))

    def spring(self, p1, p2, half_width: float, turns: int = 6) -> None:
        """A coil spring from model point ``p1`` to ``p2`` drawn as a zigzag ``half_width`` (metres) wide."""
        (a, b), (c, d) = self.at(*p1), self.at(*p2)
        length = math.hypot(c - a, d - b) or 1.0
        nx, ny = -(d - b) / length * half_width * self.k, (c - a) / length * half_width * self.k
        points = [(a, b)] + [(a + (c - a) * (i + 0.5) / (2 * turns) + (-1) ** i * nx,
                              b + (d - b) * (i + 0.5) / (2 * turns) + (-1) ** i * ny) for i in range(2 * turns)]
        points.append((c, d))
        self.items.append(f'<polyline class="spring" points="{" ".join(f"{x:.2f},{y:.2f}" for x, y in points)}"/>')
        self.parts += [Bar(x1, y1, x2, y2, 0.6) for (x1, y1), (x2, y2) in zip(points, points[1:])]

    def dimension(self, p1, p2, label: str, optimised: bool = False, offset: float = 0.0) -> None:
        """A dimension between model points p1 and p2, drawn ``offset`` px to the left of p1 -> p2 (screen), with
        extension lines; ``optimised`` draws it red and bold. Its label goes beside it, on the offset's side first."""
        (a, b), (c, d) = self.at(*p1), self.at(*p2)
        length = math.hypot(c - a, d - b) or 1.0
        ux, uy = (c - a) / length, (d - b) / length
        nx, ny = uy * offset, -ux * offset  # screen normal, left of the direction
        owner = next(OWNERS)
        if offset:
            for x, y in ((a, b), (c, d)):
                self._draw(line_element("ext", x, y, x + nx * 1.1, y + ny * 1.1), "ext",
                           Bar(x, y, x + nx * 1.1, y + ny * 1.1, 0.5), owner)
        opt = " opt" if optimised else ""
        marker = "url(#arrow-opt)" if optimised else "url(#arrow)"
        a, b, c, d = a + nx, b + ny, c + nx, d + ny
        self._draw(line_element(f"dim{opt}", a, b, c, d, f' marker-start="{marker}" marker-end="{marker}"'),
                   "dim", Bar(a, b, c, d, 3.0), owner)
        side = (uy, -ux)  # left of p1 -> p2: the offset's side when it is positive
        if offset < 0 or (offset == 0 and (side[1] > 1e-9 or (abs(side[1]) <= 1e-9 and side[0] < 0))):
            side = (-uy, ux)  # no offset: above the line, or right of an upright one
        sides = (side, (-side[0], -side[1]))
        cls = dimtext(optimised)
        spots = [beside(label, cls, a + (c - a) * t, b + (d - b) * t, sx, sy) for sx, sy in sides for t in ALONG]
        spots += [beside(label, cls, c, d, ux, uy), beside(label, cls, a, b, -ux, -uy)]
        self.labels.append(Label(label, cls, spots, ((a + c) / 2, (b + d) / 2), owner))

    def angle(self, centre, radius: float, start: float, stop: float, label: str, optimised: bool = False,
              extend_from: float | None = None) -> None:
        """An angle dimension: an arc of ``radius`` px about a model point from ``start`` to ``stop`` (rad), with
        extension lines along both sides from ``extend_from`` px out, if given."""
        cx, cy = self.at(*centre)

        def point(a, r=radius):
            return cx + r * math.cos(a), cy - r * math.sin(a)
        (x1, y1), (x2, y2) = point(start), point(stop)
        sweep = 0 if stop > start else 1
        opt = " opt" if optimised else ""
        marker = "url(#arrow-opt)" if optimised else "url(#arrow)"
        owner = next(OWNERS)
        if extend_from is not None:
            for a in (start, stop):
                (ex1, ey1), (ex2, ey2) = point(a, extend_from), point(a, radius + 4)
                self._draw(line_element("ext", ex1, ey1, ex2, ey2), "ext", Bar(ex1, ey1, ex2, ey2, 0.5), owner)
        arc = [point(start + (stop - start) * i / 12) for i in range(13)]
        self.items.append(f'<path class="dim{opt}" d="M{x1:.2f},{y1:.2f} A{radius:.2f},{radius:.2f} 0 0 {sweep} '
                          f'{x2:.2f},{y2:.2f}" marker-start="{marker}" marker-end="{marker}"/>')
        self.lines += [(owner, Bar(p[0], p[1], q[0], q[1], 3.0)) for p, q in zip(arc, arc[1:])]
        cls = dimtext(optimised)
        spots = []
        for t in ALONG:
            a = start + (stop - start) * t
            x, y = point(a)
            spots += [beside(label, cls, x, y, math.cos(a), -math.sin(a)),
                      beside(label, cls, x, y, -math.cos(a), math.sin(a))]
        self.labels.append(Label(label, cls, spots, point((start + stop) / 2), owner))

    def label(self, x: float, y: float, text: str, toward: float = 0.0, optimised: bool = False) -> None:
        """A label next to model point (x, y): in the direction ``toward`` (rad, screen angle counter-clockwise from
        +x) first, then round the point."""
        px, py = self.at(x, y)
        cls = dimtext(optimised)
        turns = [0.0] + [sign * math.pi / 4 * i for i in range(1, 4) for sign in (1, -1)] + [math.pi]
        spots = [beside(text, cls, px, py, math.cos(toward + a), -math.sin(toward + a)) for a in turns]
        self.labels.append(Label(text, cls, spots, (px, py)))

    def note(self, text: str, chosen: bool = False) -> None:
        """A line of text in the rows below the view (red and bold where ``chosen``)."""
        self.notes.append((text, dimtext(chosen)))

    def envelope(self) -> Box:
        return union(shape.box() for shape in self.parts + [s for _, s in self.lines])


def document(views: list[View], notes: tuple[str, ...] = ()) -> str:
    """The SVG of the views with every label placed (dimension labels, then the notes in rows below each view,
    then each title above it), the legend of the dimension colours and ``notes`` at the bottom."""
    obstacles = Obstacles([s for v in views for s in v.parts], [line for v in views for line in v.lines])
    texts = []
    for view in views:
        drawing = view.envelope()
        for label in view.labels:
            place(label, obstacles, drawing)
            texts.append(label)
    for view in views:
        drawn = union([view.envelope()] + [label.box() for label in view.labels])
        for text, cls in view.notes:
            texts.append(_placed(Label(text, cls, column(drawn[0], drawn[3] + ROW, ROW, "start")), obstacles))
        centre = (view.envelope()[0] + view.envelope()[2]) / 2
        texts.append(_placed(Label(view.title, "title", column(centre, view.envelope()[1] - 2 * CLEAR - 4, -ROW,
                                                                "middle")), obstacles))
    content = union([v.envelope() for v in views] + [label.box() for label in texts])
    legend = [(line, "note", Spot(content[0], content[3] + ROW * (i + 1.2), "start"))
              for i, line in enumerate((LEGEND, *notes))]
    written = [(t.text, t.cls, t.placed) for t in texts] + legend
    content = union([content] + [box_of(*text) for text in legend])
    left, top = content[0] - MARGIN, content[1] - MARGIN
    width, height = content[2] - left + MARGIN, content[3] - top + MARGIN
    leaders = "".join(line_element("leader", b.x1, b.y1, b.x2, b.y2) for b in (t.leader for t in texts) if b)
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height:.0f}" '
            f'viewBox="{left:.1f} {top:.1f} {width:.1f} {height:.1f}" role="img" aria-label="dimensioned sketch">'
            + STYLE + DEFS + "".join("<g>" + "".join(view.items) + "</g>" for view in views) + leaders
            + "".join(text_element(*text) for text in written) + "</svg>")


def _placed(label: Label, obstacles: Obstacles) -> Label:
    place(label, obstacles, box_of(label.text, label.cls, label.spots[0]))
    return label
