"""``clutchopt report CASE -o review.html``: a self-contained HTML design-review page."""

from __future__ import annotations

from clutchopt.cli.options import (
    add_case_argument,
    add_problem_options,
    add_store_options,
    open_store,
    record_solve,
    resolve_problem,
)


def add_command(commands) -> None:
    report = commands.add_parser("report", help="a self-contained HTML design-review page for a case")
    add_case_argument(report)
    report.add_argument("-o", "--out", required=True, metavar="FILE", help="the HTML page to write")
    add_problem_options(report)
    report.add_argument("--sweep", metavar="TABLE", help="a sweep table (.csv or .parquet from sweep --out) to plot")
    add_store_options(report)
    report.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.files import check_output, write_whole
    from clutchopt.optimise import SolverOptions, solve_case
    from clutchopt.optimise.sweep import read_frame
    from clutchopt.report import build_report

    case = load_case(args.case)
    check_output("--out", args.out, (".html", ".htm"))
    sweep = read_frame(args.sweep) if args.sweep else None
    resolve_problem(case, args)
    store = open_store(args)
    solution = solve_case(case, args.mode, args.objective, SolverOptions(tol=args.tol))
    record_solve(store, case, solution)
    page = build_report(case, solution, sweep)

    def write(path: str) -> None:
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(page)

    write_whole("--out", args.out, write)
    return f"design review of {case.path} ({solution.status}, {solution.objective_name} " \
           f"{solution.objective:.6g} {solution.objective_unit}) written to {args.out}"
