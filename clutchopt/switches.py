"""Environment switches read one way: on or off, or an ``error:`` line naming the variable.

A switch (``$CLUTCHOPT_BUILD_LATER``) is on for ``1``, ``true``, ``yes``, ``on`` and off for ``0``, ``false``, ``no``,
``off`` and the empty string (as ``CLUTCHOPT_CACHE=`` set empty turns compiled code off), any case, spaces around
ignored; unset, it takes its default. Any other value is refused by name (exit code 2 on the command line, checked
before a command runs: ``cli.options.check_options``), not read as on: ``CLUTCHOPT_BUILD_LATER=no`` had started
builds, since only ``0`` was off. Kept free of heavy imports: the command line checks the switches on every run.
"""

from __future__ import annotations

import os

from clutchopt.errors import InputError, shown_value

BUILD_LATER_ENV = "CLUTCHOPT_BUILD_LATER"  # off: no compiled start-up functions built in the background
# (optimise/start_up_compiled.py; a library already in the cache is still used)
SWITCHES = {BUILD_LATER_ENV: True}  # every switch and its value where unset
ON, OFF = ("1", "true", "yes", "on"), ("0", "false", "no", "off", "")


def switch(name: str) -> bool:
    """Whether the switch ``name`` (one of SWITCHES) is on; InputError naming it for a value neither on nor off."""
    text = os.environ.get(name)
    if text is None:
        return SWITCHES[name]
    word = text.strip().lower()
    if word in ON or word in OFF:
        return word in ON
    raise InputError(f"${name}", f"must be on ({', '.join(ON)}) or off ({', '.join(OFF[:-1])}, or empty), "
                                 f"got {shown_value(text)}")


def check_switches() -> None:
    """Every switch set to a value neither on nor off, refused by name in one InputError."""
    errors = []
    for name in SWITCHES:
        try:
            switch(name)
        except InputError as error:
            errors.append(error)
    if errors:
        raise InputError.several(errors)
