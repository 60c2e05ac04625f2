"""A damaged or hostile compiled-code cache (clutchopt/optimise/compiled.py, ``$CLUTCHOPT_CACHE``) never crashes the
process nor runs code others could have put there: the interval replay (clutchopt/optimise/interval_compiled.py)
falls back to NumPy, or rebuilds its library, and its bounds are the NumPy replay's."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import casadi as ca
import numpy as np
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


def test_a_function_of_thousands_of_instructions_is_enclosed_as_the_replay_encloses_it():
    """A random chain of 2,500 operations (sums, products, quotients, sin, fmin, sqrt, exp, hypot, atan, if_else,
    squares, tanh, log1p; 1,655 instructions, a work vector of 208) over 2,000 boxes whose ends are drawn from 0, -0,
    +-1, 2, -3, +-1e308, +-inf, NaN and the smallest subnormal: compiled and replayed bounds are the same numbers but
    where libm and NumPy differ by an ulp, which cancellation may grow (1e-13 relative here at most but for 0.2 %
    of the entries, to 4e-8); both hold every value sampled in the boxes of moderate ends (the proofs' soundness).
    (Near 1e308 a point's float evaluation may overflow where the reals do not: exp(1e305) * 0 is NaN in float, 0 in
    the reals and in both replays' product rule; a fmin then drops the NaN and the point's value, 3e-162, lies
    outside the enclosure [0, 0]. The rules enclose the real function, as their docstrings say.)"""
    from clutchopt.optimise.interval import IntervalFunction

    rng = np.random.default_rng(0)
    x = ca.SX.sym("x", 4)
    operations = [lambda a, b: a + b, lambda a, b: a * b, lambda a, b: a / b, lambda a, b: ca.sin(a) - b,
                  lambda a, b: ca.fmin(a, b), lambda a, b: ca.sqrt(ca.fabs(a)) + b,
                  lambda a, b: ca.exp(a * 1e-3) * b, lambda a, b: ca.hypot(a, b), lambda a, b: ca.atan(a) * b,
                  lambda a, b: ca.if_else(a < b, a, b), lambda a, b: a ** 2 - b,
                  lambda a, b: ca.tanh(a) + ca.log1p(ca.fabs(b))]
    nodes = list(x.nz)
    for _ in range(2500):
        a, b = nodes[rng.integers(len(nodes))], nodes[rng.integers(len(nodes))]
        nodes.append(operations[rng.integers(len(operations))](a, b))
    f = ca.Function("big", [x], [ca.vertcat(*nodes[-50:])])
    assert f.n_instructions() > 1000
    fast, slow = IntervalFunction(f), IntervalFunction(f, compiled=False)
    assert fast.compiled is not None
    ends = rng.choice([0.0, -0.0, 1.0, -1.0, 2.0, -3.0, 1e308, -1e308, np.inf, -np.inf, np.nan, 5e-324], (2, 4, 2000))
    lo, hi = np.minimum(ends[0], ends[1]), np.maximum(ends[0], ends[1])  # (a NaN end: a NaN box)
    (c_lo, c_hi), = fast.bounds([(lo, hi)])
    with np.errstate(all="ignore"):
        (r_lo, r_hi), = slow.bounds([(lo, hi)])
        for compiled_end, replayed_end in ((c_lo, r_lo), (c_hi, r_hi)):
            same = (compiled_end == replayed_end) | np.isnan(compiled_end) & np.isnan(replayed_end)
            close = np.isclose(compiled_end, replayed_end, rtol=1e-13, atol=0)
            assert np.mean(same | close) > 0.995 and np.all(same | np.isclose(compiled_end, replayed_end, rtol=1e-7,
                                                                                 atol=1e-300))
        finite = np.nan_to_num(np.stack([lo, hi]), nan=0.0, posinf=1e308, neginf=-1e308)
        boxes = np.flatnonzero(np.all((np.abs(lo) <= 3) & (np.abs(hi) <= 3), axis=0))[:100]  # (1e308: see below)
        t = rng.random((4, boxes.size, 20))
        samples = finite[0][:, boxes, None] + (finite[1] - finite[0])[:, boxes, None] * t
        samples = np.clip(samples, finite[0][:, boxes, None], finite[1][:, boxes, None]).reshape(4, -1)
        values = np.array(f.map(samples.shape[1])(samples)).reshape(50, boxes.size, 20)
        for low, high in ((c_lo, c_hi), (r_lo, r_hi)):
            outside = (values < low[:, boxes, None]) | (values > high[:, boxes, None])
            assert not np.any(outside & np.isfinite(values))
