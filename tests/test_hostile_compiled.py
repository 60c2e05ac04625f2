"""A damaged or hostile compiled-code cache (clutchopt/optimise/compiled.py, ``$CLUTCHOPT_CACHE``) never crashes the
process nor runs code others could have put there: the interval replay (clutchopt/optimise/interval_compiled.py)
falls back to NumPy, or rebuilds its library, and its bounds are the NumPy replay's."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import casadi as ca
import pytest

import clutchopt.optimise.compiled as compiled
from clutchopt.optimise import interval_compiled
from clutchopt.optimise.interval import _WIDEN

pytestmark = pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler here to build a library")

# the replay's library in $CLUTCHOPT_CACHE, its bounds on x * y + sin(x) over [1, 2] x [-1, 3] against the NumPy
# replay's (the product [-2, 6], sin over [1, 2] holding its peak pi/2: [sin 1, 1]; the sum [-2 + sin 1, 7]), then
# whether it ran compiled
PROBE = """
import casadi as ca, numpy as np
from clutchopt.optimise.interval import IntervalFunction
x, y = ca.SX.sym("x"), ca.SX.sym("y")
f = ca.Function("f", [x, y], [x * y + ca.sin(x)])
boxes = [(np.array([[1.0]]), np.array([[2.0]])), (np.array([[-1.0]]), np.array([[3.0]]))]
fast, slow = IntervalFunction(f), IntervalFunction(f, compiled=False)
assert all(np.array_equal(a, b) for a, b in zip(fast.bounds(boxes)[0], slow.bounds(boxes)[0]))
low, high = slow.bounds(boxes)[0]
assert low[0, 0] <= -2 + np.sin(1.0) and high[0, 0] >= 7.0
print("compiled" if fast.compiled is not None else "replayed")
"""


def run_probe(cache: Path, **env) -> str:
    """PROBE in a new process (a library it loads stays mapped there, and a crash ends only it): its output."""
    done = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, timeout=120,
                          env={**os.environ, compiled.CACHE_ENV: str(cache), **env})
    assert done.returncode == 0 and not done.stderr, (done.returncode, done.stderr)
    return done.stdout.strip()


def the_library(cache: Path) -> Path:
    """The replay's library, built into ``cache`` (its place there, whatever is in it)."""
    path = compiled.built_library(interval_compiled.source(_WIDEN), prefix="interval", flags=interval_compiled.FLAGS)
    assert path is not None and Path(path).parent == cache
    return Path(path)


@pytest.fixture
def cache(tmp_path, monkeypatch) -> Path:
    folder = tmp_path / "cache"
    monkeypatch.setenv(compiled.CACHE_ENV, str(folder))
    return folder


def test_a_truncated_library_is_rebuilt_not_loaded(cache):
    """Half of a built library (a disk that filled, a copy cut short) has the right ELF header: dlopen mapped it and
    the process died of SIGBUS (exit code 135, no message) on the first read past its end."""
    library = the_library(cache)
    whole = library.read_bytes()
    library.write_bytes(whole[: len(whole) // 2])
    assert run_probe(cache) == "compiled"
    assert library.read_bytes() == whole  # rebuilt in its place


@pytest.mark.parametrize("stand_in", ["another library", "empty file"])
def test_a_stand_in_of_the_right_name_is_rebuilt_not_used(cache, stand_in):
    """A library of the right name without ``interval_replay`` (here CasADi's own) raised AttributeError (undefined
    symbol: interval_replay) out of every interval proof; an empty file was not rebuilt (the replay stayed on NumPy,
    slower, for good)."""
    library = the_library(cache)
    if stand_in == "another library":
        shutil.copyfile(sorted(Path(ca.__file__).parent.glob("libcasadi.so*"))[0], library)  # loads, lacks it
    else:
        library.write_bytes(b"")
    assert run_probe(cache) == "compiled"


@pytest.mark.skipif(not hasattr(os, "getuid"), reason="no user ids here")
@pytest.mark.parametrize("fault", ["folder others may write", "another user's folder"])
def test_a_folder_others_control_is_not_used(cache, fault):
    """A library is only as safe as its folder: whoever may write the folder may put another library in its place
    (a rename needs no right on the file). The library there is not loaded, and none is built there."""
    library = the_library(cache)
    if fault == "folder others may write":
        cache.chmod(0o777)
    else:
        if os.getuid() != 0:
            pytest.skip("only root can give a folder to another user")
        os.chown(cache, 65534, 65534)
    assert run_probe(cache) == "replayed"
    library.unlink()
    assert run_probe(cache) == "replayed" and not library.exists()


@pytest.mark.parametrize("outcome", ["fails", "hangs"])
def test_a_compiler_that_fails_or_hangs_is_tried_once_a_process(cache, tmp_path, monkeypatch, outcome):
    """A ball sweep of four points over its infeasible region built the replay's library six times (each interval
    proof asks for it): with a compiler that fails, six compiler runs; with one that hangs, six waits of
    BUILD_TIMEOUT_S (120 s: twelve minutes for a three-second sweep). A build that failed is not tried again by the
    same process; the replay is NumPy's, the same bounds."""
    calls = tmp_path / "calls"
    script = tmp_path / "cc"
    script.write_text(f"#!/bin/sh\necho run >> {calls}\n" + ("exit 1\n" if outcome == "fails" else "sleep 5\n"))
    script.chmod(0o755)
    monkeypatch.setattr(compiled, "compiler", lambda: str(script))
    monkeypatch.setattr(compiled, "BUILD_TIMEOUT_S", 0.5)
    for _ in range(3):
        assert interval_compiled.replay_library(_WIDEN) is None
    assert calls.read_text() == "run\n"
