"""``clutchopt solve CASE``: optimise a case and verify the optimum in float64."""

from __future__ import annotations

from clutchopt.cli.options import add_case_argument, add_json_option, add_problem_options, add_store_options, add_parser


def add_command(commands) -> None:
    solve = add_parser(
        commands, "solve", "optimise a case: the design of least mass (or cost) that meets every requirement",
        "Prints the design, the derived quantities, every constraint re-evaluated in float64 with its margin and\n"
        "the elasticity of the optimum to its limit, then the parameters the optimum is most sensitive to.\n"
        "status is optimal only when IPOPT converged and the float64 check passes; an infeasible case gets a\n"
        "diagnosis naming the requirements that conflict. With options.choose in the case, every choice of\n"
        "library entries is solved and all are listed, the best first.",
        ("clutchopt solve cases/wedge_paper.toml",
         "clutchopt solve cases/wedge_paper.toml --mode geometry --objective cost",
         "clutchopt solve cases/wedge_paper.toml --verify --json > design.json"))
    add_case_argument(solve)
    add_problem_options(solve)
    add_store_options(solve)
    solve.add_argument("--verify", action="store_true",
                       help="simulate the optimised design's start-up and compare its acceleration time with t_p")
    add_json_option(solve)
    solve.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.cli.options import record_solve
    from clutchopt.formulations import get_coupling
    from clutchopt.optimise import SolverOptions, solve_case
    from clutchopt.output import solution_text, to_json

    case = load_case(args.case)
    solution = solve_case(case, args.mode, args.objective, SolverOptions(tol=args.tol))
    check = None
    if args.verify:
        from clutchopt.simulate import verify

        check = verify(case, solution)
    record_solve(args, case, solution, check)
    if args.json:
        return to_json({"case": case.path, "title": case.title, **solution.as_dict(),
                        **({"verify": check} if check else {})})
    formulation = get_coupling(case.coupling).formulation(solution.mode)
    text = solution_text(solution, formulation, case.title)
    if check:
        from clutchopt.simulate.design import verify_text

        text += "\n" + verify_text(check)
    return text
