import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CASES = ROOT / "cases"
# the cases of one coupling; a neutral case (coupling = "any") is for choose-coupling alone
COUPLING_CASES = sorted(path for path in CASES.glob("*.toml")
                        if 'coupling = "any"' not in path.read_text(encoding="utf-8"))
# the ball's paper mode poses the case's allowable contact stress: ball_crusher and ball_motor_start as given are
# proven infeasible there (the fifth root's p_0 (9) is 847 MPa against 0.5 GPa; tests/test_ball_nlp.py by hand).
# Tests whose subject is that mode's NLP (its start-up, its sweeps) allow this much (Pa), above every design they reach
BALL_PAPER_STRESS = {"allowable_contact_stress": 1.5e9}


def run_cli(*args: str, cwd: Path = ROOT, timeout: float | None = None) -> subprocess.CompletedProcess:
    """The CLI as a user runs it, from the repository root (a hang beyond ``timeout`` seconds fails the test); this
    checkout's clutchopt from any ``cwd``, not the one installed."""
    return subprocess.run([sys.executable, "-m", "clutchopt", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env={**os.environ, "PYTHONPATH": str(ROOT)})


def choosing(coupling: str) -> str:
    """The case of ``clutchopt init COUPLING`` with its ``options.choose`` line on, each role it lists taken out of
    ``[library]`` (a case names a role in one place)."""
    import tomllib

    from clutchopt.template import case_template

    text = case_template(coupling).replace("# choose = ", "choose = ")
    for role in tomllib.loads(text)["options"]["choose"]:
        text = "".join(line for line in text.splitlines(keepends=True) if not line.startswith(f"{role} = "))
    return text


def pytest_xdist_auto_num_workers(config) -> int:
    """``-n auto``: a worker per core this process may use, at most 4 (each holds CasADi, pandas and its own built
    problems, about 0.3 GB; several tests start process pools of their own)."""
    return min(4, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1)


_SESSION_CACHE: list[str] = []  # the compiled-code cache of this process's test session (pytest_configure)


def pytest_configure(config):
    """Compiled NLP functions (clutchopt.optimise.compiled) go to a cache of this test session, not the user's, from
    the collection on (tests/test_torture.py solves the start-up cases while it is collected, and a start-up problem
    reads the cache's links when its first IPOPT solver is built: the user's libraries were used); a start-up sweep
    starts no build of its own in the background (clutchopt.optimise.start_up_compiled: 8-26 s of compiling beside
    the tests a problem structure; tests/test_start_up_compiled.py builds one)."""
    _SESSION_CACHE.append(tempfile.mkdtemp(prefix="clutchopt-compiled-"))
    os.environ["CLUTCHOPT_CACHE"] = _SESSION_CACHE[-1]
    os.environ["CLUTCHOPT_BUILD_LATER"] = "0"


def pytest_unconfigure(config):
    os.environ.pop("CLUTCHOPT_CACHE", None)
    os.environ.pop("CLUTCHOPT_BUILD_LATER", None)
    while _SESSION_CACHE:
        shutil.rmtree(_SESSION_CACHE.pop(), ignore_errors=True)


@pytest.fixture(autouse=True)
def run_store(tmp_path, monkeypatch) -> Path:
    """Every test records into its own run store, never into the repository."""
    path = tmp_path / "runs.sqlite"
    monkeypatch.setenv("CLUTCHOPT_STORE", str(path))
    return path


@pytest.fixture
def cli():
    return run_cli


class Interrupted(Exception):
    """Raised from a hook: the sweep stops there, as on a kill (what was stored stays, the window in flight is lost)."""


def stopped_sweep(path, sweep, monkeypatch, cls, name: str, hook) -> Path:
    """The run store at ``path`` of ``sweep()``'s run stopped where ``hook``, standing for ``cls.name``, raises
    :class:`Interrupted`."""
    from clutchopt.store import RunStore

    with monkeypatch.context() as patch, RunStore(path) as store:
        patch.setattr(cls, name, hook)
        with pytest.raises(Interrupted):
            sweep().run(store, progress=False)
    return path


def resumed_sweep(path, sweep):
    """``sweep()`` resumed from the run store at ``path``."""
    from clutchopt.store import RunStore

    with RunStore(path) as store:
        return sweep().run(store, resume=True, progress=False)
