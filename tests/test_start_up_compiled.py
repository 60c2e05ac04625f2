"""A sweep's NLP functions compiled in the background (clutchopt/optimise/start_up_compiled.py): the build runs in a
process of its own, the problem adopts the library once the cache holds it whole, and its solves are then the
virtual machine's to the last bit (the compiled code does the same operations in the same order). The mechanism is
shown on the wedge's static sizing (a 105-instruction Hessian: its build takes about a second, a start-up problem's
1.2 MB of C 8-26 s); a start-up sweep calls it at each point (``start_up_sweep.solved_along``), and a start-up
problem's first IPOPT solver reads the link (``Posed.solver``): shown at 2 collocation intervals a phase (about a
second's build)."""

import time
from dataclasses import replace
from pathlib import Path
from types import SimpleNamespace

import pytest

import clutchopt.optimise.compiled as compiled
import clutchopt.optimise.start_up_compiled as later
from clutchopt.cases import load_case
from clutchopt.formulations import get_coupling
from clutchopt.optimise.problem import Problem, case_formulation
from clutchopt.optimise.solution import SolverOptions
from clutchopt.start_up.drive import Structure
from conftest import CASES

WAIT_S = 60.0  # the longest the test waits for the build (a second or two unloaded)


def _problem_and_case():
    case = load_case(CASES / "wedge_paper.toml")
    return Problem(case_formulation(case)), case


@pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler here (solves stay on the virtual machine)")
def test_a_library_built_in_the_background_is_adopted_and_solves_to_the_same_bits(monkeypatch, tmp_path):
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(later.BUILD_LATER_ENV, "1")
    monkeypatch.setattr(later, "_STARTED", {})
    monkeypatch.setattr(later, "GENERATE_AFTER_S", 0.0)  # (a sweep's: once its points took 2 s of solving)
    plain, case = _problem_and_case()
    reference = plain.solve(case)
    problem, _ = _problem_and_case()
    assert later.compiled_when_ready(problem.posed) is False  # the build only started: still the virtual machine
    state = problem.posed.built("compiled_later", "ipopt", None)
    assert state.library is not None and state.library.parent == tmp_path / "cache"
    assert later.wait_for_builds() == 1 and later.wait_for_builds() == 0  # (what the bench waits for before timing)
    assert compiled.ready_library(state.library) is not None  # whole once its build's process ended
    waited = time.monotonic()
    while not later.compiled_when_ready(problem.posed) and time.monotonic() - waited < WAIT_S:
        time.sleep(0.1)
    assert problem.posed.library == str(state.library)
    assert problem.posed.solver("ipopt").get_function("nlp_hess_l").is_a("External")
    assert problem.posed.solver("warm").get_function("nlp_hess_l").is_a("External")  # (built after: compiled too)
    solution = problem.solve(case)
    assert solution.status == reference.status == "optimal"
    assert solution.objective == reference.objective  # to the last bit
    assert solution.design == reference.design
    assert not list((tmp_path / "cache").glob("*.c"))  # the build removed the source handed to it
    assert not list((tmp_path / "cache").glob("*.building"))  # and its marker


def test_no_build_is_started_where_the_environment_says_so(monkeypatch, tmp_path):
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(later.BUILD_LATER_ENV, "0")  # (the test suite's own setting: tests/conftest.py)
    monkeypatch.setattr(later, "_STARTED", {})
    monkeypatch.setattr(later, "GENERATE_AFTER_S", 0.0)
    started = []
    monkeypatch.setattr(later, "build_detached", lambda source: started.append(source))
    problem, _ = _problem_and_case()
    assert later.compiled_when_ready(problem.posed) is False
    assert started == [] and problem.posed.library is None


def test_without_a_cache_folder_no_code_is_generated(monkeypatch):
    monkeypatch.setenv(compiled.CACHE_ENV, "")
    monkeypatch.setattr(later, "GENERATE_AFTER_S", 0.0)
    monkeypatch.setattr(later, "generated_source", lambda functions: pytest.fail("C generated without a cache"))
    problem, _ = _problem_and_case()
    assert later.compiled_when_ready(problem.posed) is False
    assert problem.posed.built("compiled_later", "ipopt", None).library is None


def test_a_build_under_way_is_not_started_again(monkeypatch, tmp_path):
    # a sweep's worker processes each asking for the same library: one build, marked by a fresh ``.building`` file
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    spawned = []
    monkeypatch.setattr(compiled.subprocess, "Popen", lambda command, **kwargs: spawned.append(command) or command)
    source = b"double f(double x) { return x; }\n"
    assert compiled.build_detached(source) is not None
    assert compiled.build_detached(source) is None
    assert len(spawned) == 1 and compiled.library_path(source).with_suffix(".building").is_file()


def test_the_code_is_generated_only_once_the_points_took_long_enough(monkeypatch, tmp_path):
    # GENERATE_AFTER_S = 2 s of solving: points of 0.8 s each (each counted once, however often it is the point
    # before) bring it there at the third
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    generated = []
    monkeypatch.setattr(later, "generated_source", lambda functions: generated.append(1))
    problem, _ = _problem_and_case()
    points = [SimpleNamespace(solver=SimpleNamespace(time_s=0.8)) for _ in range(3)]
    for point, expected in zip([None, points[0], points[0], points[1], points[2]], [0, 0, 0, 0, 1]):
        later.compiled_when_ready(problem.posed, point)
        assert len(generated) == expected


@pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler here (solves stay on the virtual machine)")
def test_a_linked_library_is_used_from_the_first_point_without_deriving_or_generating(monkeypatch, tmp_path):
    # the link beside the library is named by the NLP's digest: a new problem of the same NLP finds it before its
    # first solve (no 2 s of solving, no C generated, no derivatives of its own) and solves to the same bits
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(later.BUILD_LATER_ENV, "0")
    plain, case = _problem_and_case()
    reference = plain.solve(case)
    library = later.compiled_now(plain.posed)  # (built in the foreground, as the bench's "in the cache" state)
    assert library is not None and later.linked_library(plain.posed) == Path(library)
    problem, _ = _problem_and_case()
    monkeypatch.setattr(later, "generated_source", lambda functions: pytest.fail("C generated: the link not read"))
    assert problem.posed._built["solver"] == {}  # (nothing derived yet)
    assert later.compiled_when_ready(problem.posed) is True  # at the first point, no solving counted
    assert problem.posed.library == library
    assert problem.posed.solver("ipopt").get_function("nlp_hess_l").is_a("External")
    solution = problem.solve(case)
    assert solution.status == reference.status == "optimal"
    assert solution.objective == reference.objective and solution.design == reference.design  # to the last bit


def test_a_link_is_read_only_where_it_names_a_library_of_the_cache(monkeypatch, tmp_path):
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path))
    problem, _ = _problem_and_case()
    monkeypatch.setattr(later, "nlp_key", lambda posed: pytest.fail("a digest taken without any link in the cache"))
    assert later.linked_library(problem.posed) is None
    monkeypatch.setattr(later, "nlp_key", lambda posed: "0" * 32)
    link = tmp_path / f"link-{'0' * 32}.txt"
    for name, expected in (("../elsewhere/nlp-" + "a" * 32 + ".so", None), ("nlp-" + "a" * 32 + ".so\n",
                                                                            tmp_path / ("nlp-" + "a" * 32 + ".so"))):
        link.write_text(name)
        assert later.linked_library(problem.posed) == expected
    link.write_bytes(b"nlp-\xff\xfe.so")  # a damaged link (no UTF-8): no library, no error
    assert later.linked_library(problem.posed) is None

    def unserialisable(posed):
        raise RuntimeError("Function::serialize not defined for Callback")

    monkeypatch.setattr(later, "nlp_key", unserialisable)  # an NLP CasADi cannot serialise: no digest, no link
    assert later.linked_library(problem.posed) is None


@pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler here (solves stay on the virtual machine)")
def test_a_library_of_another_nlp_is_not_used(monkeypatch, tmp_path):
    # a link left by a build of another NLP (one whose rows differ: IPOPT refused the first call, "Input 4 (lbg) has
    # mismatching shape", an internal error in a start-up sweep) names a library whose oracle has other shapes: the
    # problem keeps its own functions and solves as before
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(later.BUILD_LATER_ENV, "0")
    paper, case = _problem_and_case()
    library = later.compiled_now(paper.posed)
    geometry = Problem(case_formulation(case, "geometry"))
    reference = geometry.solve(case)
    assert library is not None and geometry.posed.use_compiled(library) is False and geometry.posed.library is None
    again = geometry.solve(case)
    assert again.status == reference.status == "optimal" and again.objective == reference.objective


@pytest.mark.skipif(compiled.compiler() is None, reason="no C compiler here (solves stay on the virtual machine)")
def test_a_start_up_solve_uses_a_linked_library_from_its_first_solver(monkeypatch, tmp_path):
    # not only a sweep's point: any solve of a start-up NLP whose library the cache links (a sweep's, built before)
    # builds its IPOPT solvers over it (no derivatives of its own) and ends on the same bits, states and all
    monkeypatch.setenv(compiled.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setenv(later.BUILD_LATER_ENV, "0")
    case = load_case(CASES / "wedge_motor_start.toml")

    def start_up_problem():
        formulation = get_coupling(case.coupling).formulation(case.options.get("mode"))
        return Problem(formulation, case.options.get("objective", "mass"), SolverOptions(),
                       replace(Structure.of(case), intervals=2))

    plain = start_up_problem()
    reference = plain.solve(case, refine=False)  # (one NLP run on the first mesh, its start simulated)
    library = later.compiled_now(plain.posed)
    assert library is not None and plain.posed.library is None  # (built and linked; the plain one keeps its own)
    problem = start_up_problem()
    monkeypatch.setattr(later, "generated_source", lambda functions: pytest.fail("C generated: the link not read"))
    solution = problem.solve(case, refine=False)
    assert problem.posed.library == library
    assert problem.posed.solver("ipopt").get_function("nlp_hess_l").is_a("External")
    assert solution.status == reference.status and solution.solver.iterations == reference.solver.iterations > 0
    assert solution.objective == reference.objective and solution.design == reference.design  # to the last bit
    assert solution.internal.tobytes() == reference.internal.tobytes()
    assert solution.start_up["start_time_simulated"] == reference.start_up["start_time_simulated"]
