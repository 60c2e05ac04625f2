"""One package per coupling; each exports ``COUPLING`` (a :class:`clutchopt.model.Coupling`)."""

from __future__ import annotations

from importlib import import_module

from clutchopt.errors import InputError
from clutchopt.model import Coupling

MODULES = {
    "wedge": "clutchopt.formulations.wedge",
    "lever": "clutchopt.formulations.lever",
    "cable": "clutchopt.formulations.cable",
    "ball": "clutchopt.formulations.ball",
}


def get_coupling(name: object) -> Coupling:
    if not isinstance(name, str) or name not in MODULES:
        raise InputError("coupling", f"unknown coupling {name!r}; known: {', '.join(MODULES)}")
    return import_module(MODULES[name]).COUPLING
