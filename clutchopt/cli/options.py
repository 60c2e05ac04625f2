"""What several commands share: the parser class, option groups, the run store. Imports nothing heavy."""

from __future__ import annotations

import argparse
import sys
from contextlib import contextmanager
from typing import Iterator

from clutchopt.errors import InputError, Problems
from clutchopt.solver_tolerance import SOLVER_TOL, TOLERANCE_RANGE
from clutchopt.switches import check_switches

EXIT_BAD_INPUT = 2
EXIT_INTERNAL = 3  # a bug: one line and a crash file (clutchopt.crash)
EXIT_INTERRUPTED = 130  # Ctrl-C, as a shell reports SIGINT


# The modes of each coupling, its default first: the --mode help lists them without importing the formulations
# (tests/test_init.py checks this index against them).
COUPLING_MODES = {"wedge": ("paper", "geometry"), "lever": ("paper", "design"), "cable": ("paper", "threads"),
                  "ball": ("design", "paper")}
MODE_HELP = ("how the case is posed, i.e. what the optimiser may change: " + "; ".join(
    f"{coupling}: {modes[0]} (default), {', '.join(modes[1:])}" for coupling, modes in COUPLING_MODES.items())
    + ". `clutchopt couplings` says what each mode frees. Default: the case's [options] mode, then the "
      "coupling's default")


class Parser(argparse.ArgumentParser):
    """Usage mistakes end like bad input: one line, exit code 2. Descriptions and examples keep their lines."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        super().__init__(*args, **kwargs)

    def error(self, message: str):
        self.exit(EXIT_BAD_INPUT, f"error: {message} (see {self.prog} --help)\n")


REFUSED = "refused_options"  # the parsed arguments' list of the values Checked refused


class Checked(argparse.Action):
    """An option whose value our own code checks (``check``: text -> value, raising ArgumentTypeError): a refused
    value is set aside, so that one run names every option refused (:func:`check_refused`), where argparse stops at
    the first."""

    def __init__(self, option_strings, dest, check, **kwargs):
        super().__init__(option_strings, dest, **kwargs)
        self.check = check

    def __call__(self, parser, namespace, text, option_string=None):
        try:
            setattr(namespace, self.dest, self.check(text))
        except argparse.ArgumentTypeError as exc:
            refused = InputError(f"argument {option_string or self.metavar or self.dest}",
                                 f"{exc} (see {parser.prog} --help)")
            setattr(namespace, REFUSED, [*getattr(namespace, REFUSED, []), refused])


def check_options(args) -> None:
    """Every bad option value in one InputError, before a command runs: those :class:`Checked` set aside while
    parsing, the environment's switches (``clutchopt.switches``) and the robust method with its counts
    (:func:`robust_options`)."""
    problems = Problems()
    problems.errors += getattr(args, REFUSED, [])
    with problems.field():
        check_switches()  # (the environment's: $CLUTCHOPT_BUILD_LATER)
    if hasattr(args, "robust"):
        with problems.field():
            robust_options(args)
    problems.raise_any()


def add_parser(commands, name: str, summary: str, details: str = "", examples: tuple[str, ...] = ()):
    """A command's parser: ``summary`` in the command list, ``details`` under its usage, ``examples`` below."""
    description = summary[0].upper() + summary[1:] + "." + (f"\n\n{details}" if details else "")
    epilog = "examples:\n" + "\n".join(f"  {example}" for example in examples) if examples else None
    return commands.add_parser(name, help=summary, description=description, epilog=epilog)


LARGEST_ID = 2**63 - 1  # SQLite's INTEGER
FIGURE_SUFFIXES = (".png", ".svg", ".pdf")


def tolerance(text: str) -> float:
    """A solver tolerance: a finite number within TOLERANCE_RANGE."""
    low, high = TOLERANCE_RANGE
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r} (e.g. 1e-8)") from None
    if not low <= value <= high:  # also refuses nan and inf
        raise argparse.ArgumentTypeError(f"must be between {low:g} and {high:g}, got {text!r}")
    return value


def integer(text: str) -> int:
    """A whole number, whatever its size (the command checks its range)."""
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a whole number: {text[:40]!r}") from None


def whole_number(low: int, high: int):
    """A check of :class:`Checked`: a whole number within [low, high]."""
    def parse(text: str) -> int:
        value = integer(text)
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"must be from {low} to {high}, got {text[:40]}")
        return value

    parse.__name__ = "whole number"
    return parse


def name(text: str) -> str:
    """A name on the command line (mode, objective): not empty, printable, short."""
    if not text.strip() or not text.isprintable() or len(text) > 40:
        raise argparse.ArgumentTypeError(f"expected a name (a mode such as paper, an objective such as mass), got "
                                         f"{text[:40]!r}")
    return text.strip()


def path(text: str) -> str:
    """A file path on the command line: not empty nor blank (one would have read as the option not given: a sweep
    recorded into the default store, a table or a figure not written; review 25)."""
    if not text.strip():
        raise argparse.ArgumentTypeError(f"expected a file path, got {text!r}")
    return text


def add_case_argument(command: argparse.ArgumentParser) -> None:
    command.add_argument("case", help="the case file (TOML, quantities with units); start one with clutchopt init")


def add_json_option(command: argparse.ArgumentParser,
                    help: str = "print one JSON object instead of tables: SI values, each beside its SI unit") -> None:
    command.add_argument("--json", action="store_true", help=help)


def add_problem_options(command: argparse.ArgumentParser, objective: bool = True) -> None:
    """--mode, --objective (unless the command sets both ends itself) and --tol: how a case is posed and solved."""
    command.add_argument("--mode", metavar="MODE", action=Checked, check=name, help=MODE_HELP)
    if objective:
        command.add_argument("--objective", metavar="NAME", action=Checked, check=name,
                             help="what the optimum minimises: mass (kg), cost (EUR) or envelope_mass (kg, "
                                  "docs/envelope.md) (default: the case's [options] objective, then mass)")
    add_tolerance_option(command)


def add_tolerance_option(command: argparse.ArgumentParser) -> None:
    command.add_argument("--tol", action=Checked, check=tolerance, default=SOLVER_TOL,
                         help=f"IPOPT's convergence tolerance, {TOLERANCE_RANGE[0]:g} to {TOLERANCE_RANGE[1]:g} "
                              f"(default {SOLVER_TOL:g}; 1e-6 is faster and good to about 1e-6 relative)")


def add_quiet_option(command: argparse.ArgumentParser,
                     help: str = "no progress bar (on a terminal, one moves as options.choose's choices are "
                                 "designed)") -> None:
    command.add_argument("--quiet", action="store_true", help=help)


def add_store_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("--store", action=Checked, check=path, metavar="PATH",
                         help="the run store to record into (SQLite; default $CLUTCHOPT_STORE, then "
                              "./clutchopt-runs.sqlite)")
    command.add_argument("--no-store", action="store_true", help="do not record this run")


def add_robust_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("--robust", metavar="METHOD",
                         help="a design that holds under the case's [scatter]: worst-case (every constraint at its own "
                              "worst corner of the ranges), chance=P (each fails with probability at most 1 - P) or "
                              "system_chance=P (the design does), checked by Monte Carlo and importance sampling "
                              "beside the nominal design; e.g. --robust chance=0.999")
    command.add_argument("--samples", action=Checked, check=integer, metavar="N",
                         help="Monte Carlo samples of the scatter for --robust (default 10000)")
    command.add_argument("--starts", action=Checked, check=integer, metavar="N",
                         help="simulated starts of the Monte Carlo of a [start_up] for --robust, and with chance=P "
                              "as many again for importance sampling at each start-up limit's design point "
                              "(default 200, about 30 ms each)")


def robust_options(args):
    """The robust method ``--robust``, ``--samples`` and ``--starts`` ask for (None: the nominal design)."""
    if args.robust is None:
        for name, given, what in (("--samples", args.samples, "the Monte Carlo samples"),
                                  ("--starts", args.starts, "the simulated starts")):
            if given is not None:
                raise InputError(name, f"counts {what} of --robust; give --robust too")
        return None
    from clutchopt.optimise.design import Robustness

    return Robustness.parse(args.robust, args.samples, args.starts)


def robustness(args, case):
    """The robust method the arguments ask for (None: the nominal design), checked against the case and the problem
    the command poses (a scattered quantity that does not enter it; simulated starts of no [start_up]), before any
    store is opened or file written."""
    from clutchopt.optimise import SolverOptions
    from clutchopt.optimise.design import check_robustness
    from clutchopt.optimise.problem import case_problem

    robust = robust_options(args)
    if robust is None:
        return None
    if args.starts is not None and case.start_up is None:
        raise InputError("--starts", "counts the simulated starts of a [start_up] under scatter; this case has no "
                                     "[start_up], so nothing is started")
    mode, objective = getattr(args, "mode", None), getattr(args, "objective", None)  # compare: the case's own
    check_robustness(case, robust, case_problem(case, mode, objective, SolverOptions(tol=args.tol)))
    return robust


def nominal_note(case, robust) -> str:
    """For a case with [scatter] designed without --robust: that the design is the nominal one, said in a line."""
    if robust is not None or not case.scatter:
        return ""
    return ("nominal design: the case's [scatter] is not designed for; --robust worst-case or --robust chance=P "
            "designs for it")


def choices_note(case) -> str:
    """For commands that design every choice of ``options.choose`` at each point: that they do, said in a line."""
    if not case.options.get("choose"):
        return ""
    return "options.choose: every choice designed at every point, the best kept (column choice)"


def resolve_problem(case, args, objective: bool = True) -> None:
    """Check the mode and objective the arguments ask for (an unknown name is bad input), and that the case gives
    what the objective needs (every objective's without ``objective``: the command poses them all), before any store
    is opened or file written."""
    from clutchopt.optimise.problem import case_formulation

    formulation = case_formulation(case, args.mode)
    if objective:
        case.require(formulation.objective(case.objective_of(args.objective)).name)
    else:
        case.require(*(o.name for o in formulation.objectives))


def warn(text: str) -> None:
    """A warning for the user: one line on stderr; the command goes on."""
    print(f"warning: {text}", file=sys.stderr, flush=True)


def open_store(args, needed: bool = False):
    """The run store the arguments ask for, opened before any work; None with ``--no-store``.

    A store that cannot be used (read-only, damaged, not a store) does not stop the command: one warning says
    what will not be recorded and why, and the result is printed as usual. With ``needed`` (``--resume``, which
    reads the store) it is an error instead. Writes that fail later are reported the same way, once."""
    if getattr(args, "no_store", False):
        return None
    from clutchopt.store import RunStore, StoreError

    try:
        return RunStore(args.store, warn=warn)
    except StoreError as exc:
        if needed:
            raise
        warn(f"this run will not be recorded: {exc.problem}")
        return None


@contextmanager
def recording(args, needed: bool = False) -> Iterator:
    """``with recording(args) as store:`` the store of :func:`open_store` (or None), closed afterwards."""
    store = open_store(args, needed)
    try:
        yield store
    finally:
        if store is not None:
            store.close()


def record_solve(store, designed, method: str, check: dict | None = None, extra: dict | None = None) -> None:
    """Record a ``solve`` (and its start-up check, a simulation) in an open store (or nothing for None): a design
    (``Designed``) with its choice and robust result, made by ``method`` (nominal, worst-case, chance=P); ``extra``:
    more of its record (whether it is the chosen one)."""
    if store is None:
        return
    case, solution = designed.case, designed.solution
    store.record_solution("solve", case, solution, {**designed.as_dict(), **(extra or {})}, method)
    if check is not None:
        store.record("simulation", {"values": case.values, "design": solution.design, "method": method}, check,
                     status="verified" if check.get("verified") else "not verified",
                     objective=check.get("simulated_acceleration_time", check.get("simulated_start_time")),
                     objective_unit="s", method=method, case_path=case.path, title=case.title,
                     coupling=case.coupling, mode=solution.mode, objective_name="acceleration_time")


def record_simulation(store, scene, result) -> None:
    """Record a ``simulate`` run (scene file, headline, events) in an open store (or nothing for None)."""
    if store is None:
        return
    from clutchopt.records import lock_up_verdict

    store.record("simulation", {"scene": scene.data, "source": scene.source, "units": {"scene": scene.units}},
                 result.as_dict(),
                 status={"yes": "locks up", "no": "no lock-up"}.get(lock_up_verdict(result.headline), "not decided"),
                 objective=result.headline.get("start_time"), objective_unit="s", case_path=scene.path,
                 title=scene.title, objective_name="start_time")
