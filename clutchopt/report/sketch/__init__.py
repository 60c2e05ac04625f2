"""Dimensioned SVG sketches of optimal designs, drawn to scale, one module per coupling; the dimensions the
optimiser chose are drawn red and bold."""

from __future__ import annotations

from clutchopt.report.sketch.ball import ball_sketch
from clutchopt.report.sketch.cable import cable_sketch
from clutchopt.report.sketch.lever import lever_sketch
from clutchopt.report.sketch.wedge import wedge_sketch

SKETCHES = {"wedge": wedge_sketch, "lever": lever_sketch, "cable": cable_sketch, "ball": ball_sketch}


def sketch(coupling: str, values: dict[str, float], outputs: dict[str, float], optimised: set[str],
           effects: tuple[str, ...] = ()) -> str | None:
    """The SVG of a design: ``values`` are the case's SI values and the design merged, ``outputs`` the derived
    quantities (SI), ``optimised`` the variables the optimiser chose, ``effects`` the case's start-up effects (its
    springs are drawn where they have a preload). None where a mode lacks a dimension the sketch needs (e.g. the
    lever's lining width)."""
    draw = SKETCHES.get(coupling)
    if draw is None:
        return None
    try:
        return draw(values, outputs, optimised, effects)
    except (KeyError, TypeError, ValueError):
        return None
