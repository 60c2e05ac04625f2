"""The ``[scatter]`` section of a case: how far case quantities may stray from their nominal values.

A friction coefficient is never one number (lining batch, temperature, wear, humidity); densities, allowable
stresses, the driven inertia and the load have tolerances too. Layout (quantities with units, as in the case)::

    [scatter]
    friction_coefficient = [0.12, 0.18]                      # a range: low, high
    inertia = { normal = ["12 kg*m^2", "0.6 kg*m^2"] }        # a normal distribution: mean, standard deviation
    allowable_pressure = { uniform = ["1.35 MPa", "1.65 MPa"] }  # a uniform distribution: low, high

Worst-case designs use each quantity's range (a normal distribution: mean +- 3 standard deviations, cut to the
quantity's valid range); chance-constrained designs use its distribution (a range: uniform over it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from clutchopt.errors import InputError, Problems, shown_value
from clutchopt.units import to_si

SECTION = "scatter"
MAX_SCATTERED = 12  # quantities; worst-case designs check all 2^n corners
NORMAL_RANGE = 3.0  # standard deviations either side of the mean: a normal quantity's worst-case range
MEAN_TOLERANCE = 1e-9  # relative: a normal distribution's mean is the case's value (given in another unit)


@dataclass(frozen=True)
class Scatter:
    """One scattered quantity (SI): its worst-case range and its distribution."""

    name: str
    kind: str  # "range" | "normal" | "uniform"
    low: float  # worst-case range
    high: float
    mean: float  # distribution: normal (mean, sd); range and uniform: uniform over [low, high]
    sd: float

    def from_standard(self, u):
        """The quantity's value where a standard normal variable takes ``u`` (floats or arrays): the exact
        isoprobabilistic map x = F^-1(Phi(u)) (Rosenblatt; a normal: mean + sd u, a range or uniform:
        low + (high - low) Phi(u))."""
        from scipy.special import ndtr

        u = np.asarray(u, dtype=float)
        if self.kind == "normal":
            return self.mean + self.sd * u
        return self.low + (self.high - self.low) * ndtr(u)

    def to_standard(self, x):
        """The standard normal value u with :meth:`from_standard` (u) = ``x``: u = Phi^-1(F(x))."""
        from scipy.special import ndtri

        x = np.asarray(x, dtype=float)
        if self.kind == "normal":
            return (x - self.mean) / self.sd
        return ndtri((x - self.low) / (self.high - self.low))

    def describe(self, unit_shown) -> str:
        if self.kind == "normal":
            return f"normal, mean {unit_shown(self.mean)}, sd {unit_shown(self.sd)}"
        return f"{self.kind} {unit_shown(self.low)} to {unit_shown(self.high)}"


def correlated(u: np.ndarray, correlation=None) -> np.ndarray:
    """Independent standard normals ``u`` (one row per scattered quantity) made correlated standard normals
    z = L u, L the Cholesky factor of ``correlation`` (n x n, the correlations of the standard normal variables:
    a Gaussian copula); None: independent, z = u."""
    if correlation is None:
        return u
    return np.linalg.cholesky(np.asarray(correlation, dtype=float)) @ u


def values_from_standard(scatters, u, correlation=None) -> dict[str, np.ndarray]:
    """Quantity -> its values where the independent standard normals ``u`` (n rows in the order of ``scatters``,
    any number of columns) take theirs: correlated (:func:`correlated`), then mapped exactly
    (:meth:`Scatter.from_standard`). The map FORM, SORM and importance sampling work through."""
    z = correlated(np.asarray(u, dtype=float), correlation)
    return {s.name: s.from_standard(z[i]) for i, s in enumerate(scatters)}


def draw(scatters, rng: np.random.Generator, count: int, correlation=None) -> dict[str, np.ndarray]:
    """``count`` Monte Carlo draws of the scattered quantities: standard normals, correlated by ``correlation``
    (None: independent), mapped to each quantity's distribution (:func:`values_from_standard`)."""
    return values_from_standard(scatters, rng.standard_normal((len(scatters), count)), correlation)


def parse_scatter(table, quantities, values: dict[str, float], broken=frozenset()) -> tuple[Scatter, ...]:
    """The scattered quantities of a ``[scatter]`` table of a case with ``quantities`` and nominal ``values``; all
    problems are raised together. A quantity in ``broken`` (its case value is bad) is not checked against its
    nominal value."""
    if not isinstance(table, dict):
        raise InputError(SECTION, "must be a table of quantity = [low, high] or { normal = [mean, sd] } or "
                                  "{ uniform = [low, high] }")
    declared = {q.name: q for q in quantities}
    if len(table) > MAX_SCATTERED:
        raise InputError(SECTION, f"at most {MAX_SCATTERED} scattered quantities (their 2^n corners are checked), "
                                  f"got {len(table)}")
    problems, items = Problems(), []
    for name, raw in table.items():
        with problems.field():
            quantity = declared.get(name)
            field = f"{SECTION}.{name}"
            if quantity is None:
                raise InputError(field, "not a quantity of this case; scatter takes the case's quantities by name "
                                        "(e.g. friction_coefficient, inertia, density)")
            if quantity.integer:
                raise InputError(field, "a whole number does not scatter")
            nominal = values.get(name, math.nan)
            if math.isnan(nominal) and name not in broken:
                raise InputError(field, "the case gives no value of it to scatter around")
            items.append(_item(field, quantity, raw, nominal))
    problems.raise_any()
    return tuple(items)


def _pair(field: str, quantity, raw) -> tuple[float, float]:
    if not isinstance(raw, list) or len(raw) != 2:
        raise InputError(field, f"must be a pair of values in {quantity.unit or 'SI'}, got {shown_value(raw)}")
    return tuple(to_si(field, value, quantity.unit) for value in raw)


def _item(field: str, quantity, raw, nominal: float) -> Scatter:
    """One scattered quantity around the case's value ``nominal``: a range or uniform distribution must hold it, a
    normal distribution's mean must be it (unless ``nominal`` is NaN, unknown)."""
    if isinstance(raw, list):
        kind, (low, high) = "range", _pair(field, quantity, raw)
    elif isinstance(raw, dict) and len(raw) == 1 and next(iter(raw)) in ("normal", "uniform"):
        kind = next(iter(raw))
        first, second = _pair(f"{field}.{kind}", quantity, raw[kind])
        if kind == "normal":
            if not second > 0:
                raise InputError(f"{field}.normal", f"the standard deviation must be positive, got {quantity.show(second)}")
            quantity.check(first, f"{field}.normal")
            if not math.isnan(nominal) and not math.isclose(first, nominal, rel_tol=MEAN_TOLERANCE):
                raise InputError(f"{field}.normal", f"the mean {quantity.show(first)} is not the case's value "
                                                    f"{quantity.show(nominal)}: a scatter spreads around the value "
                                                    f"the case is designed at; set the case's value to the mean, or "
                                                    f"scatter around it (normal = [{_spelled(quantity, nominal)}, "
                                                    f"{_spelled(quantity, second)}])")
            low, high = _within(quantity, first - NORMAL_RANGE * second), _within(quantity, first + NORMAL_RANGE * second)
            quantity.check(low, f"{field}.normal"), quantity.check(high, f"{field}.normal")
            return Scatter(quantity.name, kind, low, high, first, second)
        low, high = first, second
    else:
        raise InputError(field, f"must be [low, high], {{ normal = [mean, sd] }} or {{ uniform = [low, high] }}, "
                                f"got {shown_value(raw)}")
    if not low < high:
        raise InputError(field, f"low {quantity.show(low)} must be below high {quantity.show(high)}")
    quantity.check(low, field), quantity.check(high, field)
    if not math.isnan(nominal) and not low <= nominal <= high:
        raise InputError(field, f"the case's value {quantity.show(nominal)} lies outside {quantity.show(low)} .. "
                                f"{quantity.show(high)}: a scatter spreads around the value the case is designed "
                                f"at; set the case's value inside the range, or give a range that holds it")
    return Scatter(quantity.name, kind, low, high, (low + high) / 2, (high - low) / math.sqrt(12.0))


def _spelled(quantity, value: float) -> str:
    """A value as a case file writes it: ``"12 kg*m^2"``, or a bare number where the quantity has no unit."""
    shown = quantity.show(value)
    return shown if " " not in shown else f'"{shown}"'


def _within(quantity, value: float) -> float:
    """A value moved just inside the quantity's valid range (a normal range's tail cut where the quantity ends)."""
    nudge = 1e-9
    if quantity.at_least is not None:
        value = max(value, quantity.at_least)
    if quantity.above is not None:
        value = max(value, quantity.above + nudge * max(1.0, abs(quantity.above)))
    if quantity.at_most is not None:
        value = min(value, quantity.at_most)
    if quantity.below is not None:
        value = min(value, quantity.below - nudge * max(1.0, abs(quantity.below)))
    return value
