"""A sweep's grid: the varied quantities as given (``--vary``), checked, and the points they make."""

from __future__ import annotations

import math
from dataclasses import dataclass
from numbers import Real
from typing import Iterator

import numpy as np

from clutchopt.cases import Case, check_across, check_scatter_corners
from clutchopt.errors import InputError, shown_value
from clutchopt.fields_read import fields_read_across, followers
from clutchopt.formulations import get_coupling
from clutchopt.model import Quantity
from clutchopt.units import BelowFloat64, float_text, into_si

MAX_POINTS = 100_000  # points of one sweep: hours of solving; more is a mistake (1e12 would not fit in memory)


@dataclass(frozen=True)
class Vary:
    """One varied quantity: its declaration, its values in SI and, as given in its display unit, the same values (by
    :func:`parse_vary`; without them the table converts the SI values back, e.g. 3000 rpm to 3000.0000000000005)."""

    quantity: Quantity
    values: tuple[float, ...]
    shown: tuple[float, ...] | None = None

    def __post_init__(self):
        """A Vary built by hand holds what :func:`parse_vary` would: at least one value, each a real number, and as
        many shown, each its value in the display unit (review 27: a shown 5 rpm had labelled a point solved at 100
        rad/s, 955 rpm; text had read as SI numbers)."""
        field = f"--vary {self.quantity.name}"
        numbers = (*self.values, *(self.shown or ()))
        if not self.values or not all(isinstance(v, Real) and not isinstance(v, bool) for v in numbers):
            raise InputError(field, "its values must be one or more numbers (SI; shown: in the display unit)")
        if self.shown is not None and (len(self.shown) != len(self.values) or not np.allclose(
                into_si(np.asarray(self.shown, dtype=float), self.quantity.unit), self.values, rtol=1e-9, atol=0.0)):
            raise InputError(field, f"its shown values are not its values in {self.quantity.unit or 'SI'}")

    @property
    def column(self) -> str:
        return column_name(self.quantity.name, self.quantity.unit)


def column_name(name: str, unit: str) -> str:
    return f"{name} [{unit}]" if unit else name


def parse_vary(text: str, coupling: str, quantities: tuple[Quantity, ...] | None = None) -> Vary:
    """``name=start:stop:count`` or ``name=v1,v2,...``, values in the quantity's display unit; ``quantities``:
    those a case may vary (default: the coupling's; ``Case.quantities`` adds a start-up's)."""
    if not isinstance(text, str):
        raise InputError("--vary", f"expected text such as 'speed=500:3000:26', got {shown_value(text)}")
    field = f"--vary {text if len(text) <= 80 else text[:60] + f'... ({len(text)} characters)'}"
    name, sep, spec = text.partition("=")
    declared = {q.name: q for q in quantities or get_coupling(coupling).quantities}
    if not sep or not spec.strip():
        raise InputError(field, "expected name=start:stop:count or name=v1,v2,...")
    quantity = declared.get(name.strip())
    if quantity is None:
        raise InputError(field, f"unknown quantity {name.strip()!r}; the {coupling} coupling has "
                                f"{', '.join(sorted(declared))}")
    numbers = _numbers(field, spec)
    if ":" in spec:
        if len(numbers) != 3 or numbers[2] != int(numbers[2]) or numbers[2] < 1:
            raise InputError(field, "a range is start:stop:count with a whole count >= 1")
        if numbers[2] > MAX_POINTS:
            raise InputError(field, f"{numbers[2]:.15g} values; a sweep has at most {MAX_POINTS:,} points")
        with np.errstate(all="ignore"):
            numbers = np.linspace(numbers[0], numbers[1], int(numbers[2])).tolist()
        if not all(math.isfinite(n) for n in numbers):
            raise InputError(field, "the range's span is beyond the float64 range")
    elif len(numbers) > MAX_POINTS:
        raise InputError(field, f"{len(numbers)} values; a sweep has at most {MAX_POINTS:,} points")
    with np.errstate(all="ignore"):
        values = tuple(np.asarray(into_si(np.asarray(numbers, dtype=float), quantity.unit), dtype=float).tolist())
    if not all(math.isfinite(value) for value in values):
        raise InputError(field, "values beyond the float64 range once converted to SI")
    if any(number != 0.0 and value == 0.0 for number, value in zip(numbers, values)):
        raise InputError(field, "values below the float64 range once converted to SI: they would be read as 0")
    return Vary(quantity, values, tuple(numbers))


def _numbers(field: str, spec: str) -> list[float]:
    try:
        spec = spec.replace("\u2212", "-")  # the typographic minus, as a case file reads it
        numbers = [float_text(part) for part in (spec.split(":") if ":" in spec else spec.split(","))]
    except BelowFloat64 as exc:
        raise InputError(field, str(exc)) from None
    except ValueError:
        raise InputError(field, f"not a number in {shown_value(spec)} (values are plain numbers in the quantity's "
                                "display unit)") from None
    if not all(math.isfinite(n) for n in numbers):
        raise InputError(field, "values must be finite")
    return numbers


def check_grid(varies: list[Vary], zipped: bool = False) -> int:
    """The number of points of the sweep's grid (at most MAX_POINTS; each quantity varied once; a listed sweep's
    lists equally long)."""
    names = [v.quantity.name for v in varies]
    twice = sorted({name for name in names if names.count(name) > 1})
    if twice:
        raise InputError("--vary", f"{', '.join(twice)} varied twice; give all its values in one --vary")
    count = len(varies[0].values) if zipped and varies else math.prod(len(v.values) for v in varies)
    if count > MAX_POINTS:
        raise InputError("--vary", f"the grid has {count:,} points; a sweep has at most {MAX_POINTS:,} "
                                   "(split it, or use fewer values)")
    if zipped:
        lengths = {len(v.values) for v in varies}
        if len(lengths) > 1:
            raise InputError("--zip", f"listed sweeps need equally many values per --vary, got {sorted(lengths)}")
    return count


def grid_points(varies: list[Vary], zipped: bool = False) -> "Points":
    """The sweep's points (see :func:`check_grid`), each varied quantity's values as an array (SI)."""
    count = check_grid(varies, zipped)
    return Points(np.arange(count), {v.quantity.name: np.array(v.values, dtype=float)[taken]
                                     for v, taken in zip(varies, grid_positions(varies, zipped))})


def grid_positions(varies: list[Vary], zipped: bool = False) -> list[np.ndarray | slice]:
    """Which of its values each varied quantity takes at each point of the grid (all of them in order for one
    quantity or a listed sweep)."""
    if zipped or len(varies) < 2:
        return [slice(None)] * len(varies)
    return [a.ravel() for a in np.meshgrid(*(np.arange(len(v.values)) for v in varies), indexing="ij")]


def check_points(case: Case, varies: list[Vary], points: "Points", scattered: bool = False) -> None:
    """Every point is checked before any solve, as a case is: each varied value against its valid range, the point's
    case across its fields (:func:`~clutchopt.cases.check_across`) and, where the sweep designs for the scatter
    (``scattered``), at every corner of the scatter around it; the error names the first point that fails.

    When none of the checks across fields reads a quantity the sweep changes (:mod:`clutchopt.fields_read`), they
    pass or refuse at every point as they do at the case itself: the case is checked once, each point's values
    against their ranges as arrays, and only the first point out of range is built (to raise what it raises)."""
    if not scattered and _checks_once(case, varies, points):
        return
    _check_each(case, points, scattered)


def _check_each(case: Case, points: "Points", scattered: bool = False) -> None:
    for index, values in points.pairs():
        try:
            point = case.with_values(**values)
            check_across(point)
            if scattered:
                check_scatter_corners(point)
        except InputError as exc:
            raise exc.at(f"--vary (point {index})") from None


def _checks_once(case: Case, varies: list[Vary], points: "Points") -> bool:
    """The points checked as :func:`check_points` does, without a case per point, if the checks across fields read
    no changed quantity (False: not known, so each point must be checked)."""
    read = fields_read_across(case)
    if read is None or read & followers(case, [v.quantity.name for v in varies]):
        return False
    good = np.ones(len(points), dtype=bool)
    for v in varies:
        good &= v.quantity.valid(points.columns[v.quantity.name])
    if not good.all():
        _check_each(case, points[good.argmin():good.argmin() + 1])  # raises as that point's case does
    return True


@dataclass(frozen=True)
class Points:
    """Points of a sweep: their indices, and each varied quantity's SI values at them (an array by name)."""

    index: np.ndarray
    columns: dict[str, np.ndarray]

    def __len__(self) -> int:
        return len(self.index)

    def __getitem__(self, part: slice | np.ndarray) -> "Points":
        return Points(self.index[part], {name: column[part] for name, column in self.columns.items()})

    def values(self) -> list[dict[str, float]]:
        """Each point's values by quantity name."""
        names = list(self.columns)
        if len(names) == 1:  # the common case, without a tuple per point
            return [{names[0]: value} for value in self.columns[names[0]].tolist()]
        rows = zip(*(column.tolist() for column in self.columns.values())) if names else [()] * len(self)
        return [dict(zip(names, row)) for row in rows]

    def pairs(self) -> Iterator[tuple[int, dict[str, float]]]:
        """Each point's index and values."""
        return zip(self.index.tolist(), self.values())

    @classmethod
    def joined(cls, parts: list["Points"]) -> "Points":
        return cls(np.concatenate([p.index for p in parts]),
                   {name: np.concatenate([p.columns[name] for p in parts]) for name in parts[0].columns})
