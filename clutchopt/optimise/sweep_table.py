"""A sweep's table as a file: written as CSV, Parquet or Markdown, read back checked (``clutchopt report``)."""

from __future__ import annotations

import json
import math
from typing import Callable

import numpy as np
import pandas as pd

from clutchopt.cases import Case
from clutchopt.errors import InputError, Problems
from clutchopt.files import TABLE_BYTES, check_output, read_bytes, write_whole
from clutchopt.optimise.sweep_grid import MAX_POINTS
from clutchopt.records import STATUSES, scatter_record


TABLE_SUFFIXES = (".csv", ".parquet", ".md")


def table_format(path: str, option: str = "--out") -> str:
    """csv, parquet or md, from the file's suffix; the folder must exist and be writable (checked before any
    solve, so that a long sweep does not end in a table it cannot write)."""
    return check_output(option, path, TABLE_SUFFIXES)


IDENTITY = "clutchopt_sweep"  # the frame attribute (and Parquet metadata) that identifies a sweep table's case
CSV_IDENTITY = f"# {IDENTITY} "  # a CSV sweep table's first line: this, then the identification as JSON


def write_frame(frame: pd.DataFrame, path: str, option: str = "--out", identity: dict | None = None,
                written: Callable[[str, str, Callable[[str], None]], None] = write_whole) -> None:
    """CSV, Parquet or Markdown by the file's suffix, written whole or not at all (``written``: with a run's other
    outputs, ``files.written_together``); ``identity`` (a sweep's, see :meth:`Sweep.identity`) goes into a CSV's
    first line and a Parquet file's metadata."""
    suffix = table_format(path, option)

    def write(target: str) -> None:
        if suffix == "csv":
            with open(target, "w", encoding="utf-8", newline="") as handle:
                if identity is not None:
                    handle.write(CSV_IDENTITY + json.dumps(identity) + "\n")
                frame.to_csv(handle, index=False)
        elif suffix == "parquet":
            identified = frame.copy(deep=False)
            identified.attrs = {IDENTITY: identity} if identity is not None else {}
            identified.to_parquet(target, index=False)
        else:
            with open(target, "w", encoding="utf-8") as handle:
                handle.write(markdown_table(frame) + "\n")

    try:
        written(option, path, write)
    except ImportError as exc:
        raise InputError(option, f"Parquet needs pyarrow (pip install 'clutchopt[parquet]'): {exc}") from None


def read_frame(path: str) -> pd.DataFrame:
    """A sweep table written by :func:`write_frame` (CSV or Parquet), checked column by column: ``point``, the
    varied inputs (numbers), ``status``, the objective (numbers, empty where there is no design). Its identification,
    if it has one, is ``frame.attrs[IDENTITY]``."""
    import io

    if not path.lower().endswith((".csv", ".parquet")):
        raise InputError(path, "a sweep table is read from .csv or .parquet (written by clutchopt sweep --out)")
    data = read_bytes(path, TABLE_BYTES)
    identity = None
    if data.startswith(CSV_IDENTITY.encode()):
        first, _, data = data.partition(b"\n")
        identity = _identity(first[len(CSV_IDENTITY):], path)
    data = io.BytesIO(data)
    try:
        frame = pd.read_parquet(data) if path.lower().endswith(".parquet") else pd.read_csv(data)
    except ImportError as exc:
        raise InputError(path, f"Parquet needs pyarrow (pip install 'clutchopt[parquet]'): {exc}") from None
    except (ValueError, OSError, UnicodeDecodeError) as exc:  # pandas' and pyarrow's parse errors
        raise InputError(path, f"cannot read a sweep table ({_first_line(exc)})") from None
    if identity is None and frame.attrs.get(IDENTITY) is not None:
        identity = _identity(json.dumps(frame.attrs[IDENTITY]).encode(), path)
    frame.attrs = {IDENTITY: identity} if identity is not None else {}
    _check_sweep_table(frame, path)
    return frame


def _identity(text: bytes, path: str) -> dict:
    """A sweep table's identification (JSON), checked: the keys :meth:`Sweep.identity` writes, of their kinds."""
    try:
        identity = json.loads(text)
    except (ValueError, RecursionError):
        identity = None
    kinds = {"coupling": str, "case": str, "values": dict, "mode": str, "objective": str, "robust": str, "varies": list}
    if isinstance(identity, dict) and isinstance(identity.get(ASPECTS), dict):  # (a table of an older clutchopt has
        kinds[ASPECTS] = dict  # none: its other keys are checked alone)
    if not (isinstance(identity, dict) and set(identity) == set(kinds)
            and all(isinstance(identity[key], kind) for key, kind in kinds.items())
            and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in identity["values"].values())
            and all(isinstance(column, str) for column in identity["varies"])):
        raise InputError(path, "cannot read a sweep table: its identification (the case it was swept from) is "
                               "damaged; write it again with clutchopt sweep --out")
    return identity


def check_swept_from(frame: pd.DataFrame, case: Case, path: str, warn: Callable[[str], None],
                     posed: tuple[str, str, str] | None = None) -> None:
    """Refuse a sweep table (:func:`read_frame`) swept from another case than ``case``, or of another problem than
    ``posed`` (mode, objective, robust method: empty for nominal designs), in one line naming what differs: the
    coupling, the case's values, the problem, the varied quantities. A table without identification (written
    before clutchopt identified its tables) is taken with a warning."""
    identity = frame.attrs.get(IDENTITY)
    if identity is None:
        warn(f"{path} does not say which case it was swept from (a table of an older clutchopt); it is shown as "
             f"a sweep of {case.path}")
        return
    differs = []
    if identity["coupling"] != case.coupling:
        differs.append(f"coupling {identity['coupling']!r}, not {case.coupling!r}")
    else:
        names = sorted(set(identity["values"]) ^ set(case.values)
                       | {name for name, value in case.values.items() if identity["values"].get(name, value) != value})
        if names:
            differs.append(f"case: swept from {identity['case']!r}, whose {_listed(names)} differ from this case's")
    swept = (identity["mode"], identity["objective"], identity["robust"])
    if posed is not None and swept != posed:
        shown = [f"{what} {value or 'nominal'}" for what, value in zip(("mode", "objective", "design"), swept)]
        asked = [f"{what} {value or 'nominal'}" for what, value in zip(("mode", "objective", "design"), posed)]
        differs.append(f"problem: swept with {', '.join(shown)}; this page is of {', '.join(asked)}")
    if ASPECTS in identity:  # (review 29: a table of another scatter, free set, bounds, start-up or choice was taken)
        ours = case_aspects(case)
        other = sorted(key for key in ours | identity[ASPECTS]
                       if _canonical(identity[ASPECTS].get(key)) != _canonical(ours.get(key)))
        if other:
            differs.append(f"case: swept from {identity['case']!r}, whose {_listed(other)} differ from this case's")
    status = list(frame.columns).index("status")
    if list(frame.columns[1:status]) != identity["varies"]:
        differs.append(f"quantities: its columns vary {_listed(frame.columns[1:status])}, its identification says "
                       f"{_listed(identity['varies'])}")
    if differs:
        raise InputError(path, f"not a sweep of {case.path}: {'; '.join(differs)}")


ASPECTS = "aspects"  # an identification's key: what the case poses beside its values (:func:`case_aspects`)


def case_aspects(case: Case) -> dict:
    """What a case poses beside its values, as a sweep table's identification carries it: its free variables and
    bounds, its [scatter], its start-up's effects and its options.choose."""
    return {"free": list(case.free), "bounds": {name: list(pair) for name, pair in case.bounds.items()},
            "scatter": scatter_record(case), "effects": list(case.start_up.effects) if case.start_up else [],
            "choose": case.options.get("choose") or {}}


def _canonical(value) -> str:
    """A JSON value as one text (NaN as NaN on both sides: a scatter's unset mean)."""
    return json.dumps(value, sort_keys=True)


def _listed(names, shown: int = 5) -> str:
    names = list(names)
    return ", ".join(names[:shown]) + (f" and {len(names) - shown} more" if len(names) > shown else "")


def _first_line(exc: Exception) -> str:
    return (str(exc).strip().splitlines() or [type(exc).__name__])[0][:200]


def _check_sweep_table(frame: pd.DataFrame, path: str) -> None:
    columns = [str(c) for c in frame.columns]
    layout = "written by clutchopt sweep --out: point, the varied inputs, status, the objective, ..."
    if columns[:1] != ["point"] or "status" not in columns:
        raise InputError(path, f"not a sweep table ({layout})")
    status = columns.index("status")
    if status < 2 or status + 1 >= len(columns):
        raise InputError(path, f"not a sweep table: no varied input before status or no objective after it ({layout})")
    if not 0 < len(frame) <= MAX_POINTS:
        raise InputError(path, f"a sweep table has 1 to {MAX_POINTS:,} rows, this one {len(frame):,}")
    problems = Problems()
    for column in columns[:status] + [columns[status + 1]]:
        values = pd.to_numeric(frame[column], errors="coerce")
        blank = frame[column].isna()
        if (values.isna() & ~blank).any() or (column != columns[status + 1] and blank.any()):
            problems.errors.append(InputError(f"{path}: column {column!r}", "must hold numbers in every row"))
        elif not np.isfinite(values[~blank]).all():
            problems.errors.append(InputError(f"{path}: column {column!r}", "must hold finite numbers"))
    unknown = sorted(set(map(str, frame["status"].dropna())) - set(STATUSES))
    if unknown or frame["status"].isna().any():
        problems.errors.append(InputError(f"{path}: column 'status'", f"must be one of {', '.join(STATUSES)} "
                                                                      f"in every row, got {unknown[:3] or 'blanks'}"))
    problems.raise_any()


def table_cell(value) -> str:
    """A sweep table's cell: numbers to 6 digits, ``-`` where a point has no value (no design: an infeasible point;
    no iteration count: a point solved in a batch)."""
    if value is pd.NA or (isinstance(value, float) and math.isnan(value)):
        return "-"
    return f"{value:.6g}" if isinstance(value, float) else str(value)


def markdown_table(frame: pd.DataFrame) -> str:
    lines = ["| " + " | ".join(frame.columns) + " |", "|" + "---|" * len(frame.columns)]
    lines += ["| " + " | ".join(table_cell(v) for v in row) + " |" for row in frame.itertuples(index=False)]
    return "\n".join(lines)
