"""The ``clutchopt`` command. Each sub-command is a small function; bad input ends in one line and exit code 2."""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from importlib import import_module

from clutchopt.errors import InputError

EXIT_BAD_INPUT = 2

# Further sub-commands live beside what they run; each module defines ``add_command(subparsers)``.
COMMAND_MODULES: tuple[str, ...] = (
    "clutchopt.simulate.command", "clutchopt.tradeoff_commands", "clutchopt.bench.command")


def _solve(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.formulations import get_coupling
    from clutchopt.optimise import SolverOptions, solve_case
    from clutchopt.output import solution_text, to_json
    from clutchopt.tradeoff_commands import record_solve

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


def _compare(args) -> str:
    from clutchopt.cases import load_case
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.compare import compare_case
    from clutchopt.output import comparison_text, to_json

    case = load_case(args.case)
    table = compare_case(case, SolverOptions(tol=args.tol))
    return to_json({"case": case.path, "title": case.title, **table.as_dict()}) if args.json else comparison_text(table)


def _positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be positive: {text!r}")
    return value


def add_problem_options(command: argparse.ArgumentParser, objective: bool = True) -> None:
    """--mode, --objective (unless the command sets both ends itself) and --tol: how a case is posed and solved."""
    command.add_argument("--mode", help="problem posing, e.g. paper or geometry (default: the case's, then the coupling's)")
    if objective:
        command.add_argument("--objective", help="mass or cost (default: the case's, then mass)")
    add_tolerance_option(command)


def add_tolerance_option(command: argparse.ArgumentParser) -> None:
    command.add_argument("--tol", type=_positive_float, default=1e-10, help="IPOPT tolerance (default 1e-10)")


class _Parser(argparse.ArgumentParser):
    """Usage mistakes end like bad input: one line, exit code 2."""

    def error(self, message: str):
        self.exit(EXIT_BAD_INPUT, f"error: {message} (see clutchopt {self.prog.split()[-1]} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    from clutchopt.tradeoff_commands import add_store_options

    parser = _Parser(prog="clutchopt", description=__doc__.splitlines()[0])
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND", parser_class=_Parser)

    solve = commands.add_parser("solve", help="optimise a case and verify the optimum in float64")
    solve.add_argument("case", help="case file (TOML)")
    add_problem_options(solve)
    add_store_options(solve)
    solve.add_argument("--verify", action="store_true",
                       help="simulate the optimised design's start-up and compare its acceleration time with t_p")
    solve.set_defaults(run=_solve)

    compare = commands.add_parser("compare", help="the paper's method and closed forms beside the NLP optima")
    compare.add_argument("case", help="case file (TOML)")
    add_tolerance_option(compare)
    compare.set_defaults(run=_compare)

    for command in (solve, compare):
        command.add_argument("--json", action="store_true", help="one JSON object, SI units")
    for module in COMMAND_MODULES:
        import_module(module).add_command(commands)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    warnings.filterwarnings("ignore", category=FutureWarning, module="casadi")
    try:
        text = args.run(args)
    except InputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return EXIT_BAD_INPUT
    try:
        print(text, flush=True)
    except BrokenPipeError:  # e.g. `clutchopt solve case.toml | head`: the reader left, nothing more to say
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    return 0
