"""``clutchopt pareto CASE``: mass against cost, the Pareto front by epsilon-constraint."""

from __future__ import annotations

import math
from dataclasses import replace

from clutchopt.cli.options import (
    FIGURE_SUFFIXES,
    Checked,
    add_case_argument,
    add_json_option,
    add_parser,
    add_problem_options,
    add_quiet_option,
    add_robust_options,
    add_store_options,
    nominal_note,
    path,
    recording,
    resolve_problem,
    robustness,
    whole_number,
)

MAX_FRONT_POINTS = 1000  # an epsilon-constraint solve each; a front is read from a few dozen


def add_command(commands) -> None:
    pareto = add_parser(
        commands, "pareto", "trade mass against cost: the designs between the lightest and the cheapest",
        "The front is traced by epsilon-constraint: the mass is minimised under a cap on the cost, the cap\n"
        "stepped from the lightest design's cost down to the cheapest design's. With options.choose, one front per\n"
        "choice; with --robust, every design on it is designed for the case's [scatter].",
        ("clutchopt pareto cases/wedge_centrifuge.toml --mode geometry --points 5",
         "clutchopt pareto cases/lever_centrifuge.toml --mode design --plot front.png --out front.csv"))
    add_case_argument(pareto)
    add_problem_options(pareto, objective=False)  # mass and cost are the front's two ends
    pareto.add_argument("--points", action=Checked, check=whole_number(2, MAX_FRONT_POINTS), default=9,
                        help=f"designs on the front, the lightest and the cheapest included, 2 to {MAX_FRONT_POINTS} "
                             "(default 9)")
    pareto.add_argument("--plot", action=Checked, check=path, metavar="FILE",
                        help="also draw the front, mass against cost, into FILE (.png, .svg, .pdf)")
    pareto.add_argument("--out", action=Checked, check=path, metavar="FILE",
                        help="also write the table: .csv, .parquet or .md")
    add_robust_options(pareto)
    add_json_option(pareto)
    add_store_options(pareto)
    add_quiet_option(pareto)
    pareto.set_defaults(run=run)


def run(args) -> str:
    import pandas as pd

    from clutchopt.cases import load_case
    from clutchopt.files import check_output, written_together
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.design import Designed, method_of
    from clutchopt.optimise.pareto import CAP, pareto_fronts
    from clutchopt.optimise.sweep_table import table_format, write_frame
    from clutchopt.output import UNITLESS, to_json, with_units
    from clutchopt.store import CAPPED_SUFFIX

    case = load_case(args.case)
    if args.out:
        table_format(args.out)  # a bad name fails before the solves, not after
    if args.plot:
        check_output("--plot", args.plot, FIGURE_SUFFIXES)
    resolve_problem(case, args, objective=False)
    robust = robustness(args, case)
    with recording(args) as store:
        fronts = pareto_fronts(case, args.mode, args.points, SolverOptions(tol=args.tol), robust,
                               progress=not args.quiet)
        with written_together() as written:  # (both files or neither, then recorded: review 25)
            if args.out:
                write_frame(pd.concat([_with_choice(front) for front in fronts], ignore_index=True), args.out,
                            written=written)
            if args.plot:
                written("--plot", args.plot, pareto_figure(fronts).savefig)
        for front in fronts if store is not None else ():
            for k, (cap, solution) in enumerate(zip(front.caps, front.solutions)):
                outputs = Designed(front.choice, front.case, solution, front.robust[k] if front.robust else None)
                if math.isnan(cap):
                    store.record_solution("pareto", front.case, solution, outputs.as_dict(), method_of(robust))
                else:
                    store.record_solution("pareto", replace(front.case, values={**front.case.values, CAP: cap}),
                                          solution, outputs.as_dict(), method_of(robust),
                                          mode=f"{front.mode}{CAPPED_SUFFIX}")
    if args.json:
        shown = [_front_json(front) for front in fronts]
        return to_json(with_units({"case": case.path, "mode": fronts[0].mode,
                                   "robust": robust.as_dict(case) if robust is not None else None,
                                   **(shown[0] if len(fronts) == 1 else {"fronts": shown})}, {"robust": UNITLESS}))
    how = f", {robust.label} designs" if robust is not None else ""
    lines = [f"Pareto front, mass against cost (epsilon-constraint) - {case.title or case.path}, {fronts[0].mode} "
             f"mode{how}"]
    lines += filter(None, [nominal_note(case, robust)])
    for front in fronts:
        lines += [""] + ([f"options.choose: {_choice(front)}"] if front.choice else [])
        lines += [front.note] if front.note else []
        lines += [front.caveat] if front.caveat else []
        lines.append(front.frame.to_string(index=False, float_format=lambda v: f"{v:.6g}", na_rep="-"))
    lines += [f"figure written to {args.plot}"] if args.plot else []
    return "\n".join(lines)


def _choice(front) -> str:
    return ", ".join(f"{key} = {name}" for key, name in front.choice.items())


def _with_choice(front):
    """The front's table, its choice of options.choose as the first column where it has one."""
    return front.frame.assign(choice=_choice(front))[["choice", *front.frame.columns]] if front.choice \
        else front.frame


def _front_json(front) -> dict:
    """A front's rows (SI, with their units by column; a row without a design: its diagnosis, as solve's JSON), its
    choice of options.choose and its note; with --robust, each row's robust result (with its own units)."""
    from clutchopt.optimise.pareto import CAP
    from clutchopt.optimise.problem import case_formulation
    from clutchopt.optimise.verify import evaluate_objective
    from clutchopt.output import robust_json, with_units
    from clutchopt.units import si_unit

    formulation, params = case_formulation(front.case, front.mode), front.case.params()
    rows = [{"cost_cap": None if math.isnan(cap) else cap, "status": solution.status,
             **{name: evaluate_objective(formulation, name, solution.design, params) for name in ("mass", "cost")},
             "design": solution.design, "active": [c.name for c in solution.constraints if c.active and c.name != CAP],
             "diagnosis": solution.diagnosis,  # (a point without a design: why, its proof, as solve's JSON says)
             **({"robust": robust_json(front.robust[k], front.case)} if front.robust else {})}
            for k, (cap, solution) in enumerate(zip(front.caps, front.solutions))]
    ends = {name: si_unit(formulation.objective(name).unit) for name in ("mass", "cost")}
    units = {"cost_cap": ends["cost"], **ends, "design": {v.name: v.si_unit for v in formulation.variables}}
    return with_units({**({"choice": front.choice} if front.choice else {}), "note": front.note,
                       **({"caveat": front.caveat} if front.caveat else {}), "rows": rows},
                      {"rows": units})


def pareto_figure(fronts):
    """Mass against cost, a line per front (per choice of options.choose), the ends marked."""
    from matplotlib.figure import Figure

    from clutchopt.simulate.plot import literal

    figure = Figure(figsize=(5.5, 3.8), layout="constrained")
    axes = figure.add_subplot()
    for front in fronts:
        frame = front.frame[front.frame["status"] == "optimal"]
        mass, cost = [c for c in frame.columns if c.startswith("mass")][0], [c for c in frame.columns
                                                                            if c.startswith("cost [")][0]
        axes.plot(frame[cost], frame[mass], "o-", label=_choice(front) or None)
        if len(frame):
            axes.annotate("mass optimum", (frame[cost].iloc[0], frame[mass].iloc[0]), textcoords="offset points",
                          xytext=(-4, 14), ha="right")
            axes.annotate("cost optimum", (frame[cost].iloc[-1], frame[mass].iloc[-1]), textcoords="offset points",
                          xytext=(10, -4))
    if len(fronts) > 1:
        axes.legend(fontsize=7)
    axes.set_xlabel(cost)
    axes.set_ylabel(mass)
    axes.set_title(f"Pareto front, {literal(fronts[0].case.title or fronts[0].case.path)}", fontsize=9)
    axes.grid(alpha=0.3)
    return figure
