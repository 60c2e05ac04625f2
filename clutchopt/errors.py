"""The one error users see for bad input: one line, naming the field."""


class InputError(ValueError):
    """Bad input in a case or scene file, or on the command line.

    The CLI prints ``error: <message>`` on one line and exits with code 2.
    """

    def __init__(self, field: str, problem: str):
        self.field = field
        self.problem = problem
        super().__init__(f"{field}: {problem}" if field else problem)
