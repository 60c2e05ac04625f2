"""The ball clutch: a front view along the axis and a half section through it, both to one scale.

The drum (active radius R_a, wall s), the ball layer from R_1 = K2 R_a out to R_a, the six shovels of thickness
a_n = K1 R_a, and the balls (radius r_c): in the front view the outer ring, in the section the n_p rows across
the active width l_a, the drum's outer diameter D. The ball clutch has no springs. The rotor's hub is not sized by the
model; it is drawn at 0.3 R_a."""

from __future__ import annotations

import math

from clutchopt.report.sketch.svg import View, document, mm

SIZE = 190.0  # px from the axis to the drum's outside in the front view
HUB = 0.3  # rotor hub radius over R_a, as drawn
GAP = 150.0  # px between the views


def ball_sketch(values: dict[str, float], outputs: dict[str, float], optimised: set[str],
                effects: tuple[str, ...] = ()) -> str:
    opt = optimised.__contains__
    r_a, r_c, s = values["active_radius"], values["ball_radius"], values["shell_thickness"]
    r_1, width = outputs["filling_radius"], outputs["active_width"]
    shovel, shovels = values["shovel_ratio"] * r_a, int(round(values["shovel_count"]))
    k = SIZE / (r_a + s)
    front = View("Front view along the axis", SIZE, SIZE, k)
    front.ring(r_a, r_a + s)  # drum
    front.ring(r_1, r_a, "layer")
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
    front.dimension((0, 0), (r_a * math.cos(-0.5), r_a * math.sin(-0.5)), f"R_a = {mm(r_a)}", chosen_radius)
    front.dimension((0, 0), (-r_1 * math.cos(0.5), -r_1 * math.sin(0.5)), f"R_1 = K2 R_a = {mm(r_1)}",
                    chosen_radius or opt("filling"))
    front.dimension((-(r_a + s), 0), (r_a + s, 0), f"D = 2 (R_a + s) = {mm(outputs['outer_diameter'])}",
                    chosen_radius, offset=-((r_a + s) * k + 18))
    front.note(f"{shovels} shovels, a_n = {mm(shovel)}; drum wall s = {mm(s)}")
    return document([front, _section(2 * SIZE + GAP, r_a, r_1, r_c, s, width, k, values, opt)])


def _section(left: float, r_a: float, r_1: float, r_c: float, s: float, width: float, k: float, values,
             opt) -> View:
    """Half section above the axis: drum wall and end walls, the layer, the rows of balls across l_a."""
    half = width / 2
    view = View("Half section through the axis", left + (half + s) * k, SIZE, k)
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
    view.dimension((-half, r_a + s), (half, r_a + s), f"l_a = {mm(width)}", rows_chosen, offset=14)
    view.dimension((half + s, 0), (half + s, r_1), f"R_1 = {mm(r_1)}", opt("active_radius") or opt("filling"),
                   offset=-14)
    view.dimension((half + s, 0), (half + s, r_a), f"R_a = {mm(r_a)}", opt("active_radius"), offset=-44)
    view.dimension((half + s, r_a), (half + s, r_a + s), f"s = {mm(s)}", offset=-14)
    view.note(f"n_p = {rows} rows of balls r_c = {mm(r_c)}, grooves beta = {values['groove_conformity']:.4g} r_c",
              opt("ball_radius") or opt("ball_rows"))
    return view
