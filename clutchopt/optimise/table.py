"""A sweep table's columns: what each point's row shows, read from its record or from a batch's arrays.

A table is a dict of NumPy arrays, one entry per point: ``status``, ``objective`` (SI), ``design`` (SI, one row
per design variable), ``active`` (the names of the active constraints, space-separated), ``diagnosis`` (None
where there is none) and ``iterations`` (None for a point solved in a batch). Batched points fill theirs straight
from the window's arrays (``clutchopt.optimise.batch``), so a sweep is tabulated without building each point's
record; the records (``Solution.as_dict()``) are built only for what needs them (the run store, ``--json``).
"""

from __future__ import annotations

import numpy as np

KEYS = ("status", "objective", "design", "active", "diagnosis", "iterations")


def record_table(records: list[dict], names: list[str]) -> dict[str, np.ndarray]:
    """The table of points given as records (``Solution.as_dict()``); ``names``: the design variables, in order."""
    return _rows_table([(r["status"], r["objective"]["value"], r["design"],
                         " ".join(c["name"] for c in r["constraints"] if c["active"]), r["diagnosis"],
                         r["solver"]["iterations"]) for r in records], names)


def solution_table(solutions: list, names: list[str]) -> dict[str, np.ndarray]:
    """The table of points given as ``Solution`` objects, read from their fields: the rows :func:`record_table`
    reads from their records, without building the records (``Solution.as_dict()``: each check, output and unit
    written out, about 0.2 ms a point, two fifths of a 100-point sweep of the lever beyond its edge, 0.05 ms a
    point proven without a solve)."""
    return _rows_table([(s.status, s.objective, s.design, " ".join(c.name for c in s.constraints if c.active),
                         s.diagnosis, s.solver.iterations) for s in solutions], names)


def _rows_table(rows: list[tuple], names: list[str]) -> dict[str, np.ndarray]:
    """The table of points given as rows (status, objective, design by name, active names, diagnosis, iterations)."""
    count = len(rows)
    return {
        "status": _objects([row[0] for row in rows]),
        "objective": np.array([row[1] for row in rows], dtype=float).reshape(count),
        "design": np.array([[row[2].get(name) for row in rows] for name in names],
                           dtype=float).reshape(len(names), count),
        "active": _objects([row[3] for row in rows]),
        "diagnosis": _objects([row[4] for row in rows]),
        "iterations": _objects([row[5] for row in rows]),
    }


def active_names(active: np.ndarray, names: list[str]) -> np.ndarray:
    """Each column's active constraints by name, space-separated (``active``: one row per constraint, one column
    per point; joined once per run of points with the same ones, as along a sweep)."""
    count = active.shape[1]
    starts = np.flatnonzero(np.r_[True, np.any(active[:, 1:] != active[:, :-1], axis=0)]) if count else []
    joined = _objects([" ".join(name for name, on in zip(names, active[:, k].tolist()) if on) for k in starts])
    return np.repeat(joined, np.diff(np.r_[starts, count]).astype(int))


def joined_tables(tables: list[dict[str, np.ndarray]]) -> dict[str, np.ndarray]:
    """Tables of consecutive points as one."""
    if len(tables) == 1:
        return tables[0]
    return {key: np.concatenate([t[key] for t in tables], axis=-1) for key in KEYS}


def placed(table: dict[str, np.ndarray], positions, into: dict[str, np.ndarray]) -> None:
    """Write ``table``'s points into ``into`` at ``positions``."""
    for key in KEYS:
        into[key][..., positions] = table[key]


def _objects(items: list) -> np.ndarray:
    """A 1-D object array of ``items`` (NumPy would make strings fixed-width, or lists of lists 2-D)."""
    array = np.empty(len(items), dtype=object)
    array[:] = items
    return array
