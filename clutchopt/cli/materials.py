"""``clutchopt materials [--json]``: the material library, each entry with its source."""

from __future__ import annotations

from clutchopt.cli.options import add_json_option, add_parser


def add_command(commands) -> None:
    listing = add_parser(
        commands, "materials", "list the material library: steels and cast irons, friction pairs, thread pairs, "
                               "each with its source",
        "A case names entries in its [library] section (material = \"C45_QT\", friction_pair = \"organic_dry\");\n"
        "they fill the case's fields unless the case gives them itself. clutchopt couplings says which fields.",
        ("clutchopt materials", "clutchopt materials --kind friction_pairs", "clutchopt materials --json"))
    listing.add_argument("--kind", choices=("materials", "friction_pairs", "thread_pairs"),
                         help="list one table only")
    add_json_option(listing)
    listing.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.materials import FIELDS, KIND_TITLES, library
    from clutchopt.output import materials_text, to_json
    from clutchopt.units import si_unit

    kinds = [args.kind] if args.kind else list(FIELDS)
    if args.json:
        return to_json({kind: [{"name": e.name, "description": e.description, "source": e.source,
                                "notes": e.notes,
                                "values": {q.name: {"value": e.values[q.name], "unit": si_unit(q.unit),
                                                    "display_unit": q.unit} for q in e.fields()}}
                               for e in library()[kind].values()] for kind in kinds})
    return "\n\n".join(materials_text(kind, KIND_TITLES[kind]) for kind in kinds)
