"""The parts every coupling's envelope counts that its own model does not size: the housing (drum) round the
working parts and the solid hub of a driving half. Each is a steel body of the coupling's own dimensions; the
proportions are ours, written in docs/envelope.md. Generic over floats and CasADi symbols."""

from __future__ import annotations

import math


def housing_mass(density, inner_radius, wall, inner_length, ends=1):
    """A drum: a cylinder of inner radius R and wall s over the inner length L, closed by ``ends`` end walls of
    radius R + s and thickness s: rho pi [((R + s)^2 - R^2) L + ends (R + s)^2 s]."""
    outer = inner_radius + wall
    return density * math.pi * ((outer**2 - inner_radius**2) * inner_length + ends * outer**2 * wall)


def housing_length(inner_length, wall, ends=1):
    """Axial length of that drum over its end walls: L + ends s."""
    return inner_length + ends * wall


def disc_mass(density, outer_radius, inner_radius, thickness):
    """An annular disc (a solid hub for inner_radius = 0): rho pi (R_o^2 - R_i^2) t."""
    return density * math.pi * (outer_radius**2 - inner_radius**2) * thickness
