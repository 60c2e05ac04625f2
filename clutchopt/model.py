"""The formulation mechanism shared by every coupling.

A formulation declares, once each:
- its *quantities*: everything a case file of the coupling may give (requirements, materials, fixed geometry,
  the paper's printed results), each with unit, paper symbol, valid range and default;
- its *design variables*: what the optimiser chooses, with default bounds, unit and integrality;
- its *constraints*: named inequalities ``value <= limit`` or ``value >= limit`` with the paper's equation number;
- its *objectives* (mass, cost) and *outputs* (derived quantities worth reporting).

Constraints, objectives and outputs are written with :mod:`clutchopt.backend` math, so the same code runs on
floats (float64 checks, closed forms) and on CasADi symbols (the NLP). No solver code lives here.
"""

from __future__ import annotations

import math
import operator
from dataclasses import dataclass, field
from types import SimpleNamespace
from typing import Any, Callable, Mapping

from clutchopt.errors import InputError
from clutchopt.units import from_si, si_factor, si_unit

REQUIRED = object()  # marker: a case must give this quantity
# Every case value (SI) is 0 or of a magnitude within these: beyond 1e-9 to 1e9 times any real coupling's numbers
# (7850 kg/m^3, 1.6e8 Pa, 1e-3 m; tests/test_torture.py scales cases by 1e-9 to 1e9), and small enough that
# products like m w^2 r, even powers up to the 12th, stay inside float64 in every formulation.
MAGNITUDES = (1e-18, 1e18)


@dataclass(frozen=True)
class Quantity:
    """One declared quantity: TOML key ``section.name``, unit used for input and display, valid range (SI)."""

    name: str
    unit: str
    description: str
    symbol: str = ""
    section: str = "parameters"
    default: Any = REQUIRED  # a case value ("7850 kg/m^3", 0.15), REQUIRED, or None for optional
    above: float | None = None  # valid range, SI: value > above
    at_least: float | None = None  # value >= at_least
    below: float | None = None  # value < below
    at_most: float | None = None  # value <= at_most
    integer: bool = False
    toml_key: str = ""  # the key in its TOML table, where it differs from the name (``inertia`` of the motor)
    needed_by: str = ""  # the objective that alone uses it ("cost"): a case may leave it out (NaN) unless posed

    @property
    def key(self) -> str:
        return f"{self.section}.{self.toml_key or self.name}"

    @property
    def si_unit(self) -> str:
        return si_unit(self.unit)

    def show(self, value: float, digits: int = 6) -> str:
        """An SI value written in this quantity's unit, e.g. ``15 deg``."""
        return f"{from_si(value, self.unit):.{digits}g} {self.unit}".rstrip()

    def _range_tests(self) -> list[tuple[float, Callable, str]]:
        """(bound, test, word) of each limit the valid range has; the tests take numbers or arrays."""
        limits = ((self.above, operator.gt, ">"), (self.at_least, operator.ge, ">="),
                  (self.below, operator.lt, "<"), (self.at_most, operator.le, "<="))
        return [(bound, test, word) for bound, test, word in limits if bound is not None]

    def check(self, value: float, field_name: str | None = None) -> float:
        """Return ``value`` (SI) if it is in the valid range, else raise InputError naming the field."""
        name = field_name or self.key
        for bound, ok, word in self._range_tests():
            if not ok(value, bound):
                raise InputError(name, f"must be {word} {self.show(bound)}, got {self.show(value, 15)}")
        if self.integer and value != round(value):
            raise InputError(name, f"must be a whole number, got {value:.15g}")
        if value != 0 and not MAGNITUDES[0] <= abs(value) <= MAGNITUDES[1]:
            raise InputError(name, f"{value:.6g} {self.si_unit} (SI) is outside the magnitudes clutchopt works with, "
                                   f"{MAGNITUDES[0]:g} to {MAGNITUDES[1]:g} in SI units".replace(" 1 (SI)", " (SI)"))
        return value

    def valid(self, values) -> Any:
        """Which values of a NumPy array :meth:`check` passes, tested as arrays (a sweep's values)."""
        size = abs(values)
        good = (values == 0) | ((size >= MAGNITUDES[0]) & (size <= MAGNITUDES[1]))  # NaN and inf fail here
        for bound, ok, _ in self._range_tests():
            good = good & ok(values, bound)
        if self.integer:
            good = good & (values == values.round())
        return good

    def check_all(self, values, field_name: str | None = None) -> None:
        """Every value of a NumPy array valid (:meth:`valid`); the first bad one raises as :meth:`check` does."""
        good = self.valid(values)
        if not good.all():
            self.check(float(values[good.argmin()]), field_name)

    def valid_range(self) -> str:
        """The valid range as a reader writes it: ``> 0 MPa``, ``> 0 and <= 1``, ``a whole number >= 1``."""
        parts = [f"{word} {self.show(bound)}" for bound, _, word in self._range_tests()]
        text = " and ".join(parts) or "any value"
        return f"a whole number {text}" if self.integer else text


@dataclass(frozen=True)
class Variable(Quantity):
    """A design variable: a quantity with a default search box (SI) and, optionally, integrality.

    ``fixed_unless_freed``: the variable stays at the case's value of the quantity of the same name unless
    the case lists it in ``options.free`` (e.g. the flank angle of the wedge in geometry mode).
    """

    section: str = "bounds"
    default: Any = None
    lower: float = 0.0
    upper: float = math.inf
    fixed_unless_freed: bool = False


@dataclass
class Constraint:
    """A named inequality ``value <= limit`` (sense "<=") or ``value >= limit`` (sense ">=").

    ``scale`` (positive, defaults to the limit) normalises the constraint for the solver and gives the
    relative margin: margin = (limit - value) / scale for "<=", (value - limit) / scale for ">=".
    """

    name: str
    equation: str
    value: Any
    limit: Any
    sense: str
    unit: str = ""
    scale: Any = None
    description: str = ""
    constant_acceleration: bool = False  # the papers' sizing assumption; a case's [start_up] model replaces it

    def normalised(self):
        """g <= 0 form, O(1) near the limit: the form the NLP sees."""
        scale = self.limit if self.scale is None else self.scale
        return (self.value - self.limit) / scale if self.sense == "<=" else (self.limit - self.value) / scale

    def margin(self) -> float:
        return -float(self.normalised())


def at_most(name: str, value, limit, *, equation: str, unit: str = "", scale=None, description: str = "",
            constant_acceleration: bool = False):
    return Constraint(name, equation, value, limit, "<=", unit, scale, description, constant_acceleration)


def at_least(name: str, value, limit, *, equation: str, unit: str = "", scale=None, description: str = "",
             constant_acceleration: bool = False):
    return Constraint(name, equation, value, limit, ">=", unit, scale, description, constant_acceleration)


@dataclass(frozen=True)
class Output:
    """A derived quantity reported beside the design (torque capability, centroid radius, ...)."""

    value: Any
    unit: str
    description: str = ""


ENVELOPE_PARTS = {  # what every coupling's like-for-like mass counts, the same groups for all (docs/envelope.md)
    "halves": "driving and driven halves with the housing or drum",
    "moving_parts": "the weights, balls, fingers, links, cables and screws the coupling has",
    "springs": "return springs",
    "linings": "friction linings",
}


@dataclass(frozen=True)
class Part:
    """The mass of one group of :data:`ENVELOPE_PARTS` at a design, and what it counts (a group a coupling does not
    have, or whose parts its model does not size, is 0 and says so)."""

    mass: Any
    counts: str


@dataclass(frozen=True)
class Envelope:
    """A coupling at a design as it is set beside the others: outer diameter, axial length and the mass of the same
    groups of parts (:data:`ENVELOPE_PARTS`) for every coupling. Written with the formulation's equations, so the
    values are floats or CasADi symbols alike."""

    outer_diameter: Any
    axial_length: Any
    parts: Mapping[str, Part]

    def __post_init__(self):
        if set(self.parts) != set(ENVELOPE_PARTS):
            raise ValueError(f"an envelope counts the parts {', '.join(ENVELOPE_PARTS)}; got {', '.join(self.parts)}")

    @property
    def mass(self):
        return sum(self.parts[name].mass for name in ENVELOPE_PARTS)

    def outputs(self) -> dict[str, Output]:
        """The envelope as outputs beside the design: diameter, length, like-for-like mass."""
        return {
            "envelope_diameter": Output(self.outer_diameter, "mm", "outer diameter (docs/envelope.md)"),
            "envelope_length": Output(self.axial_length, "mm", "axial length (docs/envelope.md)"),
            "envelope_mass": Output(self.mass, "kg", "like-for-like mass (docs/envelope.md)"),
        }


@dataclass(frozen=True)
class Objective:
    name: str
    unit: str
    description: str
    function: Callable[[SimpleNamespace, SimpleNamespace], Any]


@dataclass(frozen=True)
class SpeedLaw:
    """How a centrifugal coupling's torque follows its driving speed w_a in a start-up: T = K (w_a^2 - w_e^2) once
    engaged, each function written with the coupling's own equations and ``(x, p)`` as the constraints take them.

    ``torque_coefficient``: K = dT / d(w_a^2), N*m*s^2. ``mass_radius``: m r of one weight, the radial force per
    (rad/s)^2 that springs and gravity work against, and ``weight_mass``: m of one weight (gravity); both None
    for a coupling without such weights (then the effects spring_preload and gravity do not apply).
    ``friction_area``: the area of the friction surfaces that wear, m^2 (the lining's life; None: not known).
    ``worn_torque``: ``(x, p, speed, radial_force) ->`` the torque with worn linings at a driving speed, each
    weight's centrifugal force less ``radial_force`` (springs, gravity), for a coupling whose torque changes as its
    linings wear (the lever); None: it does not change.
    """

    torque_coefficient: Callable[[SimpleNamespace, SimpleNamespace], Any]
    mass_radius: Callable[[SimpleNamespace, SimpleNamespace], Any] | None = None
    weight_mass: Callable[[SimpleNamespace, SimpleNamespace], Any] | None = None
    friction_area: Callable[[SimpleNamespace, SimpleNamespace], Any] | None = None  # m^2: the lining area that
    # wears (every friction surface of the coupling's wearing part), for the lining's life; None: not declared
    worn_torque: Callable[..., Any] | None = None


@dataclass(frozen=True)
class ElasticLaw:
    """How a coupling that transmits torque through an elastic, speed-stiffened link (the cable coupling) behaves in
    a start-up: the torque and the stress of the link at a driving speed w_a and a relative twist theta of the
    halves, written with the coupling's own equations and ``(x, p, w_a, theta)``.

    ``torque``: torque through the link, N*m; ``stress``: the most loaded element's stress, Pa, checked against
    ``stress_limit`` (the name of the case quantity that bounds it in a start); ``stiffness``: dT/dtheta at
    theta = 0 and w_a, N*m/rad (the reference of the link's damping); ``damping_ratio``: (x, p) -> its equivalent
    viscous damping ratio; ``largest_twist``: (x, p) -> the twist up to which the torque grows with it;
    ``least_stress``: (x, p, w_a, T) -> a lower bound on the stress with which the link carries the torque T at w_a
    (arrays), whatever the design variables ``x`` leaves NaN (free), in any design meeting the formulation's rows,
    the twist within ``largest_twist``; None: no bound known.
    """

    torque: Callable[..., Any]
    stress: Callable[..., Any]
    stiffness: Callable[..., Any]
    damping_ratio: Callable[[SimpleNamespace, SimpleNamespace], Any]
    largest_twist: Callable[[SimpleNamespace, SimpleNamespace], Any]
    stress_limit: str
    least_stress: Callable[..., Any] | None = None


@dataclass
class Formulation:
    """One posed problem of one coupling (e.g. the wedge coupling in paper mode).

    ``constraints(x, p)`` returns a list of :class:`Constraint`, ``outputs(x, p)`` a dict of :class:`Output`;
    ``x`` holds the design variables and ``p`` the case quantities, both by attribute name.
    """

    coupling: str
    mode: str
    title: str
    quantities: tuple[Quantity, ...]
    variables: tuple[Variable, ...]
    constraints: Callable[[SimpleNamespace, SimpleNamespace], list[Constraint]]
    objectives: tuple[Objective, ...]
    outputs: Callable[[SimpleNamespace, SimpleNamespace], dict[str, Output]] = lambda x, p: {}
    speed_law: SpeedLaw | ElasticLaw | None = None  # its torque in a start-up (None: not available)
    variant: str = ""  # a formulation derived from the mode's (robust designs): part of what identifies it
    # (x, p, name) -> the design and case values (dicts) a [start_up]'s constraint ``name`` sees, and (x, p, None)
    # those its start is simulated at: a robust design's corners (a scattered fixed design variable moves with them)
    start_up_view: Callable[[dict, dict, str | None], tuple[dict, dict]] | None = None
    notes: str = ""
    # (x, p) -> the coupling's :class:`Envelope` at a design: outer diameter, axial length, like-for-like mass
    envelope: Callable[[SimpleNamespace, SimpleNamespace], Envelope] | None = None
    _objective_index: dict = field(init=False, repr=False)

    def __post_init__(self):
        self._objective_index = {o.name: o for o in self.objectives}

    def objective(self, name: str) -> Objective:
        try:
            return self._objective_index[name]
        except KeyError:
            raise InputError("objective", f"unknown objective {name!r}; choose from {', '.join(self._objective_index)}") from None

    def variable(self, name: str) -> Variable:
        return next(v for v in self.variables if v.name == name)

    def frees(self) -> str:
        """What the optimiser may change in this mode: ``weight_mass (m_r), finger_diameter (d_n)``, then the
        variables that stay at the case's value unless ``options.free`` lists them."""
        def named(variables):
            return ", ".join(f"{v.name} ({v.symbol})" if v.symbol else v.name for v in variables)

        text = named(v for v in self.variables if not v.fixed_unless_freed)
        freeable = [v for v in self.variables if v.fixed_unless_freed]
        return text + (f"; also {named(freeable)} if options.free lists them" if freeable else "")


def followed(values: Mapping[str, Any], follows: Mapping[str, tuple[str, float]]) -> dict[str, Any]:
    """``values`` (floats, arrays or CasADi symbols by name) with each default that follows another quantity,
    ``{name: (source, factor)}``, set to factor times its source's value."""
    return {**values, **{name: factor * values[source] for name, (source, factor) in follows.items()
                         if source in values}}


def namespace(values: Mapping[str, Any]) -> SimpleNamespace:
    return SimpleNamespace(**dict(values))


def si(value: float, unit: str) -> float:
    """``si(20, "mm")`` -> 0.02: literal bounds in formulations, written in the unit a designer thinks in."""
    return value * si_factor(unit)


@dataclass(frozen=True)
class ComparisonRow:
    name: str
    unit: str
    description: str


@dataclass(frozen=True)
class Comparison:
    """How ``clutchopt compare`` sets a coupling's published method beside its NLP optima.

    ``references(case)`` gives the closed-form columns: ``{column: {row: SI value}}`` (paper as printed,
    paper formulas evaluated, consistent closed form). ``solves`` lists the NLP columns as
    ``(column, mode, objective)``; ``rows_from_design(mode, design, outputs, params)`` reads the rows off
    an NLP solution. Relative differences are taken against ``baseline``.
    """

    rows: tuple[ComparisonRow, ...]
    references: Callable[[SimpleNamespace], dict[str, dict[str, float]]]
    solves: tuple[tuple[str, str, str], ...]
    rows_from_design: Callable[[str, dict, dict, SimpleNamespace], dict[str, float]]
    baseline: str
    column_notes: dict[str, str] = field(default_factory=dict)


@dataclass(frozen=True)
class MaterialRole:
    """A part of a coupling a case may name a library entry for (``friction_pair = "organic_dry"``).

    ``key`` is the case's top-level key, ``kind`` the library table (materials, friction_pairs, thread_pairs),
    ``parts`` what it is for, ``fills`` which library field gives which case quantity. Values the case gives
    explicitly win over the library's.
    """

    key: str
    kind: str
    parts: str
    fills: Mapping[str, str]  # library field -> quantity name


@dataclass
class Coupling:
    """A coupling family: its case quantities, its posed problems by mode, its comparison."""

    name: str
    title: str
    source: str
    quantities: tuple[Quantity, ...]
    formulations: dict[str, Formulation]
    default_mode: str
    comparison: Comparison | None = None
    case_checks: tuple[Callable[[Any], None], ...] = ()
    materials: tuple[MaterialRole, ...] = ()  # what a case may name from the material library

    @property
    def variables(self) -> tuple[Variable, ...]:
        seen: dict[str, Variable] = {}
        for formulation in self.formulations.values():
            for variable in formulation.variables:
                seen.setdefault(variable.name, variable)
        return tuple(seen.values())

    def formulation(self, mode: str | None = None) -> Formulation:
        mode = self.default_mode if mode is None else mode
        if mode not in self.formulations:
            raise InputError("mode", f"unknown mode {mode!r} for {self.name}; choose from {', '.join(self.formulations)}")
        return self.formulations[mode]

    def check_case(self, case) -> None:
        """Cross-field checks (contradictory requirements) after each field passed its own check."""
        for check in self.case_checks:
            check(case)
