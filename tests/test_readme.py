"""The README cannot go stale: every ``$ clutchopt ...`` example in a ```text block is run and its output compared
with the README's; every ```toml block must be a valid case; the ```python block must run.

How an example's output is compared with the README (the README's "Examples are tested" paragraph says the same):
- The commands of the README run in order, in one fresh folder that has the repository's ``cases/``, with the run
  store at its default place there (so ``recorded as sweep N in clutchopt-runs.sqlite`` reads as in the README).
- Lines are compared token by token (runs of spaces do not matter, blank lines are skipped). A line ``...`` stands
  for any number of lines; a token ``...`` for any number of tokens (an elided column or the end of a line).
- Numbers (also ``+49.80%``, ``-7.49e-11``) agree within a relative 1e-4, looser than the 6 printed digits;
  numbers below 1e-8 in magnitude (margins of active constraints and errors against closed forms, which are solver
  round-off) count as zero.
- What varies from run to run is left out of the comparison: timings (``time: 5.3 ms``, ``in 4.6 s``), IPOPT
  iteration counts, run-store ids, and progress bars (which go to stderr, not compared).
- A command whose line ends in ``# slow: not run by tests/test_readme.py`` is skipped; keep them very few.
"""

from __future__ import annotations

import math
import os
import re
import shlex
import subprocess
import sys
import tomllib
from functools import lru_cache

import pytest

from clutchopt.cases import parse_case
from tests.conftest import ROOT

README = (ROOT / "README.md").read_text(encoding="utf-8")
SLOW = "# slow: not run by tests/test_readme.py"
RELATIVE = 1e-4
ZERO = 1e-8
VARYING = (  # (pattern, what the matched group is): the group is replaced by <varies> in both texts
    (re.compile(r"time: ([0-9.]+ ms)"), "solver time"),
    (re.compile(r"in ([0-9.]+) s\b"), "wall time of a sweep"),
    (re.compile(r"iterations: (\d+)"), "IPOPT iterations"),
    (re.compile(r", (\d+) iterations"), "IPOPT iterations (compare)"),
    (re.compile(r"recorded as (?:sweep|run) (\d+)"), "run-store id"),
)
PROGRESS = re.compile(r"^\S+: +\d+%\|")  # a tqdm progress bar line


def blocks(language: str) -> list[str]:
    return re.findall(rf"^```{language}\n(.*?)^```", README, re.S | re.M)


def examples() -> list[tuple[str, list[str]]]:
    """(command, expected output lines) of every ``$ clutchopt`` line in the README's text blocks, in order."""
    found = []
    for block in blocks("text"):
        for line in block.splitlines():
            if line.startswith("$ clutchopt"):
                found.append((line[2:], []))
            else:
                found[-1][1].append(line)
    return found


def normalise(line: str) -> str:
    for pattern, _ in VARYING:
        line = pattern.sub(lambda m: m.group(0).replace(m.group(1), "<varies>"), line)
    return line


def number(token: str) -> float | None:
    try:
        return float(token.rstrip("%,;)").lstrip("(")) if any(c.isdigit() for c in token) else None
    except ValueError:
        return None


def same_token(expected: str, actual: str) -> bool:
    if expected == actual:
        return True
    x, y = number(expected), number(actual)
    if x is None or y is None or expected.endswith("%") != actual.endswith("%"):
        return False
    if abs(x) < ZERO and abs(y) < ZERO:
        return True
    return math.isclose(x, y, rel_tol=RELATIVE)


def same_tokens(expected: list[str], actual: list[str]) -> bool:
    @lru_cache(maxsize=None)
    def match(i: int, j: int) -> bool:
        if i == len(expected):
            return j == len(actual)
        if expected[i] == "...":
            return any(match(i + 1, k) for k in range(j, len(actual) + 1))
        return j < len(actual) and same_token(expected[i], actual[j]) and match(i + 1, j + 1)
    return match(0, 0)


def same_lines(expected: list[str], actual: list[str]) -> tuple[bool, str]:
    """Whether the actual lines match the README's; else the first README line that does not."""
    wanted = [normalise(line).split() for line in expected if line.strip() and not PROGRESS.match(line)]
    got = [normalise(line).split() for line in actual if line.strip()]

    @lru_cache(maxsize=None)
    def match(i: int, j: int) -> bool:
        if i == len(wanted):
            return j == len(got)
        if wanted[i] == ["..."]:
            return any(match(i + 1, k) for k in range(j, len(got) + 1))
        return j < len(got) and same_tokens(tuple(wanted[i]), tuple(got[j])) and match(i + 1, j + 1)

    if match(0, 0):
        return True, ""
    first = next((" ".join(w) for w in wanted if w != ["..."] and not any(same_tokens(tuple(w), tuple(g))
                                                                           for g in got)), "(the order or the end)")
    return False, first


EXAMPLES = examples()


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """A fresh folder with the repository's cases, where the README's commands run one after another."""
    path = tmp_path_factory.mktemp("readme")
    (path / "cases").symlink_to(ROOT / "cases")
    return path


def test_every_text_block_is_an_example_and_few_are_skipped():
    assert all(block.startswith("$ clutchopt ") for block in blocks("text"))  # no output without its command
    assert len(EXAMPLES) >= 8
    assert sum(SLOW in command for command, _ in EXAMPLES) <= 2


@pytest.mark.parametrize("index", range(len(EXAMPLES)), ids=[c[:60] for c, _ in EXAMPLES])
def test_example_output_matches_the_readme(index, folder, monkeypatch):
    command, expected = EXAMPLES[index]
    if SLOW in command:
        pytest.skip("marked slow in the README")
    monkeypatch.delenv("CLUTCHOPT_STORE", raising=False)
    env = {k: v for k, v in os.environ.items() if k != "CLUTCHOPT_STORE"}
    env["PYTHONPATH"] = str(ROOT)  # this checkout's clutchopt, not the one installed (the folder is elsewhere)
    argv = shlex.split(command, comments=True)
    assert argv[0] == "clutchopt"
    result = subprocess.run([sys.executable, "-m", "clutchopt", *argv[1:]], cwd=folder, capture_output=True,
                            text=True, env=env)
    assert result.returncode == 0, result.stderr
    ok, line = same_lines(expected, result.stdout.splitlines())
    assert ok, f"README example `{command}` is stale at: {line}\n--- actual output ---\n{result.stdout}"


@pytest.mark.parametrize("text", blocks("toml"), ids=lambda t: t.splitlines()[0][:40])
def test_case_snippets_are_valid_cases(text):
    case = parse_case(tomllib.loads(text))
    assert case.values


def test_the_python_example_runs(monkeypatch, capsys):
    (code,) = blocks("python")
    monkeypatch.chdir(ROOT)
    exec(compile(code, "README.md", "exec"), {})
    assert "optimal" in capsys.readouterr().out


def test_the_comparison_understands_the_conventions():
    """The matcher itself: elided lines and tokens, tolerance, round-off as zero, what varies; and it must fail."""
    actual = ["a 1.000001 x y z", "skipped", "also skipped", "torque -7.49e-11 +49.80%", "time: 9.9 ms"]
    assert same_lines(["a 1 x ...", "...", "torque +5e-12 +49.80%", "time: 5.3 ms"], actual)[0]
    assert not same_lines(["a 1.001 x ...", "...", "torque 0 +49.80%", "time: 1 ms"], actual)[0]
    assert not same_lines(["a 1 x y z", "torque 0 +49.80%", "time: 1 ms"], actual)[0]  # lines left out
    assert not same_tokens(("+49.80%",), ("+49.96%",)) and not same_tokens(("0.5",), ("0.5%",))
