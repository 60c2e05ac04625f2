"""``clutchopt pareto CASE``: mass against cost, the Pareto front by epsilon-constraint."""

from __future__ import annotations

import math
from dataclasses import replace

from clutchopt.cli.options import (
    FIGURE_SUFFIXES,
    add_case_argument,
    add_json_option,
    add_parser,
    add_problem_options,
    add_store_options,
    first_choice_note,
    recording,
    resolve_problem,
    whole_number,
)

MAX_FRONT_POINTS = 1000  # an epsilon-constraint solve each; a front is read from a few dozen


def add_command(commands) -> None:
    pareto = add_parser(
        commands, "pareto", "trade mass against cost: the designs between the lightest and the cheapest",
        "The front is traced by epsilon-constraint: the mass is minimised under a cap on the cost, the cap\n"
        "stepped from the lightest design's cost down to the cheapest design's.",
        ("clutchopt pareto cases/wedge_centrifuge.toml --mode geometry --points 5",
         "clutchopt pareto cases/lever_centrifuge.toml --mode design --plot front.png --out front.csv"))
    add_case_argument(pareto)
    add_problem_options(pareto, objective=False)  # mass and cost are the front's two ends
    pareto.add_argument("--points", type=whole_number(2, MAX_FRONT_POINTS), default=9,
                        help=f"designs on the front, the lightest and the cheapest included, 2 to {MAX_FRONT_POINTS} "
                             "(default 9)")
    pareto.add_argument("--plot", metavar="FILE",
                        help="also draw the front, mass against cost, into FILE (.png, .svg, .pdf)")
    pareto.add_argument("--out", metavar="FILE", help="also write the table: .csv, .parquet or .md")
    add_json_option(pareto)
    add_store_options(pareto)
    pareto.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.pareto import CAP, pareto_front
    from clutchopt.optimise.problem import case_formulation
    from clutchopt.files import check_output, write_whole
    from clutchopt.optimise.sweep import table_format, write_frame
    from clutchopt.optimise.verify import evaluate_objective
    from clutchopt.output import to_json, with_units
    from clutchopt.units import si_unit

    case = load_case(args.case)
    if args.out:
        table_format(args.out)  # a bad name fails before the solves, not after
    if args.plot:
        check_output("--plot", args.plot, FIGURE_SUFFIXES)
    resolve_problem(case, args, objective=False)
    with recording(args) as store:
        front = pareto_front(case, args.mode, args.points, SolverOptions(tol=args.tol))
        for cap, solution in zip(front.caps, front.solutions) if store is not None else ():
            capped = case if math.isnan(cap) else replace(case, values={**case.values, CAP: cap})
            store.record_solution("pareto", capped, solution)
    formulation = case_formulation(case, front.mode)
    if args.out:
        write_frame(front.frame, args.out)
    if args.plot:
        write_whole("--plot", args.plot, pareto_figure(front).savefig)
    if args.json:
        params = case.params()
        rows = [{"cost_cap": None if math.isnan(cap) else cap, "status": solution.status,
                 **{name: evaluate_objective(formulation, name, solution.design, params) for name in ("mass", "cost")},
                 "design": solution.design, "active": [c.name for c in solution.constraints if c.active and c.name != CAP]}
                for cap, solution in zip(front.caps, front.solutions)]
        ends = {name: si_unit(formulation.objective(name).unit) for name in ("mass", "cost")}
        units = {"cost_cap": ends["cost"], **ends, "design": {v.name: v.si_unit for v in formulation.variables}}
        return to_json(with_units({"case": case.path, "mode": front.mode, "note": front.note, "rows": rows},
                                  {"rows": units}))
    lines = [f"Pareto front, mass against cost (epsilon-constraint) - {case.title or case.path}, {front.mode} mode"]
    lines += [first_choice_note(case)] if case.options.get("choose") else []
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
