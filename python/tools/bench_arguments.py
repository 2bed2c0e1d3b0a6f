"""Time what the argument check of the Python API (covmap/_arguments.py)
costs a call that succeeds: each native method below called through its
wrapper and directly (the wrapper's ``__wrapped__``), alternately, the best
of many rounds of each. Prints Markdown rows for BENCHMARKS.md; asserts
nothing.

    python python/tools/bench_arguments.py [--rounds 200] [--calls 5000]
"""

from __future__ import annotations

import argparse
import timeit
from typing import Any, Callable

import numpy as np

import covmap


def pairs() -> dict[str, tuple[Callable[[], Any], Callable[[], Any]]]:
    """Each call, directly and through the wrapper, on a map of 4 x 4 cells."""
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(4, 4))
    cmap = covmap.CoverageMap(grid)
    pose, ranges, bearings, model = (0.2, 0.2, 0.0), np.array([0.1]), np.array([0.0]), covmap.LaserModel()
    ml = covmap.CoverageMap.ml.__wrapped__  # type: ignore[attr-defined]
    to_cell = covmap.Grid.world_to_cell.__wrapped__  # type: ignore[attr-defined]
    integrate = covmap.CoverageMap.integrate.__wrapped__  # type: ignore[attr-defined]
    names = covmap.World.builtin_names.__wrapped__  # type: ignore[attr-defined]
    return {
        "`cmap.ml()` (4 x 4 cells)": (lambda: ml(cmap), lambda: cmap.ml()),
        "`grid.world_to_cell(x, y)`": (lambda: to_cell(grid, 0.1, 0.1), lambda: grid.world_to_cell(0.1, 0.1)),
        "`cmap.integrate(...)` (one beam)": (
            lambda: integrate(cmap, pose, ranges, bearings, model),
            lambda: cmap.integrate(pose, ranges, bearings, model),
        ),
        "`World.builtin_names()`": (lambda: names(), lambda: covmap.World.builtin_names()),
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=200)
    parser.add_argument("--calls", type=int, default=5000)
    args = parser.parse_args()
    print("| call | direct | wrapped | added | ratio |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for name, (direct, wrapped) in pairs().items():
        best_direct = best_wrapped = float("inf")
        for _ in range(args.rounds):
            best_direct = min(best_direct, timeit.timeit(direct, number=args.calls) / args.calls)
            best_wrapped = min(best_wrapped, timeit.timeit(wrapped, number=args.calls) / args.calls)
        added = best_wrapped - best_direct
        print(
            f"| {name} | {best_direct * 1e9:.0f} ns | {best_wrapped * 1e9:.0f} ns "
            f"| {added * 1e9:.0f} ns | {best_wrapped / best_direct:.2f} |"
        )


if __name__ == "__main__":
    main()
