"""Dimensioned SVG sketches of optimal designs, drawn to scale; one function per coupling that has one.

The wedge: a front view (z annular-sector weights between r2 - h_r and r2 on radial fingers, the flank radii
r1 and r2, the sector angle gamma) and a section through one weight (axial width b, the trapezoidal top
narrowing at the flank angle alpha between r1 and r2).
"""

from __future__ import annotations

import math
from html import escape

SIZE = 220  # half-width of the front view, px
TOP = 30  # room for the view titles, px

_STYLE = ("<style>.part{fill:#cfd8e3;stroke:#2b3a4a;stroke-width:1.2}.pin{fill:#8a99a8;stroke:#2b3a4a}"
          ".ref{fill:none;stroke:#6b7785;stroke-dasharray:5 4}.dim{stroke:#b03a2e;stroke-width:1;fill:none}"
          ".dimtext{fill:#b03a2e;font:12px sans-serif}.title{font:bold 13px sans-serif;fill:#2b3a4a}</style>")


def _mm(value: float) -> str:
    return f"{value * 1e3:.4g} mm"


def _arrow_defs() -> str:
    return ('<defs><marker id="arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" '
            'orient="auto-start-reverse"><path d="M0,0 L10,5 L0,10 z" fill="#b03a2e"/></marker></defs>')


def _dimension(x1, y1, x2, y2, text, dx=0.0, dy=-6.0) -> str:
    return (f'<line class="dim" x1="{x1:.1f}" y1="{y1:.1f}" x2="{x2:.1f}" y2="{y2:.1f}" '
            f'marker-start="url(#arrow)" marker-end="url(#arrow)"/>'
            f'<text class="dimtext" x="{(x1 + x2) / 2 + dx:.1f}" y="{(y1 + y2) / 2 + dy:.1f}" '
            f'text-anchor="middle">{escape(text)}</text>')


def _sector(cx, cy, r_in, r_out, start, stop) -> str:
    """Annular sector between angles start..stop (rad, counter-clockwise from +x), SVG y downwards."""
    def point(r, a):
        return f"{cx + r * math.cos(a):.2f},{cy - r * math.sin(a):.2f}"
    large = 1 if stop - start > math.pi else 0
    return (f'<path class="part" d="M{point(r_in, start)} L{point(r_out, start)} '
            f'A{r_out:.2f},{r_out:.2f} 0 {large} 0 {point(r_out, stop)} L{point(r_in, stop)} '
            f'A{r_in:.2f},{r_in:.2f} 0 {large} 1 {point(r_in, start)} Z"/>')


def wedge_sketch(values: dict[str, float]) -> str:
    """Front view and weight section of a wedge coupling; ``values`` are SI case values and design merged."""
    r1, lam = values["flank_inner_radius"], values["radius_ratio"]
    r2, h_r = lam * r1, values["weight_height"]
    gamma, z, d_n = values["sector_angle"], int(round(values["weight_count"])), values["finger_diameter"]
    alpha, b = values["flank_angle"], values.get("weight_width")
    r_in = max(r2 - h_r, 0.0)
    k = (SIZE - 50) / r2  # px per metre
    cx, cy = SIZE, SIZE + TOP
    parts = [f'<circle class="ref" cx="{cx}" cy="{cy}" r="{r1 * k:.2f}"/>',
             f'<circle class="ref" cx="{cx}" cy="{cy}" r="{r2 * k:.2f}"/>']
    hub = values.get("hub_radius") or 0.3 * r_in
    for i in range(z):
        middle = math.pi / 2 + 2 * math.pi * i / z
        parts.append(_sector(cx, cy, r_in * k, r2 * k, middle - gamma / 2, middle + gamma / 2))
        c, s = math.cos(middle), math.sin(middle)
        half = d_n * k / 2
        inner, outer = min(hub, r_in) * k, (r_in + h_r / 2) * k
        corners = [(inner, -half), (outer, -half), (outer, half), (inner, half)]
        points = " ".join(f"{cx + r * c - t * s:.2f},{cy - r * s - t * c:.2f}" for r, t in corners)
        parts.append(f'<polygon class="pin" points="{points}"/>')
    first = math.pi / 2
    parts.append(_dimension(cx, cy, cx + r2 * k * math.cos(-0.35), cy - r2 * k * math.sin(-0.35),
                            f"r2 = {_mm(r2)}", dy=18))
    parts.append(_dimension(cx, cy, cx - r1 * k * math.cos(0.35), cy + r1 * k * math.sin(0.35),
                            f"r1 = {_mm(r1)}", dy=18))
    side = cx + r2 * k * math.sin(min(gamma, math.pi) / 2) + 12
    parts.append(_dimension(side, cy - r2 * k, side, cy - r_in * k, f"h_r = {_mm(h_r)}", dx=48, dy=4))
    arc = (r2 + 0.08 * r2) * k
    a0, a1 = first - gamma / 2, first + gamma / 2
    parts.append(f'<path class="dim" d="M{cx + arc * math.cos(a0):.2f},{cy - arc * math.sin(a0):.2f} '
                 f'A{arc:.2f},{arc:.2f} 0 0 0 {cx + arc * math.cos(a1):.2f},{cy - arc * math.sin(a1):.2f}" '
                 f'marker-start="url(#arrow)" marker-end="url(#arrow)"/>')
    parts.append(f'<text class="dimtext" x="{cx}" y="{cy - arc - 6:.1f}" text-anchor="middle">'
                 f'gamma = {math.degrees(gamma):.4g} deg, z = {z}</text>')
    parts.append(f'<text class="dimtext" x="{cx}" y="{2 * SIZE + TOP - 8}" text-anchor="middle">'
                 f'finger d_n = {_mm(d_n)}</text>')
    views = [f'<g><text class="title" x="{cx}" y="14" text-anchor="middle">Front view (to scale)</text>'
             + "".join(parts) + "</g>"]
    width = 2 * SIZE
    if b:
        views.append(_wedge_section(width + 30, r_in, r1, r2, b, alpha, k))
        width += 30 + max(b * k, 0) + 140
    return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0f}" height="{2 * SIZE + TOP}" '
            f'viewBox="0 0 {width:.0f} {2 * SIZE + TOP}" role="img" aria-label="dimensioned sketch">'
            + _STYLE + _arrow_defs() + "".join(views) + "</svg>")


def _wedge_section(x0, r_in, r1, r2, b, alpha, k) -> str:
    """Section through one weight: axial width b below r1, the flanks narrowing at alpha up to r2."""
    base = SIZE + TOP + 0.6 * r2 * k  # y of radius r_in; radii grow upwards
    def y(r):
        return base - (r - r_in) * k
    top_half = max(b / 2 - (r2 - r1) * math.tan(alpha), 0.0)
    mid = x0 + b * k / 2
    points = [(mid - b * k / 2, y(r_in)), (mid + b * k / 2, y(r_in)), (mid + b * k / 2, y(r1)),
              (mid + top_half * k, y(r2)), (mid - top_half * k, y(r2)), (mid - b * k / 2, y(r1))]
    outline = " ".join(f"{px:.2f},{py:.2f}" for px, py in points)
    parts = [f'<text class="title" x="{mid:.1f}" y="{y(r2) - 40:.1f}" text-anchor="middle">Section of a weight</text>',
             f'<polygon class="part" points="{outline}"/>',
             _dimension(mid - b * k / 2, y(r_in) + 16, mid + b * k / 2, y(r_in) + 16, f"b = {_mm(b)}", dy=16),
             _dimension(mid + b * k / 2 + 14, y(r_in), mid + b * k / 2 + 14, y(r2), f"h_r = {_mm(r2 - r_in)}",
                        dx=52, dy=4),
             f'<text class="dimtext" x="{mid:.1f}" y="{y(r2) - 8:.1f}" text-anchor="middle">'
             f'flank angle alpha = {math.degrees(alpha):.4g} deg</text>',
             f'<line class="ref" x1="{mid - b * k / 2 - 10:.1f}" y1="{y(r1):.1f}" x2="{mid + b * k / 2 + 10:.1f}" '
             f'y2="{y(r1):.1f}"/>',
             f'<text class="dimtext" x="{mid - b * k / 2 - 12:.1f}" y="{y(r1) + 4:.1f}" text-anchor="end">r1</text>']
    return "<g>" + "".join(parts) + "</g>"


SKETCHES = {"wedge": wedge_sketch}


def sketch(coupling: str, values: dict[str, float]) -> str | None:
    """The SVG of a coupling that has a sketch, else None (the report shows a dimension table instead)."""
    draw = SKETCHES.get(coupling)
    if draw is None:
        return None
    try:
        return draw(values)
    except (KeyError, TypeError, ValueError):  # a mode without the full geometry (e.g. no width given)
        return None
