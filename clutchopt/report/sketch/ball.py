"""The ball clutch: a front view along the axis and a half section through it, both to one scale.

The drum (active radius R_a, wall s), the ball layer from R_1 = K2 R_a out to R_a, the six shovels of thickness
a_n = K1 R_a, and the balls (radius r_c): in the front view the outer ring, in the section the n_p rows across
the active width l_a. The rotor's hub is not sized by the model; it is drawn at 0.3 R_a."""

from __future__ import annotations

import math

from clutchopt.report.sketch.svg import View, document, mm

SIZE = 200.0  # half-width of the front view, px
HUB = 0.3  # rotor hub radius over R_a, as drawn


def ball_sketch(values: dict[str, float], outputs: dict[str, float], optimised: set[str]) -> str:
    opt = optimised.__contains__
    r_a, r_c, s = values["active_radius"], values["ball_radius"], values["shell_thickness"]
    r_1, width = outputs["filling_radius"], outputs["active_width"]
    shovel, shovels = values["shovel_ratio"] * r_a, int(round(values["shovel_count"]))
    k = (SIZE - 40) / (r_a + s)
    front = View("Front view along the axis", SIZE, SIZE + 30, k, top=14)
    front.circle(0, 0, r_a + s, "part")  # drum
    front.circle(0, 0, r_a, "void")
    front.circle(0, 0, r_a, "layer")
    front.circle(0, 0, r_1, "void")
    ring = max(int(math.pi * (r_a - r_c) / r_c), 1)  # balls side by side in the outer ring
    for i in range(ring):
        a = 2 * math.pi * i / ring
        front.circle((r_a - r_c) * math.cos(a), (r_a - r_c) * math.sin(a), r_c, "ball")
    for i in range(shovels):
        a = math.pi / 2 + 2 * math.pi * i / shovels
        front.line(HUB * r_a * math.cos(a), HUB * r_a * math.sin(a), 0.97 * r_a * math.cos(a),
                   0.97 * r_a * math.sin(a), "dark", width=shovel)
    front.circle(0, 0, HUB * r_a, "dark")  # rotor hub
    chosen_radius = opt("active_radius")
    front.dimension((0, 0), (r_a * math.cos(-0.5), r_a * math.sin(-0.5)), f"R_a = {mm(r_a)}", chosen_radius,
                    text_dy=16, anchor="start")
    front.dimension((0, 0), (-r_1 * math.cos(0.5), -r_1 * math.sin(0.5)), f"R_1 = K2 R_a = {mm(r_1)}",
                    chosen_radius or opt("filling"), text_dy=16, anchor="end")
    front.text(0, -(r_a + s), f"D = 2 (R_a + s) = {mm(outputs['outer_diameter'])}; {shovels} shovels, "
                              f"a_n = {mm(shovel)}", dy=22)

    section = _section(2 * SIZE + 40, r_a, r_1, r_c, s, width, k, values, opt)
    return document([front, section], 2 * SIZE + 80 + (width + 2 * s) * k + 210, 2 * SIZE + 90)


def _section(x0: float, r_a: float, r_1: float, r_c: float, s: float, width: float, k: float, values, opt) -> View:
    """Half section above the axis: drum wall and end walls, the layer, the rows of balls across l_a."""
    view = View("Half section through the axis", x0 + (width / 2 + s) * k, SIZE + 30, k, top=14)
    half = width / 2
    view.line(-half - s - 8 / k, 0, half + s + 8 / k, 0, "axis")
    view.rect(-half, r_1, half, r_a, "layer")
    view.rect(-half - s, r_a, half + s, r_a + s)  # drum shell
    for side in (-1, 1):
        view.rect(side * half, HUB * r_a, side * (half + s), r_a)  # end walls
    view.rect(-half, 0, half, HUB * r_a, "dark")  # rotor hub
    rows = int((width - 2 * r_c) / (math.sqrt(3) * r_c) + 1e-9) + 1
    for i in range(rows):
        view.circle(-half + r_c + i * math.sqrt(3) * r_c, r_a - r_c, r_c, "ball")
    rows_chosen = opt("ball_rows") or opt("ball_radius") or opt("active_width")
    view.dimension((-half, r_a + s), (half, r_a + s), f"l_a = {mm(width)}", rows_chosen, offset=14, text_dy=-4)
    view.dimension((half + s, 0), (half + s, r_1), f"R_1 = {mm(r_1)}", opt("active_radius") or opt("filling"),
                   offset=-12, text_dx=6, text_dy=4, anchor="start")
    view.dimension((half + s, 0), (half + s, r_a), f"R_a = {mm(r_a)}", opt("active_radius"), offset=-96, text_dx=6,
                   text_dy=4, anchor="start")
    chosen = "dimtext opt" if opt("ball_radius") or opt("ball_rows") else "dimtext"
    view.text(-half - s, 0, f"n_p = {rows} rows of balls r_c = {mm(r_c)}, grooves beta = "
                            f"{values['groove_conformity']:.4g} r_c", chosen, anchor="start", dy=18)
    return view
