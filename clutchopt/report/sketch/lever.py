"""The lever coupling: a half section through the axis (the paper's figure a), one toggle with new linings.

The shaft and the spring flange, the weight (a steel cube of the optimal mass) at R_0 on its return spring, the two
links of length l_2 at gamma_0 to the axis, their pins on the pressure discs at d_cp / 2, the linings (width b,
thickness delta) against the faces of the driven housing (outer diameter D). The discs' thickness is not sized
by the model; they are drawn 2 delta thick."""

from __future__ import annotations

import math

from clutchopt.report.sketch.svg import View, deg, document, mm

WIDTH, HEIGHT = 720.0, 330.0  # drawing area of the section, px
LEFT, RIGHT = 150.0, 170.0  # room for the dimension labels on either side, px


def lever_sketch(values: dict[str, float], outputs: dict[str, float], optimised: set[str]) -> str:
    opt = optimised.__contains__
    d_b, d_phi, t_f = values["shaft_diameter"], values["flange_diameter"], values["flange_thickness"]
    l_2, gamma_0, gamma_pr = outputs["lever_length"], values["engagement_angle"], values["limit_angle"]
    r_0, d_cp, b = outputs["start_radius"], outputs["mean_diameter"], outputs["lining_width"]
    delta, s, outer = values["lining_thickness"], values["shell_thickness"], outputs["outer_diameter"]
    d_l, z = values["link_diameter"], int(round(values["weight_count"]))
    cube = (values["weight_mass"] / values["density"]) ** (1 / 3)
    x_pin, disc = l_2 * math.cos(gamma_0), max(2 * delta, 2 * d_l)
    x_face = x_pin + disc + delta  # the housing's inner faces
    half_width = x_face + s
    k = min((WIDTH - LEFT - RIGHT) / (2 * half_width), (HEIGHT - 60) / (outer / 2))
    axis = 44 + outer / 2 * k  # px from the top
    view = View("Half section through the axis, new linings (to scale)", LEFT + (WIDTH - LEFT - RIGHT) / 2, axis, k)
    view.line(-half_width - 8 / k, 0, half_width + 8 / k, 0, "axis")
    view.rect(-half_width, 0, half_width, d_b / 2, "dark")  # shafts
    view.rect(-t_f / 2, d_b / 2, t_f / 2, d_phi / 2)  # spring flange
    _spring(view, d_phi / 2, r_0 - cube / 2, cube / 3)
    for side in (-1, 1):
        view.line(0, r_0, side * x_pin, d_cp / 2, "dark", width=d_l)  # a link
        inner = side * x_pin, side * (x_pin + disc)
        view.rect(min(inner), d_b / 2, max(inner), d_cp / 2 + b / 2)  # pressure disc
        face = side * (x_pin + disc), side * x_face
        view.rect(min(face), d_cp / 2 - b / 2, max(face), d_cp / 2 + b / 2, "lining")
        wall = side * x_face, side * half_width
        view.rect(min(wall), d_cp / 2 - b / 2 - s, max(wall), outer / 2)  # housing face
        view.circle(side * x_pin, d_cp / 2, d_l / 2, "dark")
    view.rect(-half_width, outer / 2 - s, half_width, outer / 2)  # housing shell
    view.rect(-cube / 2, r_0 - cube / 2, cube / 2, r_0 + cube / 2, "dark")  # the weight at the knee

    geometry = opt("lever_length") or opt("engagement_angle") or opt("flange_diameter")
    view.dimension((0, r_0), (x_pin, d_cp / 2), f"l_2 = {mm(l_2)}", opt("lever_length"), offset=16, text_dy=-6)
    view.angle((0, r_0), 46, 0, gamma_0, f"gamma_0 = {deg(gamma_0)}", opt("engagement_angle"), text_dx=6,
               text_dy=14)
    view.dimension((-half_width, 0), (-half_width, d_cp / 2), f"d_cp/2 = {mm(d_cp / 2)}", geometry, offset=14,
                   text_dx=-6, anchor="end")
    view.dimension((-cube, 0), (-cube, r_0), f"R_0 = {mm(r_0)}", opt("flange_diameter"), offset=0, text_dx=-4,
                   text_dy=-4, anchor="end")
    view.dimension((half_width, d_cp / 2 - b / 2), (half_width, d_cp / 2 + b / 2), f"b = {mm(b)}",
                   opt("lining_width"), offset=-14, text_dx=6, anchor="start")
    view.dimension((half_width, 0), (half_width, outer / 2), f"D = {mm(outer)}", geometry or opt("lining_width"),
                   offset=-62, text_dx=6, anchor="start")
    view.dimension((t_f / 2, 0), (t_f / 2, d_phi / 2), f"d_phi/2 = {mm(d_phi / 2)}", opt("flange_diameter"),
                   offset=-6, text_dx=6, text_dy=10, anchor="start")

    def note(y: float, text: str, chosen: bool) -> None:
        view.text(-half_width, 0, text, "dimtext opt" if chosen else "dimtext", anchor="start", dy=y)

    note(18, f"z = {z} toggles round the axis; weight m = {values['weight_mass']:.4g} kg (a {mm(cube)} cube)",
         opt("weight_count") or opt("weight_mass"))
    note(32, f"links d_l = {mm(d_l)}, pins {mm(outputs['pin_diameter'])}", opt("link_diameter"))
    note(46, f"worn linings: gamma_pr = {deg(gamma_pr)}, toggle span 2 l_2 cos gamma_pr = "
             f"{mm(2 * l_2 * math.cos(gamma_pr))}", opt("limit_angle"))
    return document([view], WIDTH, axis + 96,
                    (f"lining thickness delta = {mm(delta)}; discs drawn 2 delta thick (not sized by the model)",))


def _spring(view: View, bottom: float, top: float, half_width: float, turns: int = 6) -> None:
    """A return spring drawn as a zigzag from the flange (``bottom``) to the weight (``top``), radially."""
    step = (top - bottom) / (2 * turns)
    points = [(0.0, bottom)] + [((-1) ** i * half_width, bottom + (i + 0.5) * step) for i in range(2 * turns)]
    points.append((0.0, top))
    for (x1, y1), (x2, y2) in zip(points, points[1:]):
        view.line(x1, y1, x2, y2)
