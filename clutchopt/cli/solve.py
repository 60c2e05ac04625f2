"""``clutchopt solve CASE``: optimise a case and verify the optimum in float64."""

from __future__ import annotations

from clutchopt.cli.options import add_case_argument, add_json_option, add_problem_options, add_store_options


def add_command(commands) -> None:
    solve = commands.add_parser("solve", help="optimise a case and verify the optimum in float64")
    add_case_argument(solve)
    add_problem_options(solve)
    add_store_options(solve)
    solve.add_argument("--verify", action="store_true",
                       help="simulate the optimised design's start-up and compare its acceleration time with t_p")
    add_json_option(solve)
    solve.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.cli.options import open_store, record_solve, resolve_problem
    from clutchopt.optimise import SolverOptions, solve_case
    from clutchopt.optimise.problem import case_formulation
    from clutchopt.output import solution_text, to_json

    case = load_case(args.case)
    resolve_problem(case, args)
    store = open_store(args)
    solution = solve_case(case, args.mode, args.objective, SolverOptions(tol=args.tol))
    check = None
    if args.verify:
        from clutchopt.simulate import verify

        check = verify(case, solution)
    record_solve(store, case, solution, check)
    if args.json:
        return to_json({"case": case.path, "title": case.title, **solution.as_dict(),
                        **({"verify": check} if check else {})})
    formulation = case_formulation(case, solution.mode)
    text = solution_text(solution, formulation, case.title)
    if check:
        from clutchopt.simulate.design import verify_text

        text += "\n" + verify_text(check)
    return text
