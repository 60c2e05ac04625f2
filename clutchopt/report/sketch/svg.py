"""What every sketch is drawn with: views to scale (model metres to px), parts, reference lines and dimensions.

A dimension of a variable the optimiser chose is drawn red and bold, one the case gives grey, so a reader sees
at a glance what the optimum changed. Coordinates of a view are model metres, x to the right and y up.
"""

from __future__ import annotations

import math
from html import escape

STYLE = ("<style>.part{fill:#cfd8e3;stroke:#2b3a4a;stroke-width:1.2}.dark{fill:#8a99a8;stroke:#2b3a4a}"
         ".lining{fill:#c9a36a;stroke:#5a4320}.ball{fill:#e3e7eb;stroke:#2b3a4a;stroke-width:0.8}"
         ".layer{fill:#eef1f4;stroke:none}.void{fill:#fff;stroke:#2b3a4a;stroke-width:1.2}"
         ".ref{fill:none;stroke:#6b7785;stroke-dasharray:5 4}.axis{stroke:#6b7785;stroke-dasharray:12 3 2 3}"
         ".line{stroke:#2b3a4a;stroke-width:1.2;fill:none}"
         ".dim{stroke:#6b7785;stroke-width:1;fill:none}.dim.opt{stroke:#b03a2e}"
         ".ext{stroke:#9aa5b1;stroke-width:0.6}.dimtext{fill:#4a5562;font:12px sans-serif;paint-order:stroke;"
         "stroke:#fff;stroke-width:3px;stroke-linejoin:round}"
         ".dimtext.opt{fill:#b03a2e;font-weight:bold}.title{font:bold 13px sans-serif;fill:#2b3a4a}"
         ".note{font:11px sans-serif;fill:#55606b}</style>")
DEFS = ('<defs>' + "".join(
    f'<marker id="arrow{suffix}" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" '
    f'orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="{colour}"/></marker>'
    for suffix, colour in (("", "#6b7785"), ("-opt", "#b03a2e"))) + "</defs>")
LEGEND = "red, bold: chosen by the optimiser; grey: given by the case"


def mm(value: float) -> str:
    return f"{value * 1e3:.4g} mm"


def deg(value: float) -> str:
    return f"{math.degrees(value):.4g} deg"


class View:
    """One view: ``scale`` px per metre, the model origin at (``x0``, ``y0``) px, a title above ``top`` px."""

    def __init__(self, title: str, x0: float, y0: float, scale: float, top: float = 18.0):
        self.x0, self.y0, self.k = x0, y0, scale
        self.items = [f'<text class="title" x="{x0:.1f}" y="{top:.1f}" text-anchor="middle">{escape(title)}</text>']

    def at(self, x: float, y: float) -> tuple[float, float]:
        return self.x0 + x * self.k, self.y0 - y * self.k

    def _points(self, points) -> str:
        return " ".join(f"{px:.2f},{py:.2f}" for px, py in (self.at(x, y) for x, y in points))

    def polygon(self, points, cls: str = "part") -> None:
        self.items.append(f'<polygon class="{cls}" points="{self._points(points)}"/>')

    def rect(self, x1: float, y1: float, x2: float, y2: float, cls: str = "part") -> None:
        self.polygon([(x1, y1), (x2, y1), (x2, y2), (x1, y2)], cls)

    def circle(self, x: float, y: float, r: float, cls: str = "part") -> None:
        cx, cy = self.at(x, y)
        self.items.append(f'<circle class="{cls}" cx="{cx:.2f}" cy="{cy:.2f}" r="{max(r * self.k, 0.4):.2f}"/>')

    def line(self, x1: float, y1: float, x2: float, y2: float, cls: str = "line", width: float | None = None) -> None:
        """A line; ``width`` (metres) draws it as a bar of that thickness, to scale."""
        (a, b), (c, d) = self.at(x1, y1), self.at(x2, y2)
        stroke = f' style="stroke-width:{max(width * self.k, 0.8):.2f}"' if width else ""
        self.items.append(f'<line class="{cls}" x1="{a:.2f}" y1="{b:.2f}" x2="{c:.2f}" y2="{d:.2f}"{stroke}/>')

    def sector(self, r_in: float, r_out: float, start: float, stop: float, cls: str = "part") -> None:
        """Annular sector about the origin between angles start..stop (rad, counter-clockwise from +x)."""
        def point(r, a):
            px, py = self.at(r * math.cos(a), r * math.sin(a))
            return f"{px:.2f},{py:.2f}"
        large = 1 if stop - start > math.pi else 0
        ro, ri = r_out * self.k, r_in * self.k
        self.items.append(f'<path class="{cls}" d="M{point(r_in, start)} L{point(r_out, start)} '
                          f'A{ro:.2f},{ro:.2f} 0 {large} 0 {point(r_out, stop)} L{point(r_in, stop)} '
                          f'A{ri:.2f},{ri:.2f} 0 {large} 1 {point(r_in, start)} Z"/>')

    def text(self, x: float, y: float, text: str, cls: str = "dimtext", anchor: str = "middle", dy: float = 0.0,
             dx: float = 0.0) -> None:
        px, py = self.at(x, y)
        self.items.append(f'<text class="{cls}" x="{px + dx:.1f}" y="{py + dy:.1f}" text-anchor="{anchor}">'
                          f"{escape(text)}</text>")

    def dimension(self, p1, p2, label: str, optimised: bool = False, offset: float = 0.0, text_dx: float = 0.0,
                  text_dy: float = -5.0, anchor: str = "middle") -> None:
        """A dimension between model points p1 and p2, drawn ``offset`` px to the left of p1 -> p2 (screen), with
        extension lines; ``optimised`` draws it red and bold."""
        (a, b), (c, d) = self.at(*p1), self.at(*p2)
        length = math.hypot(c - a, d - b) or 1.0
        nx, ny = (d - b) / length * offset, -(c - a) / length * offset  # screen normal, left of the direction
        if offset:
            for x, y in ((a, b), (c, d)):
                self.items.append(f'<line class="ext" x1="{x:.2f}" y1="{y:.2f}" x2="{x + nx * 1.1:.2f}" '
                                  f'y2="{y + ny * 1.1:.2f}"/>')
        opt = " opt" if optimised else ""
        marker = "url(#arrow-opt)" if optimised else "url(#arrow)"
        self.items.append(f'<line class="dim{opt}" x1="{a + nx:.2f}" y1="{b + ny:.2f}" x2="{c + nx:.2f}" '
                          f'y2="{d + ny:.2f}" marker-start="{marker}" marker-end="{marker}"/>')
        self.items.append(f'<text class="dimtext{opt}" x="{(a + c) / 2 + nx + text_dx:.1f}" '
                          f'y="{(b + d) / 2 + ny + text_dy:.1f}" text-anchor="{anchor}">{escape(label)}</text>')

    def angle(self, centre, radius: float, start: float, stop: float, label: str, optimised: bool = False,
              text_dx: float = 0.0, text_dy: float = 0.0, anchor: str = "start") -> None:
        """An angle dimension: an arc of ``radius`` px about a model point from ``start`` to ``stop`` (rad)."""
        cx, cy = self.at(*centre)
        def point(a):
            return cx + radius * math.cos(a), cy - radius * math.sin(a)
        (x1, y1), (x2, y2) = point(start), point(stop)
        sweep = 0 if stop > start else 1
        opt = " opt" if optimised else ""
        marker = "url(#arrow-opt)" if optimised else "url(#arrow)"
        self.items.append(f'<path class="dim{opt}" d="M{x1:.2f},{y1:.2f} A{radius:.2f},{radius:.2f} 0 0 {sweep} '
                          f'{x2:.2f},{y2:.2f}" marker-start="{marker}" marker-end="{marker}"/>')
        mx, my = point((start + stop) / 2)
        self.items.append(f'<text class="dimtext{opt}" x="{mx + text_dx:.1f}" y="{my + text_dy:.1f}" '
                          f'text-anchor="{anchor}">{escape(label)}</text>')

    def svg(self) -> str:
        return "<g>" + "".join(self.items) + "</g>"


def document(views: list[View], width: float, height: float, notes: tuple[str, ...] = ()) -> str:
    """The SVG of the views, with the legend of the dimension colours and notes at the bottom."""
    lines = [LEGEND, *notes]
    legend = "".join(f'<text class="note" x="8" y="{height - 8 - 14 * (len(lines) - 1 - i):.0f}">{escape(line)}</text>'
                     for i, line in enumerate(lines))
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{height:.0f}" '
            f'viewBox="0 0 {width:.0f} {height:.0f}" role="img" aria-label="dimensioned sketch">'
            + STYLE + DEFS + "".join(view.svg() for view in views) + legend + "</svg>")
