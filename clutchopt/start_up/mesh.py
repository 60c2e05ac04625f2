"""The mesh of a start-up's collocation: interval lengths per phase, first graded where the motor runs up, then
adapted to the simulated start; the intervals are doubled where adapting no longer pays (docs/start_up.md).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

MAX_INTERVALS = 128  # per phase, refining by doubling
MESH_STEPS = 3  # adaptations of the mesh to the simulated start before the intervals are doubled
MONITOR_FLOOR = 0.2  # of the mean error monitor, added everywhere: no interval grows without bound
STILL = 1e-9  # a state whose spread over a phase is below this share of its spread over the start stands still
GRADED_PARTS = (0.05, 0.1, 0.2, 0.4)  # share of the slip phase graded: the motor's knee times 20, rounded up
KNEE_PARTS = (0.01, 0.02) + GRADED_PARTS  # the same from the knee a simulated start shows (:func:`knee_part`)
KNEE_COVER = 6.0  # times the simulated knee the graded part covers (the optimum's knee: up to twice the start's)


@lru_cache(maxsize=64)
def graded_mesh(intervals: int, graded_part: float = 0.05, first: float = 1e-4) -> np.ndarray:
    """Interval lengths (fractions of a phase, summing to 1): half the intervals grow geometrically from ``first``
    over the first ``graded_part`` of the phase, the rest are uniform. The motor's run-up to the speed where its
    torque meets the coupling's (a knee over a small part of the start) lies in the graded part. Found once per
    arguments (a root of the geometric series: 55 us, twice a cold start-up solve), read only."""
    mesh = _graded_mesh(intervals, graded_part, first)
    mesh.setflags(write=False)
    return mesh


def _graded_mesh(intervals: int, graded_part: float, first: float) -> np.ndarray:
    graded = intervals // 2
    if graded < 2:
        return np.full(intervals, 1.0 / intervals)
    from scipy.optimize import brentq  # scipy.optimize costs 0.3 s to import: only problems with a start-up pay it

    largest = (graded_part / first) ** (1.0 / (graded - 1))  # the last term alone reaches the graded part
    ratio = brentq(lambda r: first * (r**graded - 1.0) / (r - 1.0) - graded_part, 1.0 + 1e-12, largest)
    lengths = first * ratio ** np.arange(graded)
    uniform = np.full(intervals - graded, (1.0 - graded_part) / (intervals - graded))
    return np.concatenate([lengths / lengths.sum() * graded_part, uniform])


def first_mesh(structure, phase: str, graded_part: float) -> np.ndarray:
    """Interval lengths of a phase as fractions of its duration before any adaptation: graded where the motor
    runs up through the slip phase's start (over ``graded_part``), uniform elsewhere."""
    if phase == "slip" and structure.motor:
        return graded_mesh(structure.intervals, graded_part)
    return np.full(structure.intervals, 1.0 / structure.intervals)


def knee_part(structure, history, slip: tuple[float, float], graded_part: float) -> float:
    """The graded part of the slip phase from a simulated start whose slip phase spans ``slip`` (begin, end): the
    share of the phase until the driver's speed settles within the start-up's tolerance of its speed at the phase's
    end (the motor's knee: its run-up until its torque meets the coupling's), KNEE_COVER times over, rounded up to
    one of KNEE_PARTS; never more than the case's ``graded_part`` (``drive.graded_part``: from the motor's run-up
    time at breakdown torque, which takes the knee from rest, where the slip phase takes it from the breakaway's
    speed)."""
    begin, end = slip
    t = np.asarray(history["t"])
    inside = (t >= begin) & (t <= end)
    if not structure.motor or not end > begin or inside.sum() < 5:
        return graded_part
    speed = np.asarray(history["w_driver"])[inside]
    unsettled = np.nonzero(np.abs(speed - speed[-1]) > structure.spec.tolerance * abs(speed[-1]))[0]
    settled = t[inside][min(unsettled[-1] + 1, len(speed) - 1)] if len(unsettled) else begin
    share = KNEE_COVER * (settled - begin) / (end - begin)
    return min(next((part for part in KNEE_PARTS if part >= share), KNEE_PARTS[-1]), graded_part)


MONITORED = ("w_driver", "w_driven", "friction_work", "temperature_rise")  # the states :func:`adapted_mesh` reads


class Meshes:
    """A start-up solve's meshes, read as the pair (used, suggested): the one it was solved on and the one its
    simulated start suggests for the next solve (:func:`adapted_mesh` of ``history``'s columns over ``phase_times``,
    ``graded_part`` the case's), worked out where it is first read, from the same arrays: most checks' suggestion is
    never read (a sweep's point within the tolerance solves on no other mesh), 0.4 ms a check."""

    def __init__(self, used: np.ndarray, structure, history, phase_times: list[float], graded_part: float):
        self._used, self._suggested = used, None
        self._from = (structure, {name: history[name] for name in ("t",) + MONITORED}, phase_times, graded_part)

    def __getitem__(self, index: int) -> np.ndarray:
        if index in (0, -2):
            return self._used
        if index in (1, -1):
            return self.suggested
        raise IndexError(index)

    def __len__(self) -> int:
        return 2

    def __getstate__(self) -> dict:
        """Pickled with the suggestion adapted (a solution sent to another process: the mesh, not the columns)."""
        return {"_used": self._used, "_suggested": self.suggested, "_from": None}

    @property
    def suggested(self) -> np.ndarray:
        """The mesh the simulated start suggests, adapted on first read (its columns then let go; read by two threads
        at once, adapted twice, the same mesh: ``_suggested`` is set before ``_from`` is let go)."""
        source = self._from
        if source is not None:
            self._suggested, self._from = adapted_mesh(*source), None
        return self._suggested


def settled(meshes) -> None:
    """A solution's meshes (None, a pair or :class:`Meshes`) with the suggestion adapted and the simulation's columns
    (50-90 kB a start-up) let go: for a solution kept beyond its point (a sweep's points waiting for a feasible
    neighbour, a failed start kept to be known again)."""
    if isinstance(meshes, Meshes):
        meshes.suggested  # (read: adapted)


def adapted_mesh(structure, history, phase_times: list[float], graded_part: float) -> np.ndarray:
    """A mesh for the next solve from the simulated start, over the NLP's phase timing: each phase's intervals
    equidistribute sqrt|x''| of the states (each scaled by its range and the phase duration), the error
    monitor of a corner (the motor's knee), with a fifth of its mean over the phase added everywhere; a phase the
    start hardly samples keeps its first mesh (``graded_part``: the case's, ``drive.graded_part``)."""
    t_all = np.asarray(history["t"])  # a run's columns (arrays) or its history (a DataFrame)
    columns = np.array([history[name] for name in MONITORED], dtype=float)
    ranges = columns.max(axis=1) - columns.min(axis=1)  # each state's spread over the start
    meshes, begin = [], 0.0
    for phase, end in zip(structure.phases, np.cumsum(phase_times)):
        inside = (t_all >= begin) & (t_all <= end)
        t, first = np.unique(t_all[inside], return_index=True)
        if not end > begin or len(t) < 5:
            meshes.append(first_mesh(structure, phase, graded_part))
            begin = end
            continue
        span = end - begin
        values = columns[:, inside][:, first]
        spreads = values.max(axis=1) - values.min(axis=1)
        moving = spreads > STILL * ranges  # a state at rest but for rounding shapes nothing
        curvature = np.abs(_second_derivative(values[moving], t))
        monitor = np.zeros(len(t))
        for row, spread in zip(curvature, spreads[moving]):  # the states in turn, summed in the same order
            monitor += row * span * span / spread
        weight = _cumulative(np.sqrt(monitor), t)
        mean = weight[-1] / (t[-1] - t[0])  # over time: the samples crowd where the solver's steps are short
        weight = weight + MONITOR_FLOOR * mean * (t - t[0]) if mean > 0 else t - t[0]
        edges = np.interp(np.linspace(0.0, weight[-1], structure.intervals + 1), weight, (t - begin) / span)
        edges[0], edges[-1] = 0.0, 1.0
        meshes.append(np.diff(edges))
        begin = end
    return np.concatenate(meshes)


def _second_derivative(values: np.ndarray, t: np.ndarray) -> np.ndarray:
    """np.gradient(np.gradient(values, t, axis=1), t, axis=1) with the weights of its differences over ``t`` formed
    once, not twice a gradient (the same operations, the same bits: 0.1 of a check's 0.6 ms of mesh a phase)."""
    dx = np.diff(t)
    if (dx == dx[0]).all():  # a uniform spacing: np.gradient's own case
        return np.gradient(np.gradient(values, dx[0], axis=1), dx[0], axis=1)
    before, after = dx[:-1], dx[1:]
    weights = (-after / (before * (before + after)), (after - before) / (before * after),
               before / (after * (before + after)))

    def slope(f):
        out = np.empty_like(f)
        out[:, 1:-1] = weights[0] * f[:, :-2] + weights[1] * f[:, 1:-1] + weights[2] * f[:, 2:]
        out[:, 0] = (f[:, 1] - f[:, 0]) / dx[0]
        out[:, -1] = (f[:, -1] - f[:, -2]) / dx[-1]
        return out

    return slope(slope(values))


def _cumulative(values: np.ndarray, t: np.ndarray) -> np.ndarray:
    """The integral of ``values`` over ``t`` from its start, by trapezoids."""
    return np.concatenate([[0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * np.diff(t))])
