"""What several commands share: the parser class, option groups, the run store. Imports nothing heavy."""

from __future__ import annotations

import argparse

EXIT_BAD_INPUT = 2

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


def add_parser(commands, name: str, summary: str, details: str = "", examples: tuple[str, ...] = ()):
    """A command's parser: ``summary`` in the command list, ``details`` under its usage, ``examples`` below."""
    description = summary[0].upper() + summary[1:] + "." + (f"\n\n{details}" if details else "")
    epilog = "examples:\n" + "\n".join(f"  {example}" for example in examples) if examples else None
    return commands.add_parser(name, help=summary, description=description, epilog=epilog)


def positive_float(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None
    if not value > 0:
        raise argparse.ArgumentTypeError(f"must be positive: {text!r}")
    return value


def add_case_argument(command: argparse.ArgumentParser) -> None:
    command.add_argument("case", help="the case file (TOML, quantities with units); start one with clutchopt init")


def add_json_option(command: argparse.ArgumentParser,
                    help: str = "print one JSON object instead of tables: SI values, each beside its SI unit") -> None:
    command.add_argument("--json", action="store_true", help=help)


def add_problem_options(command: argparse.ArgumentParser, objective: bool = True) -> None:
    """--mode, --objective (unless the command sets both ends itself) and --tol: how a case is posed and solved."""
    command.add_argument("--mode", metavar="MODE", help=MODE_HELP)
    if objective:
        command.add_argument("--objective", metavar="NAME",
                             help="what the optimum minimises: mass (kg) or cost (EUR) (default: the case's "
                                  "[options] objective, then mass)")
    add_tolerance_option(command)


def add_tolerance_option(command: argparse.ArgumentParser) -> None:
    command.add_argument("--tol", type=positive_float, default=1e-10,
                         help="IPOPT's convergence tolerance (default 1e-10; 1e-6 is faster and good to about 1e-6 "
                              "relative)")


def add_store_options(command: argparse.ArgumentParser) -> None:
    command.add_argument("--store", metavar="PATH",
                         help="the run store to record into (SQLite; default $CLUTCHOPT_STORE, then "
                              "./clutchopt-runs.sqlite)")
    command.add_argument("--no-store", action="store_true", help="do not record this run")


def first_choice_note(case) -> str:
    """For commands that solve one variant of a case with ``options.choose``: which one, said in a line."""
    choose = case.options.get("choose")
    if not choose:
        return ""
    first = ", ".join(f"{key} = {names[0]}" for key, names in choose.items())
    return f"options.choose: this command takes the first choice ({first}); clutchopt solve compares them all"


def open_store(args):
    """The run store the arguments ask for, or None with ``--no-store``."""
    if getattr(args, "no_store", False):
        return None
    from clutchopt.store import RunStore

    return RunStore(args.store)


def record_solve(args, case, solution, check: dict | None = None) -> None:
    """Record a ``solve`` (and its start-up check, a simulation) in the run store unless ``--no-store``."""
    store = open_store(args)
    if store is not None:
        with store:
            store.record_solution("solve", case, solution)
            if check is not None:
                store.record("simulation", {"values": case.values, "design": solution.design}, check,
                             status="verified" if check.get("verified") else "not verified",
                             objective=check.get("simulated_acceleration_time", check.get("simulated_start_time")),
                             case_path=case.path,
                             title=case.title, coupling=case.coupling, mode=solution.mode,
                             objective_name="acceleration_time")


def record_simulation(args, scene, result) -> None:
    """Record a ``simulate`` run (scene file, headline, events) unless ``--no-store``."""
    from clutchopt.cases import read_toml

    store = open_store(args)
    if store is not None:
        with store:
            store.record("simulation", {"scene": read_toml(scene.path), "source": scene.source}, result.as_dict(),
                         status="locks up" if result.headline["locks_up"] else "no lock-up",
                         objective=result.headline.get("start_time"), case_path=scene.path, title=scene.title,
                         objective_name="start_time")
