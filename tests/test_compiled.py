"""Compiled NLP functions for batched sweeps (clutchopt/optimise/compiled.py): the same optima as CasADi's virtual
machine, only where the Hessian is large, and the virtual machine wherever a library cannot be had."""

from pathlib import Path

import casadi as ca
import numpy as np
import pytest

import clutchopt.optimise.compiled as compiled
from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.batch import BatchSweep
from clutchopt.optimise.problem import Problem
from conftest import CASES


def _ball_sweep(points: int = 40):
    case = load_case(CASES / "ball_compressor.toml")
    problem = Problem(get_coupling("ball").formulation("design"))
    values = case.values["power"] * np.geomspace(0.5, 2.0, points)
    return problem, [s for part in BatchSweep(problem, case, {"power": values}).run() for s in part]


def _is_compiled(problem) -> bool:
    return problem.posed.solver("sqp_chain").get_function("nlp_hess_l").is_a("External")


@pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler here (the sweep runs on the virtual machine)")
def test_the_ball_sweep_compiled_gives_the_virtual_machines_optima(monkeypatch):
    problem, solutions = _ball_sweep()
    assert _is_compiled(problem)
    monkeypatch.setenv(compiled.CACHE_ENV, "")  # no cache: no compiled code
    plain, reference = _ball_sweep()
    assert not _is_compiled(plain)
    assert [s.status for s in solutions] == ["optimal"] * len(solutions)
    assert [s.objective for s in solutions] == [s.objective for s in reference]  # the same operations, same bits
    assert [s.design for s in solutions] == [s.design for s in reference]


def test_small_hessians_stay_on_the_virtual_machine():
    problem = Problem(get_coupling("wedge").formulation("paper"))
    assert problem.posed.solver("sqp_chain").get_function("nlp_hess_l").n_instructions() < compiled.COMPILE_ABOVE
    assert not _is_compiled(problem)


@pytest.mark.parametrize("fault", ["no compiler", "cache under a file", "damaged library", "failing build",
                                   "library others may write"])
def test_without_a_library_the_sweep_runs_on_the_virtual_machine(fault, monkeypatch, tmp_path):
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    if fault == "no compiler":
        monkeypatch.setattr(compiled, "compiler", lambda: None)
    elif fault == "cache under a file":
        (tmp_path / "file").write_text("")
        monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "file" / "cache"))
    elif fault in ("damaged library", "library others may write"):
        if compiled.compiler() is None:
            pytest.skip("no C compiler here to build a library")
        problem = Problem(get_coupling("ball").formulation("design"))
        plain = ca.nlpsol("plain", "sqpmethod", problem.posed.nlp, problem.options.sqp_chain())
        library = Path(compiled.compiled_library(plain))  # built, not loaded (a process keeps what it loaded)
        if fault == "damaged library":
            damaged = tmp_path / "damaged.so"
            damaged.write_bytes(b"\x7fELF not a library")
            damaged.replace(library)  # a new file in its place: this process has the old one mapped
            compiled._record(library).write_text(compiled._digest(library))  # as its build's (else: built again)
        else:
            library.chmod(0o777)
    else:
        monkeypatch.setattr(compiled, "BUILD_TIMEOUT_S", 1e-6)
    problem, solutions = _ball_sweep(12)
    assert not _is_compiled(problem)
    assert [s.status for s in solutions] == ["optimal"] * 12
