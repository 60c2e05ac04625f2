"""An induction motor as its nameplate and catalogue give it, read as the Kloss curve the start-up models.

``[start_up.driver]`` may give, instead of the Kloss parameters, what a catalogue prints::

    rated_power = "15 kW"       # P_n
    rated_speed = "1460 rpm"    # n_n
    poles = 4                   # 2 p
    frequency = "50 Hz"         # f
    breakdown_ratio = 2.8       # T_k / T_n
    starting_ratio = 2.2        # T_a / T_n (optional: compared with the Kloss curve's, not fitted)

From them (docs/start_up.md): synchronous speed w_s = 2 pi f / p (p pole pairs), rated slip s_n = 1 - w_n / w_s,
rated torque T_n = P_n / w_n, breakdown torque T_k = (T_k/T_n) T_n, and the breakdown slip from Kloss's
T_n = 2 T_k / (s_n/s_k + s_k/s_n): with lambda = T_k/T_n, s_k = s_n (lambda + sqrt(lambda^2 - 1)) (the root with
s_k > s_n: the motor runs at its rating on the stable side of the curve). A two-parameter curve cannot also meet the
catalogue's starting torque; T_a/T_n, when given, is set beside the Kloss curve's 2 lambda s_k / (1 + s_k^2) in a note.
"""

from __future__ import annotations

import math

from clutchopt.errors import InputError, Problems
from clutchopt.units import to_si

FIELDS = {"rated_power": "W", "rated_speed": "rad/s", "poles": "", "frequency": "Hz", "breakdown_ratio": "",
          "starting_ratio": ""}
REQUIRED = ("rated_power", "rated_speed", "poles", "frequency", "breakdown_ratio")
KLOSS = ("synchronous_speed", "breakdown_torque", "breakdown_slip")  # what the nameplate gives
DERIVED_FROM = {"synchronous_speed": ("poles", "frequency"),  # the nameplate fields each Kloss value comes from
                "breakdown_torque": ("rated_power", "rated_speed", "breakdown_ratio"),
                "breakdown_slip": ("rated_speed", "poles", "frequency", "breakdown_ratio")}
MAX_POLES = 64
MIN_SLIP = 1e-6  # the rated speed at least this far below the synchronous (an induction motor slips)


def nameplate_fields(driver: dict) -> dict:
    """The nameplate fields a ``[start_up.driver]`` table gives (raw)."""
    return {key: value for key, value in driver.items() if key in FIELDS}


def kloss_from_nameplate(raw: dict, prefix: str, kloss_given: list[str]) -> tuple[dict[str, float], str]:
    """SI synchronous speed, breakdown torque and breakdown slip from nameplate fields (``raw``, as written under
    ``prefix``, e.g. ``start_up.driver``), and a note on the starting torque; every bad field named together.
    ``kloss_given``: the Kloss fields the table gives as well (refused: one motor, one description)."""
    problems = Problems()
    for name in kloss_given:
        problems.errors.append(InputError(f"{prefix}.{name}", "given beside the nameplate fields "
                                          f"({', '.join(raw)}), which give it: give one or the other"))
    for name in REQUIRED:
        if name not in raw:
            problems.errors.append(InputError(f"{prefix}.{name}", "missing (the nameplate needs "
                                                                  f"{', '.join(REQUIRED)})"))
    v: dict[str, float] = {}
    for name, value in raw.items():
        with problems.field():
            v[name] = _checked(name, to_si(f"{prefix}.{name}", value, FIELDS[name]), f"{prefix}.{name}")
    problems.raise_any()
    synchronous = 4.0 * math.pi * v["frequency"] / v["poles"]
    rated_slip = 1.0 - v["rated_speed"] / synchronous
    if not rated_slip >= MIN_SLIP:
        raise InputError(f"{prefix}.rated_speed", f"{v['rated_speed'] * 30 / math.pi:.6g} rpm is not below the "
                                                  f"synchronous speed {synchronous * 30 / math.pi:.6g} rpm of "
                                                  f"{v['poles']:g} poles at {v['frequency']:g} Hz")
    ratio = v["breakdown_ratio"]
    breakdown_slip = rated_slip * (ratio + math.sqrt(ratio * ratio - 1.0))
    if not breakdown_slip < 1.0:
        raise InputError(f"{prefix}.breakdown_ratio", f"with a rated slip of {rated_slip:.4g}, T_k/T_n {ratio:g} "
                                                      f"puts the breakdown slip at {breakdown_slip:.4g}, not below 1")
    values = {"synchronous_speed": synchronous, "breakdown_torque": ratio * v["rated_power"] / v["rated_speed"],
              "breakdown_slip": breakdown_slip}
    kloss_start = 2.0 * ratio * breakdown_slip / (1.0 + breakdown_slip**2)
    note = (f"motor from its nameplate: synchronous speed {synchronous * 30 / math.pi:.6g} rpm, breakdown torque "
            f"{values['breakdown_torque']:.6g} N*m at slip {breakdown_slip:.4g} (Kloss, docs/start_up.md); its "
            f"starting torque is {kloss_start:.3g} T_n")
    if "starting_ratio" in v:
        note += f" against the catalogue's {v['starting_ratio']:.3g} T_n"
    return values, note


def derived_from(name: str, prefix: str) -> str:
    """``derived from the nameplate's start_up.driver.rated_power, ...``: where a Kloss value a case does not give
    came from, for an error that names it."""
    return f"derived from the nameplate's {', '.join(f'{prefix}.{field}' for field in DERIVED_FROM[name])}"


def _checked(name: str, value: float, field: str) -> float:
    if name == "poles" and not (value == int(value) and value >= 2 and value % 2 == 0 and value <= MAX_POLES):
        raise InputError(field, f"must be an even whole number from 2 to {MAX_POLES}, got {value:g}")
    if name == "breakdown_ratio" and not 1.0 < value <= 10.0:
        raise InputError(field, f"T_k/T_n must be above 1 (the motor carries its rating) and at most 10, got {value:g}")
    if name == "starting_ratio" and not 0.0 < value <= 10.0:
        raise InputError(field, f"T_a/T_n must be above 0 and at most 10, got {value:g}")
    if name in ("rated_power", "rated_speed", "frequency") and not value > 0:
        raise InputError(field, "must be > 0")
    if name == "frequency" and value > 1000:
        raise InputError(field, f"{value:g} Hz is beyond a motor's supply (at most 1000 Hz)")
    return value
