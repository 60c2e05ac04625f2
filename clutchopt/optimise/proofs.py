"""Infeasibility that can be shown, not only met: bounds no design can beat, from the case's values alone.

A solver that ends without a feasible design has shown nothing about the case (its restoration may have stalled
from a poor start). A verdict ``infeasible`` is given only with a proof (``clutchopt.optimise.problem`` otherwise
reports ``not_found``: no feasible design found from the starts it names). The proofs here hold for every design
of every coupling, because they bound what the drive can do:

- the motor cannot hold the machine at the lock-up speed asked for: above the breakdown speed w_s (1 - s_k) the
  Kloss torque falls with speed, so the largest torque at or above w_L,min is T(w_L,min) there (T_k below it); a
  locked drive turning at w >= w_L,min needs T_m(w) >= T_c, the load when it locks: a profile's least over the
  speeds from w_L,min to w_s or the times up to t_max (not its largest: a load rising after the start, or a
  breakaway below w_L,min, was proven against a design that exists); its largest against T_k is the case's own
  motor_breakdown_torque;
- the motor cannot bring the masses to the lock-up speed in time: at lock-up motor and machine turn at
  w_L >= w_L,min, so the motor has put in at least (J + J_m) w_L,min^2 / 2 (slip heat and the load's work come on
  top); it delivers at most P_peak = max_w T(w) w (at the slip s_k (sqrt(1 + s_k^2) - s_k)), so
  t_start >= (J + J_m) w_L,min^2 / (2 P_peak) (energy). By momentum, usually twice as strong: motor
  J_m dw_a/dt = T_m - T, machine J dw/dt = T - T_r (T_r the load's reaction), so
  d(J_m w_a + J w)/dt = T_m - T_r <= T_k - T_r. While the machine stands (run-up, breakaway) T_r = T >= 0 and the
  rotor gathers at most J_m w_s (an induction motor driving a coupling from rest stays below w_s,
  where its torque ends); once it moves T_r = T_c >= T_c,min, the least of the load. So
  (J + J_m) w_L,min - J_m w_s <= (T_k - T_c,min) t_start, and over the whole start, T_r >= min(0, T_c,min),
  (J + J_m) w_L,min <= (T_k - min(0, T_c,min)) t_start; the start takes at least the largest of the three. Through
  an elastic link (the cable's) the start ends when the machine reaches w_L,min, the rotor at any w_a >= 0 and the
  link twisted: J takes the place of J + J_m in each bound (the rotor's momentum and energy, and the link's, only
  add), and the torque at lock-up proves nothing (the link passes more than T_k while the rotor slows);
- the lining cannot stay within its limits (effect friction_heat): while the coupling slips it passes T >= J dw/dt
  (the load takes T_c >= 0 on top) at a driving speed w_a >= w_e (below its engagement speed it passes nothing), so
  the slip heat of a start, the integral of T (w_a - w), is at least J (integral from 0 to w_e of (w_e - w) dw) =
  J w_e^2 / 2: with a constant driving speed w (no motor_curve) W >= J w^2 / 2, with a motor W >= J w_e,min^2 / 2
  (min_engagement_speed). The lumped heat balance C dT/dt = P - G T gives a start's rise dT >= e^(-G t_max / C) W / C
  (the heat released by lock-up, t <= max_start_time, less what the housing shed meanwhile), the steady rise of
  repeated starts W n_h / G; so the lining reaches at least T_0 + W n_h / G + e^(-G t_max / C) W / C.
"""

from __future__ import annotations

import math

from clutchopt.start_up.drive import elastic_link
from clutchopt.start_up.equations import kloss_torque


def start_up_proofs(case) -> list[str]:
    """What the case's drive makes impossible whatever the coupling, each in words with its numbers (none: no
    proof). Applies to a [start_up] with an induction motor (effect motor_curve) and a lock-up speed limit."""
    if case.start_up is None:
        return []
    if not case.start_up.has("motor_curve"):
        return lining_proofs(case)
    v = case.values
    if "min_lock_up_speed" not in v:
        return []
    w_s, t_k, s_k, w_l = v["synchronous_speed"], v["breakdown_torque"], v["breakdown_slip"], v["min_lock_up_speed"]
    profile = case.start_up.load_profile
    load = v["load_torque"] if profile is None else least_at_lock_up(profile, w_l, w_s, v["max_start_time"])
    proofs = []
    if w_l >= w_s:
        proofs.append(f"min_lock_up_speed {w_l * 30 / math.pi:.6g} rpm is not below the motor's synchronous speed "
                      f"{w_s * 30 / math.pi:.6g} rpm, where an induction motor gives no torque")
        return proofs
    largest = t_k if w_l < w_s * (1.0 - s_k) else float(kloss_torque(w_l, w_s, t_k, s_k))
    rigid = not elastic_link(case)
    if largest < load and rigid:
        named = f"load_profile at its least {WINDOW[profile.over]}" if profile is not None else "load_torque"
        proofs.append(f"the motor gives at most {largest:.6g} N*m (breakdown_torque {t_k:.6g} N*m) at or above "
                      f"min_lock_up_speed {w_l * 30 / math.pi:.6g} rpm, less than the machine's {named} "
                      f"{load:.6g} N*m")
    elif t_k < v["load_torque"]:  # the load's largest value (motor_breakdown_torque, whatever the design)
        named = "load_profile at its largest" if profile is not None else "load_torque"
        proofs.append(f"the motor's breakdown_torque {t_k:.6g} N*m is below the machine's {named} "
                      f"{v['load_torque']:.6g} N*m (motor_breakdown_torque)")
    least = min(profile.values) if profile is not None else v["load_torque"]
    shortest, how = shortest_start(v["driven_inertia"], v["motor_inertia"], w_l, w_s, t_k, s_k, least, rigid)
    if shortest > v["max_start_time"] * (1.0 + 1e-6):
        moved = v["driven_inertia"] + (v["motor_inertia"] if rigid else 0.0)
        proofs.append(f"bringing {moved:.6g} kg*m^2 to {w_l * 30 / math.pi:.6g} "
                      f"rpm takes at least {shortest:.4g} s {how}, more than max_start_time "
                      f"{v['max_start_time']:.6g} s")
    return proofs + lining_proofs(case)


WINDOW = {"speed": "from min_lock_up_speed to the synchronous speed", "time": "until max_start_time"}


def told_apart(a: float, b: float, digits: int = 6) -> tuple[str, str]:
    """``a`` and ``b`` in at least ``digits`` significant digits, more where they would read the same (a proof just
    over its edge read "at least 2741.56 J, above its limit 2741.56 J")."""
    for shown_digits in range(digits, 18):
        shown = f"{a:.{shown_digits}g}", f"{b:.{shown_digits}g}"
        if shown[0] != shown[1]:
            break
    return shown


def least_at_lock_up(profile, lock_up: float, synchronous: float, max_start_time: float) -> float:
    """The least load (N*m) the machine can ask when the drive locks up: over its speeds from ``lock_up`` w_L,min to
    ``synchronous`` w_s, or over the times up to ``max_start_time`` (a load rising after the start, or a breakaway
    below w_L,min, is no load at lock-up). The table is linear between its points and held beyond its ends, so its
    least over [a, b] is at a, b or a point between."""
    low, high = (lock_up, synchronous) if profile.over == "speed" else (0.0, max_start_time * (1.0 + 1e-6))
    inside = [y for x, y in zip(profile.points, profile.values) if low < x < high]
    return min([float(profile.at(low, low)), float(profile.at(high, high)), *inside])


def shortest_start(driven: float, motor: float, lock_up: float, synchronous: float, breakdown: float, slip: float,
                   least_load: float, rigid: bool = True) -> tuple[float, str]:
    """The least time (s) in which an induction motor (Kloss: ``synchronous`` speed w_s, ``breakdown`` torque T_k at
    ``slip`` s_k, rotor inertia ``motor`` J_m) brings itself and the machine (``driven`` J, its load never below
    ``least_load`` T_c,min) to the speed ``lock_up`` w_L whatever the coupling between them, and by which bound (module
    docstring): energy (J + J_m) w_L^2 / (2 P_peak) where the load is never negative, momentum (J + J_m) w_L /
    (T_k - min(0, T_c,min)), momentum with the load ((J + J_m) w_L - J_m w_s) / (T_k - T_c,min); the largest.
    Not ``rigid`` (an elastic link, the cable's: the start ends when the machine reaches w_L, the rotor then at any
    speed w_a >= 0, its twist storing energy), J + J_m is J: the rotor's momentum J_m w_a >= 0 and its energy only add
    to what the motor put in."""
    inertia = driven + (motor if rigid else 0.0)
    # the Kloss power 2 T_k s s_k w_s (1 - s) / (s^2 + s_k^2) peaks where d/ds [s (1 - s) / (s^2 + s_k^2)] = 0,
    # s^2 + 2 s_k^2 s - s_k^2 = 0: s = s_k (sqrt(1 + s_k^2) - s_k) (a grid of 1e5 speeds agrees to 1e-9)
    peak_slip = slip * (math.sqrt(1.0 + slip**2) - slip)
    peak_speed = synchronous * (1.0 - peak_slip)
    peak = float(kloss_torque(peak_speed, synchronous, breakdown, slip)) * peak_speed
    bounds = [(inertia * lock_up / (breakdown - min(0.0, least_load)),
               f"by momentum at the motor's breakdown torque {breakdown:.6g} N*m")]
    if least_load >= 0:  # (a load that drives the machine puts in energy of its own)
        bounds.append((0.5 * inertia * lock_up**2 / peak, f"at the motor's peak power {peak / 1e3:.6g} kW"))
    if breakdown > least_load:
        bounds.append(((inertia * lock_up - motor * synchronous) / (breakdown - least_load),
                       f"by momentum at the motor's breakdown torque {breakdown:.6g} N*m less the machine's least "
                       f"load {least_load:.6g} N*m (the rotor's own {motor * synchronous:.6g} N*m*s at most "
                       f"gathered before the machine moves)"))
    return max(bounds)


def least_friction_work(case) -> tuple[float, str]:
    """A friction work every start of every design releases (J), and how it follows (module docstring); 0 where none
    is known."""
    v, spec = case.values, case.start_up
    if spec.load_profile is not None and min(spec.load_profile.values) < 0:
        return 0.0, ""  # a load that drives the machine: T >= J dw/dt does not hold
    if not spec.has("motor_curve"):
        speed, how = v["speed"], "the constant driving speed"
    elif "min_engagement_speed" in v:
        speed, how = v["min_engagement_speed"], "min_engagement_speed"
    else:
        return 0.0, ""
    work = 0.5 * v["driven_inertia"] * speed**2
    return work, (f"every start releases at least J w^2 / 2 = {work / 1e3:.6g} kJ of slip heat (J "
                  f"{v['driven_inertia']:.6g} kg*m^2, w {speed * 30 / math.pi:.6g} rpm, {how})")


def lining_proofs(case) -> list[str]:
    """The lining's limits no design can meet (effect friction_heat), each with its numbers."""
    v, spec = case.values, case.start_up
    if not spec.has("friction_heat") or "heat_capacity" not in v:
        return []
    work, why = least_friction_work(case)
    if work <= 0:
        return []
    limits = spec.limits
    capacity, conductance = v["heat_capacity"], v.get("heat_conductance", 0.0)
    rise = math.exp(-conductance * v["max_start_time"] / capacity) * work / capacity
    steady = work * v["starts_per_hour"] / conductance if "starts_per_hour" in limits and conductance > 0 else 0.0
    found = []

    def beyond(name: str, least: float, limit: float, what: str, unit: str = "K", offset: float = 0.0) -> None:
        if least > limit * (1.0 + 1e-9):
            shown, allowed = told_apart(least - offset, limit - offset)
            found.append(f"{name}: {why}, so {what} at least {shown} {unit}, above its limit {allowed} {unit}")

    if "max_friction_work" in limits:
        beyond("friction_work", work, v["max_friction_work"], "the heat of a start is", "J")
    if "max_temperature_rise" in limits:
        beyond("temperature_rise", rise, v["max_temperature_rise"], "the friction parts rise by")
    if "max_lining_temperature" in limits:
        beyond("lining_temperature", v["ambient_temperature"] + steady + rise, v["max_lining_temperature"],
               "the lining reaches", "degC", 273.15)
    if steady and "max_continuous_temperature" in limits:
        beyond("continuous_temperature", v["ambient_temperature"] + steady, v["max_continuous_temperature"],
               "repeated starts keep the lining at", "degC", 273.15)
    if "heat_dissipation" in limits and "starts_per_hour" in limits:
        beyond("heat_per_hour", work * v["starts_per_hour"], v["heat_dissipation"], "the mean slip heat is", "W")
    return found
