"""``clutchopt solve CASE``: optimise a case and verify the optimum in float64."""

from __future__ import annotations

from clutchopt.cli.options import (
    add_case_argument,
    add_json_option,
    add_parser,
    add_problem_options,
    add_quiet_option,
    add_robust_options,
    add_store_options,
)


def add_command(commands) -> None:
    solve = add_parser(
        commands, "solve", "optimise a case: the design of least mass (or cost) that meets every requirement",
        "Prints the design, the derived quantities, every constraint re-evaluated in float64 with its margin and\n"
        "the elasticity of the optimum to its limit, then the parameters the optimum is most sensitive to.\n"
        "status is optimal only when IPOPT converged and the float64 check passes; an infeasible case gets a\n"
        "diagnosis naming the requirements that conflict. With options.choose in the case, every choice of\n"
        "library entries is solved and all are listed, the best first; with --robust, each is designed for the\n"
        "case's [scatter].",
        ("clutchopt solve cases/wedge_paper.toml",
         "clutchopt solve cases/wedge_paper.toml --mode geometry --objective cost",
         "clutchopt solve cases/wedge_paper.toml --verify --json > design.json"))
    add_case_argument(solve)
    add_problem_options(solve)
    add_store_options(solve)
    solve.add_argument("--verify", action="store_true",
                       help="simulate the optimised design's start-up and compare its acceleration time with t_p "
                            "(with --robust: at every corner of the scatter, the slowest shown)")
    add_robust_options(solve)
    add_json_option(solve)
    add_quiet_option(solve)
    solve.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.cli.options import nominal_note, record_solve, recording, resolve_problem, robustness
    from clutchopt.formulations import get_coupling
    from clutchopt.materials import chosen
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.design import design_case, method_of
    from clutchopt.optimise.problem import case_formulation
    from clutchopt.optimise.robust_verify import check_verifiable, verify_robust
    from clutchopt.output import choices_text, library_json, library_text, robust_text, solution_json, \
        solution_text, to_json, with_units

    case = load_case(args.case)
    resolve_problem(case, args)
    robust = robustness(args, case)
    if args.verify and robust is not None:
        check_verifiable(case)
    with recording(args) as store:
        ranked = design_case(case, args.mode, args.objective, SolverOptions(tol=args.tol), robust,
                             progress=not args.quiet)
        best = ranked[0]
        check = None
        if args.verify:
            from clutchopt.simulate import verify

            check = verify_robust(best.case, best.robust) if best.robust else verify(best.case, best.solution)
        for designed in ranked:  # each with its choice, the best one marked, and its robust result
            chosen_one = {"chosen": designed is best} if len(ranked) > 1 else {}
            record_solve(store, designed, method_of(robust), check if designed is best else None, chosen_one)
    if args.json:
        choices = [solution_json(d.as_dict()) for d in ranked] if len(ranked) > 1 else []
        return to_json(with_units({"case": case.path, "title": case.title, **solution_json(best.as_dict()),
                                   "library": library_json(best.case), **({"choices": choices} if choices else {}),
                                   **({"verify": check} if check else {})}, {"verify": verify_units(case, check)}))
    formulation = case_formulation(best.case, best.solution.mode)
    parts = [choices_text(ranked, chosen(case, get_coupling(case.coupling))[1])] if len(ranked) > 1 else []
    parts += filter(None, [nominal_note(case, robust)])
    parts.append(solution_text(best.solution, formulation, case.title))
    if best.robust is not None:
        parts.append(robust_text(best.robust, best.case))
    if best.case.filled:
        parts.append(library_text(best.case))
    if check:
        from clutchopt.start_up.simulation import verify_text

        quantities = {q.name: q for q in case.quantities}
        parts.append(verify_text(check) + ("" if "corner" not in check else
                                           f" (the robust design at the slowest of {check['corners']} corners of "
                                           f"the scatter: " + ", ".join(f"{q} {quantities[q].show(v)}"
                                                                        for q, v in check["corner"].items()) + ")"))
    return "\n\n".join(parts)


def verify_units(case, check: dict | None) -> dict:
    """The units of a --verify check's numbers: a robust design's corner in its quantities' SI units."""
    from clutchopt.output import CHECK_UNITS, UNITLESS

    corner = {"corner": {q.name: q.si_unit for q in case.quantities}, "corners": UNITLESS}
    return {**CHECK_UNITS, **(corner if check and "corner" in check else {})}
