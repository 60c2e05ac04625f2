"""The cases of the composition test (tests/test_composition.py): every coupling with every combination of the
aspects a case may have, made from its motor-start case (cases/<coupling>_motor_start.toml).

- ``start_up``: the case's own ``[start_up]``, collocated on 8 intervals a phase to 1e-4 (without it: the section,
  its free spring preload and bounds removed);
- ``scatter``: a range of +-10 % on a quantity that enters every mode: the friction coefficient of the wedge, lever
  and ball, the duty torque of the cable coupling;
- ``choose``: ``options.choose`` between two steels of the library for the coupling's material, whose fields the
  case then leaves to the library.
"""

from __future__ import annotations

import contextlib
import io
import itertools
import tomllib

from clutchopt.cli import main
from clutchopt.formulations import get_coupling
from tests.conftest import CASES

COUPLINGS = ("wedge", "ball", "lever", "cable")
ASPECTS = ((), ("start_up",), ("scatter", "worst-case"), ("scatter", "chance"), ("choose",),
           ("start_up", "scatter", "worst-case"), ("choose", "scatter", "worst-case"), ("choose", "start_up"))
SCATTERED = {"wedge": ("material", "friction_coefficient"), "ball": ("balls", "friction_coefficient"),
             "lever": ("material", "friction_coefficient"), "cable": ("duty", "torque")}
CHOSEN = {"wedge": "material", "ball": "ball_material", "lever": "material", "cable": "material"}
STEELS = ("C45_QT", "42CrMo4_QT")
COMMANDS = ("solve", "compare", "sweep", "pareto", "report")


def modes(coupling: str) -> tuple[str, ...]:
    return tuple(get_coupling(coupling).formulations)


def combinations() -> list[tuple[str, str, tuple[str, ...], str]]:
    """(command, coupling, aspects, mode), compare once per coupling and aspects (it solves every mode itself)."""
    return [(command, coupling, aspects, mode)
            for command, coupling, aspects in itertools.product(COMMANDS, COUPLINGS, ASPECTS)
            for mode in (modes(coupling)[:1] if command == "compare" else modes(coupling))]


def case_data(coupling: str, aspects: tuple[str, ...]) -> dict:
    """The motor-start case of ``coupling`` with the aspects named (see the module's docstring)."""
    data = tomllib.loads((CASES / f"{coupling}_motor_start.toml").read_text(encoding="utf-8"))
    if "start_up" in aspects:  # a coarser start than the cases' (what is tested here is that the aspects compose)
        data["start_up"].update(intervals=8, tolerance=1e-4)
    else:
        del data["start_up"]
        options, bounds = data.get("options", {}), data.get("bounds", {})
        options["free"] = [name for name in options.get("free", []) if name != "spring_preload"]
        bounds.pop("spring_preload", None)
    if "scatter" in aspects:
        section, name = SCATTERED[coupling]
        data["scatter"] = {name: [_scaled(data[section][name], 0.9), _scaled(data[section][name], 1.1)]}
    if "choose" in aspects:
        role = next(r for r in get_coupling(coupling).materials if r.key == CHOSEN[coupling])
        for table in data.values():
            if isinstance(table, dict):
                for quantity in role.fills.values():
                    table.pop(quantity, None)
        data.get("library", {}).pop(role.key, None)  # options.choose names the role, its first choice fills it
        data.setdefault("options", {})["choose"] = {role.key: list(STEELS)}
    return data


def _scaled(value, factor: float):
    """A case value (a number, or a quantity with its unit as text) times ``factor``."""
    if isinstance(value, str):
        number, _, unit = value.partition(" ")
        return f"{float(number) * factor!r} {unit}"
    return value * factor


def toml_text(data: dict, prefix: str = "") -> str:
    """TOML of a case: its keys, then its tables (the few value types cases use)."""
    def value(item) -> str:
        if isinstance(item, bool):
            return "true" if item else "false"
        if isinstance(item, str):
            return '"' + item.replace("\\", "\\\\").replace('"', '\\"') + '"'
        if isinstance(item, list):
            return "[" + ", ".join(value(v) for v in item) + "]"
        if isinstance(item, dict):
            return "{" + ", ".join(f"{k} = {value(v)}" for k, v in item.items()) + "}"
        return repr(item)

    tables = {k: v for k, v in data.items() if isinstance(v, dict)}
    lines = [f"{key} = {value(item)}" for key, item in data.items() if key not in tables]
    for key, table in tables.items():
        name = f"{prefix}{key}"
        lines += ["", f"[{name}]", toml_text(table, f"{name}.")]
    return "\n".join(lines)


def run(*argv) -> tuple[int, str, str]:
    """The command as a user runs it, in this process (its problems built once per worker): exit code, output,
    errors."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main([str(a) for a in argv])
    return code, out.getvalue(), err.getvalue()


SWEPT = {"wedge": "resisting_torque", "lever": "resisting_torque", "ball": "power", "cable": "speed"}  # enter every mode
