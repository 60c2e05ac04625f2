"""``clutchopt report CASE -o review.html``: a self-contained HTML design-review page."""

from __future__ import annotations

from clutchopt.cli.options import (
    add_case_argument,
    add_parser,
    add_problem_options,
    add_store_options,
    first_choice_note,
    record_solve,
    recording,
    resolve_problem,
    warn,
)


def add_command(commands) -> None:
    report = add_parser(
        commands, "report", "write a design-review page (one HTML file, no links out) for a case",
        "Requirements, the optimal design with a dimensioned sketch to scale, constraint margins, sensitivities,\n"
        "the comparison with the paper's method, the start-up simulation, and a sweep plot if --sweep is given.",
        ("clutchopt report cases/wedge_paper.toml --mode geometry -o review.html",
         "clutchopt report cases/wedge_paper.toml --sweep sweep.csv -o review.html"))
    add_case_argument(report)
    report.add_argument("-o", "--out", required=True, metavar="FILE", help="the HTML page to write, e.g. review.html")
    add_problem_options(report)
    report.add_argument("--sweep", metavar="TABLE",
                        help="add a plot of this sweep table (.csv or .parquet written by clutchopt sweep --out)")
    add_store_options(report)
    report.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.files import check_output, write_whole
    from clutchopt.optimise import SolverOptions, solve_case
    from clutchopt.optimise.sweep import check_swept_from, read_frame
    from clutchopt.report import build_report

    case = load_case(args.case)
    check_output("--out", args.out, (".html", ".htm"))
    sweep = read_frame(args.sweep) if args.sweep else None
    if sweep is not None:
        check_swept_from(sweep, case, args.sweep, warn)
    resolve_problem(case, args)
    with recording(args) as store:
        solution = solve_case(case, args.mode, args.objective, SolverOptions(tol=args.tol))
        record_solve(store, case, solution)
    page = build_report(case, solution, sweep)

    def write(path: str) -> None:
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(page)

    write_whole("--out", args.out, write)
    note = first_choice_note(case)
    return (note + "\n" if note else "") + f"design review of {case.path} ({solution.status}, {solution.objective_name} " \
           f"{solution.objective:.6g} {solution.objective_unit}) written to {args.out}"
