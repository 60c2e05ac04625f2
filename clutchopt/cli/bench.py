"""The ``clutchopt bench`` sub-command."""

from __future__ import annotations

from clutchopt.cli.options import add_json_option


def run(args) -> str:
    from clutchopt.bench import BenchConfig, bench_text, run_bench
    from clutchopt.output import to_json

    report = run_bench(BenchConfig.quick() if args.quick else BenchConfig(), quick=args.quick)
    return to_json(report) if args.json else bench_text(report)


def add_command(commands) -> None:
    bench = commands.add_parser("bench", help="accuracy against time of every solver, throughput of warm sweeps")
    bench.add_argument("--quick", action="store_true", help="few repeats, 100-point sweeps, no Dask clusters (about a minute)")
    add_json_option(bench, "one JSON object, times in seconds")
    bench.set_defaults(run=run)
