"""Which of a case's fields its checks across fields read: found once by running them, so that a sweep whose varied
quantities none of them reads checks the case once instead of at every point.

Why this is sound: a check is a pure function of the values it reads (``values[name]``, ``name in values``,
``values.get(name)``). Run at the case's own values, it reads a sequence of fields; at a point that differs only in
fields outside that sequence it reads the same fields, gets the same values at each read, so takes the same branches
and ends the same way (passes, or refuses with the same message). A check that looks at the whole mapping (iterates
it, copies it, counts it) reads every field; a check that refuses the case's own values decides nothing for another
point. Either way the answer is "unknown", and the sweep checks every point as before.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from typing import Any, Iterator


class ReadRecorder(Mapping):
    """A case's values that remember which names were asked for (``everything`` once the whole mapping was)."""

    def __init__(self, values: Mapping[str, Any]):
        self._values = values
        self.read: set[str] = set()
        self.everything = False

    def __getitem__(self, name: str) -> Any:
        self.read.add(name)
        return self._values[name]

    def __contains__(self, name: object) -> bool:
        self.read.add(name)  # type: ignore[arg-type]
        return name in self._values

    def __iter__(self) -> Iterator[str]:
        self.everything = True
        return iter(self._values)

    def __len__(self) -> int:
        self.everything = True
        return len(self._values)


def fields_read_across(case) -> frozenset[str] | None:
    """The names :func:`~clutchopt.cases.check_across` reads at ``case`` (all of its checks pass there), or None when
    that is not known: a check refuses the case (or fails on it), or reads the whole mapping of values."""
    from clutchopt.cases import check_across

    recorder = ReadRecorder(case.values)
    try:
        check_across(replace(case, values=recorder))
    except Exception:  # refused, or a field the case leaves out that a sweep gives (each point checked, as before)
        return None
    return None if recorder.everything else frozenset(recorder.read)


def followers(case, names) -> set[str]:
    """``names`` and every default that follows one of them (``Case.follows``, followed through chains): the fields
    a sweep of ``names`` changes."""
    changed = set(names)
    while True:
        more = {name for name, (source, _) in case.follows.items() if source in changed} - changed
        if not more:
            return changed
        changed |= more
