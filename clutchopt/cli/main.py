"""The ``clutchopt`` command: sizes centrifugal clutches and couplings by constrained optimisation.

One module per command in this package, each with ``add_command(subparsers)`` and ``run(args) -> str``; command
modules import only argparse helpers at the top, so building the parser stays cheap, and what a command needs is
imported when it runs. Bad input ends in ``error:`` lines and exit code 2.
"""

from __future__ import annotations

import os
import sys
import warnings
from importlib import import_module

from clutchopt import __version__
from clutchopt.cli.options import EXIT_BAD_INPUT, Parser
from clutchopt.errors import InputError

COMMANDS = ("init", "couplings", "materials", "solve", "compare", "simulate", "sweep", "pareto", "report", "runs",
            "bench")
DESCRIPTION = """\
Size centrifugal clutches and couplings by constrained optimisation (CasADi/IPOPT): the design of least mass or
cost that carries the torque within the allowable pressures and stresses. Every optimum is re-checked in float64
and set beside the published hand method.

start here:
  clutchopt couplings                   the couplings, what each mode lets the optimiser change, the objectives
  clutchopt init lever -o mine.toml     a new case to edit: every field with its unit, meaning and typical range
  clutchopt solve mine.toml             the optimum, every constraint with its margin, the sensitivities
  clutchopt materials                   the material library a case can name ([library] friction_pair = ...)

Every command explains itself: clutchopt solve --help."""


def build_parser() -> Parser:
    parser = Parser(prog="clutchopt", description=DESCRIPTION)
    parser.add_argument("--version", action="version", version=f"clutchopt {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND", parser_class=Parser,
                                     title="commands")
    for name in COMMANDS:
        import_module(f"clutchopt.cli.{name}").add_command(commands)
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
