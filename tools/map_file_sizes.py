"""A saved posterior stored and deflated, side by side: the file sizes and
the times to save and to load each (best of three), in one run.

Run: ``python tools/map_file_sizes.py MAP.npz`` (a map ``covmap map`` or
``CoverageMap.save`` wrote, e.g. ``covmap map
../shared/data/carmen/intel-corrected.log.gz --out DIR`` then
``DIR/coverage.npz``). Writes only into a temporary directory it makes.
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import covmap


def best_of(n: int, work) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(n):
        started = time.perf_counter()
        work()
        times.append(time.perf_counter() - started)
    return min(times)


def main() -> None:
    cmap = covmap.CoverageMap.load(sys.argv[1])
    rows, cols = cmap.grid.shape
    print(f"{sys.argv[1]}: {rows} x {cols} cells (rows x columns), {cmap.bins} bins")
    with tempfile.TemporaryDirectory() as folder:
        for name, compress in (("stored", False), ("deflated", True)):
            path = Path(folder) / f"{name}.npz"
            save = best_of(3, lambda: cmap.save(path, compress=compress))
            load = best_of(3, lambda: covmap.CoverageMap.load(path))
            assert (covmap.CoverageMap.load(path).histograms == cmap.histograms).all()
            print(f"{name:9s} {path.stat().st_size / 1e6:8.2f} MB   save {save:6.3f} s   load {load:6.3f} s")


if __name__ == "__main__":
    main()
