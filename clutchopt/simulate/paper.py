"""The paper's start-up both ways: closed forms and simulation, for comparisons and torture runs."""

from __future__ import annotations

from clutchopt.simulate.analytic import PaperTransient
from clutchopt.simulate.engine import Model, simulate
from clutchopt.simulate.laws import Load, PaperFriction

HEADLINE = ("locks_up", "reason", "start_time", "friction_work", "source_work")


def paper_start_up(inertia: float, k: float, a: float, resisting_torque: float, speed: float,
                   rtol: float = 1e-11, end_time: float | None = None) -> dict:
    """{"analytic": ..., "simulated": ...}: t_c, L, L_s and the lock-up verdict (SI) of J, k, a, M_r, w0.

    Never raises for positive J, k, w0 and M_r >= 0, and always ends: either both lock up (agreeing to about 1e-10
    relative at the default tolerance) or both report a reason starting "no lock-up".
    """
    analytic = PaperTransient(inertia, k, a, resisting_torque, speed).summary()
    model = Model(PaperFriction(k, a), inertia, Load(resisting_torque), ("slip_friction", "lockup"),
                  driver_speed=speed, rtol=rtol, end_time=end_time)
    head = simulate(model).headline
    return {"analytic": {key: analytic[key] for key in HEADLINE}, "simulated": {key: head[key] for key in HEADLINE}}
