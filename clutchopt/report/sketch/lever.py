"""The lever coupling: a half section through the axis (the paper's figure a), one toggle with new linings.

The shaft and the spring flange, the weight (a steel cube of the optimal mass) at R_0 on its return spring, the two
links of length l_2 at gamma_0 to the axis, their pins on the pressure discs at d_cp / 2, the linings (width b,
thickness delta) against the faces of the driven housing (outer diameter D). The discs' thickness is not sized
by the model; they are drawn 2 delta thick."""

from __future__ import annotations

import math

from clutchopt.report.sketch.svg import View, deg, document, mm

WIDTH, HEIGHT = 560.0, 330.0  # px the section fits in


def lever_sketch(values: dict[str, float], outputs: dict[str, float], optimised: set[str],
                 effects: tuple[str, ...] = ()) -> str:
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
    k = min(WIDTH / (2 * half_width), HEIGHT / (outer / 2))
    view = View("Half section through the axis, new linings (to scale)", WIDTH / 2, HEIGHT, k)
    view.line(-half_width - 8 / k, 0, half_width + 8 / k, 0, "axis")
    view.rect(-half_width, 0, half_width, d_b / 2, "dark")  # shafts
    view.rect(-t_f / 2, d_b / 2, t_f / 2, d_phi / 2)  # spring flange
    view.spring((0, d_phi / 2), (0, r_0 - cube / 2), cube / 3)
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
    view.dimension((0, r_0), (x_pin, d_cp / 2), f"l_2 = {mm(l_2)}", opt("lever_length"), offset=16)
    view.angle((0, r_0), 90, 0, gamma_0, f"gamma_0 = {deg(gamma_0)}", opt("engagement_angle"), extend_from=cube / 2 * k)
    view.dimension((-half_width, 0), (-half_width, d_cp / 2), f"d_cp/2 = {mm(d_cp / 2)}", geometry, offset=14)
    view.dimension((-cube, 0), (-cube, r_0), f"R_0 = {mm(r_0)}", opt("flange_diameter"))
    view.dimension((half_width, d_cp / 2 - b / 2), (half_width, d_cp / 2 + b / 2), f"b = {mm(b)}",
                   opt("lining_width"), offset=-14)
    view.dimension((half_width, 0), (half_width, outer / 2), f"D = {mm(outer)}", geometry or opt("lining_width"),
                   offset=-62)
    view.dimension((half_width, outer / 2 - s), (half_width, outer / 2), f"s = {mm(s)}", offset=-38)
    view.dimension((t_f / 2, 0), (t_f / 2, d_phi / 2), f"d_phi/2 = {mm(d_phi / 2)}", opt("flange_diameter"))

    view.note(f"z = {z} toggles round the axis; weight m = {values['weight_mass']:.4g} kg (a {mm(cube)} cube)",
              opt("weight_count") or opt("weight_mass"))
    view.note(f"links d_l = {mm(d_l)}, pins {mm(outputs['pin_diameter'])}", opt("link_diameter"))
    view.note(f"worn linings: gamma_pr = {deg(gamma_pr)}, toggle span 2 l_2 cos gamma_pr = "
              f"{mm(2 * l_2 * math.cos(gamma_pr))}", opt("limit_angle"))
    spring = f"return spring: free length l_pr = {mm(values['spring_free_length'])}"
    if "spring_preload" in effects:
        spring += f", preload F_s = {values['spring_preload']:.4g} N"
    view.note(spring, opt("spring_preload"))
    return document([view], (f"lining thickness delta = {mm(delta)}; discs drawn 2 delta thick (not sized by the "
                             "model)",))
