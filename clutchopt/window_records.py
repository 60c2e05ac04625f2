"""The records of a window's batched sweep points as arrays, one column per point, and their bytes in the run store.

A batched window (``clutchopt.optimise.batch_window``) holds its points' numbers as arrays; :class:`WindowRecords`
keeps them so (with the template the points share, ``clutchopt.records``) and builds a point's compact record
only when it is read. Points solved alone one after another that share a template (a region proof's points
without a design) are gathered into such records from their full ones (:func:`gathered`), or from their Solutions
without building those (:func:`gathered_solutions`: the same arrays). The run store keeps a window's points as
one row: :func:`pack` turns their arrays into bytes and a layout (each array's name, type and shape),
:func:`unpack` reads them back, refusing bytes that do not fit their layout; :func:`checksum` is kept beside them,
so that bytes changed in place (a page zeroed, a bit flipped: the layout still fits) are refused too.
Pure NumPy: the store reads windows without importing the solvers.
"""

from __future__ import annotations

import math
import zlib
from functools import cached_property
from itertools import compress
from operator import attrgetter, itemgetter
from typing import Callable, NamedTuple

import numpy as np

from clutchopt.records import (CONSTRAINT_COLUMNS, CONSTRAINT_STATICS, SOLVER_STATICS, STATUSES, TEMPLATE, expand,
                               laid_out, template_key, template_of)

NUMBER, FLAG, WHOLE, CODE = "<f8", "|b1", "<i8", "|i1"
LABELS = 127  # the most texts a CODE array can index (diagnoses)
_TYPES = {NUMBER: frozenset({float, np.float64, type(None)}),  # what each array keeps as it is (None: NaN, as JSON
          FLAG: frozenset({bool, np.bool_}), WHOLE: frozenset({int, np.int64})}  # keeps NaN)
GATHERED = 2  # the fewest points solved alone, one after another with one template, kept as arrays (:func:`gathered`)
KINDS = {  # each array of a window's records: its type, and whether it holds a row per item (else one value a point)
    "status": (CODE, False),  # index into STATUSES
    "diagnosis": (CODE, False),  # index into the diagnoses named beside the arrays; -1: none
    "objective": (NUMBER, False), "time_s": (NUMBER, False), "solves": (WHOLE, False),
    "priced": (FLAG, False),  # whether the constraints' elasticities apply (a finite, non-zero objective)
    "design": (NUMBER, True), "outputs": (NUMBER, True),
    **{name: (FLAG if name in ("active", "feasible") else NUMBER, True) for name in CONSTRAINT_COLUMNS},
    "sensitivity": (NUMBER, True), "sensitive": (FLAG, True),  # each point's sensitivities and which apply
}


class WindowRecords:
    """Compact records (``clutchopt.records``) of batched points as arrays (:data:`KINDS`; the last axis runs over
    the points), with their ``template``; ``labels``: the texts the arrays index (``diagnoses``), the name of each
    sensitivity row (``sensitivities``; a name that repeats adds its row to the one before) and the integer searches
    by column (``integer_search``, only of the points that ran one)."""

    def __init__(self, template: dict, arrays: dict[str, np.ndarray], labels: dict):
        self.template, self.arrays, self.labels = template, arrays, labels

    @cached_property
    def key(self) -> str:
        return template_key(self.template)

    def __len__(self) -> int:
        return len(self.arrays["objective"])

    def take(self, columns: np.ndarray) -> "WindowRecords":
        """The records of the points ``columns`` only."""
        position = {int(column): str(j) for j, column in enumerate(np.asarray(columns).tolist())}
        searches = {position[int(column)]: search for column, search in self.labels["integer_search"].items()
                    if int(column) in position}
        return WindowRecords(self.template, {name: array[..., columns] for name, array in self.arrays.items()},
                             {**self.labels, "integer_search": searches})

    def compact(self, json_numbers: bool = False) -> list[dict]:
        """Each point's compact record; ``json_numbers``: NaN and infinities as None, as JSON keeps them (what a
        record read back from the store holds)."""
        a, labels, count = self.arrays, self.labels, len(self)
        lists = {name: (a[name].T if rows else a[name]).tolist() if kind != NUMBER or not json_numbers
                 else _json_numbers(a[name].T if rows else a[name]) for name, (kind, rows) in KINDS.items()}
        statuses = [STATUSES[code] for code in lists["status"]]
        diagnoses = [labels["diagnoses"][code] if code >= 0 else None for code in lists["diagnosis"]]
        searches = labels["integer_search"]
        sensitivities = values_by_name(labels["sensitivities"], lists["sensitivity"], lists["sensitive"])
        unpriced = [None] * len(self.template["constraints"])
        key = self.key
        return [{
            TEMPLATE: key, "status": statuses[j], "objective": lists["objective"][j],
            "design": lists["design"][j], "outputs": lists["outputs"][j],
            "constraints": {name: lists[name][j] if name != "elasticity" or lists["priced"][j] else unpriced
                            for name in CONSTRAINT_COLUMNS},
            "solver": {"time_s": lists["time_s"][j], "solves": lists["solves"][j]},
            "diagnosis": diagnoses[j], "integer_search": searches.get(str(j), []),
            "sensitivities": sensitivities[j],
        } for j in range(count)]

    def records(self, json_numbers: bool = False) -> list[dict]:
        """Each point's ``Solution.as_dict()``: its compact record expanded with the template."""
        return [expand(record, self.template) for record in self.compact(json_numbers)]

    @classmethod
    def of(cls, records: list[dict]) -> "WindowRecords | None":
        """The records (full, ``Solution.as_dict()``, laid out as :func:`~clutchopt.records.expand` gives them) of
        points that share a template (:func:`~clutchopt.records.template_of`), as arrays, read back as they are
        (``records(json_numbers=True)`` is their JSON, bit for bit); None where a value is not of its array's type
        (a whole number where a float goes or beyond 64 bits, NumPy's float32, text): they stay records of their own."""
        return cls._of(_record_fields(records), lambda: template_of(records[0]))

    @classmethod
    def of_solutions(cls, solutions: list) -> "WindowRecords | None":
        """:meth:`of` the solutions' records (``Solution.as_dict()``) without building them, read from the
        solutions themselves (duck-typed: this module imports no solver code): the same arrays, bit for bit."""
        return cls._of(_solution_fields(solutions), lambda: template_of(solutions[0].as_dict()))

    @classmethod
    def _of(cls, fields: "_Fields", template) -> "WindowRecords | None":
        """:meth:`of` the points whose numbers ``fields`` holds, their template as ``template()`` builds it."""
        count, sensitivities = len(fields.status), fields.sensitivities
        names = next((list(found) for found in sensitivities if found), [])
        if any(found and list(found) != names for found in sensitivities):
            return None  # (sensitivities named in another order: their JSON would differ)
        if not fields.constraints["value"]:
            return None  # (no constraints)
        per_point = {"objective": fields.objective, "time_s": fields.time_s, "solves": fields.solves}
        per_item = {"design": fields.design, "outputs": fields.outputs,
                    "sensitivity": [value for found in sensitivities for value in found.values()],  # (of the points
                    **fields.constraints}  # with sensitivities: each has every name, in order)
        diagnoses = list(dict.fromkeys(text for text in fields.diagnosis if text is not None))
        searches = {str(j): search for j, search in enumerate(fields.integer_search) if search}
        types = {name: set(map(type, values)) for values in (per_point, per_item) for name, values in values.items()}
        if not (all(found <= _TYPES[KINDS[name][0]] for name, found in types.items())
                and all(status in STATUSES for status in fields.status)
                and len(diagnoses) <= LABELS and all(type(text) is str for text in diagnoses)
                and all(type(search) is list for search in searches.values())):
            return None
        code = {text: j for j, text in enumerate(diagnoses)}
        sensed = np.array([bool(found) for found in sensitivities])
        lists = {"status": [STATUSES.index(status) for status in fields.status],
                 "diagnosis": [code.get(text, -1) for text in fields.diagnosis],
                 "sensitive": np.repeat(sensed[:, None], len(names), axis=1), **per_point, **per_item}
        lists["sensitivity"] = np.full((count, len(names)), np.nan)  # (a row a point: NaN where none apply)
        if names:
            lists["sensitivity"][sensed] = np.array(per_item["sensitivity"], dtype=NUMBER).reshape(-1, len(names))
        try:
            arrays = {name: _array(lists[name], kind, types.get(name)).reshape(count, -1).T.copy() if rows  # (a
                      else _array(lists[name], kind, types.get(name))  # point's rows: a column)
                      for name, (kind, rows) in KINDS.items() if name in lists}
        except OverflowError:  # a whole number beyond 64 bits
            return None
        arrays["priced"] = ~np.isnan(arrays["elasticity"]).all(axis=0)  # (unpriced: every elasticity None)
        window = cls(template(), arrays, {"diagnoses": diagnoses, "sensitivities": names, "integer_search": searches})
        try:
            window.key  # (kept: the store names the row's template by it)
        except TypeError:  # (a whole number beyond 64 bits in what the points share: no key, kept as rows)
            return None
        return window

    @classmethod
    def read(cls, template: dict, arrays: dict[str, np.ndarray], labels: dict) -> "WindowRecords":
        """Records read back from the run store (the arrays of :func:`unpack`); ValueError, KeyError or TypeError
        where the arrays or labels are not those of a window's records (their types, shapes, codes)."""
        count = len(arrays["objective"])
        for name, (kind, rows) in KINDS.items():
            if arrays[name].dtype.str != kind or arrays[name].ndim != 1 + rows or arrays[name].shape[-1] != count:
                raise ValueError("its numbers do not fit their layout")
        labels = {key: labels[key] for key in ("diagnoses", "sensitivities", "integer_search")}
        sizes = (len(STATUSES), len(labels["diagnoses"]), len(labels["sensitivities"]))
        if (not all(0 <= code < sizes[0] for code in arrays["status"].tolist())
                or not all(-1 <= code < sizes[1] for code in arrays["diagnosis"].tolist())
                or arrays["sensitivity"].shape[0] != sizes[2] or arrays["sensitive"].shape[0] != sizes[2]
                or not all(type(name) is str for name in (*labels["diagnoses"], *labels["sensitivities"]))
                or type(labels["integer_search"]) is not dict
                or not all(type(search) is list for search in labels["integer_search"].values())):
            raise ValueError("its numbers do not fit their layout")
        return cls(template, arrays, labels)


def _array(values, kind: str, types: set | None) -> np.ndarray:
    """``np.array(values, dtype=kind)``, where ``types`` are the types of ``values``: NaN at once where every value is
    None (a proven point's multipliers and elasticities; NumPy reads a None four times slower than a float: 0.11 ms
    for the 2088 of the lever's 232 points without a design), in ``values``' shape (a row a point: sensitivities)."""
    return np.full(np.shape(values), np.nan, dtype=kind) if types == _NONE else np.array(values, dtype=kind)


_NONE = {type(None)}


def gathered(alone: dict[int, dict]) -> tuple[dict[int, dict], list[tuple[np.ndarray, WindowRecords]]]:
    """Points solved alone (their full records, ``Solution.as_dict()``, by position) as the run store keeps them:
    each run of GATHERED or more at consecutive positions that share a template and whose numbers are numbers
    (:meth:`WindowRecords.of`) as a window's records, with their positions; the rest alone. E.g. a sweep's points
    without a design come so (the points a region proof covers: one design, one proof, one solver status; the lever
    over its inertia 0.5x-2x: 232 of 1000 points), where each had been a row of JSON of its own (4.8 kB)."""
    return _gathered(alone, _RECORDS)


def gathered_solutions(alone: dict) -> tuple[dict, list[tuple[np.ndarray, WindowRecords]]]:
    """:func:`gathered` the points' Solutions (by position) without building their records: the same runs and arrays
    (:meth:`WindowRecords.of_solutions`; a run broken also where two points differ only in a display unit of one SI
    unit, which one case never makes: the same records read back), the rest left Solutions. A window's points
    solved alone go so to the store (the lever's 232 points without a design: 2.1 ms, where their records took 4.5
    and :func:`gathered` 4.3)."""
    return _gathered(alone, _SOLUTIONS)


class _Reading(NamedTuple):
    """How :func:`_gathered` reads a point: its statics (:func:`_statics`; None: none to share), whether a run may
    start at it (its record laid out as a template expands), its diagnosis, and the records of a run as arrays."""

    statics: Callable
    laid_out: Callable
    diagnosis: Callable
    of: Callable


def _gathered(alone: dict, reading: _Reading) -> tuple[dict, list[tuple[np.ndarray, WindowRecords]]]:
    kept, windows, run, shared, diagnoses = {}, [], [], None, set()

    def close() -> None:
        found = reading.of([alone[position] for position in run]) if len(run) >= GATHERED else None
        if found is None:
            kept.update((position, alone[position]) for position in run)
        else:
            windows.append((np.array(run), found))

    for position in sorted(alone):
        point = alone[position]
        statics, diagnosis = reading.statics(point), None
        if statics is not None:
            diagnosis = reading.diagnosis(point)
        if (statics is None or statics != shared or not run or position != run[-1] + 1
                or (len(diagnoses) == LABELS and diagnosis not in diagnoses)):
            close()
            run, diagnoses = [], set()
            shared = statics = statics if statics is not None and reading.laid_out(point) else None  # (the same
            # statics: the same keys, in the same order)
        if statics is None:
            kept[position] = point
        else:
            run.append(position)
            diagnoses.add(diagnosis)
    close()
    return kept, windows


_CONSTRAINT_STATICS = itemgetter(*CONSTRAINT_STATICS)
_SOLVER_STATICS = itemgetter(*SOLVER_STATICS)


def _statics(record) -> tuple | None:
    """What a record's template (``records.template_of``) holds, and the order of its keys, compared without
    building the template: records with equal statics have equal templates, their keys in one order; None for what
    is no record."""
    try:
        objective, solver = record["objective"], record["solver"]
        constraints, units = record["constraints"], record["units"]
        return (tuple(record), record["coupling"], record["mode"], tuple(objective), objective["name"],
                objective["unit"], list(record["design"]), list(record["outputs"]), units,
                list(map(list, units.values())), list(map(tuple, constraints)),
                list(map(_CONSTRAINT_STATICS, constraints)), tuple(solver), _SOLVER_STATICS(solver), record["bounds"],
                list(record["bounds"]))
    except (KeyError, TypeError, IndexError, AttributeError):
        return None


def _solution_statics(solution) -> tuple | None:
    """:func:`_statics` of a Solution (duck-typed), from its fields: equal ones give records with equal templates,
    their keys in one order (display units compared where the record holds their SI units: no looser); None for a
    solution whose record holds more than a template expands (a start-up's path, the starts tried, ``solve_alone``) or
    for what is no Solution."""
    try:
        if solution.start_up is not None or solution.starts or solution.solve_alone is not None:
            return None
        solver, outputs = solution.solver, solution.outputs
        return (type(solution), solution.coupling, solution.mode, solution.objective_name, solution.objective_unit,
                list(solution.design), list(outputs), [out.unit for out in outputs.values()],
                list(solution.design_units.items()), list(map(_CHECK_STATICS, solution.constraints)), type(solver),
                tuple(vars(solver)), solver.name, solver.status, solver.iterations, list(solution.bounds.items()))
    except (AttributeError, TypeError):
        return None


_CHECK_STATICS = attrgetter("__class__", *CONSTRAINT_STATICS[:-1])  # (a check's display unit is its unit)


class _Fields(NamedTuple):
    """What :meth:`WindowRecords.of` reads of points' records: per point its status, objective, solver seconds and
    calls, sensitivities (by name), diagnosis and integer search; per item its design and output values, and their
    constraints' numbers (each of CONSTRAINT_COLUMNS: a list over the points' constraints)."""

    status: list
    objective: list
    time_s: list
    solves: list
    sensitivities: list
    diagnosis: list
    integer_search: list
    design: list
    outputs: list
    constraints: dict[str, list]


def _record_fields(records: list[dict]) -> _Fields:
    """The numbers of full records (``Solution.as_dict()``) as :meth:`WindowRecords.of` reads them."""
    return _Fields([r["status"] for r in records], [r["objective"]["value"] for r in records],
                   [r["solver"]["time_s"] for r in records], [r["solver"]["solves"] for r in records],
                   [r["sensitivities"] for r in records], [r["diagnosis"] for r in records],
                   [r["integer_search"] for r in records],
                   [value for r in records for value in r["design"].values()],
                   [value for r in records for value in r["outputs"].values()],
                   _item_columns([c for r in records for c in r["constraints"]]))


def _item_columns(constraints: list[dict]) -> dict[str, list]:
    """:func:`_check_columns` of constraints as records hold them."""
    return {name: list(map(itemgetter(name), constraints)) for name in CONSTRAINT_COLUMNS}


def _solution_fields(solutions: list) -> _Fields:
    """:func:`_record_fields` of the solutions' records (``Solution.as_dict()``: the same objects), read from them."""
    solvers = [s.solver for s in solutions]
    return _Fields([s.status for s in solutions], [s.objective for s in solutions], [v.time_s for v in solvers],
                   [v.solves for v in solvers], [s.sensitivities for s in solutions],
                   [s.diagnosis for s in solutions], [s.integer_search for s in solutions],
                   [value for s in solutions for value in s.design.values()],
                   [out.value for s in solutions for out in s.outputs.values()],
                   _check_columns([c for s in solutions for c in s.constraints]))


def _check_columns(checks: list) -> dict[str, list]:
    """Each of CONSTRAINT_COLUMNS of constraint checks, a list each (no tuple a check: fewer objects for Python's
    garbage collector to follow)."""
    return {name: list(map(attrgetter(name), checks)) for name in CONSTRAINT_COLUMNS}


_RECORDS = _Reading(_statics, laid_out, itemgetter("diagnosis"), WindowRecords.of)
_SOLUTIONS = _Reading(_solution_statics, lambda solution: laid_out(solution.as_dict()), attrgetter("diagnosis"),
                      WindowRecords.of_solutions)


def in_order(count: int, alone: dict[int, dict], windows: list[tuple[np.ndarray, WindowRecords]]) -> list[dict]:
    """The full records (``Solution.as_dict()``) of ``count`` points in order: ``alone`` by position, and each
    window's at its positions."""
    records = [None] * count
    for position, record in alone.items():
        records[position] = record
    for positions, window in windows:
        for position, record in zip(positions.tolist(), window.records()):
            records[position] = record
    return records


def _json_numbers(array: np.ndarray) -> list:
    """``array.tolist()`` with None for NaN and infinities."""
    finite = np.isfinite(array)
    return array.tolist() if finite.all() else np.where(finite, array, None).tolist()


def values_by_name(names: list[str], points: list[list[float]], applies: list[list[bool]]) -> list[dict[str, float]]:
    """Each point's values (a list in the order of ``names``) by name, of those that apply to it (a name that
    repeats adds its value to the one before)."""
    if len(set(names)) == len(names):
        return [dict(compress(zip(names, row), keep)) for row, keep in zip(points, applies)]
    found = []
    for row, keep in zip(points, applies):
        point = {}
        for name, value in compress(zip(names, row), keep):
            point[name] = point[name] + value if name in point else value
        found.append(point)
    return found


def pack(arrays: dict[str, np.ndarray]) -> tuple[dict, bytes]:
    """Arrays (a value per point, or rows of them) as one byte string, and their layout: each array's name, type,
    shape and the rows whose points all hold the same value (bit for bit), kept once: about half the rows of a
    window's records (limits, scales, flags, sensitivities to quantities that do not move)."""
    layout, parts = {}, []
    for name, array in arrays.items():
        rows = array.reshape(math.prod(array.shape[:-1]), array.shape[-1])
        bits = rows.view(f"u{rows.itemsize}") if rows.dtype.kind == "f" else rows
        same = (bits == bits[:, :1]).all(axis=1) if rows.shape[1] else np.zeros(len(rows), dtype=bool)
        kept = same.tolist()
        layout[name] = [array.dtype.str, list(array.shape), [row for row, once in enumerate(kept) if once]]
        if not any(kept):
            parts.append(rows.tobytes())
        elif all(kept):
            parts.append(rows[:, 0].tobytes())
        else:
            parts += [rows[~same].tobytes(), rows[same, 0].tobytes()]
    return layout, b"".join(parts)


CHECKSUM = "crc32"  # the key of a window row's header that holds its bytes' checksum (none in a store of an older
# clutchopt: its rows are read unchecked)


def checksum(data: bytes) -> int:
    """The CRC-32 of a window row's bytes (about 1 us for 4 kB, 70 us for a 1000-point wedge window of 300 kB). It
    finds every single bit flipped and every burst of 32 bits or fewer (the changed bits within 32 in a row), and of
    other changes all but about 1 in 4 billion (Koopman, "32-bit cyclic redundancy codes for Internet
    applications", DSN 2002: more scattered flips are certain to be found only up to a count that falls with the
    row's length)."""
    return zlib.crc32(data)


def unpack(layout: dict, data: bytes) -> dict[str, np.ndarray]:
    """The arrays :func:`pack` gave ``layout`` and ``data`` for; ValueError where the bytes do not fit the layout (a
    type other than a window's, a shape or rows that are no lists of whole numbers, too few or too many bytes)."""
    arrays, start = {}, 0
    if type(layout) is not dict or type(data) is not bytes:
        raise ValueError("its numbers do not fit their layout")
    for name, entry in layout.items():
        if not (type(entry) is list and len(entry) == 3 and entry[0] in (NUMBER, FLAG, WHOLE, CODE)
                and type(entry[1]) is list and 1 <= len(entry[1]) <= 2 and type(entry[2]) is list
                and all(type(n) is int and n >= 0 for n in (*entry[1], *entry[2]))):
            raise ValueError("its numbers do not fit their layout")
        dtype, shape, same = np.dtype(entry[0]), tuple(entry[1]), entry[2]
        count = shape[-1]
        rows = np.zeros(math.prod(shape[:-1]), dtype=bool)
        if len(set(same)) != len(same) or any(row >= len(rows) for row in same):
            raise ValueError("its numbers do not fit their layout")
        rows[same] = True
        size = dtype.itemsize * ((len(rows) - len(same)) * count + len(same))
        if start + size > len(data):
            raise ValueError("its numbers do not fit their layout")
        values = np.frombuffer(data, dtype, size // dtype.itemsize, start)
        array = np.empty((len(rows), count), dtype)
        varying = len(rows) - len(same)
        array[~rows] = values[:varying * count].reshape(varying, count)
        array[rows] = values[varying * count:, None]
        arrays[name] = array.reshape(shape)
        start += size
    if start != len(data):
        raise ValueError("its numbers do not fit their layout")
    return arrays
