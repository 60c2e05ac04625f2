"""How many points a batched sweep chains next (``clutchopt.optimise.batch``).

A chained call cannot stop early: a chain that runs past the point where it fails a test spends a solve on every
point after it, for nothing; one that stops short of that point costs one more call (0.1-0.2 ms with its checks)
but no solve. Along a smooth stretch chains double from ``first`` to ``longest`` points while they pass. Where the
integer search has decided a point (a chain broke there: its integers excluded, or a neighbouring integer promised
a gain), the next break is expected as far on as the last gap between breaks, grown as that gap grew from the one
before (the relaxed integer crosses integer boundaries at a slowly changing pace along a sweep of evenly or
geometrically spaced points), and the chain ends at that point: a break on a chain's last point wastes nothing, its
column being the search's first attempt; it ends one point short of that (:data:`SHORT`), so that a break one
point sooner wastes nothing either, and the probe after it takes the expected break. Should the chain pass, the
break is near: the next chains are probes of one point (two: :data:`PROBES`), then doubling again. After the first
break (no gap known yet) the next chain is ``first`` points long, probing after it; after a point solved alone,
chains restart from ``first``, unless the chain failed at its first point with integers to search: that point is a
break (``BatchSweep.run``), so that where the integers are decided at every point the chains are one point long (the
ball over its power past 4.6x: chains of 8 had failed at their first point, 7 solves lost at each).

With free integers a chain also ends where an inactive constraint or bound is expected to become active
(:func:`until_active`), where a fixed integer's multiplier can jump from nothing (the ball over its power: its first
chain past 4.5x had run 35 points past the break); a chain aimed at a break and cut short there leaves the rest of the
way to the next chain. A search that keeps the chain's integers (its promised neighbour without a design, ruled out
from then on) is no break. The slacks are followed from the last two kept points with the same integers, also the
first two after a break, and also where the integers' multipliers promise a gain at neighbours that are ruled out:
where the rows of the ball carry no more past 7.5x its power, the slack that closes there foretold each break.

Measured on the 100-point user sweeps of the benchmark (``docs/tradeoffs.md``, "Batches"): the cable over its
allowable stress broke at 7 points with gaps 9, 9, 11, 13, 16, 21, the ball over its speed at 7 with gaps 9, 9, 10,
11, 13, 14; with chains doubling past each break, 48 and 31 solves went to points after a break.
"""

from __future__ import annotations

import numpy as np

PROBE = 1  # the chain after one aimed at an expected break passed: the break is most often the next point (of 10
# predicted gaps on the cable and ball sweeps, 4 were exact, 4 one point longer, 1 two longer, 1 one shorter)
PROBES = 2  # probes of PROBE points before doubling again (a break one point past the aim ends the second probe)
SHORT = 1  # an aimed chain ends this many points before the expected break: a break there or one point sooner wastes
# nothing (its probe, or the chain's last column, is the search's first attempt), where a chain aimed at the break
# itself spent a solve on each point past a break that came sooner (the ball over its power 1x-10x, rows rising every
# 3-5 points as each carries no more: 2 of 6)


class BatchPace:
    """The length of the next chain (:attr:`size`), told what became of each: passed whole, broke for the integer
    search at a point, or ended in a point solved alone."""

    def __init__(self, first: int, longest: int):
        self.first, self.longest = first, longest
        self.size = first
        self._breaks: list[int] = []  # the last three points where the integer search decided
        self._aimed = False  # the size ends the chain at an expected break
        self._probes = 0  # probes left after this one

    def passed(self, points: int | None = None) -> None:
        """A chain of :attr:`size` points (or ``points``) passed every test: doubled, or a probe after one aimed at a
        break; a chain aimed at a break but cut short (an active set expected to change before it: ``until_active``)
        leaves the rest of the way to it for the next chain."""
        if self._aimed and points is not None and points < self.size:
            self.size -= points
        elif self._aimed:
            self.size, self._aimed, self._probes = PROBE, False, PROBES - 1
        elif self._probes:
            self._probes -= 1
        else:
            self.size = min(2 * self.size, self.longest)

    def broke(self, k: int) -> None:
        """The integer search decided point ``k``: the next chain ends where the next break is expected."""
        self._breaks = (self._breaks + [k])[-3:]
        gaps = [b - a for a, b in zip(self._breaks, self._breaks[1:])]
        if not gaps:  # no gap known: a first chain as after a point solved alone, probing after it
            self.size, self._aimed = self.first, True
            return
        growth = min(max(gaps[-1] / gaps[0], 0.5), 2.0)  # 1 with a single gap
        self.size, self._aimed = min(max(1, round(gaps[-1] * growth) - SHORT), self.longest), True

    def near(self) -> None:
        """The integer search kept the chain's integers at a point where a neighbour promised a gain and, solved, did
        worse: the integers are near a change (on ``ball_crusher``'s rows most often at the next point, where they
        carry no more), and the next chains are probes (:data:`PROBES`); no break is recorded (a pace aimed by gaps of
        one point between such a point and the change had run chains of 9 that failed at their first point)."""
        self.size, self._aimed, self._probes = PROBE, False, PROBES - 1

    @property
    def state(self) -> dict:
        """What the next chains depend on, as numbers (a resumed sweep's window takes it back: ``carry``)."""
        return {"size": self.size, "breaks": list(self._breaks), "aimed": self._aimed, "probes": self._probes}

    def carry(self, state: dict) -> None:
        """Go on as :attr:`state` left off."""
        self.size, self._breaks, self._aimed, self._probes = (int(state["size"]), [int(b) for b in state["breaks"]],
                                                              bool(state["aimed"]), int(state["probes"]))

    def restart(self) -> None:
        """A point failed a test other than the integer search's (solved alone): chains restart from ``first``."""
        self.size, self._aimed, self._probes = self.first, False, 0


def until_active(posed, block, ratios, free: np.ndarray, tol: float) -> int | None:
    """Points ahead of ``block`` (batched points with free integers, its last two consecutive with the same
    integers: a chain's, or a search's and a chain's) until the first
    where an inactive constraint row or variable bound is expected to become active, or None (none is expected, or
    the block has one point). A change of the active set is where a fixed integer's bound multiplier jumps (the ball
    over its power: 0 at 7 rows up to 4.5x, where the contact stress becomes active and one row fewer is promised
    from the next point on) and where the chain's integers may stop serving (its rows at their largest radius): a
    chain that ends there wastes no solve on the points after it (the ball's first chain past 4.5x: 35 solves). Each
    slack (the row's -g, the variable's distance to its bound, scaled) is followed from its last value by its last
    step, grown as the case's steps grow (``ratios``, each point's step against the one before: a geometric sweep's
    steps grow by the same factor); ``free``: the variables neither fixed nor integer; ``tol``: a slack or multiplier
    within it is taken as active."""
    if len(block.index) < 2:
        return None
    a = block.arrays
    x, lam_x, lam_g = a["x"][:, -2:], a["lam_x"][:, -1], a["lam_g"][:, -1]
    g = np.asarray(posed.mapped(posed.constraint_values, 2)(x, a["p"][:, -2:])[0])
    slack = np.concatenate([-g[: posed.n_ineq][np.abs(lam_g[: posed.n_ineq]) <= tol],
                            (x - a["lbx"][:, -2:])[free & (np.abs(lam_x) <= tol)],
                            (a["ubx"][:, -2:] - x)[free & (np.abs(lam_x) <= tol)]])
    step = slack[:, 1] - slack[:, 0]
    closing = (slack[:, 1] > tol) & (step < 0)
    if not closing.any():
        return None
    ahead = np.cumsum(np.cumprod(np.where(ratios > 0, ratios, 1.0)))  # the slack's steps ahead, summed
    left = slack[closing, 1:2] + step[closing, None] * ahead  # each closing slack over the points ahead
    reached = (left <= 0).any(axis=0)
    return int(np.argmax(reached)) + 1 if reached.any() else None
