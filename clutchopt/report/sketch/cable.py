"""The cable coupling: a front view along the axis (the paper's figure 1), to scale.

z radial cables of diameter d_k run over the free length l from their clamps in the driven half-coupling out to
the moving weights at R_rv; each passes through a finger (diameter d_n) of the driving cup on the finger circle
D. The cup's centre of mass is at R_m. The weights are drawn as steel cubes of the optimal mass; the outlines of
the half-couplings are not sized by the model and are drawn as their reference circles. The return spring and the
threads lie along the axis, out of this view: the notes give them."""

from __future__ import annotations

import math

from clutchopt.report.sketch.svg import View, deg, document, mm

SIZE = 210.0  # px from the axis to the outermost weight corner


def cable_sketch(values: dict[str, float], outputs: dict[str, float], optimised: set[str],
                 effects: tuple[str, ...] = ()) -> str:
    opt = optimised.__contains__
    z, d_n, d_1 = int(round(values["cable_count"])), values["finger_diameter"], values["screw_diameter"]
    finger_circle, r_weight, r_mass = values["finger_circle_diameter"], values["weight_radius"], values["mass_radius"]
    span, d_k = values["span"], outputs["cable_diameter"]
    cube = (values["weight_mass"] / values["density"]) ** (1 / 3)
    r_clamp = max(r_weight - span, 0.1 * r_weight)
    outer = max(r_weight + cube, finger_circle / 2 + d_n)
    view = View("Front view along the axis (to scale)", SIZE, SIZE, SIZE / outer)
    for radius in (finger_circle / 2, r_mass, r_weight):
        view.circle(0, 0, radius, "ref")
    view.circle(0, 0, r_clamp + d_1, "part")  # the driven half-coupling's clamp ring
    for i in range(z):
        a = math.pi / 2 + 2 * math.pi * i / z
        c, s = math.cos(a), math.sin(a)
        corners = [(r_weight + u * cube / 2, v * cube / 2) for u, v in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
        view.polygon([(r * c - t * s, r * s + t * c) for r, t in corners])  # its weight
        view.line(r_clamp * c, r_clamp * s, r_weight * c, r_weight * s, "dark", width=d_k)  # a cable
        view.circle(finger_circle / 2 * c, finger_circle / 2 * s, d_n / 2, "lining")  # its finger, on top
        view.circle(r_clamp * c, r_clamp * s, d_1 / 2, "part")  # its clamp screw

    between = math.pi / 2 + math.pi / z  # a direction between two cables
    view.dimension((-finger_circle / 2, 0), (finger_circle / 2, 0), f"D = {mm(finger_circle)}",
                   offset=-(outer * view.k + 16))
    view.dimension((0, 0), (r_mass * math.cos(between), r_mass * math.sin(between)), f"R_m = {mm(r_mass)}")
    view.dimension((0, 0), (r_weight * math.cos(-between), r_weight * math.sin(-between)), f"R_rv = {mm(r_weight)}")
    view.dimension((0, r_clamp), (0, r_weight), f"l = {mm(span)}", offset=-(cube * view.k / 2 + 12))

    view.note(f"z = {z} cables, fingers and weights", opt("cable_count"))
    view.note(f"fingers d_n = {mm(d_n)}; clamp screws d_1 = {mm(d_1)}", opt("finger_diameter") or opt("screw_diameter"))
    view.note(f"weights m_rv = {values['weight_mass']:.4g} kg (drawn as {mm(cube)} cubes); cup m = "
              f"{values['half_coupling_mass']:.4g} kg", opt("weight_mass") or opt("half_coupling_mass"))
    view.note(f"lead angles: hub thread beta = {deg(values['lead_angle'])}, weight threads beta_w = "
              f"{deg(values['weight_lead_angle'])}; thread flanks alpha_1 = {deg(values['flank_angle'])}",
              opt("lead_angle") or opt("weight_lead_angle"))
    view.note(f"return spring 6 on the hub thread (axial, behind the cup): c_pr = "
              f"{values['spring_stiffness'] / 1e3:.4g} kN/m, compressed x_1 = {mm(values['spring_compression'])}")
    view.note(f"cable d_k = {mm(d_k)} (eq. 17, from the case)")
    return document([view])
