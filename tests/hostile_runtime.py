"""Hostile inputs for what runs beside the solve (issue 25): Dask addresses and servers that misbehave, user text
that looks like mathtext or TeX wherever it reaches a plot, run stores with part of their schema or another
program's, and options.choose beyond its cap. Each says what a correct answer is, as in ``tests/hostile.py``;
``tests/test_hostile_runtime.py`` runs them all through the CLI. Run as a script, this module writes every input
to a folder and prints its command line (a ``{server}`` needs one of your own)::

    python tests/hostile_runtime.py /tmp/hostile-runtime
"""

from __future__ import annotations

import json
import os
import sqlite3
import struct
import sys
import tempfile
from contextlib import closing
from dataclasses import dataclass
from pathlib import Path

from hostile import (CASES, LEVER, OTHER_DATABASE, SCENE, SWEEP_TABLE, WEDGE, Hostile, case, command, edit, sweep,
                     write_all)

from clutchopt.store import RunStore
from clutchopt.store_kept import close_kept

BALL = (CASES / "ball_crusher.toml").read_text()
STARTING = (CASES / "wedge_motor_start.toml").read_text()  # a [start_up]: the report draws the simulated start
MATERIALS = ("S235JR", "C45_N", "C45_QT", "41Cr4_QT", "42CrMo4_QT", "100Cr6_hardened", "carbon_steel_balls", "GJL-250",
             "GJS-400-15")
FRICTION_PAIRS = ("organic_dry", "organic_oiled", "sintered_bronze_dry", "sintered_bronze_oiled", "cermet_dry",
                  "steel_steel_dry", "steel_steel_oiled")
MATHTEXT = "Fan $\\frac{$ drive"  # unbalanced mathtext: matplotlib's parser raised, exit code 3


@dataclass(frozen=True)
class Served(Hostile):
    """A hostile input whose command line names ``{server}``: a local TCP server that greets its i-th connection
    with the i-th of ``greetings`` (the last one all after; None: says nothing) and holds each ``hold_s`` seconds."""

    greetings: tuple[bytes | None, ...] = (None,)
    hold_s: float = 2.0


@dataclass(frozen=True)
class ReadOnly(Hostile):
    """A hostile input whose files are written read-only (which root may write all the same)."""

    def write(self, folder: Path) -> list[str]:
        argv = super().write(folder)
        for name, _ in self.files:
            (folder / name).chmod(0o444)
        return argv


# --- Dask -------------------------------------------------------------------------------------------------------
def framed(message: bytes) -> bytes:
    """A greeting as distributed frames one: its length, then one frame (the count, the frame's length, msgpack)."""
    body = struct.pack("QQ", 1, len(message)) + message
    return struct.pack("Q", len(body)) + body


HANDSHAKE = framed(b"\x83\xabcompression\xc0\xa6python\x93\x03\x0b\x07\xafpickle-protocol\x05")  # a scheduler's
JUNK = struct.pack("Q", 64) + bytes(range(64))  # a plausible length, then junk


def dask(name: str, address: str, expect: str | None) -> Hostile:
    return sweep(name, "--vary", "speed=800", "--dask", address, expect=expect)


def served(name: str, *greetings: bytes | None, expect: str, hold_s: float = 2.0) -> Served:
    return Served(name, ("sweep", "{dir}/case.toml", "--quiet", "--vary", "speed=800", "--dask", "{server}"), expect,
                  (("case.toml", WEDGE),), greetings=greetings, hold_s=hold_s)


# --- user text reaching a plot ----------------------------------------------------------------------------------
def titled(text: str, title: str) -> str:
    """A case or scene with its title replaced (TOML's basic strings escape as JSON's do)."""
    old = next(line for line in text.splitlines() if line.startswith("title = "))
    return edit(text, old, f"title = {json.dumps(title)}")


def report(name: str, text: str, expect: str | None, *extra: str) -> Hostile:
    return case(name, text, expect, "-o", "{dir}/review.html", *extra, command="report")


def front(name: str, text: str, expect: str | None) -> Hostile:
    return case(name, text, expect, "--points", "3", "--plot", "{dir}/front.png", command="pareto")


def swept(name: str, header: str, expect: str | None) -> Hostile:
    """``report --sweep`` with a sweep table whose header is ``header``."""
    return command(name, ("report", "{dir}/case.toml", "-o", "{dir}/review.html", "--sweep", "{dir}/sweep.csv"),
                   expect, ("case.toml", WEDGE), ("sweep.csv", header + SWEEP_TABLE[SWEEP_TABLE.index("\n"):]))


# --- run stores -------------------------------------------------------------------------------------------------
PARTIAL_SQL = {  # what a creation cut off after each statement left (each in its own transaction then), or an
    # older clutchopt: completed when opened
    "only-sweeps": "DROP TABLE runs; DROP TABLE templates",
    "only-runs": "DROP TABLE sweeps; DROP TABLE templates",
    "only-templates": "DROP TABLE runs; DROP TABLE sweeps",
    "no-index": "DROP INDEX runs_by_kind",
    "no-templates": "DROP TABLE templates",
    "no-objective-unit": "ALTER TABLE runs DROP COLUMN objective_unit",
}
FOREIGN_SQL = {  # databases of other programs, some with a table of one of our names: refused, untouched
    "its-own-tables": "DROP TABLE runs; DROP TABLE sweeps; DROP TABLE templates; "
                      "CREATE TABLE invoices (id INTEGER PRIMARY KEY, amount REAL)",
    "a-runs-table-of-its-own": "DROP TABLE runs; DROP TABLE sweeps; DROP TABLE templates; "
                               "CREATE TABLE runs (id INTEGER PRIMARY KEY, name TEXT)",
    "a-templates-table-of-its-own": "DROP TABLE runs; DROP TABLE sweeps; DROP TABLE templates; "
                                    "CREATE TABLE templates (id INTEGER PRIMARY KEY, html TEXT)",
    "our-sweeps-beside-its-own": "DROP TABLE runs; DROP TABLE templates; CREATE TABLE invoices (id INTEGER)",
    "runs-with-other-columns": "DROP TABLE runs; CREATE TABLE runs (id INTEGER PRIMARY KEY, path TEXT)",
}
NOT_OURS = "is an SQLite database but not a clutchopt run store"


def store_with(sql: str) -> bytes:
    """A new run store, with ``sql`` run on it, as bytes."""
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "runs.sqlite"
        RunStore(path).close()
        close_kept()  # its connection: the schema folded into the file
        with closing(sqlite3.connect(path)) as db:  # closed: its WAL checkpointed into the file
            db.executescript(sql)
        return path.read_bytes()


def stored(name: str, content: bytes | object, expect: str | None, *argv: str) -> Hostile:
    """A command with ``--store`` a file holding ``content``."""
    return command(name, (*argv, "--store", "{dir}/runs.sqlite"), expect, ("runs.sqlite", content))


PAPER = str(CASES / "wedge_paper.toml")
LIST = ("runs", "list")
SOLVE = ("solve", PAPER)


# --- options.choose ---------------------------------------------------------------------------------------------
def chosen(name: str, base: str, expect: str | tuple[str, ...] | None, **roles: tuple[str, ...]) -> Hostile:
    listed = ", ".join(f"{role} = {json.dumps(list(names))}" for role, names in roles.items())
    return case(name, base + f"\n[options]\nchoose = {{ {listed} }}\n", expect, "--no-store")


HOSTILE: list[Hostile] = [
    # --- Dask: schemes, malformed addresses ------------------------------------------------------------------------
    dask("dask-tls", "tls://127.0.0.1:8786", "--dask: tls:// needs the cluster's TLS certificates and keys"),
    dask("dask-inproc", "inproc://10.0.0.1/4242/1", "--dask: inproc:// names a scheduler inside another Python "
                                                     "process"),
    dask("dask-websocket", "ws://127.0.0.1:8786", "--dask: ws:// is not supported; give the scheduler's tcp://"),
    dask("dask-ucx", "ucx://127.0.0.1:13337", "--dask: ucx:// is not supported"),
    dask("dask-dashboard-url", "http://127.0.0.1:8787/status", "--dask: http:// is not supported"),
    dask("dask-empty-address", "", "--dask: expected an address like tcp://host:8786, got ''"),
    dask("dask-no-scheme", "://127.0.0.1:8786", "--dask: expected an address like tcp://host:8786"),
    dask("dask-no-host", "tcp://:8786", "--dask: expected an address like tcp://host:8786"),
    dask("dask-ipv6-brackets", "tcp://[::1]:8786", "--dask: expected an address like tcp://host:8786"),
    dask("dask-path-after-port", "tcp://127.0.0.1:8786/scheduler", "--dask: expected an address like"),
    dask("dask-port-zero", "tcp://127.0.0.1:0", "--dask: port 0 is out of range (1 to 65535)"),
    # --- Dask: servers that are not a scheduler, or stop half-way ---------------------------------------------------
    served("dask-junk-after-a-plausible-length", JUNK, expect="is not a Dask scheduler: its greeting of 64 bytes is "
                                                               "no Dask handshake"),
    served("dask-length-then-silence", struct.pack("Q", 64), expect="closed the connection"),
    served("dask-half-a-greeting", HANDSHAKE[:30], expect="closed the connection"),
    served("dask-length-zero", struct.pack("Q", 0), expect="is not a Dask scheduler: it greets with"),
    served("dask-length-of-a-terabyte", struct.pack("Q", 1 << 40), expect="is not a Dask scheduler: it greets with"),
    served("dask-msgpack-list", framed(b"\x93\x01\x02\x03"), expect="is no Dask handshake"),
    served("dask-msgpack-other-dict", framed(b"\x81\xa2op\xa4ping"), expect="is no Dask handshake"),
    served("dask-frame-count-absurd", struct.pack("QQQ", 16, 1 << 62, 5), expect="is no Dask handshake"),
    served("dask-http-answer", b"HTTP/1.1 400 Bad Request\r\n\r\n", expect="it greets with b'HTTP/1.1'"),
    served("dask-closes-at-once", b"", expect="closed the connection", hold_s=0.0),
    served("dask-handshake-then-silence", HANDSHAKE, None, expect="cannot connect to a Dask scheduler at"),
    served("dask-handshake-then-junk", HANDSHAKE, JUNK, expect="cannot connect to a Dask scheduler at"),
    served("dask-handshake-but-no-answers", HANDSHAKE, expect="cannot connect to a Dask scheduler at"),
    # --- user text that looks like mathtext or TeX, wherever it reaches a plot --------------------------------------
    report("report-title-mathtext", titled(STARTING, MATHTEXT), None),
    report("report-title-tex-commands", titled(STARTING, "\\textbf{x} $\\alpha$ \\\\ 100% {"), None),
    report("report-title-escaped-dollar", titled(STARTING, "a\\$b$ and $"), None),
    report("report-title-empty-math", titled(STARTING, "$$"), None),
    report("report-title-markup-and-math", titled(STARTING, "<script>alert(1)</script> $x^$"), None),
    report("report-description-mathtext", "description = " + json.dumps(MATHTEXT) + "\n" + WEDGE, None),
    front("pareto-plot-title-mathtext", titled(WEDGE, MATHTEXT), None),
    front("pareto-plot-title-superscript", titled(WEDGE, "$x^$ and $_$"), None),
    command("pareto-plot-file-name-mathtext", ("pareto", "{dir}/$\\frac{$.toml", "--points", "3", "--plot",
                                               "{dir}/front.png"), None,
            ("$\\frac{$.toml", edit(WEDGE, 'title = "Ambartsumyants & Deli (2015), worked example"\n', ""))),
    command("simulate-plot-title-mathtext", ("simulate", "{dir}/scene.toml", "--plot", "{dir}/start.png"), None,
            ("scene.toml", titled(SCENE, MATHTEXT))),
    swept("sweep-table-input-mathtext", "point,speed $\\frac{$ [rpm],status,mass [kg],weight_mass [kg]", None),
    swept("sweep-table-objective-mathtext", "point,speed [rpm],status,mass $^$ [kg],weight_mass [kg]", None),
    command("sweep-table-second-input-mathtext", ("report", "{dir}/case.toml", "-o", "{dir}/review.html",
                                                  "--sweep", "{dir}/sweep.csv"), None, ("case.toml", WEDGE),
            ("sweep.csv", "point,speed [rpm],inertia $\\sqrt{$ [kg*m^2],status,mass [kg]\n0,900,0.5,optimal,0.8\n"
                          "1,1000,0.5,optimal,0.7\n2,900,1,optimal,0.9\n3,1000,1,optimal,0.8\n")),
    report("coupling-name-mathtext", edit(WEDGE, 'coupling = "wedge"', 'coupling = "$\\\\frac{$"'),
           "coupling: unknown coupling '$\\\\frac{$'"),  # the name's repr
    chosen("choose-name-mathtext", LEVER, "options.choose.friction_pair: unknown friction pair '$x^$'",
           friction_pair=("$x^$",)),
    # --- run stores: partial, older, another program's, empty, read-only -------------------------------------------
    *[stored(f"store-{name}-listed", store_with(sql), None, *LIST) for name, sql in PARTIAL_SQL.items()],
    stored("store-only-sweeps-solved", store_with(PARTIAL_SQL["only-sweeps"]), None, *SOLVE),
    stored("store-no-index-solved", store_with(PARTIAL_SQL["no-index"]), None, *SOLVE),
    stored("store-only-runs-resumed", store_with(PARTIAL_SQL["only-runs"]), None, "sweep", PAPER, "--quiet",
           "--vary", "speed=800", "--resume"),
    *[stored(f"store-foreign-{name}", store_with(sql), NOT_OURS, *LIST) for name, sql in FOREIGN_SQL.items()],
    stored("store-foreign-resumed", OTHER_DATABASE, NOT_OURS, "sweep", PAPER, "--quiet", "--vary", "speed=800",
           "--resume"),
    stored("store-zero-bytes-listed", b"", "is empty: nothing has been recorded in it yet", *LIST),
    stored("store-zero-bytes-solved", b"", None, *SOLVE),
    stored("store-header-only", store_with("")[:100], "the run store is damaged", *LIST),
    ReadOnly("store-read-only-partial", (*LIST, "--store", "{dir}/runs.sqlite"),
             None if os.geteuid() == 0 else "its run store schema is incomplete (no runs table",  # root writes it
             (("runs.sqlite", store_with(PARTIAL_SQL["only-sweeps"])),)),
    # --- options.choose: capped before any solve, fine within the cap -----------------------------------------------
    chosen("choose-9-by-9-materials", BALL, "options.choose: 81 combinations (9 ball_material x 9 body_material); "
           "at most 30 are designed in one run", ball_material=MATERIALS, body_material=MATERIALS),
    chosen("choose-567-combinations", BALL, "options.choose: 567 combinations", ball_material=MATERIALS,
           body_material=MATERIALS, friction_pair=FRICTION_PAIRS),
    chosen("choose-63-on-the-lever", LEVER, "63 combinations (9 material x 7 friction_pair)", material=MATERIALS,
           friction_pair=FRICTION_PAIRS),
    chosen("choose-36-just-beyond", BALL, "36 combinations", ball_material=MATERIALS[:4], body_material=MATERIALS),
    chosen("choose-cap-beside-another-problem", edit(BALL, "service_factor = 1.2", "service_factor = -1"),
           ("options.choose: 81 combinations", "duty.service_factor"), ball_material=MATERIALS,
           body_material=MATERIALS),
    chosen("choose-30-at-the-cap", BALL, None, body_material=MATERIALS[:6], friction_pair=FRICTION_PAIRS[:5]),
    chosen("choose-one-each", BALL, None, ball_material=MATERIALS[:1], body_material=MATERIALS[:1]),
    chosen("choose-two-friction-pairs", WEDGE, None, friction_pair=FRICTION_PAIRS[5:]),
]



if __name__ == "__main__":
    write_all(Path(sys.argv[1] if len(sys.argv) > 1 else "hostile-runtime-inputs"), HOSTILE)
