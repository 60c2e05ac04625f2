"""Where a sketch's drawn things lie, in px, so that its labels can be placed clear of them.

Each shape answers one question, whether it meets a box (left, top, right, bottom) grown by a gap: a polygon
(rectangles, sectors, rotated squares), a ring (a disc is a ring without a hole, a circle outline a thin ring) and
a bar (a line drawn with a width). Exact for polygons and rings; a bar is taken as its box-grown segment.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

Box = tuple[float, float, float, float]  # left, top, right, bottom (px, y down)


def grown(box: Box, gap: float) -> Box:
    return box[0] - gap, box[1] - gap, box[2] + gap, box[3] + gap


def boxes_meet(a: Box, b: Box) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def union(boxes) -> Box:
    left, top, right, bottom = zip(*boxes)
    return min(left), min(top), max(right), max(bottom)


def segment_meets(x1: float, y1: float, x2: float, y2: float, box: Box) -> bool:
    """Whether the segment crosses the box (Liang-Barsky clipping)."""
    low, high = 0.0, 1.0
    dx, dy = x2 - x1, y2 - y1
    for p, q in ((-dx, x1 - box[0]), (dx, box[2] - x1), (-dy, y1 - box[1]), (dy, box[3] - y1)):
        if p == 0:
            if q < 0:
                return False
        elif p < 0:
            low = max(low, q / p)
        else:
            high = min(high, q / p)
        if low > high:
            return False
    return True


@dataclass(frozen=True)
class Polygon:
    points: tuple[tuple[float, float], ...]

    def box(self) -> Box:
        xs, ys = zip(*self.points)
        return min(xs), min(ys), max(xs), max(ys)

    def meets(self, box: Box, gap: float = 0.0) -> bool:
        box = grown(box, gap)
        edges = zip(self.points, self.points[1:] + self.points[:1])
        if any(segment_meets(x1, y1, x2, y2, box) for (x1, y1), (x2, y2) in edges):
            return True
        return self.contains((box[0] + box[2]) / 2, (box[1] + box[3]) / 2)  # the box wholly inside

    def contains(self, x: float, y: float) -> bool:
        inside = False
        for (x1, y1), (x2, y2) in zip(self.points, self.points[1:] + self.points[:1]):
            if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
                inside = not inside
        return inside


@dataclass(frozen=True)
class Ring:
    cx: float
    cy: float
    inner: float  # 0: a disc
    outer: float

    def box(self) -> Box:
        return self.cx - self.outer, self.cy - self.outer, self.cx + self.outer, self.cy + self.outer

    def meets(self, box: Box, gap: float = 0.0) -> bool:
        nearest = math.hypot(max(box[0] - self.cx, 0.0, self.cx - box[2]), max(box[1] - self.cy, 0.0, self.cy - box[3]))
        farthest = math.hypot(max(abs(box[0] - self.cx), abs(box[2] - self.cx)),
                              max(abs(box[1] - self.cy), abs(box[3] - self.cy)))
        return nearest <= self.outer + gap and farthest >= self.inner - gap


@dataclass(frozen=True)
class Bar:
    x1: float
    y1: float
    x2: float
    y2: float
    half_width: float

    def box(self) -> Box:
        return grown((min(self.x1, self.x2), min(self.y1, self.y2), max(self.x1, self.x2), max(self.y1, self.y2)),
                     self.half_width)

    def meets(self, box: Box, gap: float = 0.0) -> bool:
        return segment_meets(self.x1, self.y1, self.x2, self.y2, grown(box, gap + self.half_width))
