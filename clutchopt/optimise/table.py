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
    return {
        "status": _objects([r["status"] for r in records]),
        "objective": np.array([r["objective"]["value"] for r in records], dtype=float).reshape(len(records)),
        "design": np.array([[r["design"].get(name) for r in records] for name in names],
                           dtype=float).reshape(len(names), len(records)),
        "active": _objects([" ".join(c["name"] for c in r["constraints"] if c["active"]) for r in records]),
        "diagnosis": _objects([r["diagnosis"] for r in records]),
        "iterations": _objects([r["solver"]["iterations"] for r in records]),
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
