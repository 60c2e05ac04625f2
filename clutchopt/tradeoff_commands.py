"""Sub-commands for trade-offs, recorded runs and reviews: ``sweep``, ``pareto``, ``report``, ``runs list/show/export``."""

from __future__ import annotations

import argparse
import math
from dataclasses import replace

import pandas as pd

from clutchopt.errors import InputError

COLUMNS_SHOWN = 12  # a sweep up to this many points prints one column per point; longer ones a summary


def add_store_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("--store", metavar="PATH",
                         help="run store (SQLite; default $CLUTCHOPT_STORE, then ./clutchopt-runs.sqlite)")
    command.add_argument("--no-store", action="store_true", help="do not record this run")


def open_store(args):
    """The run store the arguments ask for, or None with ``--no-store``."""
    from clutchopt.store import RunStore

    return None if getattr(args, "no_store", False) else RunStore(args.store)


def record_solve(args, case, solution, check: dict | None = None) -> None:
    """Record a ``solve`` (and its start-up check, a simulation) in the run store unless ``--no-store``."""
    store = open_store(args)
    if store is not None:
        with store:
            store.record_solution("solve", case, solution)
            if check is not None:
                store.record("simulation", {"values": case.values, "design": solution.design}, check,
                             status="verified" if check.get("verified") else "not verified",
                             objective=check.get("simulated_acceleration_time"), case_path=case.path,
                             title=case.title, coupling=case.coupling, mode=solution.mode,
                             objective_name="acceleration_time")


def record_simulation(args, scene, result) -> None:
    """Record a ``simulate`` run (scene file, headline, events) unless ``--no-store``."""
    from clutchopt.cases import read_toml

    store = open_store(args)
    if store is not None:
        with store:
            store.record("simulation", {"scene": read_toml(scene.path), "source": scene.source}, result.as_dict(),
                         status="locks up" if result.headline["locks_up"] else "no lock-up",
                         objective=result.headline.get("start_time"), case_path=scene.path, title=scene.title,
                         objective_name="start_time")


def add_command(commands) -> None:
    from clutchopt.cli import _Parser, add_problem_options

    sweep = commands.add_parser("sweep", help="re-solve a case over a grid of requirements (warm-started, recorded)")
    sweep.add_argument("case", help="case file (TOML)")
    sweep.add_argument("--vary", action="append", required=True, metavar="NAME=START:STOP:COUNT|NAME=V1,V2,...",
                       help="a case quantity in its display unit (speed in rpm, pressures in MPa, lengths in mm); "
                            "repeat for a full-factorial grid")
    sweep.add_argument("--zip", action="store_true", help="listed sweep: the i-th point takes the i-th value of each")
    add_problem_options(sweep)
    sweep.add_argument("--jobs", type=int, default=1, help="local worker processes (default 1)")
    sweep.add_argument("--dask", metavar="ADDRESS", help="run on an existing Dask cluster, e.g. tcp://host:8786")
    sweep.add_argument("--resume", action="store_true",
                       help="continue the latest identical sweep in the store; stored points are not solved again")
    sweep.add_argument("--out", metavar="FILE", help="write the table: .csv, .parquet or .md")
    sweep.add_argument("--quiet", action="store_true", help="no progress bar")
    sweep.add_argument("--json", action="store_true", help="one JSON object, SI units: every point's inputs and solution")
    add_store_options(sweep)
    sweep.set_defaults(run=_sweep)

    pareto = commands.add_parser("pareto", help="mass against cost: the Pareto front by epsilon-constraint")
    pareto.add_argument("case", help="case file (TOML)")
    add_problem_options(pareto, objective=False)  # mass and cost are the front's two ends
    pareto.add_argument("--points", type=int, default=9, help="points on the front, both ends included (default 9)")
    pareto.add_argument("--plot", metavar="FILE", help="write the front as a figure (.png, .svg, .pdf)")
    pareto.add_argument("--out", metavar="FILE", help="write the table: .csv, .parquet or .md")
    pareto.add_argument("--json", action="store_true", help="one JSON object, SI units")
    add_store_options(pareto)
    pareto.set_defaults(run=_pareto)

    report = commands.add_parser("report", help="a self-contained HTML design-review page for a case")
    report.add_argument("case", help="case file (TOML)")
    report.add_argument("-o", "--out", required=True, metavar="FILE", help="the HTML page to write")
    add_problem_options(report)
    report.add_argument("--sweep", metavar="TABLE", help="a sweep table (.csv or .parquet from sweep --out) to plot")
    add_store_options(report)
    report.set_defaults(run=_report)

    runs = commands.add_parser("runs", help="the run store: list, show or export recorded runs")
    actions = runs.add_subparsers(dest="action", required=True, metavar="ACTION", parser_class=_Parser)
    listing = actions.add_parser("list", help="recorded runs, newest first, and the sweeps")
    listing.add_argument("--kind", choices=("solve", "sweep", "pareto", "simulation"))
    listing.add_argument("--sweep", type=int, metavar="ID", help="only the points of this sweep")
    listing.add_argument("--limit", type=int, default=20, help="at most this many runs (default 20, 0: all)")
    listing.add_argument("--json", action="store_true", help="one JSON object, SI units")
    show = actions.add_parser("show", help="one run with its inputs, outputs and versions (JSON)")
    show.add_argument("id", type=int)
    export = actions.add_parser("export", help="runs as a table (.csv, .parquet, .md): status, objective, SI inputs "
                                               "and design, active constraints")
    export.add_argument("-o", "--out", required=True, metavar="FILE")
    export.add_argument("--kind", choices=("solve", "sweep", "pareto", "simulation"))
    export.add_argument("--sweep", type=int, metavar="ID")
    for action in (listing, show, export):
        action.add_argument("--store", metavar="PATH", help="run store (default $CLUTCHOPT_STORE, then "
                                                            "./clutchopt-runs.sqlite)")
    runs.set_defaults(run=_runs)


def _sweep(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.optimise.sweep import Sweep, dask_runner, parse_vary, table_format, write_frame

    case = load_case(args.case)
    if args.jobs < 1:
        raise InputError("--jobs", f"must be at least 1, got {args.jobs}")
    if args.resume and args.no_store:
        raise InputError("--resume", "continues a sweep from the run store; drop --no-store")
    sweep = Sweep(case, [parse_vary(text, case.coupling) for text in args.vary], args.mode, args.objective,
                  args.tol, args.zip)
    if args.out:
        table_format(args.out)  # a bad name fails before the solves, not after
    runner = dask_runner(args.dask) if args.dask else None
    store = open_store(args)
    try:
        result = sweep.run(store, args.resume, args.jobs, runner, progress=not args.quiet)
    except KeyboardInterrupt:
        where = f"; the points solved so far are in {store.path}, continue with --resume" if store else ""
        raise SystemExit(f"sweep interrupted{where}") from None
    finally:
        if store is not None:
            store.close()
    if args.out:
        write_frame(result.frame, args.out)
    if args.json:
        from clutchopt.output import to_json

        return to_json({"case": case.path, "mode": sweep.formulation.mode, "objective": sweep.objective.name,
                        "sweep_id": result.sweep_id, "points": [{"point": i, "values": values, **solution}
                        for i, (values, solution) in enumerate(zip(sweep.points, result.solutions))]})
    text = sweep_text(sweep, result, store.path if store else None, args.out)
    if args.resume and not result.reused:
        text += "\n(nothing resumed: no stored points of an identical sweep)"
    return text


def sweep_text(sweep, result, store_path: str | None, out: str | None) -> str:
    frame = result.frame
    counts = ", ".join(f"{count} {status}" for status, count in frame["status"].value_counts().items())
    objective = frame.columns[len(sweep.varies) + 2]
    lines = [f"Sweep of {sweep.case.title or sweep.case.path} ({sweep.formulation.mode} mode, "
             f"objective {sweep.objective.name}): {len(frame)} points, {counts}",
             f"solved {result.solved} points in {result.elapsed_s:.1f} s"
             + (f", {result.reused} taken from the store" if result.reused else "")]
    if len(frame) <= COLUMNS_SHOWN:
        shown = frame.drop(columns=["diagnosis", "active"]).map(lambda v: f"{v:.6g}" if isinstance(v, float) else v)
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
    if store_path:
        lines.append(f"recorded as sweep {result.sweep_id} in {store_path}")
    if out:
        lines.append(f"table written to {out}")
    return "\n".join(lines)


def _pareto(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.optimise import SolverOptions
    from clutchopt.formulations import get_coupling
    from clutchopt.optimise.pareto import CAP, pareto_front
    from clutchopt.optimise.sweep import write_frame
    from clutchopt.optimise.verify import evaluate_objective
    from clutchopt.output import to_json

    case = load_case(args.case)
    if args.points < 2:
        raise InputError("--points", f"a front needs at least 2 points, got {args.points}")
    front = pareto_front(case, args.mode, args.points, SolverOptions(tol=args.tol))
    formulation = get_coupling(case.coupling).formulation(front.mode)
    store = open_store(args)
    if store is not None:
        with store:
            for cap, solution in zip(front.caps, front.solutions):
                capped = case if math.isnan(cap) else replace(case, values={**case.values, CAP: cap})
                store.record_solution("pareto", capped, solution)
    if args.out:
        write_frame(front.frame, args.out)
    if args.plot:
        pareto_figure(front).savefig(args.plot)
    if args.json:
        params = case.params()
        rows = [{"cost_cap": None if math.isnan(cap) else cap, "status": solution.status,
                 **{name: evaluate_objective(formulation, name, solution.design, params) for name in ("mass", "cost")},
                 "design": solution.design, "active": [c.name for c in solution.constraints if c.active and c.name != CAP]}
                for cap, solution in zip(front.caps, front.solutions)]
        return to_json({"case": case.path, "mode": front.mode, "note": front.note, "rows": rows})
    lines = [f"Pareto front, mass against cost (epsilon-constraint) - {case.title or case.path}, {front.mode} mode"]
    if front.note:
        lines.append(front.note)
    lines += ["", front.frame.to_string(index=False, float_format=lambda v: f"{v:.6g}", na_rep="-")]
    lines += [f"figure written to {args.plot}"] if args.plot else []
    return "\n".join(lines)


def pareto_figure(front):
    """Mass against cost, the ends marked."""
    from matplotlib.figure import Figure

    frame = front.frame[front.frame["status"] == "optimal"]
    mass, cost = [c for c in frame.columns if c.startswith("mass")][0], [c for c in frame.columns
                                                                        if c.startswith("cost [")][0]
    figure = Figure(figsize=(5.5, 3.8), layout="constrained")
    axes = figure.add_subplot()
    axes.plot(frame[cost], frame[mass], "o-", color="tab:blue")
    if len(frame):
        axes.annotate("mass optimum", (frame[cost].iloc[0], frame[mass].iloc[0]), textcoords="offset points",
                      xytext=(-4, 14), ha="right")
        axes.annotate("cost optimum", (frame[cost].iloc[-1], frame[mass].iloc[-1]), textcoords="offset points",
                      xytext=(10, -4))
    axes.set_xlabel(cost)
    axes.set_ylabel(mass)
    axes.set_title(f"Pareto front, {front.case.title or front.case.path}", fontsize=9)
    axes.grid(alpha=0.3)
    return figure


def _report(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.optimise import SolverOptions, solve_case
    from clutchopt.optimise.sweep import read_frame
    from clutchopt.report import build_report

    case = load_case(args.case)
    sweep = read_frame(args.sweep) if args.sweep else None
    solution = solve_case(case, args.mode, args.objective, SolverOptions(tol=args.tol))
    record_solve(args, case, solution)
    page = build_report(case, solution, sweep)
    try:
        with open(args.out, "w", encoding="utf-8") as handle:
            handle.write(page)
    except OSError as exc:
        raise InputError("--out", f"cannot write {args.out!r} ({exc.strerror})") from None
    return f"design review of {case.path} ({solution.status}, {solution.objective_name} " \
           f"{solution.objective:.6g} {solution.objective_unit}) written to {args.out}"


def _runs(args) -> str:
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
