"""The ``clutchopt bench`` sub-command."""

from __future__ import annotations

from clutchopt.cli.options import add_json_option, add_parser


def run(args) -> str:
    from clutchopt.bench import BenchConfig, bench_json, bench_text, run_bench
    from clutchopt.output import to_json

    report = run_bench(BenchConfig.quick() if args.quick else BenchConfig(), quick=args.quick)
    return to_json(bench_json(report)) if args.json else bench_text(report)


def add_command(commands) -> None:
    bench = add_parser(
        commands, "bench", "time every solver against its accuracy, on every coupling and mode",
        "IPOPT at several tolerances, the closed forms, cvxpy's geometric programme and SciPy's SLSQP against\n"
        "IPOPT at 1e-10; the time to build and re-solve a problem; sweep throughput batched, point by point, cold\n"
        "and in parallel; warm re-solves by SQP against warm IPOPT; command start-up against the bare imports; the\n"
        "simulator on a stiff scene; a sweep on a local Dask cluster (not with --quick).",
        ("clutchopt bench --quick", "clutchopt bench --json > bench.json"))
    bench.add_argument("--quick", action="store_true",
                       help="fewer repeats, 50-point sweeps, no Dask clusters: about half a minute")
    add_json_option(bench, "one JSON object, times in seconds")
    bench.set_defaults(run=run)
