"""A start-up under scatter: its start designed at one corner (of the ranges, or of the quantiles), each of its
constraints at its own, simulated at every corner and by Monte Carlo of simulated starts
(``clutchopt.optimise.robust``; docs/robust.md)."""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from types import SimpleNamespace
from typing import NamedTuple

import numpy as np

from clutchopt.cases import Case
from clutchopt.formulations import get_coupling
from clutchopt.model import Quantity, namespace
from clutchopt.optimise.robust_models import SEED, START_UP, clopper_pearson, corner_table, design_at
from clutchopt.optimise.verify import ConstraintCheck, check_constraints
from clutchopt.scatter import Scatter, _within, draw
from clutchopt.start_up.drive import CLOSED_FORM, Structure

START_SAMPLES = 200  # simulated starts of a start-up's Monte Carlo (about 30 ms of CPU each)
START_RTOL = 1e-9  # of the simulated starts: far inside a start-up's tolerance (1e-6)
MAX_START_CORNERS = 4  # scattered quantities up to which a start-up is simulated at all 2^n corners
TIE = 1e-9  # relative margins this near are one (the corners' starts are simulated at START_RTOL): of such corners
#             the first is the worst, not the one round-off makes smaller (lock_up_speed, which driven_inertia does
#             not move, 1e-14 apart at its two ends: the corner flipped from one robust solve to the next)


# --- A start-up under scatter: designed at one corner, simulated at every corner and by Monte Carlo -------------------
def quantile(s: Scatter, probability: float, quantity: Quantity) -> float:
    """The value a scattered quantity stays below with ``probability`` (:meth:`Scatter.from_standard` of its normal
    quantile), cut where the quantity's valid range ends."""
    from scipy.special import ndtri

    return _within(quantity, float(s.from_standard(ndtri(probability))))


def quantile_ends(case: Case, scatter, share: float) -> dict[str, tuple[float, float]]:
    """Quantity -> its quantiles 1 - ``share`` and ``share`` (:func:`quantile`)."""
    declared = {q.name: q for q in case.quantities}
    return {s.name: (quantile(s, 1.0 - share, declared[s.name]), quantile(s, share, declared[s.name]))
            for s in scatter}


class StartUpCorners(NamedTuple):
    """A start-up under scatter at a design (:func:`start_up_corners`)."""

    ends: dict[str, tuple[float, float]]  # quantity -> its two ends: of its range, or its quantiles
    corners: dict[str, dict[str, float]]  # START_UP and each start-up constraint -> quantity -> value
    bars: Mapping[str, dict[str, float]]  # constraint -> quantity -> change of its margin over the range, others
    # nominal (a dict, or :class:`Bars` simulated on first read)


def start_up_corners(case: Case, mode: str, design: dict, scatter, target: float | None = None) -> StartUpCorners:
    """Where a start-up under scatter is designed at ``design``, simulated at each end of each quantity's range
    alone (the others nominal: the tornado's bars) and at the corners.

    The ends: those of its range or, with a ``target`` P (chance), its quantiles 1 - P_k and P_k, P_k = P^(1/k) for
    the k quantities that move the start-up's margins at all, through its figures or its limits (Sidak: margins
    monotone in each of k independent quantities are smaller than at every corner of their P_k quantiles only when
    one of them lies beyond its quantile, with probability 1 - P_k^k = 1 - P).
    The corners: each start-up constraint's own, where its margin is smallest (a limit at its strict end, whatever
    the figures do; the engagement window at the preload that narrows it), and START_UP, where the start is
    simulated in the NLP: where the smallest margin of the constraints that read its figures is smallest (a start
    that does not lock up counts as the worst). Of all 2^k corners, up to MAX_START_CORNERS quantities; with more,
    each quantity at the end where that margin is smaller alone."""
    names, alone = _alone(case, mode, design, scatter)
    ends = {s.name: (s.low, s.high) for s in scatter}
    if target is not None:
        moving = sum(not np.array_equal(low, high) for low, high in alone.values())
        ends = quantile_ends(case, scatter, target ** (1.0 / max(1, moving)))
    if len(scatter) <= MAX_START_CORNERS:
        points = corner_points(corner_table(scatter, ends))
        margins = np.array([_margins(run) for run in simulated_start_ups(case, mode, design, points)])

        def worst(columns: list[int]) -> dict[str, float]:
            return points[worst_corner(margins[:, columns].min(axis=1))]
    else:
        def worst(columns: list[int]) -> dict[str, float]:
            return {q: ends[q][worst_corner(np.array([low[columns].min(), high[columns].min()]))]
                    for q, (low, high) in alone.items()}

    figures = [i for i, name in enumerate(names) if name not in CLOSED_FORM]
    return StartUpCorners(ends, {START_UP: worst(figures), **{name: worst([i]) for i, name in enumerate(names)}},
                          _bars(names, alone))


def _alone(case: Case, mode: str, design: dict, scatter) -> tuple[list[str], dict[str, list[np.ndarray]]]:
    """(the start-up limits' names, quantity -> the limits' relative margins with the start simulated at each end of
    its range, the others nominal)."""
    runs = {s.name: simulated_start_ups(case, mode, design, [{s.name: s.low}, {s.name: s.high}]) for s in scatter}
    return [c.name for c in next(iter(runs.values()))[0]], {q: [_margins(run) for run in pair]
                                                            for q, pair in runs.items()}


def _bars(names: list[str], alone: dict[str, list[np.ndarray]]) -> dict[str, dict[str, float]]:
    return {name: {q: float(high[i]) - float(low[i]) for q, (low, high) in alone.items()}
            for i, name in enumerate(names)}


def start_up_bars(case: Case, mode: str, design: dict, scatter) -> dict[str, dict[str, float]]:
    """The tornado's bars of the start-up limits: limit -> quantity -> change of its relative margin as the
    quantity goes from the low to the high end of its range, the others nominal (simulated)."""
    return _bars(*_alone(case, mode, design, scatter))


class Bars(Mapping):
    """:func:`start_up_bars` at a design, simulated on first read (2 starts per quantity): a SORA loop finds the
    start-up's corners at every design and shows the bars of its last only. ``known``: bars already simulated at
    that design (a :class:`StartUpCorners`' of :func:`start_up_corners`, from the same starts)."""

    def __init__(self, case: Case, mode: str, design: dict, scatter):
        self.at, self.bars = (case, mode, design, scatter), None

    def known(self, bars: dict[str, dict[str, float]]) -> None:
        self.bars = bars if self.bars is None else self.bars

    def _simulated(self) -> dict[str, dict[str, float]]:
        if self.bars is None:
            self.bars = start_up_bars(*self.at)
        return self.bars

    def __getitem__(self, name: str) -> dict[str, float]:
        return self._simulated()[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._simulated())

    def __len__(self) -> int:
        return len(self._simulated())


def worst_corner(margins: np.ndarray) -> int:
    """The corner (an index of ``margins``, each corner's smallest relative margin) where the margin is smallest: the
    first within TIE of the smallest, so that corners round-off tells apart do not trade places between solves."""
    return int(np.flatnonzero(margins <= margins.min() + TIE)[0])


def _margins(run: list[ConstraintCheck]) -> np.ndarray:
    """The relative margins of one simulated start's checks, a start that does not lock up (NaN) the worst."""
    return np.array([-math.inf if math.isnan(c.margin) else c.margin for c in run])


def corner_points(table: dict[str, np.ndarray]) -> list[dict[str, float]]:
    """The corners of a corner table, one dict each."""
    return [{q: float(values[i]) for q, values in table.items()} for i in range(len(next(iter(table.values()))))]


def start_up_corner(case: Case, mode: str, design: dict, scatter, target: float | None = None) -> dict[str, float]:
    """The corner a start-up's start is designed at, where it binds (:func:`start_up_corners`: of the ranges, or
    with a ``target`` of the quantiles)."""
    return start_up_corners(case, mode, design, scatter, target).corners[START_UP]


def simulated_start_ups(case: Case, mode: str, design: dict, points: list[dict]) -> list[list[ConstraintCheck]]:
    """Every start-up limit of the case (start time, friction work, temperature rise, engagement and lock-up
    speeds, ...) checked with the design's start simulated at each point (scattered quantity -> value, the defaults
    that follow one following it): a list of checks per point, in one order."""
    from clutchopt.start_up.drive import Drive, named_constraints
    from clutchopt.start_up.simulation import run_start_up, start_up_model

    law = get_coupling(case.coupling).formulation(mode).speed_law
    runs = []
    for point in points:
        at, seen = case.with_values(**point), design_at(design, point)
        structure = Structure.of(at)
        result = run_start_up(start_up_model(at, mode, seen, rtol=START_RTOL))
        head = result.headline
        figures = SimpleNamespace(
            start_time=head["start_time"], friction_work=head["friction_work"], lock_up_speed=head["lock_up_speed"],
            temperatures=head.get("temperature_rise", 0.0),
            stresses=result.columns["stress"] if structure.elastic and head["locks_up"] else math.inf)
        drive = Drive(structure, law, namespace(seen), at.params())
        runs.append(check_constraints(named_constraints(structure, drive, figures), structure.spec.tolerance))
    return runs


def start_up_checks(case: Case, mode: str, design: dict, points: list[dict]) -> list[ConstraintCheck]:
    """The start-up's limits simulated at each point, each reported at its worst."""
    return [min(column, key=lambda c: -math.inf if math.isnan(c.margin) else c.margin)
            for column in zip(*simulated_start_ups(case, mode, design, points))]


def start_up_failures(case: Case, mode: str, design: dict, scatter, starts: int = START_SAMPLES,
                      seed: int = SEED) -> dict[str, list[float]]:
    """Monte Carlo of the simulated start: ``starts`` draws of the distributions (cut where each quantity's valid
    range ends; correlated as the case's [scatter.correlation] when ``scatter`` is the case's), each start-up
    limit's failure probability with its Clopper-Pearson interval."""
    declared = {q.name: q for q in case.quantities}
    correlation = case.correlation if tuple(scatter) == case.scatter else None
    drawn = draw(scatter, np.random.default_rng(seed), starts, correlation)
    points = [{q: _within(declared[q], float(values[i])) for q, values in drawn.items()} for i in range(starts)]
    return {column[0].name: clopper_pearson(sum(not c.feasible for c in column), starts)
            for column in zip(*simulated_start_ups(case, mode, design, points))}
