"""``clutchopt couplings [--json]``: the couplings, their modes (what each frees), objectives and library roles."""

from __future__ import annotations

from clutchopt.cli.options import add_json_option, add_parser


def add_command(commands) -> None:
    couplings = add_parser(
        commands, "couplings", "list the couplings: their modes (what the optimiser may change), objectives and "
                               "the material-library entries a case can name",
        examples=("clutchopt couplings", "clutchopt couplings --json"))
    add_json_option(couplings, "print one JSON object instead of text")
    couplings.set_defaults(run=run)


def describe(coupling) -> dict:
    """A coupling as data: modes with what each frees, objectives, library roles."""
    return {
        "name": coupling.name, "title": coupling.title, "source": coupling.source,
        "default_mode": coupling.default_mode,
        "modes": [{"name": name, "title": f.title, "frees": f.frees(),
                   "variables": [v.name for v in f.variables if not v.fixed_unless_freed],
                   "freeable": [v.name for v in f.variables if v.fixed_unless_freed]}
                  for name, f in coupling.formulations.items()],
        "objectives": [{"name": o.name, "unit": o.unit, "description": o.description}
                       for o in coupling.formulation().objectives],
        "library": [{"key": r.key, "kind": r.kind, "parts": r.parts, "fills": dict(r.fills)}
                    for r in coupling.materials],
    }


def run(args) -> str:
    from clutchopt.formulations import MODULES, get_coupling
    from clutchopt.output import to_json

    described = [describe(get_coupling(name)) for name in MODULES]
    if args.json:
        return to_json({"couplings": described})
    lines = []
    for c in described:
        lines += [f"{c['name']}: {c['title']} ({c['source']})", "  modes:"]
        for mode in c["modes"]:
            label = mode["name"] + (" (default)" if mode["name"] == c["default_mode"] else "")
            lines += _wrapped(f"{label}: frees {mode['frees']}", "    ")
        lines += _wrapped("objectives: " + "; ".join(f"{o['name']} [{o['unit']}], {o['description']}"
                                                    for o in c["objectives"]), "  ")
        lines += _wrapped("[library]: " + "; ".join(f"{r['key']} ({r['kind']}): {r['parts']}"
                                                   for r in c["library"]), "  ")
        lines += [f"  start a case: clutchopt init {c['name']} -o my_{c['name']}.toml", ""]
    return "\n".join(lines).rstrip()


def _wrapped(text: str, indent: str) -> list[str]:
    import textwrap

    return textwrap.wrap(text, 116, initial_indent=indent, subsequent_indent=indent + "    ")
