"""``clutchopt compare CASE``: the paper's method and closed forms beside the NLP optima."""

from __future__ import annotations

from clutchopt.cli.options import (
    add_case_argument,
    add_json_option,
    add_parser,
    add_tolerance_option,
    first_choice_note,
)


def add_command(commands) -> None:
    compare = add_parser(
        commands, "compare", "set the paper's hand method beside the optimiser's designs, quantity by quantity",
        "Columns: the paper's example as printed (where it has one), the paper's formulas evaluated, the\n"
        "consistent closed form, and IPOPT's optima in each mode; then every value relative to the closed form.\n"
        "docs/errata.md explains where and why the paper's formulas differ.",
        ("clutchopt compare cases/wedge_paper.toml", "clutchopt compare cases/ball_crusher.toml --json"))
    add_case_argument(compare)
    add_tolerance_option(compare)
    add_json_option(compare)
    compare.set_defaults(run=run)


def run(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.compare import compare_case
    from clutchopt.output import comparison_json, comparison_text, to_json

    case = load_case(args.case)
    table = compare_case(case, SolverOptions(tol=args.tol))
    if args.json:
        return to_json({"case": case.path, "title": case.title, **comparison_json(table)})
    return "\n".join(filter(None, [first_choice_note(case), comparison_text(table)]))
