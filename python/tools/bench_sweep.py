"""Time covmap.sweep: one sweep on a local Dask cluster of 1 and of 2 worker
processes side by side (the clusters started before the clock starts), and
the default ``covmap fig7`` sweep on the local cores. Prints the figures as
Markdown rows for BENCHMARKS.md; asserts nothing.

    python python/tools/bench_sweep.py [--runs 8] [--rounds 2] [--no-fig7]
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import covmap
from covmap.cli.fig7 import DEFAULT_RESOLUTION_M, DEFAULT_SEEDS
from covmap.experiments import fig7


def dask_specs(runs: int) -> list[dict[str, Any]]:
    """``runs`` corridor runs of similar length: counting n = 10 and coverage
    maps alternating, seeds 0 upward, at the fig7 default's cells, each at
    most 60 steps."""
    strategies = [covmap.Strategy.counting(10, covmap.DEFAULT_DISCOUNT_BEYOND_M), covmap.Strategy.coverage(0.5)]
    return [
        {
            "world": "corridor",
            "strategy": strategies[i % 2],
            "seed": i // 2,
            "resolution": DEFAULT_RESOLUTION_M,
            "max_steps": 60,
        }
        for i in range(runs)
    ]


def _cpu_s() -> float:
    """CPU seconds this process has used (in a worker: the runs' work)."""
    import resource

    usage = resource.getrusage(resource.RUSAGE_SELF)
    return usage.ru_utime + usage.ru_stime


def time_on_dask(specs: list[dict[str, Any]], workers: int) -> tuple[float, float, list[covmap.RunSummary]]:
    """Wall time of the sweep on a fresh local cluster of ``workers``, the
    CPU seconds its workers spent meanwhile, and its summaries."""
    with covmap.dask_client(workers=workers) as client:
        client.wait_for_workers(workers)
        # Every worker imports covmap once before the clock starts.
        client.run(lambda: __import__("covmap") and None)
        before = sum(client.run(_cpu_s).values())
        t = time.perf_counter()
        summaries = covmap.sweep(specs, executor=client, progress=False)
        seconds = time.perf_counter() - t
        return seconds, sum(client.run(_cpu_s).values()) - before, summaries


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--runs", type=int, default=8, help="runs of the Dask sweep (default 8)")
    p.add_argument("--rounds", type=int, default=2, help="rounds of 1 then 2 workers (default 2)")
    p.add_argument("--no-fig7", action="store_true", help="skip the default fig7 sweep")
    args = p.parse_args()

    specs = dask_specs(args.runs)
    reference = None
    rows = []
    for round_ in range(args.rounds):
        times: dict[int, float] = {}
        runs_s: dict[int, float] = {}
        cpus_s: dict[int, float] = {}
        for workers in (1, 2):
            seconds, cpu_s, summaries = time_on_dask(specs, workers)
            if reference is None:
                reference = summaries
            same = summaries == reference
            times[workers] = seconds
            run_s = sum(s.seconds for s in summaries)
            runs_s[workers], cpus_s[workers] = run_s, cpu_s
            print(
                f"round {round_}, {workers} worker(s): {seconds:.1f} s ({run_s:.1f} s of runs, "
                f"{cpu_s:.1f} CPU s, {cpu_s / seconds:.2f} cores), same summaries: {same}",
                flush=True,
            )
        rows.append(
            f"| {round_} | {args.runs} | {times[1]:.1f} s ({runs_s[1]:.1f} s; {cpus_s[1] / times[1]:.2f}) "
            f"| {times[2]:.1f} s ({runs_s[2]:.1f} s; {cpus_s[2] / times[2]:.2f}) | {times[1] / times[2]:.2f}x |"
        )
    print(
        "| round | runs | 1 worker (runs' wall times summed; cores the workers got) | 2 workers (same) | speed-up |"
    )
    print("| --- | --- | --- | --- | --- |")
    print("\n".join(rows))
    if not args.no_fig7:
        seeds = list(range(DEFAULT_SEEDS))
        t = time.perf_counter()
        f = fig7.run(
            "corridor", seeds=seeds, progress=False, resolution=DEFAULT_RESOLUTION_M
        )
        seconds = time.perf_counter() - t
        runs = len(f.counting) + len(f.coverage)
        run_s = sum(r.seconds for r in [*f.counting, *f.coverage])
        print(
            f"default fig7 sweep: {runs} runs in {seconds:.1f} s on {covmap._executors.local_cores()} cores "
            f"({run_s:.1f} s of runs)"
        )
        print(fig7.report(f))


if __name__ == "__main__":
    main()
