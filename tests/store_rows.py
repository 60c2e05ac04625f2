"""A run store's rows read and changed by SQL, as tests of the store need them: a window of sweep points is one row
(``run_count`` points from ``point``, ids from ``id``; its numbers packed in ``window``, their layout in ``outputs``).
"""

import json
import sqlite3
from contextlib import closing
from pathlib import Path
from typing import Callable

import numpy as np

from clutchopt.window_records import CHECKSUM, checksum, pack, unpack


def sweep_points(store: Path) -> list[tuple[int, int, str]]:
    """Each stored sweep point's run id, point number and time of recording, by id (a window's points one by one)."""
    with closing(sqlite3.connect(store, timeout=60)) as db:
        rows = db.execute("SELECT id, point, IFNULL(run_count, 1), created FROM runs WHERE kind = 'sweep' "
                          "ORDER BY id").fetchall()
    return [(run_id + k, point + k, created) for run_id, point, count, created in rows for k in range(count)]


def window_ids(store: Path) -> list[int]:
    """The run ids of the points stored in windows."""
    with closing(sqlite3.connect(store)) as db:
        rows = db.execute("SELECT id, run_count FROM runs WHERE window IS NOT NULL").fetchall()
    return [run_id + k for run_id, count in rows for k in range(count)]


def rewrite_windows(store: Path, change: Callable[[dict, dict[str, np.ndarray]], None]) -> None:
    """Every window row's header (its outputs) and arrays changed in place by ``change(header, arrays)``, and
    packed again (with the checksum of the new bytes)."""
    with closing(sqlite3.connect(store)) as db, db:
        for run_id, outputs, data in db.execute("SELECT id, outputs, window FROM runs WHERE window IS NOT NULL"
                                                ).fetchall():
            header = json.loads(outputs)
            arrays = {name: array.copy() for name, array in unpack(header["arrays"], data).items()}
            change(header, arrays)
            header["arrays"], data = pack(arrays)
            header[CHECKSUM] = checksum(data)
            db.execute("UPDATE runs SET outputs = ?, window = ? WHERE id = ?", (json.dumps(header), data, run_id))


def forget_points(store: Path, forget: Callable[[int], bool]) -> None:
    """Delete the stored sweep points whose point number ``forget`` picks; a window keeps each other point as a
    window row of its own (its id and point number as they were)."""
    with closing(sqlite3.connect(store)) as db, db:
        db.row_factory = sqlite3.Row
        for row in db.execute("SELECT * FROM runs WHERE kind = 'sweep'").fetchall():
            db.execute("DELETE FROM runs WHERE id = ?", (row["id"],))
            if row["window"] is None:
                if not forget(row["point"]):
                    db.execute(f"INSERT INTO runs ({', '.join(row.keys())}) VALUES ({', '.join('?' * len(row))})",
                               tuple(row))
                continue
            header = json.loads(row["outputs"])
            arrays = unpack(header["arrays"], row["window"])
            for k in range(row["run_count"]):
                if forget(row["point"] + k):
                    continue
                layout, data = pack({name: np.ascontiguousarray(array[..., k:k + 1]) for name, array in arrays.items()})
                searches = {"0": search for column, search in header["integer_search"].items() if int(column) == k}
                kept = {**dict(row), "id": row["id"] + k, "point": row["point"] + k, "run_count": 1, "window": data,
                        "outputs": json.dumps({**header, "arrays": layout, "integer_search": searches,
                                               CHECKSUM: checksum(data)})}
                db.execute(f"INSERT INTO runs ({', '.join(kept)}) VALUES ({', '.join('?' * len(kept))})",
                           tuple(kept.values()))
