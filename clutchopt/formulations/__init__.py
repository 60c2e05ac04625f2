"""One package per coupling; each exports ``COUPLING`` (a :class:`clutchopt.model.Coupling`)."""

from __future__ import annotations

from importlib import import_module

from clutchopt.errors import InputError, shown_value
from clutchopt.model import Coupling

MODULES = {
    "wedge": "clutchopt.formulations.wedge",
    "lever": "clutchopt.formulations.lever",
    "cable": "clutchopt.formulations.cable",
    "ball": "clutchopt.formulations.ball",
}


def get_coupling(name: object) -> Coupling:
    if isinstance(name, dict):  # (a scene's [coupling] table read as a case's: review 27)
        raise InputError("coupling", f"must be a coupling's name ({', '.join(MODULES)}), got {shown_value(name)}: "
                                     "is this a case file?")
    if not isinstance(name, str) or name not in MODULES:
        raise InputError("coupling", f"unknown coupling {name!r}; known: {', '.join(MODULES)}")
    return import_module(MODULES[name]).COUPLING
