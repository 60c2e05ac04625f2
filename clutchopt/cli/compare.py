"""``clutchopt compare CASE``: the paper's method and closed forms beside the NLP optima."""

from __future__ import annotations

from clutchopt.cli.options import (
    add_case_argument,
    add_json_option,
    add_parser,
    add_quiet_option,
    add_robust_options,
    add_tolerance_option,
    robustness,
)


def add_command(commands) -> None:
    compare = add_parser(
        commands, "compare", "set the paper's hand method beside the optimiser's designs, quantity by quantity",
        "Columns: the paper's example as printed (where it has one), the paper's formulas evaluated, the\n"
        "consistent closed form, and IPOPT's optima in each mode; then every value relative to the closed form.\n"
        "docs/errata.md explains where and why the paper's formulas differ. With [start_up], [scatter] (and\n"
        "--robust to pick the method) and options.choose (the best choice, as solve ranks them), their columns too.",
        ("clutchopt compare cases/wedge_paper.toml", "clutchopt compare cases/ball_crusher.toml --json"))
    add_case_argument(compare)
    add_tolerance_option(compare)
    add_robust_options(compare)
    add_json_option(compare)
    add_quiet_option(compare)
    compare.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.compare import compare_case
    from clutchopt.optimise.design import design_case
    from clutchopt.output import comparison_json, comparison_text, to_json

    case = load_case(args.case)
    robust = robustness(args, case)
    note = ""
    if case.options.get("choose"):
        ranked = design_case(case, options=SolverOptions(tol=args.tol), robust=robust, progress=not args.quiet)
        case = ranked[0].case
        note = f"options.choose: compared for the best of {len(ranked)} choices, {ranked[0].choice_text} " \
               "(clutchopt solve lists them)"
    table = compare_case(case, SolverOptions(tol=args.tol), robust)
    if args.json:
        return to_json({"case": case.path, "title": case.title, **({"note": note} if note else {}),
                        **comparison_json(table)})
    return "\n".join(filter(None, [note, comparison_text(table.as_dict())]))
