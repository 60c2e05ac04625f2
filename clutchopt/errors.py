"""The one error users see for bad input: one line per problem, each naming its field."""

from __future__ import annotations

from contextlib import contextmanager
from typing import Iterator

NOT_SIMULATED = "start-up"  # the field of the error a start-up outside the simulator's ranges raises (simulate.engine)


class InputError(ValueError):
    """Bad input in a case or scene file, or on the command line.

    One error may carry several problems (``problems``: every bad field of a case, found in one pass); the CLI
    prints ``error: <field>: <problem>`` once for each and exits with code 2.
    """

    def __init__(self, field: str, problem: str):
        self.field = field
        self.problem = problem
        self.problems: list[InputError] = [self]
        super().__init__(f"{field}: {problem}" if field else problem)

    @classmethod
    def several(cls, errors: list[InputError]) -> InputError:
        """One error carrying every problem of ``errors``; it names the first field."""
        combined = cls(errors[0].field, errors[0].problem)
        combined.problems = [problem for error in errors for problem in error.problems]
        combined.args = ("\n".join(problem.args[0] for problem in combined.problems),)
        return combined

    def at(self, where: str) -> InputError:
        """Every problem of this error as found at one point of a larger input (a sweep's point, a scatter's corner):
        each under ``where``, its own field said in its problem."""
        return InputError.several([InputError(where, str(problem)) for problem in self.problems])


def shown_value(value: object, limit: int = 60) -> str:
    """``repr`` of a value for a message, cut to a readable length (a 20,000-element list is not printed)."""
    try:
        text = repr(value)
    except RecursionError:  # a structure nested deeper than repr goes
        return f"a deeply nested {type(value).__name__}"
    length = len(value) if isinstance(value, str) else len(text)  # (a text's own characters, not its repr's quotes)
    return text if len(text) <= limit else f"{text[:limit - 10]}... ({length} characters)"


class Problems:
    """Collects the problems of an input field by field, so that one run reports them all.

    ``with problems.field(): ...`` records an InputError raised inside and goes on; ``raise_any()`` raises one
    error carrying them all (``InputError.several``).
    """

    def __init__(self):
        self.errors: list[InputError] = []

    @contextmanager
    def field(self) -> Iterator[None]:
        try:
            yield
        except InputError as error:
            self.errors.append(error)

    def __bool__(self) -> bool:
        return bool(self.errors)

    def raise_any(self) -> None:
        if self.errors:
            raise InputError.several(self.errors)
