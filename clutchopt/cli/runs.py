"""``clutchopt runs list|show|export``: the run store."""

from __future__ import annotations

from clutchopt.cli.options import Parser, add_json_option

KINDS = ("solve", "sweep", "pareto", "simulation")


def add_command(commands) -> None:
    runs = commands.add_parser("runs", help="the run store: list, show or export recorded runs")
    actions = runs.add_subparsers(dest="action", required=True, metavar="ACTION", parser_class=Parser)
    listing = actions.add_parser("list", help="recorded runs, newest first, and the sweeps")
    listing.add_argument("--kind", choices=KINDS)
    listing.add_argument("--sweep", type=int, metavar="ID", help="only the points of this sweep")
    listing.add_argument("--limit", type=int, default=20, help="at most this many runs (default 20, 0: all)")
    add_json_option(listing)
    show = actions.add_parser("show", help="one run with its inputs, outputs and versions (JSON)")
    show.add_argument("id", type=int)
    export = actions.add_parser("export", help="runs as a table (.csv, .parquet, .md): status, objective, SI inputs "
                                               "and design, active constraints")
    export.add_argument("-o", "--out", required=True, metavar="FILE")
    export.add_argument("--kind", choices=KINDS)
    export.add_argument("--sweep", type=int, metavar="ID")
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
