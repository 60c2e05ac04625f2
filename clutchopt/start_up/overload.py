"""The overload of a coupling on its drive: the largest torque it can pass, against the motor's breakdown torque and
the driven machine's limit (docs/start_up.md, "Overload").

When the driven machine jams, the machine stops and the coupling slips; it then passes its *slip torque* at the
driving speed, which the motor keeps near its synchronous speed as long as it carries that torque. That torque is
the largest the coupling can pass: at the top driving speed w_top (the motor's synchronous speed, else the duty's
constant speed), with the linings worn where the torque grows as they wear (the lever: the stronger of new and
worn), with the highest friction coefficient f_max the pair reaches. It must stay

- below the motor's breakdown torque T_k: on the motor's stable branch (slip below s_k) its torque falls from T_k to
  0 as the speed rises from (1 - s_k) w_s to w_s, while the coupling's slip torque rises with w_a^2; the two meet on
  that branch (the motor keeps running, the coupling slips) if the slip torque at the breakdown speed is below T_k.
  T(w_s) <= T_k is sufficient whatever the speed (T grows with w_a), conservative by T(w_s) / T(w_k), at least
  (1 - s_k)^-2;
  otherwise the motor is pulled over its breakdown point and stalls, the coupling locked to it (it protects
  nothing);
- below the driven machine's ``max_transmitted_torque`` where given: the coupling as a torque limiter.

Couplings whose torque changes as the linings wear (the lever) start more slowly new or worn? With new linings
T_n = K_n (w^2 - e_n), worn T_w = K_w (w^2 - e_w) (e the engagement speed squared), K_w >= K_n (the lever:
K_w / K_n = (R_0 + dr) tan gamma_0 / (R_0 tan gamma_pr), 5 to 10). T_w - T_n grows with w, so T_w >= T_n at every
speed exactly when it holds at the new engagement speed, T_w(w_e,new) >= 0: the worn coupling engages no later than
the new one. Then at every driving speed the worn coupling passes at least the new one's torque, the slip ends
sooner, and the start with new linings, the one the start-up checks, is the slower (``worn_engages_first``).

Equations written once for floats and CasADi symbols (:mod:`clutchopt.backend`).
"""

from __future__ import annotations

from types import SimpleNamespace

from clutchopt.backend import fmax, fmin
from clutchopt.model import SpeedLaw

FRICTION = "friction_coefficient"  # the case quantity f_max replaces


def top_speed(p, motor: bool):
    """w_top: the synchronous speed of an induction motor (it runs just below it when the machine jams), else the
    duty's constant driving speed."""
    return p.synchronous_speed if motor else p.speed


def highest_friction(p):
    """max(f, f_max): the nominal f where a sweep or a scatter's corner moves it above the pair's f_max."""
    return fmax(getattr(p, FRICTION), p.friction_max)


def slip_torque(law: SpeedLaw, x, p, speed, preload):
    """The stronger of the coupling's torque with new linings, K (w_a^2 - F_s / (m r)), and with worn ones (a law
    whose torque changes as they wear: the lever), at the driving speed w_a with a spring preload F_s per weight.
    The weights' own weight is left out: over z >= 2 weights spaced evenly round the axis its radial components sum
    to zero, and the torque is the weights' sum."""
    reduction = preload / law.mass_radius(x, p) if law.mass_radius is not None else 0.0
    new = law.torque_coefficient(x, p) * (speed**2 - reduction)
    return new if law.worn_torque is None else fmax(new, law.worn_torque(x, p, speed, preload))


def overload_torque(law: SpeedLaw, x, p, effects, motor: bool):
    """The largest torque the coupling passes: its slip torque at the top speed with the highest friction, the
    return springs at their preload (effect spring_preload)."""
    hot = SimpleNamespace(**{**vars(p), FRICTION: highest_friction(p)})
    preload = x.spring_preload if "spring_preload" in effects else 0.0
    return slip_torque(law, x, hot, top_speed(p, motor), preload)


def overload_limit(p, motor: bool, machine: bool):
    """The torque the coupling must slip below: the motor's breakdown torque T_k, the driven machine's
    max_transmitted_torque, or the lesser of the two."""
    if motor and machine:
        return fmin(p.breakdown_torque, p.max_transmitted_torque)
    return p.breakdown_torque if motor else p.max_transmitted_torque
