"""A new case file to start from (``clutchopt init``): complete, commented, and solvable as written.

Everything the file says about a field (meaning, paper symbol, unit, valid range, default) comes from the
coupling's quantity declarations; the starting values, their typical ranges and sources from a small table,
clutchopt/data/starting_values.toml; the library entries it names from the material library.
"""

from __future__ import annotations

import math
import textwrap
import tomllib
from functools import lru_cache
from importlib.resources import files

from clutchopt import __version__, materials
from clutchopt.formulations import get_coupling
from clutchopt.model import REQUIRED, Coupling, Formulation, Quantity, Variable

WIDTH = 116  # characters per comment line


@lru_cache(maxsize=1)
def starting_values() -> dict:
    """The table of starting values, by coupling."""
    return tomllib.loads(files("clutchopt.data").joinpath("starting_values.toml").read_text(encoding="utf-8"))


def case_template(coupling_name: str, mode: str | None = None) -> str:
    """The text of a new case of ``coupling_name``, posed in ``mode`` (default: the coupling's default mode)."""
    coupling = get_coupling(coupling_name)
    formulation = coupling.formulation(mode)
    start = starting_values()[coupling.name]
    entries = {role.key: materials.lookup(role, name, f"starting values: {role.key}")
               for role in coupling.materials if (name := start.get("library", {}).get(role.key))}
    lines = _header(coupling, formulation, mode) + [f'coupling = "{coupling.name}"', f'title = "{start["title"]}"', ""]
    lines += _library_section(coupling, entries, start.get("unset", {}))
    filled = {quantity: (role, entries[role.key]) for role in coupling.materials if role.key in entries
              for field, quantity in role.fills.items() if field in entries[role.key].values}
    sections = list(dict.fromkeys(q.section for q in coupling.quantities))
    for section in sections:
        fields = [line for quantity in coupling.quantities if quantity.section == section
                  for line in _field(quantity, start["values"].get(quantity.name, {}), filled.get(quantity.name))]
        lines += ["", f"[{section}]", *fields[1:]]  # each field opens with a blank line; not the first
    lines += _bounds_section(formulation, start.get("bounds", {}))
    lines += _options_section(coupling, formulation, mode, start)
    return "\n".join(lines) + "\n"


def _comment(text: str, indent: str = "") -> list[str]:
    """``text`` as comment lines; continuation lines indented by ``indent`` (a list item's hanging indent)."""
    return textwrap.wrap(text, WIDTH, initial_indent="# ", subsequent_indent="# " + indent, break_on_hyphens=False)


def _header(coupling: Coupling, formulation: Formulation, mode: str | None) -> list[str]:
    command = f"clutchopt init {coupling.name}" + (f" --mode {mode}" if mode else "")
    modes = "; ".join(f"{name}{' (default)' if name == coupling.default_mode else ''} frees {f.frees()}"
                      for name, f in coupling.formulations.items())
    lines = _comment(f"A new case of the {coupling.title.lower()} ({coupling.source}), written by `{command}` "
                     f"(clutchopt {__version__}). It solves as written: clutchopt solve THIS_FILE.")
    lines.append("#")
    for paragraph in (
        "Every value carries its unit; any unit of the same dimension works (\"1450 rpm\" or \"151.8 rad/s\"), "
        "a bare number is SI. Above each field: its meaning (paper symbol), unit, valid range, typical range and "
        "where the value comes from.",
        "A line \"# name = value\" is a default or a value from the material library: uncomment it to set it.",
        "[library] names entries of the material library (clutchopt materials lists them with their sources); "
        "each fills the fields marked \"from the library\" unless the case gives them itself.",
        f"Modes ([options] mode, or --mode on the command line): {modes}.",
    ):
        lines += _comment(f"- {paragraph}", "  ")
    return lines + [""]


def _library_section(coupling: Coupling, entries: dict, unset: dict) -> list[str]:
    if not coupling.materials:
        return []
    lines = ["[library]"]
    for role in coupling.materials:
        known = ", ".join(materials.library()[role.kind])
        lines += _comment(f"{role.key}: {role.parts}. Fills {', '.join(role.fills.values())}. Known {role.kind}: "
                          f"{known}.")
        entry = entries.get(role.key)
        if entry is None:
            lines.append(f'# {role.key} = "{unset.get(role.key, next(iter(materials.library()[role.kind])))}"')
            continue
        lines += _comment(f"{entry.name}: {entry.description} ({entry.source}).")
        lines.append(f'{role.key} = "{entry.name}"')
    return lines


def _literal(value) -> str:
    """A case value as TOML: text quoted, numbers bare."""
    if isinstance(value, str):
        return f'"{value}"'
    return repr(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else str(value)


def _shown(quantity: Quantity, si_value: float) -> str:
    """An SI value as a case line writes it: ``"0.25 MPa"``, or a bare number for a dimensionless quantity."""
    return _literal(quantity.show(si_value)) if quantity.unit else f"{si_value:.6g}"


def _field(quantity: Quantity, start: dict, filled) -> list[str]:
    """Comment and line of one quantity: active when the starting table gives a value, else commented."""
    what = quantity.description + (f" ({quantity.symbol})" if quantity.symbol else "")
    facts = [quantity.unit or "dimensionless", f"valid {quantity.valid_range()}"]
    if "typical" in start:
        facts.append(f"typical {start['typical']}")
    if "value" in start:
        facts.append(f"value: {start.get('source', 'ours')}")
        line = f"{quantity.name} = {_literal(start['value'])}"
    elif filled is not None:
        role, entry = filled
        library_field = next(f for f, q in role.fills.items() if q == quantity.name)
        facts.append(f"from the library: {role.key} {entry.name} ({library_field})")
        line = f"# {quantity.name} = {_shown(quantity, entry.values[library_field])}"
    elif quantity.default is REQUIRED:
        raise KeyError(f"starting values: {quantity.key} is required and has no starting value")
    elif quantity.default is None:
        facts.append("optional: leave it out unless you need it")
        line = f'# {quantity.name} = "? {quantity.unit}"' if quantity.unit else f"# {quantity.name} = ?"
    else:
        facts.append("default: clutchopt's (the formulation's declaration)")
        line = f"# {quantity.name} = {_literal(quantity.default)}"
    return ["", *_comment(what), *_comment("  " + "; ".join(facts), "  "), line]


def _bound(variable: Variable, value: float) -> str:
    if variable.integer:
        return str(int(value))
    return _shown(variable, value) if math.isfinite(value) else "inf"


def _bounds_section(formulation: Formulation, start: dict) -> list[str]:
    lines = ["", "[bounds]"]
    lines += _comment(f"The search box of the design variables in {formulation.mode} mode, [lower, upper]: the "
                      "defaults, commented; uncomment a line to narrow or widen it.")
    for variable in formulation.variables:
        if variable.name in start:
            lines += _comment(f"{variable.description} ({variable.symbol}): {start[variable.name]['source']}.")
            lines.append(f"{variable.name} = [{', '.join(_literal(v) for v in start[variable.name]['value'])}]")
            continue
        pair = f"[{_bound(variable, variable.lower)}, {_bound(variable, variable.upper)}]"
        lines.append(f"# {variable.name} = {pair}".ljust(56) + f"# {variable.description}")
    return lines


def _options_section(coupling: Coupling, formulation: Formulation, mode: str | None, start: dict) -> list[str]:
    lines = ["", "[options]"]
    lines += _comment(f"mode: how the case is posed ({', '.join(coupling.formulations)}; clutchopt couplings says "
                      f"what each frees). This case: {formulation.mode}, which frees {formulation.frees()}.")
    lines.append(f'{"" if mode else "# "}mode = "{formulation.mode}"')
    objectives = "; ".join(f"{o.name} [{o.unit}]: {o.description}" for o in formulation.objectives)
    lines += _comment(f"objective: what the optimum minimises ({objectives}).")
    lines.append(f'# objective = "{formulation.objectives[0].name}"')
    freeable = [v.name for v in coupling.variables if v.fixed_unless_freed]
    if freeable:
        lines += _comment("free: variables that stay at the case's value unless listed here.")
        lines.append(f"# free = [{', '.join(_literal(name) for name in freeable)}]")
    if "choose" in start:
        lines += _comment("choose: library entries to try, in place of the one [library] names (delete its line "
                          "there); each combination is solved and all are reported, the best first.")
        lines.append("# choose = { " + ", ".join(f"{key} = [{', '.join(map(_literal, names))}]"
                                               for key, names in start["choose"].items()) + " }")
    return lines
