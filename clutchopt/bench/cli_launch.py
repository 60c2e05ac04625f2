"""What a user waits for at the command line: whole CLI runs as new processes, beside the bare imports.

The baseline is ``python -c "import casadi, numpy"``, the least a process that solves with CasADi must load;
each command's median wall time is reported as a ratio to it, all commands taking turns in one loop so that
a busy machine slows them alike. ``solve`` records into a throw-away run store, as a user's would.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
BASELINE = ("python -c 'import casadi, numpy'", ("-c", "import casadi, numpy"))


def _solve(case: str, *flags: str) -> tuple[str, tuple[str, ...]]:
    """``clutchopt solve cases/<case>.toml <flags>``: its name and the interpreter's arguments."""
    args = ("solve", f"cases/{case}.toml", *flags)
    return " ".join(("clutchopt", *args)), ("-m", "clutchopt", *args)


COMMANDS = (
    ("clutchopt --help", ("-m", "clutchopt", "--help")),
    _solve("wedge_paper", "--json"),
    _solve("wedge_paper", "--json", "--no-store"),
    _solve("wedge_paper"),
    *(_solve(case, "--json") for case in ("lever_centrifuge", "ball_crusher", "cable_pump", "wedge_motor_start")),
)  # (each coupling's static solve, and a start-up's: what a user of each waits for, not only the wedge's)


def _wall(args: tuple[str, ...], env: dict) -> float:
    started = time.perf_counter()
    subprocess.run([sys.executable, *args], cwd=ROOT, env=env, check=True, capture_output=True)
    return time.perf_counter() - started


def cli_launch_rows(config) -> list[dict]:
    runs = max(1, config.repeats // 2)
    warm_up = 1 if runs > 1 else 0  # a first round warms the file cache and is not counted (not in --quick)
    with tempfile.TemporaryDirectory() as scratch:
        env = {**os.environ, "CLUTCHOPT_STORE": str(Path(scratch) / "runs.sqlite")}
        times: dict[str, list[float]] = {name: [] for name, _ in (BASELINE, *COMMANDS)}
        for _ in range(runs + warm_up):
            for name, args in (BASELINE, *COMMANDS):
                times[name].append(_wall(args, env))
    base = float(np.median(times[BASELINE[0]][warm_up:]))
    rows = []
    for name, _ in (BASELINE, *COMMANDS):
        median = float(np.median(times[name][warm_up:]))
        rows.append({"command": name, "runs": runs, "median_s": median, "ratio_to_import": median / base})
    return rows
