"""An NLP's functions compiled to machine code once per machine, for the SQP re-solves of batched sweeps.

CasADi evaluates its functions on a virtual machine, a few ns an instruction. Where the Hessian of the Lagrangian is
large (the ball clutch's: Hertz's elliptic integrals, 4,400 instructions, 50 us an evaluation against 6 us compiled)
it is most of an SQP iteration. Compiling CasADi's generated C takes about 0.6 s, more than a 1000-point sweep
saves, so the library is kept in a cache folder (``$CLUTCHOPT_CACHE``, else the user's cache folder), named by a
hash of its C source, the CasADi version, the compiler and its flags: built by the first sweep of a problem on a
machine, loaded by the next ones (only a library of this user's, in a folder of this user's, that no one else may
write, and whose bytes are those its build recorded). Without a C compiler, with a cache folder that cannot be
written, or where a build or load fails, the functions stay on CasADi's virtual machine (same numbers: the compiled
code does the same operations in the same order).
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import casadi as ca

CACHE_ENV = "CLUTCHOPT_CACHE"  # the cache folder; empty: no compiled code
COMPILE_ABOVE = 2000  # Hessian instructions above which compiling pays (ball 4,447; cable 681, lever 238, wedge 105)
BUILD_TIMEOUT_S = 120
FLAGS = ("-O1", "-fPIC", "-shared", "-ffp-contract=off")  # no fast-math, no fused multiply-add: IEEE, op by op
_FAILED: set[Path] = set()  # the libraries whose build failed in this process (a compiler that fails or hangs is
# waited for once a process, not by every interval proof of a sweep)


def cache_folder() -> Path | None:
    """``$CLUTCHOPT_CACHE``, else ``$XDG_CACHE_HOME/clutchopt``, else ``~/.cache/clutchopt``; None if set empty."""
    given = os.environ.get(CACHE_ENV)
    if given is not None:
        return Path(given) if given.strip() else None
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "clutchopt"


def compiler() -> str | None:
    return shutil.which(os.environ.get("CC") or "cc") or shutil.which("gcc")


def compiled_library(solver: ca.Function) -> str | None:
    """The shared library of ``solver``'s NLP functions (its oracle and the derivatives it evaluates), from the cache
    or built now; None where that is not possible (the solver then stays as it is)."""
    return _library(nlp_functions(solver))


def nlp_functions(solver: ca.Function) -> list[ca.Function]:
    """An nlpsol's NLP functions: its oracle and the derivatives it evaluates."""
    return [solver.oracle(), *(solver.get_function(name) for name in solver.get_function())]


def _library(functions: list[ca.Function]) -> str | None:
    """The shared library of ``functions``, from the cache or built now; None where that is not possible."""
    if compiler() is None or cache_folder() is None:
        return None
    source = generated_source(functions)
    return None if source is None else built_library(source)


def generated_source(functions: list[ca.Function]) -> bytes | None:
    """CasADi's C of ``functions`` (one file); None where it cannot be written."""
    generator = ca.CodeGenerator("clutchopt_nlp", {"with_header": False})
    for function in functions:
        generator.add(function)
    try:
        with tempfile.TemporaryDirectory() as scratch:
            generator.generate(scratch + os.sep)
            return Path(scratch, "clutchopt_nlp.c").read_bytes()
    except (OSError, RuntimeError):
        return None


def built_library(source: bytes, prefix: str = "nlp", flags: tuple[str, ...] = FLAGS) -> str | None:
    """The shared library of the C ``source``, from the cache (``prefix``-<hash>.so) or built now; None where that is
    not possible (no compiler, no cache folder or one others may write, a build that fails). A library in the cache
    is loaded only if its bytes are those its build recorded beside it (``.sha256``): a damaged one (cut short by a
    full disk or a copy, or another file of its name) is built again, never mapped (a truncated ELF kills the process
    that maps it with SIGBUS)."""
    library = library_path(source, prefix, flags)
    if library is None:
        return None
    folder = library.parent
    try:
        if not _own_folder(folder):
            return None
        if library.is_file():
            if not trusted(library):
                return None
            if _recorded(library) == _digest(library):
                return str(library)
        if library in _FAILED:
            return None
        with tempfile.TemporaryDirectory(dir=folder) as build:  # built beside its place, then moved in at once
            Path(build, "nlp.c").write_bytes(source)
            subprocess.run([compiler(), *flags, "nlp.c", "-o", "nlp.so", "-lm"], cwd=build, check=True,
                           capture_output=True, timeout=BUILD_TIMEOUT_S)
            built = Path(build, "nlp.so")
            Path(build, "nlp.sha256").write_text(_digest(built))
            os.replace(built, library)  # (a process building the same at once: either library, each whole)
            os.replace(Path(build, "nlp.sha256"), _record(library))
        return str(library)
    except (OSError, subprocess.SubprocessError, RuntimeError):
        _FAILED.add(library)
        return None


def library_path(source: bytes, prefix: str = "nlp", flags: tuple[str, ...] = FLAGS) -> Path | None:
    """Where the cache keeps the library of the C ``source`` (``prefix``-<hash of the source, the CasADi version, the
    compiler and its flags>.so); None without a compiler or a cache folder."""
    cc, folder = compiler(), cache_folder()
    if cc is None or folder is None:
        return None
    key = hashlib.sha256(source + " ".join((ca.__version__, cc, *flags)).encode()).hexdigest()[:32]
    return folder / f"{prefix}-{key}.so"


def ready_library(library: Path) -> str | None:
    """``library`` (:func:`library_path`) where the cache holds it whole (this user's, its bytes those its build
    recorded), else None; nothing is built."""
    try:
        if library.is_file() and trusted(library.parent) and trusted(library) \
                and _recorded(library) == _digest(library):
            return str(library)
    except OSError:
        pass
    return None


def build_detached(source: bytes, prefix: str = "nlp", flags: tuple[str, ...] = FLAGS) -> subprocess.Popen | None:
    """:func:`built_library` of the C ``source`` in a Python process of its own and in a session of its own, so that
    this one neither waits for it nor stops it on exit (a build a short run starts serves the next run). The source
    is handed over in the build's ``.building`` marker beside the library, created only where none is (a second
    process asking at once is refused), removed by the build when it ends; one older than twice BUILD_TIMEOUT_S is
    a killed build's and replaced. None where nothing can be started (no compiler or cache folder, one others may
    write, or a build of the same library under way, as where a sweep's worker processes each ask for it)."""
    library = library_path(source, prefix, flags)
    if library is None:
        return None
    marker, created = library.with_suffix(".building"), False
    try:
        if not _own_folder(library.parent):
            return None
        try:
            if time.time() - marker.stat().st_mtime < 2 * BUILD_TIMEOUT_S:
                return None
            marker.unlink()  # (a killed build's)
        except FileNotFoundError:
            pass
        with os.fdopen(os.open(marker, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o600), "wb") as file:
            created = True
            file.write(source)
        package = str(Path(__file__).resolve().parents[2])  # (the child imports this clutchopt, not another)
        env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, (package, os.environ.get("PYTHONPATH"))))}
        return subprocess.Popen([sys.executable, "-c", _DETACHED, str(marker), prefix, *flags], env=env,
                                stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                start_new_session=True)
    except OSError:  # (FileExistsError: another process began the build at once)
        if created:
            marker.unlink(missing_ok=True)
        return None


_DETACHED = """import sys
from pathlib import Path
marker = Path(sys.argv[1])
try:
    from clutchopt.optimise.compiled import built_library
    built_library(marker.read_bytes(), sys.argv[2], tuple(sys.argv[3:]))
finally:
    marker.unlink(missing_ok=True)
"""


def _own_folder(folder: Path) -> bool:
    """Whether ``folder`` (made this user's alone where it is not there; one there is kept as it is) may hold
    libraries: none that others may write (:func:`trusted`). Raises OSError where it cannot be made."""
    folder.mkdir(mode=0o700, parents=True, exist_ok=True)
    return trusted(folder)


def _record(library: Path) -> Path:
    return library.with_suffix(".sha256")


def _digest(library: Path) -> str:
    return hashlib.sha256(library.read_bytes()).hexdigest()


def _recorded(library: Path) -> str | None:
    """The digest the build of ``library`` recorded, None where there is none (a library of an earlier version)."""
    try:
        with open(_record(library), "rb") as record:
            return record.read(64).decode().strip()  # (64 hex digits: no more is read, whatever the file is)
    except (OSError, UnicodeDecodeError):
        return None


def trusted(path: Path) -> bool:
    """A library to load, or a folder to build and load from: this user's, writable by no one else (code in a shared
    folder is not run: whoever may write a folder may put another file in a library's place; where the system has no
    user ids, none is)."""
    info = path.stat()
    return hasattr(os, "getuid") and info.st_uid == os.getuid() and not info.st_mode & 0o022


def compiled_solver(name: str, solver: ca.Function, options: dict) -> ca.Function:
    """``solver`` (an ``sqpmethod`` nlpsol) with its NLP functions compiled where its Hessian is large enough for
    that to pay and a library can be had; else ``solver`` itself."""
    if solver.get_function("nlp_hess_l").n_instructions() <= COMPILE_ABOVE:
        return solver
    library = compiled_library(solver)
    if library is None:
        return solver
    try:
        return ca.nlpsol(name, "sqpmethod", library, options)
    except RuntimeError:  # a library that does not load (damaged cache)
        return solver


def is_compiled(solver: ca.Function) -> bool:
    """Whether ``solver`` (of :func:`compiled_solver`) evaluates its NLP's functions compiled."""
    return solver.get_function("nlp_hess_l").is_a("External")


def compiled_function(function: ca.Function) -> ca.Function:
    """``function`` compiled where a library can be had (the same operations in the same order: the same numbers),
    else ``function`` itself."""
    library = _library([function])
    if library is None:
        return function
    try:
        return ca.external(function.name(), library)
    except RuntimeError:  # a library that does not load (damaged cache)
        return function
