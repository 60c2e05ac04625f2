"""The wedge coupling: a front view and a section of a weight in its groove.

Front view, to scale: the z annular-sector weights between r2 - h_r and r2 on radial fingers (d_n) of the hub
(r_hub), the flank radii r1 and r2, the sector angle gamma, the driven half-coupling's rim (wall s outside r2, outer
diameter D) and, where the case's start-up has spring preload, a return spring under each weight. Section, enlarged:
a weight (axial width b) whose trapezoidal top, its flanks inclined alpha to the radial direction between r1 and r2,
sits in the V-groove of the driven half-coupling. The groove's side walls are not sized by the model; they are
drawn s wide."""

from __future__ import annotations

import math

from clutchopt.report.sketch.svg import View, deg, document, mm

SIZE = 190.0  # px from the axis to the front view's outer diameter
SECTION = 230.0  # px of the section's height (enlarged)
GAP = 150.0  # px between the views
ARC = 36.0  # px: the flank angle's arc at least this long (its arrows fit)


def wedge_sketch(values: dict[str, float], outputs: dict[str, float], optimised: set[str],
                 effects: tuple[str, ...] = ()) -> str:
    """``values``: SI case values and design merged; ``optimised``: the variables the optimiser chose;
    ``effects``: the case's start-up effects."""
    r1, lam = values["flank_inner_radius"], values["radius_ratio"]
    r2, h_r, s = lam * r1, values["weight_height"], values["shell_thickness"]
    gamma, z, d_n = values["sector_angle"], int(round(values["weight_count"])), values["finger_diameter"]
    alpha, b = values["flank_angle"], values.get("weight_width")  # paper mode: only if the case gives one
    r_in = max(r2 - h_r, 0.0)
    hub = min(values.get("hub_radius") or 0.3 * r_in, r_in)
    opt = optimised.__contains__
    front = View("Front view", SIZE, SIZE, SIZE / (r2 + s))
    if s > 0:
        front.ring(r2, r2 + s)  # the driven half-coupling's rim
    front.circle(0, 0, r1, "ref")
    front.circle(0, 0, hub, "dark")
    springs = "spring_preload" in effects and r_in > hub
    for i in range(z):
        middle = math.pi / 2 + 2 * math.pi * i / z
        front.sector(r_in, r2, middle - gamma / 2, middle + gamma / 2)
        c, si = math.cos(middle), math.sin(middle)
        front.line(hub * c, hub * si, (r_in + h_r / 2) * c, (r_in + h_r / 2) * si, "dark", width=d_n)
        if springs:
            side = middle + gamma / 4
            front.spring((hub * math.cos(side), hub * math.sin(side)), (r_in * math.cos(side), r_in * math.sin(side)),
                         min(0.35 * r_in * gamma / 4, 0.4 * (r_in - hub)), turns=4)
    shape = opt("flank_inner_radius") or opt("radius_ratio")
    front.dimension((0, 0), (r2 * math.cos(-0.3), r2 * math.sin(-0.3)), f"r2 = {mm(r2)}", shape)
    front.dimension((0, 0), (-r1 * math.cos(0.3), -r1 * math.sin(0.3)), f"r1 = {mm(r1)}", opt("flank_inner_radius"))
    corner = (r2 * math.cos(math.pi / 2 - gamma / 2), r2 * math.sin(math.pi / 2 - gamma / 2))
    front.dimension(corner, (r_in * math.cos(math.pi / 2 - gamma / 2), r_in * math.sin(math.pi / 2 - gamma / 2)),
                    f"h_r = {mm(h_r)}", opt("weight_height"), offset=-14)
    front.angle((0, 0), (r2 + s) * front.k + 16, math.pi / 2 - gamma / 2, math.pi / 2 + gamma / 2,
                f"gamma = {deg(gamma)}", opt("sector_angle"), extend_from=r2 * front.k)
    front.dimension((-(r2 + s), 0), (r2 + s, 0), f"D = 2 (r2 + s) = {mm(2 * (r2 + s))}", shape,
                    offset=-((r2 + s) * front.k + 18))
    front.note(f"z = {z} weights", opt("weight_count"))
    front.note(f"fingers d_n = {mm(d_n)}", opt("finger_diameter"))
    front.note(f"hub r_hub = {mm(hub)}; driven half-coupling: rim s = {mm(s)} outside r2")
    if springs:
        front.note(f"return springs: preload F_s = {values['spring_preload']:.4g} N on each weight",
                   opt("spring_preload"))
    if not b:
        return document([front])
    return document([front, _section(2 * SIZE + GAP, r_in, r1, r2, s, b, alpha, front.k, opt)])


def _section(left: float, r_in: float, r1: float, r2: float, s: float, b: float, alpha: float, front_k: float,
             opt) -> View:
    """Section through one weight and the groove it sits in: axial width b below r1, the flanks narrowing at
    alpha up to r2, the groove's walls beside them and the rim above."""
    wall = max(s, 0.25 * b)
    k = min(SECTION / (r2 + s - r_in), 1.6 * SECTION / (b + 2 * wall))
    view = View(f"Section of a weight in its groove ({k / front_k:.2g} x the front view)", left + (b / 2 + wall) * k,
                SIZE + (r_in + (r2 + s - r_in) / 2) * k, k)
    top = max(b / 2 - (r2 - r1) * math.tan(alpha), 0.0)
    view.polygon([(-b / 2, r_in), (b / 2, r_in), (b / 2, r1), (top, r2), (-top, r2), (-b / 2, r1)])
    view.polygon([(-b / 2 - wall, r1), (-b / 2, r1), (-top, r2), (top, r2), (b / 2, r1), (b / 2 + wall, r1),
                  (b / 2 + wall, r2 + s), (-b / 2 - wall, r2 + s)], "dark")  # the driven half-coupling
    view.dimension((-b / 2, r_in), (b / 2, r_in), f"b = {mm(b)}", opt("weight_width"), offset=-16)
    view.dimension((-b / 2 - wall, r2), (-b / 2 - wall, r_in), f"h_r = {mm(r2 - r_in)}", opt("weight_height"),
                   offset=-16)
    view.dimension((b / 2 + wall, r2), (b / 2 + wall, r2 + s), f"s = {mm(s)}", offset=-16)
    view.line(b / 2 + wall + 4 / k, r1, -b / 2 - wall - 10 / k, r1, "ref")
    view.label(-b / 2 - wall - 10 / k, r1, f"r1 = {mm(r1)}", toward=math.pi)
    radius = min(max(1.2 * (r2 - r1) / math.cos(alpha) * k, ARC / max(alpha, 1e-3)), 3 * ARC)  # px
    view.line(b / 2, r1, b / 2, r1 + 1.1 * radius / k)  # the radial direction at the flank's foot
    view.line(b / 2, r1, b / 2 - 1.1 * radius / k * math.sin(alpha), r1 + 1.1 * radius / k * math.cos(alpha))
    view.angle((b / 2, r1), radius, math.pi / 2, math.pi / 2 + alpha, f"alpha = {deg(alpha)}", opt("flank_angle"))
    return view
