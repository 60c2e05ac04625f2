"""A case's aspects applied in one place: every design command (solve, compare, sweep, pareto, report) designs
through :func:`design_case`, so that each takes the library's choices (``options.choose``), the scatter
(``[scatter]`` with a robust method) and the start-up (``[start_up]``, posed by the problem itself) alike.

Each choice of ``options.choose`` is a variant of the case (``clutchopt.materials.variants``); each variant is
designed nominally, or for its scatter by the robust method asked for (``clutchopt.optimise.robust``); the variants
are ranked, verified designs first by objective, then the others in the order listed.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterable, NamedTuple

from clutchopt.cases import Case
from clutchopt.errors import InputError, Problems
from clutchopt.formulations import get_coupling
from clutchopt.materials import variants
from clutchopt.optimise.entering import check_entering
from clutchopt.optimise.problem import case_problem, solve_case
from clutchopt.optimise.robust import MAX_SAMPLES, MAX_STARTS, RobustResult, parse_method, solve_robust
from clutchopt.optimise.robust_models import SAMPLES
from clutchopt.optimise.robust_start_up import START_SAMPLES
from clutchopt.optimise.solution import Solution, SolverOptions
from clutchopt.records import NOMINAL, method_text, target_text


@dataclass(frozen=True)
class Robustness:
    """How a command designs for a case's scatter: ``worst-case`` or ``chance`` with its target probability, and
    the Monte Carlo samples that check it."""

    method: str
    target: float | None = None
    samples: int = SAMPLES
    starts: int = START_SAMPLES  # simulated starts of a [start_up]'s Monte Carlo

    @classmethod
    def parse(cls, text: str, samples: int | None, starts: int | None = None) -> "Robustness":
        """``--robust worst-case|chance=P``, ``--samples N`` and ``--starts N`` from the command line (each bad one
        named)."""
        problems, (method, target) = Problems(), (None, None)
        with problems.field():
            method, target = parse_method(text)
        samples = SAMPLES if samples is None else samples
        if not 100 <= samples <= MAX_SAMPLES:
            problems.errors.append(InputError("--samples", f"must be a whole number from 100 to {MAX_SAMPLES}, "
                                                           f"got {samples}"))
        starts = START_SAMPLES if starts is None else starts
        if not 10 <= starts <= MAX_STARTS:
            problems.errors.append(InputError("--starts", f"must be a whole number from 10 to {MAX_STARTS}, "
                                                          f"got {starts}"))
        problems.raise_any()
        return cls(method, target, samples, starts)

    def solve(self, case: Case, mode: str | None = None, objective: str | None = None,
              options: SolverOptions = SolverOptions(), base=None) -> RobustResult:
        """The robust design of ``case`` by this method (``base``: the formulation made robust, if not the mode's)."""
        return solve_robust(case, self.method, self.target, mode, objective, options, self.samples, self.starts,
                            base=base)

    @property
    def label(self) -> str:
        return self.method if self.target is None else f"{self.method} {target_text(self.target)}"

    @property
    def spelled(self) -> str:
        """As --robust spells it, and the run store records it: ``worst-case``, ``chance=0.999``."""
        return method_text(self.method, self.target)

    def as_dict(self, case: Case) -> dict:
        """The settings that apply to ``case``: its simulated starts only where it has a [start_up]."""
        return {"method": self.method, "target": self.target, "samples": self.samples,
                **({"starts": self.starts} if case.start_up is not None else {})}


class Designed(NamedTuple):
    """One choice of a case designed: the choice (``{}`` without options.choose), its case, its design (the robust
    one, its status the robust verdict, when designed for the scatter) and the robust result."""

    choice: dict[str, str]
    case: Case
    solution: Solution
    robust: RobustResult | None = None

    @property
    def choice_text(self) -> str:
        return ", ".join(f"{key} = {name}" for key, name in self.choice.items())

    def as_dict(self) -> dict:
        """The design's record (``Solution.as_dict()``), with its choice and the robust result (with its units) where
        there are."""
        from clutchopt.output import robust_json

        return {**self.solution.as_dict(), **({"choice": self.choice} if self.choice else {}),
                **({"robust": robust_json(self.robust, self.case)} if self.robust is not None else {})}


def method_of(robust: Robustness | None) -> str:
    """How a design is made, as the run store records it: ``nominal``, ``worst-case`` or ``chance=P``."""
    return NOMINAL if robust is None else robust.spelled


def check_robustness(case: Case, robust: Robustness | None, problem=None) -> None:
    """A robust design needs the case's scatter, and each scattered quantity must enter ``problem`` (the problem
    posed for the case, where given): refused by name before any solve."""
    if robust is None:
        return
    if not case.scatter:
        raise InputError("--robust", "the case has no [scatter] section: say which quantities scatter and how "
                                     "(docs/robust.md)")
    if problem is not None:
        check_entering(case, problem, [s.name for s in case.scatter], "scatter.{}", objective=False)


def choices(case: Case, progress: bool = False) -> Iterable[tuple[dict[str, str], Case]]:
    """Every choice of ``options.choose`` as (choice, its case); with ``progress``, a bar on stderr that moves as
    each is designed (where there are several, and stderr is a terminal)."""
    from tqdm import tqdm

    found = variants(case, get_coupling(case.coupling))
    return tqdm(found, desc="choices", unit="choice", leave=False,
                disable=None if progress and len(found) > 1 else True)


def design_case(case: Case, mode: str | None = None, objective: str | None = None,
                options: SolverOptions = SolverOptions(), robust: Robustness | None = None,
                progress: bool = False) -> list[Designed]:
    """Every choice of ``options.choose`` (the case alone without it) designed nominally or, with ``robust``, for
    the case's scatter (``progress``: see :func:`choices`); optimal designs first by objective, then the others in
    the order listed."""
    check_robustness(case, robust, case_problem(case, mode, objective, options) if robust is not None else None)
    designed = []
    for choice, variant in choices(case, progress):
        if robust is None:
            designed.append(Designed(choice, variant, solve_case(variant, mode, objective, options)))
        else:
            result = robust.solve(variant, mode, objective, options)
            designed.append(Designed(choice, variant, result.solution, result))
    return sorted(designed, key=lambda d: (d.solution.status != "optimal",
                                           d.solution.objective if d.solution.status == "optimal" else 0.0))
