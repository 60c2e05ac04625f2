"""The ``[scatter]`` section of a case: how far case quantities may stray from their nominal values.

A friction coefficient is never one number (lining batch, temperature, wear, humidity); densities, allowable
stresses, the driven inertia and the load have tolerances too. Layout (quantities with units, as in the case)::

    [scatter]
    friction_coefficient = [0.12, 0.18]                      # a range: low, high
    inertia = { normal = ["12 kg*m^2", "0.6 kg*m^2"] }        # a normal distribution: mean, standard deviation
    allowable_pressure = { uniform = ["1.35 MPa", "1.65 MPa"] }  # a uniform distribution: low, high
    density = { lognormal = ["7850 kg/m^3", "100 kg/m^3"] }   # lognormal: mean, sd of the quantity itself
    speed = { normal = ["1450 rpm", "10 rpm"], within = ["1430 rpm", "1460 rpm"] }  # a normal cut to [low, high]
    resisting_torque = "+-20 %"                              # a range: the case's value -+ 20 %
    # friction_coefficient = "library"                       # a range: friction_min .. friction_max of [library]'s pair

    [scatter.correlation]                                     # correlations of the normal scores (Gaussian copula)
    friction_coefficient.inertia = 0.5

Worst-case designs use each quantity's range (a normal distribution: mean +- 3 standard deviations, cut to the
quantity's valid range; a lognormal one: its 0.135 % and 99.865 % quantiles, where a normal's +-3 sd lie; a cut
normal: its cut); chance-constrained designs and Monte Carlo use its distribution (a range: uniform over it), every
one an exact map of a standard normal variable (:meth:`Scatter.from_standard`), correlated by
``[scatter.correlation]`` (:func:`draw`; docs/robust.md).
"""

from __future__ import annotations

import functools
import itertools
import math
import re
from dataclasses import dataclass

import numpy as np

from clutchopt.errors import InputError, Problems, shown_value
from clutchopt.model import MAGNITUDES
from clutchopt.units import difference_unit, to_si, unit_info

SECTION = "scatter"
CORRELATION = "correlation"  # the subtable [scatter.correlation]
MAX_SCATTERED = 12  # quantities; worst-case designs check all 2^n corners
NORMAL_RANGE = 3.0  # standard deviations either side of the mean: a normal quantity's worst-case range
MEAN_TOLERANCE = 1e-9  # relative: a normal distribution's mean is the case's value (given in another unit)
KINDS = ("range", "normal", "uniform", "lognormal", "truncated")
FORMS = ('[low, high], { normal = [mean, sd] } or { uniform = [low, high] }, or { lognormal = [mean, sd] }, '
         '{ normal = [mean, sd], within = [low, high] }, "+-20 %" or "library"')
BAND = re.compile(r"^\s*(?:\+-|\+/-|±)\s*(\d+(?:\.\d*)?|\.\d+)\s*%\s*$")  # "+-20 %", "±20 %", "+/-20%"
LIBRARY = "library"
SINGULAR = 1e-12  # smallest eigenvalue of a correlation matrix taken as positive definite


@dataclass(frozen=True)
class Scatter:
    """One scattered quantity (SI): its worst-case range and its distribution.

    ``mean``, ``sd``: normal and lognormal, the distribution's own mean and standard deviation (a lognormal's log
    parameters follow from them, :meth:`log_parameters`); truncated (a normal cut to [low, high]), those of the
    normal before the cut; range and uniform, those of the uniform distribution over [low, high]."""

    name: str
    kind: str  # one of KINDS
    low: float  # worst-case range
    high: float
    mean: float
    sd: float

    def from_standard(self, u) -> np.ndarray:
        """The value x with P(X <= x) = Phi(u) (vectorised): the exact isoprobabilistic map of a standard normal
        variable u to the quantity (Rosenblatt; for a normal quantity mean + sd u)."""
        u = np.asarray(u, dtype=float)
        if self.kind == "normal":
            return self.mean + self.sd * u
        if self.kind == "lognormal":
            mu, sigma = self.log_parameters()
            return np.exp(mu + sigma * u)
        if self.kind == "truncated":
            law = self._truncated()
            return _by_tails(u, law.ppf, law.isf)
        width = self.high - self.low
        return _by_tails(u, lambda p: self.low + width * p, lambda q: self.high - width * q)

    def to_standard(self, x) -> np.ndarray:
        """The standard normal u with Phi(u) = P(X <= x) (vectorised): the inverse of :meth:`from_standard`."""
        x = np.asarray(x, dtype=float)
        if self.kind == "normal":
            return (x - self.mean) / self.sd
        if self.kind == "lognormal":
            mu, sigma = self.log_parameters()
            return (np.log(x) - mu) / sigma
        if self.kind == "truncated":
            law = self._truncated()
            return _to_standard(x, law.cdf, law.sf, law.median())
        width = self.high - self.low
        return _to_standard(x, lambda v: (v - self.low) / width, lambda v: (self.high - v) / width,
                            (self.low + self.high) / 2)

    def log_parameters(self) -> tuple[float, float]:
        """A lognormal quantity's (mu, sigma), those of ln X, from its mean m and sd s:
        sigma^2 = ln(1 + (s/m)^2), mu = ln m - sigma^2 / 2 (so that E X = exp(mu + sigma^2/2) = m and
        Var X = (exp(sigma^2) - 1) m^2 = s^2); for s/m above 1 as 2 ln(s/m) + ln(1 + (m/s)^2), the same number,
        which (s/m)^2 cannot overflow."""
        ratio = self.sd / self.mean
        variance = math.log1p(ratio ** 2) if ratio <= 1 else 2 * math.log(ratio) + math.log1p(ratio ** -2)
        return math.log(self.mean) - variance / 2, math.sqrt(variance)

    def _truncated(self):
        return _truncated_law(self.mean, self.sd, self.low, self.high)

    def describe(self, unit_shown, spread_shown=None) -> str:
        """``normal, mean 40 degC, sd 5 K``: values by ``unit_shown``, the sd by ``spread_shown`` (a difference: a
        temperature's in K, :func:`shown_spread`; default ``unit_shown``)."""
        sd = (spread_shown or unit_shown)(self.sd)
        if self.kind in ("normal", "lognormal"):
            return f"{self.kind}, mean {unit_shown(self.mean)}, sd {sd}"
        if self.kind == "truncated":
            return (f"normal, mean {unit_shown(self.mean)}, sd {sd}, within {unit_shown(self.low)} "
                    f"to {unit_shown(self.high)}")
        return f"{self.kind} {unit_shown(self.low)} to {unit_shown(self.high)}"


@functools.lru_cache(maxsize=64)
def _truncated_law(mean: float, sd: float, low: float, high: float):
    """SciPy's cut normal, built once per quantity (building one costs about 2 ms; a chance design maps thousands of
    points through it)."""
    from scipy.stats import truncnorm

    return truncnorm((low - mean) / sd, (high - mean) / sd, mean, sd)


def _by_tails(u: np.ndarray, ppf, isf) -> np.ndarray:
    """ppf(Phi(u)) computed from the nearer tail (isf(Phi(-u)) above the median), so that a far upper tail is not
    lost in 1 - Phi(u) rounding to 1."""
    lower = u <= 0
    from scipy.special import ndtr  # on first use: scipy.special takes 0.2 s to import, every case reads this module

    return np.where(lower, ppf(ndtr(np.where(lower, u, 0.0))), isf(ndtr(-np.where(lower, 0.0, u))))


def _to_standard(x: np.ndarray, cdf, sf, median: float) -> np.ndarray:
    """Phi^-1(cdf(x)), from the nearer tail (-Phi^-1(sf(x)) above the median)."""
    lower = x <= median
    from scipy.special import ndtri  # on first use (see _by_tails)

    return np.where(lower, ndtri(np.clip(cdf(x), 0.0, 1.0)), -ndtri(np.clip(sf(x), 0.0, 1.0)))


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


def parse_scatter(table, quantities, values: dict[str, float], broken=frozenset(),
                  library_ranges: dict | None = None) -> tuple[Scatter, ...]:
    """The scattered quantities of a ``[scatter]`` table of a case with ``quantities`` and nominal ``values``; all
    problems are raised together. A quantity in ``broken`` (its case value is bad) is not checked against its
    nominal value. ``library_ranges``: quantity -> (low, high, "friction_pair = organic_dry"), the ranges the
    case's ``[library]`` entries give (``"library"``). The subtable ``[scatter.correlation]`` is read by
    :func:`parse_correlation`."""
    if not isinstance(table, dict):
        raise InputError(SECTION, f"must be a table of quantity = {FORMS}")
    table = {name: raw for name, raw in table.items() if name != CORRELATION}
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
            if isinstance(raw, str):
                ends = _spelled_range(field, quantity, raw, nominal, (library_ranges or {}).get(name))
                if ends is not None:  # None: a band around a case value that is refused itself
                    items.append(_range(field, quantity, "range", *ends, nominal))
                continue
            items.append(_item(field, quantity, raw, nominal))
    problems.raise_any()
    return tuple(items)


def _pair(field: str, quantity, raw, spread: bool = False) -> tuple[float, float]:
    """Two values of ``quantity`` (SI); ``spread``: the second a standard deviation, for a temperature a temperature
    difference (K, delta_degC: "5 degC" would be 278.15 K)."""
    if not isinstance(raw, list) or len(raw) != 2:
        raise InputError(field, f"must be a pair of values in {quantity.unit or 'SI'}, got {shown_value(raw)}")
    units = (quantity.unit, difference_unit(quantity.unit) if spread else quantity.unit)
    return tuple(to_si(field, value, unit) for value, unit in zip(raw, units))


def _spelled_range(field: str, quantity, raw: str, nominal: float, library) -> list[float] | None:
    """The range [low, high] (SI) a text entry spells: a relative band ``"+-20 %"`` around the case's value
    (nominal (1 -+ 0.2)), or ``"library"``: friction_min .. friction_max of the entry [library] names."""
    if raw.strip() == LIBRARY:
        if library is None:
            raise InputError(field, f'"library" takes the range of the friction or thread pair the case names in '
                                    f'[library] (its friction_min .. friction_max), and this case names none that '
                                    f'gives {quantity.name}: name one in [library] (clutchopt materials) or give '
                                    f'a range')
        return [library[0], library[1]]
    band = BAND.match(raw)
    if band is None:
        raise InputError(field, f"must be {FORMS}, got {shown_value(raw)}")
    if unit_info(quantity.unit).offset:
        raise InputError(field, "a relative band of an absolute temperature depends on its scale (20 % of 40 degC "
                                "is 8 K, of 313.15 K 63 K): give a range [low, high]")
    share = float(band.group(1)) / 100
    if not 0 < share < 1:
        raise InputError(field, f"a relative band must lie above 0 % and below 100 %, got {band.group(1)} %")
    if math.isnan(nominal):
        return None  # the case's value is refused itself
    if nominal == 0:
        raise InputError(field, "a relative band of a zero value is no scatter: give a range [low, high]")
    ends = sorted((nominal * (1 - share), nominal * (1 + share)))
    for end, word in zip(ends, ("low", "high")):
        try:
            quantity.check(end, field)
        except InputError as exc:
            raise InputError(field, f"the band's {word} end {quantity.show(end)} ({quantity.show(nominal)} "
                                    f"{'-' if end < nominal else '+'} {band.group(1)} %) leaves the quantity's "
                                    f"valid range: {exc.problem}") from None
    return ends


def _item(field: str, quantity, raw, nominal: float) -> Scatter:
    """One scattered quantity around the case's value ``nominal``: a range or uniform distribution must hold it, a
    normal or lognormal distribution's mean must be it, as must a cut normal's before its cut (unless ``nominal`` is
    NaN, unknown)."""
    if isinstance(raw, list):
        return _range(field, quantity, "range", *_pair(field, quantity, raw), nominal)
    if isinstance(raw, dict) and set(raw) == {"normal", "within"}:
        return _truncated(field, quantity, raw, nominal)
    if isinstance(raw, dict) and len(raw) == 1 and next(iter(raw)) in ("normal", "uniform", "lognormal"):
        kind = next(iter(raw))
        first, second = _pair(f"{field}.{kind}", quantity, raw[kind], spread=kind != "uniform")
        if kind in ("normal", "lognormal"):
            _mean_and_sd(f"{field}.{kind}", quantity, first, second, nominal)
            if kind == "lognormal" and not first > 0:
                raise InputError(f"{field}.lognormal", f"a lognormal quantity is positive: its mean must be above 0, "
                                                       f"got {quantity.show(first)}")
            trial = Scatter(quantity.name, kind, math.nan, math.nan, first, second)
            low, high = (_within(quantity, float(trial.from_standard(u))) for u in (-NORMAL_RANGE, NORMAL_RANGE))
            quantity.check(low, f"{field}.{kind}"), quantity.check(high, f"{field}.{kind}")
            if not low <= first <= high:  # a lognormal with sigma above 2 NORMAL_RANGE: s/m above about 6.6e7
                raise InputError(f"{field}.{kind}", f"the standard deviation {shown_spread(quantity, second)} against the mean "
                                                    f"{quantity.show(first)} puts the whole worst-case range (its "
                                                    f"0.135 % to 99.865 % quantiles) below the mean: no range of "
                                                    f"values spreads around the case's value; give a smaller sd")
            return Scatter(quantity.name, kind, low, high, first, second)
        return _range(field, quantity, kind, first, second, nominal)
    raise InputError(field, f"must be {FORMS}, got {shown_value(raw)}")


def _range(field: str, quantity, kind: str, low: float, high: float, nominal: float) -> Scatter:
    """A range or uniform distribution over [low, high] (SI) that holds the case's value."""
    _holds(field, quantity, low, high, nominal)
    return Scatter(quantity.name, kind, low, high, (low + high) / 2, (high - low) / math.sqrt(12.0))


def _mean_and_sd(field: str, quantity, mean: float, sd: float, nominal: float) -> None:
    """A distribution's mean is a valid value of the quantity, and the case's; its standard deviation positive."""
    if not sd > 0:
        raise InputError(field, f"the standard deviation must be positive, got {shown_spread(quantity, sd)}")
    quantity.check(mean, field)
    if mean + NORMAL_RANGE * sd == mean or mean - NORMAL_RANGE * sd == mean:  # else every estimate says "exact"
        raise InputError(field, f"the standard deviation {shown_spread(quantity, sd)} does not move the mean "
                                f"{quantity.show(mean)} in float64 (mean +- {NORMAL_RANGE:g} sd rounds to the mean): "
                                f"no scatter; leave {quantity.name} out of [scatter] or give a wider sd")
    if sd > MAGNITUDES[1] and field.rsplit(".", 1)[-1] == "normal":  # (1e300 had overflowed in the model's
        # arithmetic, review 25; a lognormal's is refused against its mean, below)
        raise InputError(field, f"the standard deviation {sd:.6g} {quantity.si_unit} (SI) is outside the magnitudes "
                                f"clutchopt works with, {MAGNITUDES[0]:g} to {MAGNITUDES[1]:g} in SI units"
                         .replace(" 1 (SI)", " (SI)"))
    if not math.isnan(nominal) and not math.isclose(mean, nominal, rel_tol=MEAN_TOLERANCE):
        kind = field.rsplit(".", 1)[-1]
        raise InputError(field, f"the mean {quantity.show(mean)} is not the case's value {quantity.show(nominal)}: "
                                f"a scatter spreads around the value the case is designed at; set the case's value "
                                f"to the mean, or scatter around it ({kind} = [{_spelled(quantity, nominal)}, "
                                f"{_spelled(quantity, sd, spread=True)}])")


def _holds(field: str, quantity, low: float, high: float, nominal: float) -> None:
    """A range [low, high] of valid values that holds the case's value."""
    if not low < high:
        raise InputError(field, f"low {quantity.show(low)} must be below high {quantity.show(high)}")
    quantity.check(low, field), quantity.check(high, field)
    if not math.isnan(nominal) and not low <= nominal <= high:
        raise InputError(field, f"the case's value {quantity.show(nominal)} lies outside {quantity.show(low)} .. "
                                f"{quantity.show(high)}: a scatter spreads around the value the case is designed "
                                f"at; set the case's value inside the range, or give a range that holds it")


def _truncated(field: str, quantity, raw: dict, nominal: float) -> Scatter:
    """``{ normal = [mean, sd], within = [low, high] }``: a normal distribution cut to [low, high] (its mean and sd
    those before the cut; the mean is the case's value); its worst-case range is the cut."""
    mean, sd = _pair(f"{field}.normal", quantity, raw["normal"], spread=True)
    _mean_and_sd(f"{field}.normal", quantity, mean, sd, nominal)
    low, high = _pair(f"{field}.within", quantity, raw["within"])
    _holds(f"{field}.within", quantity, low, high, nominal)
    return Scatter(quantity.name, "truncated", low, high, mean, sd)


def parse_correlation(table, scatter: tuple[Scatter, ...]) -> tuple[tuple[float, ...], ...] | None:
    """The correlation matrix (n x n, in the order of ``scatter``) of ``[scatter.correlation]``: ``a.b = rho`` for
    two scattered quantities a and b, each pair once, |rho| < 1, the whole matrix positive definite; None without
    the subtable. The correlations are those of the quantities' normal scores (a Gaussian copula, :func:`draw`)."""
    if not isinstance(table, dict) or CORRELATION not in table:
        return None
    field, given = f"{SECTION}.{CORRELATION}", table[CORRELATION]
    if not isinstance(given, dict):
        raise InputError(field, f"must be a table of quantity.other = rho, e.g. [scatter.correlation] "
                                f"friction_coefficient.inertia = 0.5, got {shown_value(given)}")
    order = {s.name: i for i, s in enumerate(scatter)}
    matrix = np.eye(len(scatter))
    problems, seen = Problems(), {}
    for first, row in given.items():
        with problems.field():
            if first not in order:
                raise InputError(f"{field}.{first}", _unscattered(first, order))
            if not isinstance(row, dict):
                raise InputError(f"{field}.{first}", f"must be a table of other = rho, e.g. {first}.{next(iter(order))}"
                                                     f" = 0.5, got {shown_value(row)}")
        if first not in order or not isinstance(row, dict):
            continue
        for second, rho in row.items():
            with problems.field():
                key = f"{field}.{first}.{second}"
                if second not in order:
                    raise InputError(key, _unscattered(second, order))
                if second == first:
                    raise InputError(key, "a quantity with itself: its correlation is 1 by definition; give the "
                                          "correlation of two different quantities")
                if isinstance(rho, bool) or not isinstance(rho, (int, float)) or not -1 < rho < 1:
                    raise InputError(key, f"must be a number above -1 and below 1 (|rho| = 1 makes two quantities "
                                          f"one), got {shown_value(rho)}")
                pair = frozenset((first, second))
                if pair in seen:
                    raise InputError(key, f"given twice: also as {seen[pair]}")
                seen[pair] = key
                matrix[order[first], order[second]] = matrix[order[second], order[first]] = float(rho)
    problems.raise_any()
    names = [s.name for s in scatter]
    if not _positive_definite(matrix):
        worst = _smallest_indefinite(matrix)
        smallest = float(np.linalg.eigvalsh(matrix[np.ix_(worst, worst)]).min())
        if smallest > 0:  # positive definite, but too near singular to factor and sample reliably
            raise InputError(field, f"the correlations of {', '.join(names[i] for i in worst)} are nearly singular "
                                    f"(smallest eigenvalue {smallest:.2g}, below {SINGULAR:g}: one quantity all but "
                                    f"another); weaken one of them, or scatter one quantity")
        raise InputError(field, f"the correlations of {', '.join(names[i] for i in worst)} are not positive "
                                f"definite (no joint distribution has them: e.g. a with b and b with c strongly "
                                f"positive, a with c strongly negative); weaken one of them")
    return tuple(tuple(float(v) for v in row) for row in matrix)


def correlation_text(scatter: tuple[Scatter, ...], correlation) -> str:
    """``correlated (normal scores): friction_coefficient with inertia -0.4``, or "" for independent quantities."""
    pairs = [f"{a.name} with {b.name} {correlation[i][j]:+.3g}" for (i, a), (j, b)
             in itertools.combinations(enumerate(scatter), 2) if correlation is not None and correlation[i][j]]
    return f"correlated (of the normal scores; the corners do not change): {'; '.join(pairs)}" if pairs else ""


def _unscattered(name: str, order: dict) -> str:
    return (f"not a scattered quantity of this case; correlations are between the quantities [scatter] gives "
            f"({', '.join(order) or 'none'})")


def _positive_definite(matrix: np.ndarray) -> bool:
    try:
        np.linalg.cholesky(matrix)
    except np.linalg.LinAlgError:
        return False
    return bool(np.linalg.eigvalsh(matrix).min() > SINGULAR)


def _smallest_indefinite(matrix: np.ndarray) -> tuple[int, ...]:
    """The indices of a smallest set of quantities whose correlations alone are not positive definite (a pair only
    when nearly singular, |rho| < 1)."""
    n = len(matrix)
    for size in range(2, n + 1):
        for subset in itertools.combinations(range(n), size):
            if not _positive_definite(matrix[np.ix_(subset, subset)]):
                return subset
    return tuple(range(n))


def _spelled(quantity, value: float, spread: bool = False) -> str:
    """A value (``spread``: a standard deviation) as a case file writes it: ``"12 kg*m^2"``, or a bare number where
    the quantity has no unit."""
    shown = shown_spread(quantity, value) if spread else quantity.show(value)
    return shown if " " not in shown else f'"{shown}"'


def shown_spread(quantity, value: float) -> str:
    """A standard deviation in the quantity's unit; a temperature's in K, a difference (5 K, not -268.15 degC)."""
    unit = difference_unit(quantity.unit)
    return quantity.show(value) if unit == quantity.unit else f"{value:.6g} {unit}"


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
