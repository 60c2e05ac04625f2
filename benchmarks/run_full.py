"""The full benchmark: every section of ``clutchopt bench`` with 20 timed re-solves and a 1,000-point sweep.

Writes ``benchmarks/latest.json`` and the table between the markers of ``benchmarks/README.md``.
Run from the repository root: ``python benchmarks/run_full.py``.
"""

from __future__ import annotations

import re
import sys
from datetime import datetime, timezone
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from clutchopt.bench import BenchConfig, bench_json, bench_text, run_bench  # noqa: E402
from clutchopt.output import to_json  # noqa: E402

START, END = "<!-- bench:start -->", "<!-- bench:end -->"


def main() -> None:
    report = run_bench(BenchConfig())
    report["taken"] = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    (HERE / "latest.json").write_text(to_json(bench_json(report)) + "\n")
    text = bench_text(report)
    readme = HERE / "README.md"
    block = f"{START}\nTaken {report['taken']}.\n\n```\n{text}\n```\n{END}"
    readme.write_text(re.sub(f"{START}.*?{END}", lambda _: block, readme.read_text(), flags=re.S))
    print(text)


if __name__ == "__main__":
    main()
