"""A start-up sweep's NLP functions compiled, built in the background (issue 26).

CasADi evaluates the start-up NLP's functions (the collocation's, 14,000-24,000 instructions in its constraints'
Jacobian and as many in the Lagrangian's Hessian) on its virtual machine: half of IPOPT's time on the cable's elastic
link, a sixth on the slipping couplings'. Compiled (:mod:`clutchopt.optimise.compiled`: the same operations in the
same order, so IPOPT's runs are the same to the last bit) they cost a third to a half less, but the C of one
problem structure (1.2-1.4 MB) takes 8-26 s to compile (-O1, this machine): more than a sweep saves while it waits.
So a sweep's first point looks for the library in the compiled-code cache; where it is not there, it starts its
build in a process of its own (:func:`clutchopt.optimise.compiled.build_detached`) and solves on, on CasADi's virtual
machine; each later point looks again, and from the first that finds it the problem's IPOPT solvers evaluate the
compiled functions (``Posed.use_compiled``). The build outlives the run that started it: the next sweep of that
structure on the machine finds the library. Generating the C takes 0.1-0.3 s a problem structure and a process,
which a single solve does not spend, nor a sweep whose solves are short (the wedge's, 0.2 s of IPOPT for 20 points,
would save 0.03 s): it is generated once a problem's sweep points took GENERATE_AFTER_S of solving (the cable's after
three or four points, the ball's after two).

Finding the library by its C costs that generation, more than the wedge's whole sweep: so the cache also keeps, beside
a library, a link named by a digest of the NLP itself (its objective and constraints serialised, 7-9 ms a start-up
problem: :func:`nlp_key`), written where the library's place is first worked out (:func:`_look_for`,
:func:`compiled_now`). A start-up problem looks for its link when its first IPOPT solver is built (``Posed.solver``:
in any solve, not only a sweep's, whose first point asks first): where the link names a library the cache holds
whole, every IPOPT solver of the problem is built over it from the start (no symbolic differentiation, the cold
solver's 45-50 ms on the wedge, and the compiled evaluations from its first iteration: cable_motor_start's re-solve
96-101 to 76-81 ms of CPU); the derivatives CasADi generates from an NLP are a function of it (and of CasADi's
version, in the digest), so the linked library is the one its C would name. A solve generates no C and starts no
build: only a sweep's points count the solving that pays for one.

``CLUTCHOPT_BUILD_LATER=0`` (or ``false``, ``no``, ``off``: ``clutchopt.switches``) starts no build (a library already
in the cache is still used): the test suite's, so that its sweeps do not compile beside the tests
(``tests/conftest.py``).
"""

from __future__ import annotations

import hashlib
import re
import subprocess
import time
from pathlib import Path

import casadi as ca

from clutchopt.optimise.compiled import (BUILD_TIMEOUT_S, FLAGS, build_detached, built_library, cache_folder, compiler,
                                         generated_source, library_path, nlp_functions, ready_library, trusted)
from clutchopt.switches import BUILD_LATER_ENV, switch  # off: no build started (a library in the cache is still used)

LIBRARY_NAME = re.compile(r"nlp-[0-9a-f]{32}\.so")  # what a link may name (a library of the cache's, nothing else)
GENERATE_AFTER_S = 2.0  # the solver seconds a problem's sweep points take before its C is generated (0.1-0.3 s)
_STARTED: dict[Path, subprocess.Popen | None] = {}  # the builds this process started (one a library, whatever the
# sweeps): their processes (None: not started, one of another process's under way), for :func:`wait_for_builds`


class CompiledLater:
    """A posed start-up problem's compiled functions: the solver seconds its sweep points took so far (``spent``),
    where the cache keeps its library (``library``; None: not looked for yet, no compiler or cache, or its C not
    generated) and whether the problem's solvers use it (``used``)."""

    def __init__(self, posed):
        self.posed, self.spent, self.counted = posed, 0.0, None
        self.generated, self.used, self.library = False, False, linked_library(posed)

    def after(self, solved) -> bool:
        """Whether the problem's solvers evaluate the compiled functions, ``solved`` (a sweep point's solution, or
        None) counted: its C generated and its library looked for once the points took GENERATE_AFTER_S."""
        if solved is not None and solved is not self.counted:
            self.spent, self.counted = self.spent + solved.solver.time_s, solved
        if not self.generated and not self.used and self.spent >= GENERATE_AFTER_S:  # (one used already, by its
            # link: its solvers' functions are the library's, no C to generate from them)
            self.generated = True
            self._look_for()
        return self.look()

    def _look_for(self) -> None:
        """The library's place from the problem's C; its build started where the cache does not have it."""
        if compiler() is None or cache_folder() is None:
            return
        source = generated_source(nlp_functions(self.posed.solver("ipopt")))
        self.library = None if source is None else library_path(source)
        if self.library is not None:
            link_library(self.posed, self.library)
        if self.library is not None and not self.look() and self.library not in _STARTED \
                and switch(BUILD_LATER_ENV):
            _STARTED[self.library] = build_detached(source)

    def look(self) -> bool:
        """Whether the problem's solvers evaluate the compiled functions: from now on where the cache has them whole."""
        if not self.used and self.library is not None:
            found = ready_library(self.library)  # (None where it is not there, or its folder cannot be read)
            if found is not None:
                self.used = self.posed.use_compiled(found)
                self.library = self.library if self.used else None  # (one that does not load: not tried again)
        return self.used


def compiled_when_ready(posed, previous=None) -> bool:
    """At a start-up sweep's point (``previous``: the point before's solution): ``posed``'s IPOPT solvers made to
    evaluate its NLP's functions compiled where the cache has them, their build started (once) where it has not,
    once its points took GENERATE_AFTER_S of solving; whether they do now."""
    return posed.built("compiled_later", "ipopt", lambda _: CompiledLater(posed)).after(previous)


def compiled_now(posed) -> str | None:
    """``posed``'s NLP functions compiled now, in the foreground (from the cache where it has them), and the link to
    them written (:func:`link_library`): a later sweep of the problem uses them from its first point. The library's
    path; None where none can be had (no compiler or cache folder, a build that fails)."""
    if posed.library is not None:  # (its solvers over a library already: no C to generate from them)
        link_library(posed, Path(posed.library))
        return posed.library
    source = generated_source(nlp_functions(posed.solver("ipopt")))
    library = None if source is None else built_library(source)
    if library is not None:
        link_library(posed, Path(library))
    return library


def nlp_key(posed) -> str:
    """A digest of ``posed``'s NLP (its objective and constraints over its variables and parameters, serialised by
    CasADi: 0.7 MB, 7-9 ms a start-up problem), of CasADi's version, the compiler and its flags: what names its
    library's link (:func:`link_library`). The library's own name digests its C (:func:`~clutchopt.optimise.compiled.
    library_path`), which CasADi generates from the NLP and its derivatives, themselves derived from the NLP. Taken
    once a problem (a sweep reads it for the link at its first point and writes the link later)."""
    def digest(_):
        nlp = posed.nlp
        serialised = ca.Function("nlp", [nlp["x"], nlp["p"]], [nlp["f"], nlp["g"]]).serialize()
        return hashlib.sha256(" ".join((serialised, ca.__version__, str(compiler()), *FLAGS)).encode()).hexdigest()[:32]

    return posed.built("nlp_key", None, digest)


def link_library(posed, library: Path) -> None:
    """The link from ``posed``'s NLP (:func:`nlp_key`) to ``library`` (its place in the cache, built or not yet)
    written beside it (``link-<key>.txt``: the library's file name), where the cache folder is this user's alone."""
    link = library.parent / f"link-{nlp_key(posed)}.txt"
    try:
        if trusted(library.parent) and not link.is_file():
            link.write_text(library.name)
    except OSError:
        pass


def linked_library(posed) -> Path | None:
    """The library the cache's link names for ``posed``'s NLP (:func:`link_library`; the library itself looked for
    by ``CompiledLater.look``); None without a compiler, a cache folder, or any link in it (then no digest is taken),
    or without this NLP's."""
    folder = cache_folder()
    if compiler() is None or folder is None:
        return None
    try:
        if not any(folder.glob("link-*.txt")):
            return None
        name = (folder / f"link-{nlp_key(posed)}.txt").read_text()[:64].strip()
    except (OSError, ValueError, RuntimeError):  # no folder or link, a damaged one (no UTF-8), an NLP CasADi cannot
        return None  # serialise (a Callback): no library
    return folder / name if LIBRARY_NAME.fullmatch(name) else None  # (a file name of the cache's, nothing else)


def wait_for_builds() -> int:
    """Returns once no build this process asked for is under way (its process ended; one another process had under
    way: its ``.building`` marker gone, or older than twice BUILD_TIMEOUT_S, as :func:`build_detached` judges it): what
    a benchmark waits for before it times anything, so that no compiler runs beside what it times. How many builds
    it waited for."""
    waited = 0
    for library, build in list(_STARTED.items()):
        marker, running = library.with_suffix(".building"), build is not None and build.poll() is None
        if running:
            build.wait()
        elif build is None and _under_way(marker):
            running = True
            while _under_way(marker):
                time.sleep(0.2)
        waited += running
    return waited


def _under_way(marker: Path) -> bool:
    try:
        return time.time() - marker.stat().st_mtime < 2 * BUILD_TIMEOUT_S
    except OSError:  # (gone)
        return False
