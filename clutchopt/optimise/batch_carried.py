"""What a window of a batched sweep takes from the points before it, so that a resumed sweep goes on exactly as the
uninterrupted one did.

``BatchSweep.run`` hands its points on (and the run store records them) a window at a time. The next window starts
from the last kept point's primal-dual optimum and the step that led to it (the secant predictor's), the chains'
pace, the points until an active set is expected to change, the last feasible design (a failed point's start) and
the integer combinations IPOPT found without a design at recent points, and the boxes of the last interval proof
(``interval_proof.last_boxes``: a region search's budget, kept by the built problem across windows in one process;
a resumed process had started from none). That is all a window reads of the windows before it: each window starts
its region proofs afresh (``region_proof.Regions``) and its exclusion tables are a cache of values that do not depend
on where they were computed. The run store keeps :class:`Carried` beside the
window's points, in the same transaction (``RunStore.record_points``); ``sweep --resume`` reads it back at the first
point not stored and starts the window there from it, so the resumed rows equal the uninterrupted run's bit for
bit (JSON keeps every float64 exactly), where a resume used to start cold (docs/store.md, "Resumed sweeps").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

BY_VARIABLE = ("scale", "x", "lam_x", "dx", "dlam_x")  # a start's numbers, one per design variable
BY_ROW = ("lam_g", "dlam_g")  # and one per constraint row


@dataclass(frozen=True)
class Carried:
    """What point ``point`` of a batched sweep starts from, the first point of a window (see the module text).
    ``start``: the primal-dual point and step of ``_Start.carried`` (None: cold, after a point without a design);
    ``boxes``: ``interval_proof.last_boxes`` (0 in a start stored before it was carried)."""

    point: int
    start: dict | None
    pace: dict
    ahead: int | None
    feasible: dict[str, float] | None
    undesigned: list[tuple[tuple[float, ...], int, str]]
    boxes: int

    def as_dict(self) -> dict:
        return {"point": self.point, "start": self.start, "pace": self.pace, "ahead": self.ahead,
                "feasible": self.feasible, "undesigned": [[list(combo), k, status]
                                                          for combo, k, status in self.undesigned],
                "boxes": self.boxes}

    @classmethod
    def from_dict(cls, data: dict, point: int, variables: list[str], rows: int) -> "Carried":
        """Read back from :meth:`as_dict`'s JSON, stored as the start of point ``point`` of a sweep of the design
        ``variables`` and ``rows`` constraint rows: every number converted and checked here (finite, the scales
        positive, whole where a count, each array as long as the problem's, the last feasible design one of
        ``variables``), so that a damaged store (an array cut short, a NaN, a string, another problem's start) is one
        ValueError naming what is wrong (``RunStore.sweep_start``: the store's error), not an error of the window
        that would read it."""
        try:
            if _whole(data["point"], "point") != point:
                raise ValueError(f"its point is {data['point']!r}")
            start = data["start"]
            if start is not None:
                start = {**{key: _numbers(start[key], key, len(variables)) for key in BY_VARIABLE},
                         **{key: _numbers(start[key], key, rows) for key in BY_ROW},
                         "objective": _number(start["objective"], "objective")}
                if min(start["scale"]) <= 0:
                    raise ValueError("a scale of its start is not positive")
            pace = data["pace"]
            pace = {"size": _whole(pace["size"], "pace size", 1), "breaks": [_whole(b, "breaks") for b in pace["breaks"]],
                    "aimed": _flag(pace["aimed"], "aimed"), "probes": _whole(pace["probes"], "probes")}
            ahead = None if data["ahead"] is None else _whole(data["ahead"], "ahead", 1)
            feasible = None if data["feasible"] is None else stored_design(data["feasible"], variables)
            undesigned = [(tuple(_numbers(combo, "undesigned")), _whole(k, "undesigned"), _text(status, "undesigned"))
                          for combo, k, status in data["undesigned"]]
            boxes = _whole(data.get("boxes", 0), "boxes")
        except KeyError as exc:
            raise ValueError(f"no {exc}") from None
        except (TypeError, AttributeError) as exc:
            raise ValueError(f"not a sweep's carried start ({exc})") from None
        return cls(point, start, pace, ahead, feasible, undesigned, boxes)


def stored_design(design, variables: list[str]) -> dict[str, float]:
    """A feasible design read back from a store: one of the design ``variables`` by name, each a finite number
    (floats, in the variables' order); else ValueError naming what is wrong."""
    if type(design) is not dict or sorted(design) != sorted(variables):
        raise ValueError("its feasible design is not one of the design variables")
    return {name: _number(design[name], "feasible") for name in variables}


def _number(value, name: str) -> float:
    if type(value) not in (int, float) or not math.isfinite(value):
        raise ValueError(f"its {name} is not a finite number")
    return float(value)


def _numbers(values, name: str, length: int | None = None) -> list[float]:
    if type(values) is not list or length is not None and len(values) != length:
        raise ValueError(f"its {name} is not {length} numbers" if length is not None else f"its {name} is no list")
    return [_number(value, name) for value in values]


def _whole(value, name: str, least: int = 0) -> int:
    if type(value) is not int or value < least:
        raise ValueError(f"its {name} is not a whole number from {least}")
    return value


def _flag(value, name: str) -> bool:
    if type(value) is not bool:
        raise ValueError(f"its {name} is not true or false")
    return value


def _text(value, name: str) -> str:
    if type(value) is not str:
        raise ValueError(f"its {name} is not a text")
    return value
