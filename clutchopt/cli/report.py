"""``clutchopt report CASE -o review.html``: a self-contained HTML design-review page; ``-o review.pdf``: the same
page printed by headless Chromium."""

from __future__ import annotations

from clutchopt.cli.options import (
    Checked,
    add_case_argument,
    add_parser,
    add_problem_options,
    add_quiet_option,
    add_robust_options,
    add_store_options,
    path,
    record_solve,
    recording,
    resolve_problem,
    robustness,
    warn,
)


def add_command(commands) -> None:
    report = add_parser(
        commands, "report", "write a design-review page (one HTML file, no links out, or a PDF) for a case",
        "What was verified, the requirements, the optimal design with a dimensioned sketch to scale, constraint\n"
        "margins, sensitivities, the comparison with the paper's method, the start-up simulation, and a sweep plot\n"
        "if --sweep is given. With options.choose the best choice is reviewed (as solve ranks them); with --robust\n"
        "the design for the case's [scatter] is, the nominal one beside it with its failure probabilities.\n"
        "-o review.pdf prints the page with headless Chromium (A4).",
        ("clutchopt report cases/wedge_paper.toml --mode geometry -o review.html",
         "clutchopt report cases/wedge_paper.toml --sweep sweep.csv -o review.html",
         "clutchopt report cases/wedge_motor_start.toml -o review.pdf"))
    add_case_argument(report)
    report.add_argument("-o", "--out", required=True, action=Checked, check=path, metavar="FILE",
                        help="the page to write: review.html, or review.pdf (printed by headless Chromium)")
    add_problem_options(report)
    report.add_argument("--sweep", action=Checked, check=path, metavar="TABLE",
                        help="add a plot of this sweep table (.csv or .parquet written by clutchopt sweep --out)")
    add_robust_options(report)
    add_store_options(report)
    add_quiet_option(report)
    report.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.files import check_output, write_whole
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.design import design_case, method_of
    from clutchopt.optimise.problem import case_formulation
    from clutchopt.optimise.sweep_table import check_swept_from, read_frame
    from clutchopt.report import build_report
    from clutchopt.report.sections import designed
    from clutchopt.report.pdf import print_pdf, require_chromium

    case = load_case(args.case)
    pdf = check_output("--out", args.out, (".html", ".htm", ".pdf")) == "pdf"
    chromium = require_chromium("--out") if pdf else None  # before any work
    sweep = read_frame(args.sweep) if args.sweep else None
    resolve_problem(case, args)
    robust = robustness(args, case)
    if sweep is not None:
        posed = (case_formulation(case, args.mode).mode, case.objective_of(args.objective),
                 robust.label if robust is not None else "")
        check_swept_from(sweep, case, args.sweep, warn, posed)
    with recording(args) as store:
        options = SolverOptions(tol=args.tol)
        ranked = design_case(case, args.mode, args.objective, options, robust, progress=not args.quiet)
        best = ranked[0]
        notes = (f"options.choose: the best of {len(ranked)} choices, {best.choice_text} (clutchopt solve lists "
                 "them)",) if best.choice else ()
        page = build_report(best.case, best.solution, sweep, best.robust, notes, options)

        def write(path: str) -> None:
            if pdf:
                print_pdf(chromium, page, path, "--out")
                return
            with open(path, "w", encoding="utf-8") as handle:
                handle.write(page)

        write_whole("--out", args.out, write)
        record_solve(store, best, method_of(robust))  # (once the page is written: review 25)
    solution = best.solution
    shown = (f"{solution.objective_name} {solution.objective:.6g} {solution.objective_unit}"
             + (f", {robust.label} design" if robust is not None else "")) if designed(solution) else "no design"
    return "\n".join([*notes, f"design review of {case.path} ({solution.status}, {shown}) written to {args.out}"])
