"""The ``clutchopt`` command: sizes centrifugal clutches and couplings by constrained optimisation.

One module per command in this package, each with ``add_command(subparsers)`` and ``run(args) -> str``; command
modules import only argparse helpers at the top, so building the parser stays cheap, and what a command needs is
imported when it runs.

What a user sees when things go wrong: bad input ends in one ``error: <field>: <problem>`` line per problem and
exit code 2; Ctrl-C in one line and exit code 130; a bug (an exception no input check foresaw) in one line
``internal error: ... (details in <file>)`` and exit code 3, the traceback written to a crash file in the system's
temporary folder. A user never sees a traceback.
"""

from __future__ import annotations

import os
import sys
import warnings
from importlib import import_module

from clutchopt import __version__
from clutchopt.cli.options import EXIT_BAD_INPUT, EXIT_INTERNAL, EXIT_INTERRUPTED, Parser, check_options
from clutchopt.errors import InputError

COMMANDS = ("init", "couplings", "materials", "solve", "choose-coupling", "compare", "simulate", "sweep", "pareto", "report", "runs",
            "bench")
MAX_ERROR_LINES = 50  # a file with thousands of bad fields still gives a readable answer
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
        import_module(f"clutchopt.cli.{name.replace('-', '_')}").add_command(commands)
    return parser


def main(argv: list[str] | None = None) -> int:
    for stream in (sys.stdout, sys.stderr):  # a title in any script prints even where the terminal is ASCII
        if hasattr(stream, "reconfigure"):
            stream.reconfigure(errors="backslashreplace")
    try:
        return _run(argv)
    except KeyboardInterrupt as stop:  # Ctrl-C; a command may say what was kept (a sweep: how to resume)
        print(str(stop) or "interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception as exc:  # the last resort: every foreseeable failure is an InputError raised at the boundary
        from clutchopt.crash import write_crash_report

        where = write_crash_report(exc, sys.argv if argv is None else ["clutchopt", *argv])
        print(f"internal error: {type(exc).__name__}: {_one_line(str(exc))} (details in {where})", file=sys.stderr)
        return EXIT_INTERNAL


def _run(argv: list[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    warnings.filterwarnings("ignore", category=FutureWarning, module="casadi")
    try:
        check_options(args)
        text = args.run(args)
    except InputError as exc:
        print_errors(exc)
        return EXIT_BAD_INPUT
    try:
        print(text, flush=True)
    except BrokenPipeError:  # e.g. `clutchopt solve case.toml | head`: the reader left, nothing more to say
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
    except OSError as exc:  # e.g. `> /dev/full`: the output went where it cannot be written, like a bad --out
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        print_errors(InputError("standard output", f"cannot write the result ({exc.strerror or exc})"))
        return EXIT_BAD_INPUT
    return 0


def print_errors(exc: InputError) -> None:
    """One ``error:`` line per problem (at most MAX_ERROR_LINES, then how many more)."""
    problems = exc.problems
    for problem in problems[:MAX_ERROR_LINES]:
        print(f"error: {_one_line(str(problem))}", file=sys.stderr)
    if len(problems) > MAX_ERROR_LINES:
        print(f"error: ... and {len(problems) - MAX_ERROR_LINES} more problems", file=sys.stderr)


def _one_line(text: str) -> str:
    """A message on one line, not longer than a screen's worth."""
    text = " ".join(text.split())
    return text if len(text) <= 600 else text[:580] + " ..."
