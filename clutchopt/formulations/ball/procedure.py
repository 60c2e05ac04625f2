"""The ball paper's sizing procedure as printed, step by step, with the K2 loop it leaves open (docs/ball.md)."""

from __future__ import annotations

import math

from clutchopt.formulations.ball.clutch import BallClutch
from clutchopt.formulations.ball.contact import curvatures, hertz_coefficients_exact
from clutchopt.formulations.ball.equations import (
    filling_coefficient,
    paper_active_radius,
    paper_ball_rows,
    required,
    width_from_rows,
)
from clutchopt.formulations.ball.paper import (
    paper_eq2,
    paper_eq8,
    paper_eq9,
    paper_eq10,
    paper_eq12_balls,
    paper_groove_depth,
)


def _procedure_pass(p, filling, geometry=None):
    """Eqs. (4)-(8) at one K2; with ``geometry`` (a previous pass) R_a, l, n_p and l_a are kept."""
    if geometry is None:
        radius = paper_active_radius(required(p), p.friction_coefficient, p.density, p.packing_density, p.speed,
                                     p.width_ratio, filling)
        approximate = p.width_ratio * radius
        rows = paper_ball_rows(approximate, p.ball_radius)
        geometry = {"active_radius": radius, "approximate_width": approximate, "ball_rows": rows,
                    "active_width": width_from_rows(rows, p.ball_radius)}
    torque = paper_eq8(p, geometry["active_radius"], geometry["active_width"], geometry["approximate_width"], filling)
    return {"filling": filling, **{k: geometry[k] for k in ("active_radius", "approximate_width", "ball_rows",
                                                             "active_width")},
            "torque_eq8": torque, "torque_ratio": torque / required(p)}


def paper_procedure(p, rule: str = "refill", max_passes: int = 60):
    """The paper's sizing as printed: K2 (1), R_a (4), l (5), n_p (6) up, l_a (7), M (8); while M (8) is off M_c
    by more than the tolerance (10 %), change K2 and calculate again; then p_0 (9), (10), masses (2), (12), (13).

    The paper does not say how to change K2. Our rule (``refill``, the default): keep the machined geometry
    (R_a, l, n_p, l_a of the first pass) and change only the filling K2 by bisection on (0, 1): too much torque,
    K2 up (fewer balls); too little, K2 down; the first K2 within the tolerance is kept. ``restart`` is the
    literal reading, every pass again from (4) with the new K2: (4) then rescales R_a to hold the leading torque
    at M_c, the excess of (8) (end faces, rounding up) only fades as K2 -> 1, and the bisection ends at a layer
    one ball thick in a drum several times larger (docs/ball.md). Returns every intermediate value and the passes.
    """
    if rule not in ("refill", "restart"):
        raise ValueError(f"rule must be 'refill' or 'restart', got {rule!r}")
    low, high = 0.0, 1.0
    filling = float(filling_coefficient(p.construction_density, p.packing_density))
    passes = [_procedure_pass(p, filling)]
    geometry = passes[0] if rule == "refill" else None
    while abs(passes[-1]["torque_ratio"] - 1) > p.torque_tolerance and len(passes) < max_passes:
        low, high = (filling, high) if passes[-1]["torque_ratio"] > 1 else (low, filling)
        filling = (low + high) / 2
        passes.append(_procedure_pass(p, filling, geometry))
    final = dict(passes[-1])
    radius, width, filling = final["active_radius"], final["active_width"], final["filling"]
    clutch = BallClutch(radius, width, filling, p.ball_radius, p.groove_conformity, final["ball_rows"])
    total, ratio = curvatures(radius, p.ball_radius, p.groove_conformity)
    n_a, n_b = hertz_coefficients_exact(ratio)
    final.update({
        "filling_eq1": passes[0]["filling"],
        "converged": abs(final["torque_ratio"] - 1) <= p.torque_tolerance,
        "passes": passes,
        "required_torque": required(p),
        "width_ratio": width / radius,
        "torque": float(clutch.torque(p)),
        "hertz_n_a": n_a, "hertz_n_b": n_b, "curvature_ratio": ratio,
        "contact_stress": float(clutch.contact_stress(p)),
        "contact_stress_eq9": paper_eq9(p, radius, filling, n_a, n_b),
        "contact_stress_eq10": paper_eq10(p, radius, filling, p.groove_conformity),
        "groove_pitch": math.sqrt(3) * p.ball_radius,
        "groove_depth_eq11": paper_groove_depth(p, radius, p.ball_radius, p.groove_conformity),
        "ball_mass_eq2": paper_eq2(p, radius, width, filling),
        "ball_mass_eq12": paper_eq12_balls(p, radius, width, filling),
        "ball_mass": float(clutch.balls(p)),
        "body_mass": float(clutch.body(p)),
        "total_mass": float(clutch.mass(p)),
        "cost": float(clutch.cost(p)),
        "ball_radius": p.ball_radius, "groove_conformity": p.groove_conformity,
        "outer_diameter": 2 * (radius + p.shell_thickness),
    })
    return final
