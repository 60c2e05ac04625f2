"""The command line: ``clutchopt COMMAND ...`` (see :mod:`clutchopt.cli.main`)."""

from clutchopt.cli.options import EXIT_BAD_INPUT
from clutchopt.cli.main import main

__all__ = ["EXIT_BAD_INPUT", "main"]
