"""``clutchopt solve CASE``: optimise a case and verify the optimum in float64."""

from __future__ import annotations

from clutchopt.cli.options import add_case_argument, add_json_option, add_parser, add_problem_options, add_store_options
from clutchopt.errors import InputError


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
    solve.add_argument("--robust", metavar="METHOD",
                       help="a design that holds under the case's [scatter]: worst-case (every constraint at its own "
                            "worst corner of the ranges) or chance=P (each holds with probability P, to first "
                            "order), checked by Monte Carlo beside the nominal design; e.g. --robust chance=0.999")
    solve.add_argument("--samples", type=int, metavar="N",
                       help="Monte Carlo samples of the scatter for --robust (default 10000)")
    add_json_option(solve)
    solve.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.cli.options import record_solve, recording, resolve_problem
    from clutchopt.materials import solve_choices
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.problem import case_formulation
    from clutchopt.output import CHECK_UNITS, choices_text, library_json, library_text, solution_json, \
        solution_text, to_json, with_units

    case = load_case(args.case)
    resolve_problem(case, args)
    if args.robust is not None:
        return _robust(case, args)
    if args.samples is not None:
        raise InputError("--samples", "counts the Monte Carlo samples of --robust; give --robust too")
    with recording(args) as store:
        ranked = solve_choices(case, args.mode, args.objective, SolverOptions(tol=args.tol))
        _, case, solution = ranked[0]
        check = None
        if args.verify:
            from clutchopt.simulate import verify

            check = verify(case, solution)
        for _, variant, variant_solution in ranked:
            record_solve(store, variant, variant_solution, check if variant_solution is solution else None)
    if args.json:
        choices = [{"choice": choice, **solution_json(s.as_dict())} for choice, _, s in ranked] if len(ranked) > 1 \
            else []
        return to_json(with_units({"case": case.path, "title": case.title, **solution_json(solution.as_dict()),
                                   "library": library_json(case), **({"choices": choices} if choices else {}),
                                   **({"verify": check} if check else {})}, {"verify": CHECK_UNITS}))
    formulation = case_formulation(case, solution.mode)
    parts = [choices_text(ranked)] if len(ranked) > 1 else []
    parts.append(solution_text(solution, formulation, case.title))
    if case.filled:
        parts.append(library_text(case))
    if check:
        from clutchopt.simulate.design import verify_text

        parts.append(verify_text(check))
    return "\n\n".join(parts)


def _robust(case, args) -> str:
    from clutchopt.cli.options import record_solve, recording
    from clutchopt.errors import InputError
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.problem import case_formulation
    from clutchopt.optimise.robust import MAX_SAMPLES, SAMPLES, parse_method, solve_robust
    from clutchopt.output import robust_json, robust_text, solution_json, solution_text, to_json

    method, target = parse_method(args.robust)
    samples = SAMPLES if args.samples is None else args.samples
    if not 100 <= samples <= MAX_SAMPLES:
        raise InputError("--samples", f"must be a whole number from 100 to {MAX_SAMPLES}, got {samples}")
    if case.options.get("choose"):
        raise InputError("--robust", "the case lets the optimiser choose library entries (options.choose): name one "
                                     "entry each for a robust design")
    if not case.scatter:
        raise InputError("--robust", "the case has no [scatter] section: say which quantities scatter and how "
                                     "(docs/robust.md)")
    with recording(args) as store:
        result = solve_robust(case, method, target, args.mode, args.objective, SolverOptions(tol=args.tol), samples)
        record_solve(store, case, result.solution)
    if args.json:
        return to_json({"case": case.path, "title": case.title, **solution_json(result.solution.as_dict()),
                        "status": result.status, "diagnosis": result.diagnosis, "robust": robust_json(result, case)})
    formulation = case_formulation(case, result.solution.mode)
    return "\n\n".join([solution_text(result.solution, formulation, case.title), robust_text(result, case)])
