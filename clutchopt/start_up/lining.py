"""What a start does to the lining, for the report: its temperature (peak of a start, steady of repeated starts)
and its wear (starts and hours until worn), from a start's friction work and temperature rise, and what was not
checked and why (docs/start_up.md, "The lining: temperature and life")."""

from __future__ import annotations

import math

from clutchopt.start_up.drive import Drive

UNITS = {"lining_temperature": "K", "steady_temperature": "K", "ambient_temperature": "K", "wear_per_start": "m",
         "starts_until_worn": "", "life": "s"}


def lining_figures(drive: Drive, friction_work: float, temperature_rise: float | None) -> dict[str, float | None]:
    """The lining's figures of one start (SI; None where the case lacks what it needs): peak and steady temperature
    (friction_heat), wear per start, starts and hours until worn (wear rate, allowance and friction area known;
    hours with starts_per_hour)."""
    s = drive.s
    heat = s.heat and temperature_rise is not None
    figures = {"lining_temperature": float(drive.lining_temperature(friction_work, temperature_rise)) if heat
               else None,
               "steady_temperature": float(drive.lining_temperature(friction_work, 0.0)) if heat and drive.repeated
               else None,
               "wear_per_start": None, "starts_until_worn": None, "life": None}
    if not _missing_for_wear(drive):
        figures.update(wear_per_start=float(drive.wear_per_start(friction_work)),
                       starts_until_worn=float(drive.starts_until_worn(friction_work)),
                       life=float(drive.life(friction_work)) if drive.repeated else None)
    return figures


def lining_notes(drive: Drive, coupling: str) -> list[str]:
    """What the report says was not checked about the lining, and why (empty: temperature checked, life known)."""
    s, limits, notes = drive.s, drive.s.spec.limits, []
    if s.elastic:
        return notes
    pair = "name a friction_pair in [library] or give"
    if not s.heat:
        notes.append("lining temperature not checked: the start-up has no heat data (list friction_heat in effects "
                     "and give [start_up.heat] capacity)")
    else:
        if "max_lining_temperature" not in limits:
            notes.append(f"lining temperature not checked against a limit: {pair} [start_up.limits] "
                         "max_lining_temperature")
        if drive.repeated and "max_continuous_temperature" not in limits:
            notes.append(f"steady temperature of repeated starts not checked against a limit: {pair} "
                         "[start_up.limits] max_continuous_temperature")
        if not drive.repeated:
            notes.append("steady temperature of repeated starts not computed: give [start_up.limits] starts_per_hour")
    missing = _missing_for_wear(drive)
    if missing:
        notes.append(f"lining life not computed: {missing.format(coupling=coupling, pair=pair)}")
    elif not drive.repeated:
        notes.append("lining life in hours not computed: give [start_up.limits] starts_per_hour")
    return notes


def _missing_for_wear(drive: Drive) -> str:
    """Why the wear of the lining cannot be computed ("" if it can)."""
    if drive.law.friction_area is None:
        return "the {coupling} coupling declares no friction area that wears"
    for name, how in (("wear_rate", "{pair} [start_up.wear] wear_rate"),
                      ("wear_allowance", "give [start_up.wear] allowance, the thickness that may wear")):
        if not math.isfinite(float(getattr(drive.p, name, math.nan))):
            return f"no {name.replace('_', ' ')} ({how})"
    return ""
