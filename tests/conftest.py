import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"


def run_cli(*args: str, cwd: Path = ROOT) -> subprocess.CompletedProcess:
    """The CLI as a user runs it, from the repository root."""
    return subprocess.run([sys.executable, "-m", "clutchopt", *args], cwd=cwd, capture_output=True, text=True)


@pytest.fixture
def cli():
    return run_cli
