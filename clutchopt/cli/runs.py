"""``clutchopt runs list|show|export``: the run store."""

from __future__ import annotations

from clutchopt.cli.options import Parser, add_json_option, add_parser

KINDS = ("solve", "sweep", "pareto", "simulation")


def add_command(commands) -> None:
    runs = add_parser(
        commands, "runs", "list, show or export the runs recorded in the run store",
        "Every solve, sweep point, Pareto point and simulation is recorded (./clutchopt-runs.sqlite unless\n"
        "--store or $CLUTCHOPT_STORE says otherwise), with its inputs, outputs, status and versions.",
        ("clutchopt runs list", "clutchopt runs show 3", "clutchopt runs export -o runs.csv --kind sweep"))
    actions = runs.add_subparsers(dest="action", required=True, metavar="ACTION", parser_class=Parser)
    listing = actions.add_parser("list", help="recorded runs, newest first, and the sweeps")
    listing.add_argument("--kind", choices=KINDS, help="only runs of this kind")
    listing.add_argument("--sweep", type=int, metavar="ID",
                         help="only the points of sweep ID (clutchopt runs list shows the sweeps)")
    listing.add_argument("--limit", type=int, default=20,
                         help="show at most this many runs, newest first (default 20; 0: all)")
    add_json_option(listing)
    show = actions.add_parser("show", help="one run with its inputs, outputs and versions (JSON)")
    show.add_argument("id", type=int, help="the run's id, as runs list shows it")
    export = actions.add_parser("export", help="runs as a table (.csv, .parquet, .md): status, objective, SI inputs "
                                               "and design, active constraints")
    export.add_argument("-o", "--out", required=True, metavar="FILE", help="the table to write: .csv, .parquet or .md")
    export.add_argument("--kind", choices=KINDS, help="only runs of this kind")
    export.add_argument("--sweep", type=int, metavar="ID", help="only the points of sweep ID")
    for action in (listing, show, export):
        action.add_argument("--store", metavar="PATH", help="run store (default $CLUTCHOPT_STORE, then "
                                                            "./clutchopt-runs.sqlite)")
    runs.set_defaults(run=run)


def run(args) -> str:
    import pandas as pd

    from clutchopt.optimise.sweep import table_format, write_frame
    from clutchopt.output import to_json
    from clutchopt.store import RunStore

    with RunStore(args.store) as store:
        if args.action == "show":
            return to_json(store.run(args.id))
        if args.action == "export":
            table_format(args.out)
            runs = pd.DataFrame(store.flat(args.kind, args.sweep))
            write_frame(runs, args.out)
            return f"{len(runs)} runs written to {args.out}"
        listed, swept = store.runs(args.kind, args.sweep, args.limit or None), store.sweeps()
        if args.json:
            return to_json({"store": str(store.path), "runs": listed, "sweeps": swept})
        runs, sweeps = pd.DataFrame(listed), pd.DataFrame(swept)
    lines = [f"Runs in {store.path} (newest first)", runs.to_string(index=False) if len(runs) else "(none)"]
    if len(sweeps) and args.sweep is None:
        lines += ["", "Sweeps", sweeps.to_string(index=False)]
    return "\n".join(lines)
