"""What a window of a batched sweep takes from the points before it, so that a resumed sweep goes on exactly as the
uninterrupted one did.

``BatchSweep.run`` hands its points on (and the run store records them) a window at a time. The next window starts
from the last kept point's primal-dual optimum and the step that led to it (the secant predictor's), the chains'
pace, the points until an active set is expected to change, the last feasible design (a failed point's start) and
the integer combinations IPOPT found without a design at recent points. That is all a window reads of the windows
before it: each window starts its region proofs afresh (``region_proof.Regions``) and its exclusion tables are a
cache of values that do not depend on where they were computed. The run store keeps :class:`Carried` beside the
window's points, in the same transaction (``RunStore.record_points``); ``sweep --resume`` reads it back at the first
point not stored and starts the window there from it, so the resumed rows equal the uninterrupted run's bit for
bit (JSON keeps every float64 exactly), where a resume used to start cold (docs/store.md, "Resumed sweeps").
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class Carried:
    """What point ``point`` of a batched sweep starts from, the first point of a window (see the module text).
    ``start``: the primal-dual point and step of ``_Start.carried`` (None: cold, after a point without a design)."""

    point: int
    start: dict | None
    pace: dict
    ahead: int | None
    feasible: dict[str, float] | None
    undesigned: list[tuple[tuple[float, ...], int, str]]

    def as_dict(self) -> dict:
        return {"point": self.point, "start": self.start, "pace": self.pace, "ahead": self.ahead,
                "feasible": self.feasible, "undesigned": [[list(combo), k, status]
                                                          for combo, k, status in self.undesigned]}

    @classmethod
    def from_dict(cls, data: dict) -> "Carried":
        """Read back from :meth:`as_dict`'s JSON; ValueError where it is not one (a damaged store): every number of
        the start finite (the scales positive), its arrays of one length each (x, scale, lam_x and their steps; lam_g
        and its step), the pace's chain at least one point long, ``ahead`` None or a count."""
        try:
            carried = cls(int(data["point"]), _start(data["start"]), _pace(data["pace"]), _count(data["ahead"]),
                          _feasible(data["feasible"]),
                          [(tuple(_finite(v) for v in combo), int(k), str(status))
                           for combo, k, status in data["undesigned"]])
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise ValueError(f"not a sweep's carried start: {exc}") from None
        return carried

    def check_fits(self, names: list[str], rows: int) -> None:
        """DamagedStart where the start is not the sweep's problem's: its arrays ``len(names)`` long (x, scale, lam_x
        and their steps) and ``rows`` long (lam_g and its step), the last feasible design a value of each of
        ``names``: a start stored by another sweep or cut short."""
        wrong = [] if self.start is None else [
            f"{key} has {len(self.start[key])} numbers, not {want}"
            for keys, want in ((PRIMAL, len(names)), (DUAL, rows)) for key in keys if len(self.start[key]) != want]
        if self.feasible is not None and set(self.feasible) != set(names):
            wrong.append(f"its last feasible design names {', '.join(sorted(self.feasible))}, not "
                         f"{', '.join(sorted(names))}")
        if wrong:
            raise DamagedStart(self.point, "; ".join(wrong))


class DamagedStart(ValueError):
    """A stored start that cannot be this sweep's (``Carried.check_fits``): the run store is damaged."""

    def __init__(self, point: int, what: str):
        super().__init__(what)
        self.point = point


PRIMAL, DUAL = ("scale", "x", "lam_x", "dx", "dlam_x"), ("lam_g", "dlam_g")  # a start's arrays by their length


def _finite(value) -> float:
    if isinstance(value, (bool, str)) or value is None:
        raise TypeError(f"{value!r} is not a number")
    number = float(value)
    if not math.isfinite(number):
        raise ValueError(f"{number} is not finite")
    return number


def _start(start) -> dict | None:
    """A start's arrays (finite, the scales positive, one length per group: ``PRIMAL``, ``DUAL``) and objective."""
    if start is None:
        return None
    arrays = {key: [_finite(v) for v in start[key]] for key in PRIMAL + DUAL}
    for group in (PRIMAL, DUAL):
        if len({len(arrays[key]) for key in group}) != 1:
            raise ValueError(f"the start's {', '.join(group)} differ in length")
    if any(v <= 0 for v in arrays["scale"]):
        raise ValueError("a scale is not positive")
    objective = start["objective"]  # (a number; _Start reads one not finite as no normaliser)
    if isinstance(objective, (bool, str)) or objective is None:
        raise TypeError(f"the objective {objective!r} is not a number")
    return {**arrays, "objective": float(objective)}


def _pace(pace) -> dict:
    size, breaks = _count(pace["size"]), [_count(b) for b in pace["breaks"]]
    if size is None or size < 1:
        raise ValueError(f"the chains' length {pace['size']!r} is not a positive count")
    return {"size": size, "breaks": breaks, "aimed": bool(pace["aimed"]), "probes": _count(pace["probes"]) or 0}


def _count(value) -> int | None:
    """None, or a whole number of points at least 0."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, int) or value < 0:
        raise ValueError(f"{value!r} is not a count")
    return value


def _feasible(feasible) -> dict[str, float] | None:
    return None if feasible is None else {str(name): _finite(value) for name, value in feasible.items()}
