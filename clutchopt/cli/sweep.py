"""``clutchopt sweep CASE --vary ...``: re-solve a case over a grid of requirements (warm-started, recorded)."""

from __future__ import annotations

import os

from clutchopt.cli.options import (
    Checked,
    add_case_argument,
    add_json_option,
    add_parser,
    add_problem_options,
    add_quiet_option,
    add_robust_options,
    add_store_options,
    choices_note,
    nominal_note,
    open_store,
    path,
    robustness,
    whole_number,
)
from clutchopt.errors import InputError, Problems

MAX_JOBS = 4 * (os.cpu_count() or 1)  # worker processes beyond this only compete for the cores
COLUMNS_SHOWN = 12  # a sweep up to this many points prints one column per point; longer ones a summary


def add_command(commands) -> None:
    sweep = add_parser(
        commands, "sweep", "re-solve a case over a grid of requirements: how the optimum moves with speed, sizes, ...",
        "Each --vary names a case quantity and its values in the quantity's display unit (speed in rpm, pressures\n"
        "in MPa, lengths in mm); several make a full-factorial grid. Each point starts from the last optimum;\n"
        "every point is recorded in the run store, so a sweep stopped half-way continues with --resume.\n"
        "With options.choose every choice is designed at every point and the best kept (column choice); with\n"
        "--robust each point is designed for the case's [scatter].",
        ("clutchopt sweep cases/wedge_paper.toml --vary speed=800,1000,1200",
         "clutchopt sweep cases/wedge_paper.toml --mode geometry --vary speed=500:3000:26 --out sweep.csv",
         "clutchopt sweep cases/wedge_paper.toml --vary speed=500:3000:40 --vary allowable_pressure=2:8:25 --jobs 2"))
    add_case_argument(sweep)
    sweep.add_argument("--vary", action="append", required=True, metavar="NAME=START:STOP:COUNT|NAME=V1,V2,...",
                       help="a case quantity in its display unit (speed in rpm, pressures in MPa, lengths in mm); "
                            "repeat for a full-factorial grid")
    sweep.add_argument("--zip", action="store_true",
                       help="pair the lists instead of crossing them: point i takes the i-th value of each --vary")
    add_problem_options(sweep)
    add_robust_options(sweep)
    sweep.add_argument("--jobs", action=Checked, check=whole_number(1, MAX_JOBS), default=1,
                       help=f"solve on N local processes, 1 to {MAX_JOBS} (default 1)")
    sweep.add_argument("--dask", metavar="ADDRESS",
                       help="solve on an existing Dask cluster, e.g. tcp://host:8786 (pip install 'clutchopt[dask]')")
    sweep.add_argument("--resume", action="store_true",
                       help="continue the latest identical sweep in the store; stored points are not solved again")
    sweep.add_argument("--out", action=Checked, check=path, metavar="FILE",
                       help="also write the table, one row per point: .csv, .parquet or .md")
    add_quiet_option(sweep, "no progress bar")
    add_json_option(sweep, "print one JSON object instead of tables: every point's inputs and solution, SI values "
                           "beside SI units")
    add_store_options(sweep)
    sweep.set_defaults(run=run)


def run(args) -> str:
    import gc

    from clutchopt.cases import load_case
    from clutchopt.optimise.sweep import Sweep, dask_runner
    from clutchopt.optimise.sweep_grid import parse_vary
    from clutchopt.optimise.sweep_table import table_format, write_frame

    gc.freeze()  # the modules just imported (150,000 objects) out of the cyclic collector's way (reference counting
    # still frees them): a full collection, which a stored sweep's records set off every 3000-4000 points, took 0.1 s

    case = load_case(args.case)
    if args.resume and args.no_store:
        raise InputError("--resume", "continues a sweep from the run store; drop --no-store")
    problems = Problems()
    varies = []
    for text in args.vary:
        with problems.field():
            varies.append(parse_vary(text, case.coupling, case.quantities))
    problems.raise_any()
    sweep = Sweep(case, varies, args.mode, args.objective, args.tol, args.zip, robustness(args, case))
    if args.out:
        table_format(args.out)  # a bad name fails before the solves, not after
    runner = dask_runner(args.dask) if args.dask is not None else None  # "" is an address too: refused
    store = open_store(args, needed=args.resume)
    try:
        result = sweep.run(store, args.resume, args.jobs, runner, progress=not args.quiet)
    except KeyboardInterrupt:
        where = f"; the points solved so far are in {store.path}, continue with --resume" if store else ""
        raise KeyboardInterrupt(f"sweep interrupted{where}") from None
    finally:
        if store is not None:
            store.close()
    if args.out:
        write_frame(result.frame, args.out, identity=sweep.identity())
    if args.json:
        from clutchopt.output import UNITLESS, shown_point, solution_json, to_json, with_units

        varied = {"point": UNITLESS, "values": {v.quantity.name: v.quantity.si_unit for v in sweep.varies}}
        points = [with_units(solution_json({"point": i, "values": values, **shown_point(solution)}), varied)
                  for i, (values, solution) in enumerate(zip(sweep.points, result.solutions))]
        return to_json(with_units({"case": case.path, "mode": sweep.formulation.mode,
                                   "objective": sweep.objective.name,
                                   "robust": sweep.robust.as_dict(case) if sweep.robust is not None else None,
                                   "sweep_id": result.sweep_id, "points": points},
                                  {"sweep_id": UNITLESS, "robust": UNITLESS}))
    text = "\n".join(filter(None, [choices_note(case), nominal_note(case, sweep.robust),
                                   sweep_text(sweep, result, store, args.out)]))
    if args.resume and not result.reused:
        text += "\n(nothing resumed: no stored points of an identical sweep)"
    return text


def sweep_text(sweep, result, store, out: str | None) -> str:
    from clutchopt.optimise.sweep_table import table_cell

    frame = result.frame
    counts = ", ".join(f"{count} {status}" for status, count in frame["status"].value_counts().items())
    objective = frame.columns[len(sweep.varies) + 2]
    designs = f", {sweep.robust.label} designs" if sweep.robust is not None else ""  # (review 30: not said)
    lines = [f"Sweep of {sweep.case.title or sweep.case.path} ({sweep.formulation.mode} mode, "
             f"objective {sweep.objective.name}{designs}): {len(frame)} points, {counts}",
             f"solved {result.solved} points in {result.elapsed_s:.1f} s"
             + (f", {result.reused} taken from the store" if result.reused else "")]
    if len(frame) <= COLUMNS_SHOWN:
        shown = frame.drop(columns=["diagnosis", "active"]).map(table_cell)
        table = shown.set_index("point").T
        table.columns = [f"point {i}" for i in table.columns]
        lines += ["", table.to_string(), ""]
        for active, group in frame[frame["status"] == "optimal"].groupby("active", sort=False):
            lines.append(f"active at points {', '.join(map(str, group['point']))}: {active or '(none)'}")
        lines += [f"point {row.point}: {row.diagnosis}" for row in frame.itertuples() if row.diagnosis]
    else:
        optimal = frame[frame["status"] == "optimal"][objective]
        if len(optimal):
            lines.append(f"{objective}: {optimal.min():.6g} to {optimal.max():.6g} over the optimal points")
    if store is not None and result.sweep_id is not None:
        held = len(frame) - store.unrecorded
        lines.append(f"recorded as sweep {result.sweep_id} in {store.path}" if held == len(frame) else
                     f"sweep {result.sweep_id} in {store.path} holds {held} of its {len(frame)} points")
    if store is not None and store.failure:
        lines.append(f"{store.unrecorded} points not recorded: {store.failure}")
    if out:
        lines.append(f"table written to {out}")
    return "\n".join(lines)
