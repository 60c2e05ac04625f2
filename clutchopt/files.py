"""The files a user names, read and written without trusting them.

Reading: only regular files (a FIFO or a device would block or never end), at most a stated size, UTF-8 text
(a UTF-8 byte-order mark is skipped; UTF-16/32 and other encodings are refused with the fix). Writing: the
suffix and the folder are checked before any work is done, and a file is written whole or not at all (a
temporary file beside it, renamed into place).
"""

from __future__ import annotations

import codecs
import os
import stat
import tempfile
from contextlib import contextmanager
from pathlib import Path
from typing import Callable, Iterator

from clutchopt.errors import InputError

MiB = 1 << 20
CASE_BYTES = MiB  # a case or scene file is a few kB
TABLE_BYTES = 256 * MiB  # a sweep table of 100,000 points is about 50 MB


def shown(path: str | Path) -> str:
    """A path as a message names it: ``''`` for an empty one, the ends of a very long one."""
    text = str(path)
    return "''" if not text else text if len(text) <= 200 else f"{text[:120]}...{text[-60:]}"


def _kind(mode: int) -> str:
    for test, name in ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                       (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
                       (stat.S_ISSOCK, "a socket")):
        if test(mode):
            return name
    return "not a regular file"


def read_bytes(path: str | Path, limit: int, field: str | None = None) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes; anything else is an InputError naming ``field``
    (default: the path). Opened without blocking, so a FIFO is refused instead of waited on."""
    field = field or shown(path)
    try:
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_CLOEXEC", 0))
    except FileNotFoundError:
        raise InputError(field, "no such file") from None
    except (OSError, ValueError) as exc:  # ValueError: a NUL byte in the name
        raise InputError(field, f"cannot read ({getattr(exc, 'strerror', None) or exc})") from None
    info = os.fstat(fd)
    if not stat.S_ISREG(info.st_mode):
        os.close(fd)
        raise InputError(field, f"cannot read {_kind(info.st_mode)}; expected a regular file")
    with os.fdopen(fd, "rb") as handle:
        if info.st_size > limit:
            raise InputError(field, f"file of {info.st_size / MiB:.1f} MiB is too large (at most {limit / MiB:g} MiB)")
        try:
            data = handle.read(limit + 1)
        except OSError as exc:
            raise InputError(field, f"cannot read ({exc.strerror})") from None
    if len(data) > limit:
        raise InputError(field, f"file grew beyond {limit / MiB:g} MiB while being read")
    return data


_WIDE_BOMS = ((codecs.BOM_UTF32_LE, "UTF-32"), (codecs.BOM_UTF32_BE, "UTF-32"), (codecs.BOM_UTF16_LE, "UTF-16"),
              (codecs.BOM_UTF16_BE, "UTF-16"))


def read_text(path: str | Path, limit: int = CASE_BYTES, field: str | None = None) -> str:
    """A UTF-8 text file (a leading UTF-8 byte-order mark is dropped); other encodings are refused."""
    field = field or shown(path)
    data = read_bytes(path, limit, field)
    for bom, name in _WIDE_BOMS:
        if data.startswith(bom):
            raise InputError(field, f"is {name} text; save it as UTF-8")
    if b"\x00" in data:
        raise InputError(field, f"contains NUL bytes (at offset {data.index(0)}): not a UTF-8 text file "
                                "(UTF-16 without a byte-order mark, or binary); save it as UTF-8")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        raise InputError(field, f"is not UTF-8 text (byte 0x{data[exc.start]:02x} at offset {exc.start}); "
                                "save it as UTF-8") from None


def status(path: str | Path, field: str) -> os.stat_result | None:
    """``os.stat`` of a path the user named: None if nothing is there; any other failure (a name too long, a
    folder that may not be searched, a NUL byte) is an InputError naming ``field``."""
    try:
        return os.stat(path)
    except (FileNotFoundError, NotADirectoryError):
        return None
    except (OSError, ValueError) as exc:
        raise InputError(field, f"cannot use {shown(path)!r} ({getattr(exc, 'strerror', None) or exc})") from None


def check_output(option: str, path: str, suffixes: tuple[str, ...]) -> str:
    """Refuse an output path before any work: a suffix not in ``suffixes`` (e.g. ``(".csv", ".md")``), a folder
    that does not exist or cannot be written, a path that is a folder or a FIFO. Returns the suffix, without dot."""
    suffix = Path(path).suffix.lower()
    if suffix not in suffixes:
        raise InputError(option, f"write {', '.join(suffixes[:-1])} or {suffixes[-1]}, got {path!r}"
                         if len(suffixes) > 1 else f"write {suffixes[0]}, got {path!r}")
    target = Path(path)
    folder = target.parent
    found = status(folder, option)
    if found is None or not stat.S_ISDIR(found.st_mode):
        raise InputError(option, f"cannot write {path!r}: the folder {str(folder)!r} does not exist")
    found = status(target, option)
    if found is not None:
        if stat.S_ISDIR(found.st_mode) or stat.S_ISFIFO(found.st_mode) or stat.S_ISSOCK(found.st_mode):
            raise InputError(option, f"cannot write {path!r}: it is {_kind(found.st_mode)}")
        if stat.S_ISREG(found.st_mode) and not os.access(target, os.W_OK):
            raise InputError(option, f"cannot write {path!r}: the file is read-only")
    if not os.access(folder, os.W_OK):
        raise InputError(option, f"cannot write {path!r}: the folder {str(folder)!r} is not writable")
    return suffix[1:]


def write_whole(option: str, path: str, write: Callable[[str], None]) -> None:
    """Call ``write(temporary_path)`` and move the result to ``path``: the file appears whole or not at all.

    A device (``/dev/null``) is written directly. Errors of the file system are InputErrors naming ``option``."""
    with written_together() as written:
        written(option, path, write)


@contextmanager
def written_together() -> Iterator[Callable[[str, str, Callable[[str], None]], None]]:
    """``with written_together() as written:`` each ``written(option, path, write)`` calls ``write`` on a temporary
    file beside ``path``; every file is moved into its place once all are written, and none where one fails: a run
    with several outputs leaves all of them or none (review 25: a Pareto front's table had been written where its
    figure failed, exit 2). A device (``/dev/null``) is written directly. Errors of the file system are InputErrors
    naming the option."""
    staged: list[tuple[str, str, str]] = []  # (option, path, temporary)

    def written(option: str, path: str, write: Callable[[str], None]) -> None:
        target = Path(path)
        try:
            found = status(target, option)
            if found is not None and not stat.S_ISREG(found.st_mode):  # a device such as /dev/null
                write(path)
                return
            handle, temporary = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix,
                                                 dir=target.parent or ".")
            os.close(handle)
            staged.append((option, path, temporary))
            mask = os.umask(0)
            os.umask(mask)
            os.chmod(temporary, 0o666 & ~mask)  # as a plainly created file would be, not mkstemp's 0600
            write(temporary)
        except OSError as exc:
            raise InputError(option, f"cannot write {path!r} ({exc.strerror or exc})") from None

    try:
        yield written
        for option, path, temporary in staged:
            try:
                os.replace(temporary, path)
            except OSError as exc:
                raise InputError(option, f"cannot write {path!r} ({exc.strerror or exc})") from None
    finally:
        for _, _, temporary in staged:
            if os.path.exists(temporary):
                os.unlink(temporary)
