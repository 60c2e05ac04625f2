"""What the couplings' formulations share: a coupling posed in its modes from one state of a design, the speed law
of weights whose torque grows with the square of the driving speed, and the parts and case checks several
couplings have.

Written with :mod:`clutchopt.backend` math like the equations, so it serves floats and CasADi symbols alike.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
from dataclasses import dataclass
from functools import cached_property
from types import SimpleNamespace
from typing import Any, Callable

from clutchopt.errors import InputError
from clutchopt.formulations.duty import required_torque
from clutchopt.model import ElasticLaw, Formulation, Objective, Quantity, SpeedLaw, Variable

ENVELOPE_MASS = "halves and housing, moving parts, springs, linings alike (docs/envelope.md)"
State = Callable[[SimpleNamespace, SimpleNamespace], Any]  # (x, p) -> the coupling at design x of case p


@dataclass(frozen=True)
class CouplingModel:
    """What every mode of one coupling shares. A mode differs only in how it obtains the state of a design,
    ``state(x, p)`` (the weights, toggles or clutch at that design), and in constraints and outputs of its own.

    ``mass`` and ``cost``: (description, ``(state, p) -> value``) of the two objectives, kg and EUR;
    ``outputs`` and ``constraints``: ``(state, x, p) ->`` those every mode reports and meets;
    ``speed_law``: ``state -> `` the coupling's law in a start-up;
    ``envelope``: ``(state, x, p) ->`` its :class:`clutchopt.model.Envelope` (outer diameter, axial length,
    like-for-like mass), reported as outputs by every mode;
    ``outputs_once``: whether the outputs read the state with each of its properties computed once
    (:func:`computed_once`: the lever's, whose outputs read its toggles' R_0 20 times; a state whose outputs read each
    property about once, the wedge's or the ball's, would only pay for the copy, 2-4 us an evaluation).
    """

    coupling: str
    quantities: tuple[Quantity, ...]
    mass: tuple[str, Callable]
    cost: tuple[str, Callable]
    outputs: Callable
    speed_law: Callable[[State], SpeedLaw | ElasticLaw]
    constraints: Callable = lambda state, x, p: []
    envelope: Callable | None = None
    outputs_once: bool = False

    def formulation(self, mode: str, title: str, variables: tuple[Variable, ...], state: State,
                    constraints: Callable = lambda state, x, p: [],
                    outputs: Callable = lambda state, x, p: {}) -> Formulation:
        """The posed problem of one mode, from how it obtains the state and what it adds."""
        (mass_description, mass), (cost_description, cost) = self.mass, self.cost
        envelope, read = self.envelope, computed_once if self.outputs_once else (lambda s: s)

        def envelope_outputs(s, x, p):
            return envelope(s, x, p).outputs() if envelope else {}

        return Formulation(
            coupling=self.coupling,
            mode=mode,
            title=title,
            quantities=self.quantities,
            variables=variables,
            constraints=lambda x, p: self.constraints(s := state(x, p), x, p) + constraints(s, x, p),
            objectives=(Objective("mass", "kg", mass_description, lambda x, p: mass(state(x, p), p)),
                        Objective("cost", "EUR", cost_description, lambda x, p: cost(state(x, p), p)))
            + ((Objective("envelope_mass", "kg", ENVELOPE_MASS, lambda x, p: envelope(state(x, p), x, p).mass),)
               if envelope else ()),
            outputs=lambda x, p: {**self.outputs(s := read(state(x, p)), x, p), **outputs(s, x, p),
                                  **envelope_outputs(s, x, p)},
            speed_law=self.speed_law(state),
            envelope=(lambda x, p: envelope(state(x, p), x, p)) if envelope else None,
        )


def computed_once(state):
    """``state`` (a coupling's state of a design) whose properties are each computed once, where its outputs read
    them again and again (the lever's R_0 20 times, its d_cp 11: 0.36 ms for 1000 points where 0.15 once each, 48 us
    for one where 38): the same numbers (the same operations on the same values). For the outputs, which are
    evaluated on numbers only; the constraints and objectives keep their graph (a term shared would change the order
    in which CasADi sums a derivative's parts, and so its last bits). Only a frozen dataclass (a state no property
    of which can go stale) is copied so; any other state is left as it is. Each property is the one the state's class
    resolves (``inspect.getattr_static``: a subclass's override kept)."""
    kind = type(state)
    if not (dataclasses.is_dataclass(kind) and kind.__dataclass_params__.frozen and hasattr(state, "__dict__")):
        return state
    once = _COMPUTED_ONCE.get(kind)
    if once is None:
        resolved = {name: inspect.getattr_static(kind, name) for name in dir(kind)}
        properties = {name: cached_property(value.fget) for name, value in resolved.items()
                      if isinstance(value, property)}
        once = _COMPUTED_ONCE[kind] = type(kind.__name__, (kind,), {**properties, "__doc__": kind.__doc__})
    copy = object.__new__(once)
    copy.__dict__.update(vars(state))
    return copy


_COMPUTED_ONCE: dict[type, type] = {}  # a state's class -> its class with each property computed once


def at_unit_speed(p):
    """The case values with the driving speed set to 1 rad/s."""
    return SimpleNamespace(**{**vars(p), "speed": 1.0})


def centrifugal_speed_law(state: State, torque: Callable, weight_mass: Callable | None = None,
                          weight_radius: Callable | None = None, friction_area: Callable | None = None) -> SpeedLaw:
    """T = K w_a^2 for a coupling whose torque comes from centrifugal forces: K is ``torque(state, p)`` at
    w_a = 1 rad/s. ``weight_mass(state)`` and ``weight_radius(state)`` give m and r of one weight, whose
    centrifugal force m r w_a^2 springs and gravity act against; without them those effects do not apply.
    ``friction_area(state)``: the area of the friction surfaces that wear (the lining's life)."""
    def torque_coefficient(x, p):
        unit = at_unit_speed(p)
        return torque(state(x, unit), unit)

    area = (lambda x, p: friction_area(state(x, p))) if friction_area else None
    if weight_mass is None:
        return SpeedLaw(torque_coefficient, friction_area=area)
    return SpeedLaw(torque_coefficient,
                    lambda x, p: weight_mass(s := state(x, p)) * weight_radius(s),
                    lambda x, p: weight_mass(state(x, p)), area)


def duty_torque(p):
    """T_max = I_n w_a / t_p + T_c of the case's duty (wedge paper eqs. (5), (17); lever paper T_max = I_M e + T_p)."""
    return required_torque(p.inertia, p.speed, p.acceleration_time, p.resisting_torque)


def rod_mass(density, diameter, length):
    """rho pi d^2 / 4 l: a solid round rod (finger, link, screw)."""
    return density * math.pi * diameter**2 / 4.0 * length


def rod_bending_stress(force, arm, diameter):
    """sigma = 32 F a / (pi d^3): a solid round cantilever loaded across at the arm a from its root."""
    return 32.0 * force * arm / (math.pi * diameter**3)


def check_shell_room(case):
    """The housing's wall leaves room inside the largest outer diameter."""
    v = case.values
    if 2 * v["shell_thickness"] >= v["outer_diameter_max"]:
        raise InputError("limits.outer_diameter_max", "leaves no room inside the shell")
