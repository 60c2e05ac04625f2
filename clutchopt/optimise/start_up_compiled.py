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
structure on the machine finds the library at its first point. Generating the C takes 0.1-0.3 s a problem structure
and a process, which a single solve does not spend: only sweeps (``Sweep``'s start-up points) do.

``CLUTCHOPT_BUILD_LATER=0`` starts no build (a library already in the cache is still used): the test suite's, so that
its sweeps do not compile beside the tests (``tests/conftest.py``).
"""

from __future__ import annotations

import os
from pathlib import Path

from clutchopt.optimise.compiled import (build_detached, cache_folder, compiler, generated_source, library_path,
                                         nlp_functions, ready_library)

BUILD_LATER_ENV = "CLUTCHOPT_BUILD_LATER"  # "0": no build started (a library in the cache is still used)
_STARTED: set[Path] = set()  # the builds this process started (one a library, whatever the sweeps)


class CompiledLater:
    """A posed start-up problem's compiled functions: where the cache keeps them (``library``; None: no compiler or
    cache, or its C not generated) and whether the problem's solvers use them (``used``)."""

    def __init__(self, posed):
        self.posed, self.used, self.library = posed, False, None
        if compiler() is None or cache_folder() is None:
            return
        source = generated_source(nlp_functions(posed.solver("ipopt")))
        self.library = None if source is None else library_path(source)
        if self.library is not None and not self.look() and self.library not in _STARTED \
                and os.environ.get(BUILD_LATER_ENV, "1") != "0":
            _STARTED.add(self.library)
            build_detached(source)

    def look(self) -> bool:
        """Whether the problem's solvers evaluate the compiled functions: from now on where the cache has them whole."""
        if not self.used and self.library is not None and self.library.is_file():
            found = ready_library(self.library)
            if found is not None:
                self.used = self.posed.use_compiled(found)
                self.library = self.library if self.used else None  # (one that does not load: not tried again)
        return self.used


def compiled_when_ready(posed) -> bool:
    """At a start-up sweep's point: ``posed``'s IPOPT solvers made to evaluate its NLP's functions compiled where the
    cache has them, their build started (once) where it has not; whether they do now."""
    return posed.built("compiled_later", "ipopt", lambda _: CompiledLater(posed)).look()

