"""The full benchmark: every section of ``clutchopt bench`` with 20 timed re-solves and a 1,000-point sweep.

Writes ``benchmarks/latest.json`` and the table between the markers of ``benchmarks/README.md``.
Run from the repository root: ``python benchmarks/run_full.py``; ``python benchmarks/run_full.py user_sweeps
start_up_solve`` takes those sections again at full size and keeps the others of ``latest.json`` (the text says
which sections were taken when).
"""

from __future__ import annotations

import json
import re
import sys
from datetime import datetime, timezone
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from clutchopt.bench import SECTIONS, BenchConfig, bench_json, bench_text, run_bench  # noqa: E402
from clutchopt.output import to_json  # noqa: E402

START, END = "<!-- bench:start -->", "<!-- bench:end -->"


def main(names: list[str]) -> None:
    known = {section.name: section for section in SECTIONS}
    unknown = [name for name in names if name not in known]
    if unknown:
        print(f"error: unknown section {', '.join(unknown)}; sections are {', '.join(known)}", file=sys.stderr)
        sys.exit(2)
    kept = _kept() if names else None  # read before the minutes of measuring, not after
    now = datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    report = run_bench(BenchConfig(), tuple(s for s in SECTIONS if s.name in names) if names else SECTIONS)  # in order:
    # a section may warm what the next reads (start_up_accuracy the simulator's imports for start_up_solve's first solve)
    if names:
        taken = {**kept.get("sections_taken", {}), **dict.fromkeys(names, now)}
        report = {**kept, "machine": report["machine"], "sections_taken": taken,
                  "sections": {name: report["sections"].get(name, section)
                               for name, section in kept["sections"].items()} | report["sections"]}
        report.pop("units", None)
        stamp = f"Taken {kept['taken']}; " + "; ".join(f"{name} again {when}" for name, when in taken.items()) + "."
    else:
        report["taken"], stamp = now, f"Taken {now}."
    (HERE / "latest.json").write_text(to_json(bench_json(report)) + "\n")
    text = bench_text(report)
    readme = HERE / "README.md"
    block = f"{START}\n{stamp}\n\n```\n{text}\n```\n{END}"
    readme.write_text(re.sub(f"{START}.*?{END}", lambda _: block, readme.read_text(), flags=re.S))
    print(text)


def _kept() -> dict:
    """The last full run's report, whose other sections a partial run keeps."""
    try:
        kept = json.loads((HERE / "latest.json").read_text(encoding="utf-8"))
        if not isinstance(kept.get("sections"), dict) or "taken" not in kept:
            raise ValueError("no sections or no time taken")
    except (OSError, ValueError, AttributeError) as exc:
        print(f"error: benchmarks/latest.json: cannot keep its other sections ({exc}); run every section",
              file=sys.stderr)
        sys.exit(2)
    return kept


if __name__ == "__main__":
    main(sys.argv[1:])
