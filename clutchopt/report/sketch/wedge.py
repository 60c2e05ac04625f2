"""The wedge coupling: a front view (z annular-sector weights between r2 - h_r and r2 on radial fingers, the flank
radii r1 and r2, the sector angle gamma) and a section through one weight (axial width b, the trapezoidal top
narrowing at the flank angle alpha between r1 and r2), both to one scale."""

from __future__ import annotations

import math

from clutchopt.report.sketch.svg import View, deg, document, mm

SIZE = 220  # half-width of the front view, px
TOP = 30  # room for the view titles, px


def wedge_sketch(values: dict[str, float], outputs: dict[str, float], optimised: set[str]) -> str:
    """``values``: SI case values and design merged; ``optimised``: the variables the optimiser chose."""
    r1, lam = values["flank_inner_radius"], values["radius_ratio"]
    r2, h_r = lam * r1, values["weight_height"]
    gamma, z, d_n = values["sector_angle"], int(round(values["weight_count"])), values["finger_diameter"]
    alpha, b = values["flank_angle"], values.get("weight_width")  # paper mode: only if the case gives one
    r_in = max(r2 - h_r, 0.0)
    opt = optimised.__contains__
    front = View("Front view", SIZE, SIZE + TOP, (SIZE - 50) / r2, top=14)
    front.circle(0, 0, r1, "ref")
    front.circle(0, 0, r2, "ref")
    hub = min(values.get("hub_radius") or 0.3 * r_in, r_in)
    for i in range(z):
        middle = math.pi / 2 + 2 * math.pi * i / z
        front.sector(r_in, r2, middle - gamma / 2, middle + gamma / 2)
        c, s = math.cos(middle), math.sin(middle)
        front.line(hub * c, hub * s, (r_in + h_r / 2) * c, (r_in + h_r / 2) * s, "dark", width=d_n)
    front.dimension((0, 0), (r2 * math.cos(-0.35), r2 * math.sin(-0.35)), f"r2 = {mm(r2)}",
                    opt("flank_inner_radius") or opt("radius_ratio"), text_dy=18)
    front.dimension((0, 0), (-r1 * math.cos(0.35), -r1 * math.sin(0.35)), f"r1 = {mm(r1)}", opt("flank_inner_radius"),
                    text_dy=18)
    side = r2 * math.sin(min(gamma, math.pi) / 2)
    front.dimension((side, r2), (side, r_in), f"h_r = {mm(h_r)}", opt("weight_height"), offset=14, text_dx=8,
                    text_dy=4, anchor="start")
    front.angle((0, 0), 1.08 * r2 * front.k, math.pi / 2 - gamma / 2, math.pi / 2 + gamma / 2,
                f"gamma = {deg(gamma)}", opt("sector_angle"), text_dy=-8, anchor="middle")
    front.text(0, -r2, f"z = {z}", "dimtext opt" if opt("weight_count") else "dimtext", dy=26)
    front.text(0, -r2, f"finger d_n = {mm(d_n)}", "dimtext opt" if opt("finger_diameter") else "dimtext", dy=42)
    if not b:
        return document([front], 2 * SIZE, 2 * SIZE + TOP + 40)
    section = _section(2 * SIZE + 30, r_in, r1, r2, b, alpha, front.k, opt)
    return document([front, section], 2 * SIZE + 30 + b * front.k + 150, 2 * SIZE + TOP + 40)


def _section(x0: float, r_in: float, r1: float, r2: float, b: float, alpha: float, k: float, opt) -> View:
    """Section through one weight: axial width b below r1, the flanks narrowing at alpha up to r2."""
    view = View("Section of a weight", x0 + b * k / 2, SIZE + TOP + 0.6 * r2 * k + r_in * k, k,
                top=SIZE + TOP + 0.6 * r2 * k - (r2 - r_in) * k - 40)
    top_half = max(b / 2 - (r2 - r1) * math.tan(alpha), 0.0)
    view.polygon([(-b / 2, r_in), (b / 2, r_in), (b / 2, r1), (top_half, r2), (-top_half, r2), (-b / 2, r1)])
    view.dimension((-b / 2, r_in), (b / 2, r_in), f"b = {mm(b)}", opt("weight_width"), offset=-16, text_dy=16)
    view.dimension((b / 2, r2), (b / 2, r_in), f"h_r = {mm(r2 - r_in)}", opt("weight_height"), offset=14,
                   text_dx=8, text_dy=4, anchor="start")
    view.line(-b / 2 - 10 / k, r1, b / 2 + 10 / k, r1, "ref")
    view.text(-b / 2, r1, "r1", anchor="end", dx=-12, dy=4)
    view.text(0, r2, f"flank angle alpha = {deg(alpha)}", "dimtext opt" if opt("flank_angle") else "dimtext", dy=-8)
    return view
