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
        """Read back from :meth:`as_dict`'s JSON; ValueError where it is not one (a damaged store)."""
        try:
            return cls(int(data["point"]), data["start"], dict(data["pace"]), data["ahead"], data["feasible"],
                       [(tuple(float(v) for v in combo), int(k), str(status))
                        for combo, k, status in data["undesigned"]])
        except (KeyError, TypeError, ValueError) as exc:
            raise ValueError(f"not a sweep's carried start: {exc}") from None
