"""clutchopt's imports, at module and at function level, go down the layers of clutchopt/layers.py and never round
in a circle; docs/architecture.md shows the same table."""

from __future__ import annotations

import ast
from pathlib import Path

from clutchopt.layers import LAYERS
from tests.conftest import ROOT


def _modules() -> dict[str, Path]:
    """Every module of clutchopt by its dotted name (a package by its own)."""
    modules = {}
    for path in sorted((ROOT / "clutchopt").rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        modules[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return modules


MODULES = _modules()


def _imports(name: str) -> dict[str, int]:
    """The modules of clutchopt that module ``name`` imports anywhere, each with the line of its first import.
    ``from x import y`` imports x.y where that is a module, else x; importing a module runs its packages first, so
    they count too (all but the packages of ``name`` itself, already running)."""
    found: dict[str, int] = {}
    for node in ast.walk(ast.parse(MODULES[name].read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            assert node.level == 0, f"{name}, line {node.lineno}: clutchopt imports absolutely"
            targets = [f"{node.module}.{alias.name}" for alias in node.names] + [node.module]
        else:
            continue
        for target in targets:
            while target and target not in MODULES:  # a name inside a module, or not clutchopt's
                target = target.rpartition(".")[0]
            if not target or target == name:
                continue
            found.setdefault(target, node.lineno)
            package = target.rpartition(".")[0]
            while package and not f"{name}.".startswith(f"{package}."):
                found.setdefault(package, node.lineno)
                package = package.rpartition(".")[0]
    return found


def _layer(module: str) -> int | None:
    """Index in LAYERS of the entry that names the module or, failing that, its closest package."""
    short = module.removeprefix("clutchopt").removeprefix(".") or "__init__"
    while short:
        for index, (_, _, names) in enumerate(LAYERS):
            if short in names:
                return index
        short = short.rpartition(".")[0]
    return None


GRAPH = {name: _imports(name) for name in MODULES}


def _reached(start: str) -> set[str]:
    seen, stack = set(), [start]
    while stack:
        for target in GRAPH[stack.pop()]:
            if target not in seen:
                seen.add(target)
                stack.append(target)
    return seen


def test_the_graph_sees_module_and_function_level_imports():
    assert GRAPH["clutchopt.cases"]["clutchopt.materials"]  # from clutchopt import materials: the submodule
    assert "clutchopt.start_up.section" in GRAPH["clutchopt.cases"]  # inside parse_case
    assert "clutchopt.optimise" in GRAPH["clutchopt.bench.reference"]  # optimise.verify's package runs first


def test_no_import_circles():
    reached = {name: _reached(name) for name in GRAPH}
    circles = {frozenset({name} | {other for other in reached[name] if name in reached[other]})
               for name in GRAPH if name in reached[name]}
    shown = ["; ".join(f"{a} -> {b} (line {GRAPH[a][b]})" for a in sorted(circle) for b in sorted(GRAPH[a])
                       if b in circle) for circle in circles]
    assert not shown, "import circles:\n" + "\n".join(shown)


def test_every_module_has_a_layer_and_every_entry_a_module():
    assert [name for name in MODULES if _layer(name) is None] == []  # place it in clutchopt/layers.py
    short = {name.removeprefix("clutchopt").removeprefix(".") or "__init__" for name in MODULES}
    assert [entry for _, _, names in LAYERS for entry in names if entry not in short] == []


def test_no_upward_imports():
    upward = [f"{name} ({LAYERS[_layer(name)][0]}) imports {target} ({LAYERS[_layer(target)][0]}), line {line}"
              for name, targets in GRAPH.items() for target, line in targets.items() if _layer(target) > _layer(name)]
    assert not upward, "upward imports:\n" + "\n".join(upward)


def test_the_architecture_page_shows_the_table():
    rows = [f"| {layer} | {', '.join(f'`{name}`' for name in names)} | {holds} |" for layer, holds, names in LAYERS]
    table = "\n".join(["| layer | modules of `clutchopt` | holds |", "|---|---|---|", *rows])
    assert table in (ROOT / "docs" / "architecture.md").read_text(encoding="utf-8"), table
