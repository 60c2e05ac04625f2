"""The labels of a sketch, placed where they cover no part and no other label.

A label's box is measured with the metrics of DejaVu Sans (the sketches' font; matplotlib ships it, and it is
wider than the usual fallbacks, so a box measured here holds the text drawn in another sans-serif face). Each label
has its spots in order of preference (beside its dimension line, round its point); the first spot whose box meets
no part, no label placed before it and no line of another dimension is taken; failing that, a spot beside the view,
with a leader line to what it names; then the same two without regard to the lines.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

from clutchopt.report.sketch.shapes import Bar, Box, boxes_meet

FONTS = {"dimtext": (12.0, "normal"), "dimtext opt": (12.0, "bold"), "title": (13.0, "bold"), "note": (11.0, "normal")}
FAMILY = "DejaVu Sans"
ASCENT, DESCENT = 0.93, 0.24  # of the font size: DejaVu Sans's line box above and below the baseline
CLEAR = 3.0  # px kept clear between a label and a part, a line or another label
LEADER_GAP = 14.0  # px between a view's drawing and a label beside it
ROW = 18.0  # px between the rows of labels beside or below a view


@lru_cache(maxsize=None)
def text_width(text: str, cls: str) -> float:
    """The advance width of ``text`` in px, as a label of class ``cls``."""
    from matplotlib.font_manager import FontProperties
    from matplotlib.textpath import TextToPath

    size, weight = FONTS[cls]
    width, _, _ = TextToPath().get_text_width_height_descent(
        text, FontProperties(family=FAMILY, size=size, weight=weight), ismath=False)
    return width


@dataclass(frozen=True)
class Spot:
    """Where a label's text is anchored: its baseline's start, middle or end at (x, y) px."""

    x: float
    y: float
    anchor: str = "middle"


def box_of(text: str, cls: str, spot: Spot) -> Box:
    width, size = text_width(text, cls), FONTS[cls][0]
    left = spot.x - {"start": 0.0, "middle": width / 2, "end": width}[spot.anchor]
    return left, spot.y - ASCENT * size, left + width, spot.y + DESCENT * size


def centred(cls: str, cx: float, cy: float) -> Spot:
    """The spot that centres a label's box on (cx, cy)."""
    return Spot(cx, cy + (ASCENT - DESCENT) * FONTS[cls][0] / 2)


def size_of(text: str, cls: str) -> tuple[float, float]:
    return text_width(text, cls), (ASCENT + DESCENT) * FONTS[cls][0]


def beside(text: str, cls: str, x: float, y: float, nx: float, ny: float) -> Spot:
    """The spot whose box lies beside (x, y), CLEAR px off in the direction (nx, ny) (a unit vector)."""
    width, height = size_of(text, cls)
    reach = CLEAR + abs(nx) * width / 2 + abs(ny) * height / 2
    return centred(cls, x + nx * reach, y + ny * reach)


@dataclass
class Label:
    text: str
    cls: str
    spots: list[Spot]  # in order of preference
    target: tuple[float, float] | None = None  # px: what a leader points at when the label goes beside the view
    owner: int = -1  # the lines of its own dimension (they may touch it)
    placed: Spot | None = None
    leader: Bar | None = None

    def box(self, spot: Spot | None = None) -> Box:
        return box_of(self.text, self.cls, spot or self.placed)


@dataclass
class Obstacles:
    """What a label must keep clear of: parts (never covered), lines (avoided where a spot allows), labels placed."""

    parts: list = field(default_factory=list)
    lines: list[tuple[int, object]] = field(default_factory=list)  # (owner, shape)
    labels: list[Box] = field(default_factory=list)

    def free(self, box: Box, owner: int, lines: bool) -> bool:
        if any(boxes_meet(box, (b[0] - CLEAR, b[1] - CLEAR, b[2] + CLEAR, b[3] + CLEAR)) for b in self.labels):
            return False
        if any(shape.meets(box, CLEAR) for shape in self.parts):
            return False
        return not lines or not any(shape.meets(box, CLEAR) for who, shape in self.lines if who != owner or who < 0)

    def take(self, label: Label) -> None:
        self.labels.append(label.box())
        if label.leader is not None:
            self.lines.append((label.owner, label.leader))


def place(label: Label, obstacles: Obstacles, envelope: Box) -> None:
    """Put ``label`` on its first free spot (see the module's docstring); ``envelope``: its view's drawing."""
    away = beside_view(label, envelope)
    for lines, spots in ((True, label.spots), (True, away), (False, label.spots), (False, away)):
        for spot in spots:
            if obstacles.free(label.box(spot), label.owner, lines):
                label.placed = spot
                if spots is away:
                    label.leader = leader(label)
                obstacles.take(label)
                return
    label.placed = label.spots[0]  # nowhere free: the browser test names it
    obstacles.take(label)


def beside_view(label: Label, envelope: Box, rows: int = 12) -> list[Spot]:
    """Spots left and right of the view, the target's side first, from the target's height outward by rows."""
    if label.target is None:
        return []
    x, y = label.target
    right = Spot(envelope[2] + LEADER_GAP, 0.0, "start")
    left = Spot(envelope[0] - LEADER_GAP, 0.0, "end")
    sides = (right, left) if x >= (envelope[0] + envelope[2]) / 2 else (left, right)
    baseline = centred(label.cls, x, y).y
    offsets = [0.0] + [sign * ROW * i for i in range(1, rows) for sign in (1, -1)]
    return [Spot(side.x, baseline + dy, side.anchor) for side in sides for dy in offsets]


def leader(label: Label) -> Bar:
    """A line from the label's near side to its target."""
    box, (x, y) = label.box(), label.target
    start = box[0] - 2 if label.placed.anchor == "start" else box[2] + 2
    return Bar(start, (box[1] + box[3]) / 2, x, y, 0.5)


def column(x: float, first: float, step: float, anchor: str, rows: int = 40) -> list[Spot]:
    """Spots in a column at ``x``: the baselines ``first``, ``first + step``, ... (a negative step goes up)."""
    return [Spot(x, first + step * i, anchor) for i in range(rows)]
