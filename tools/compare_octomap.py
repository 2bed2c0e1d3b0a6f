"""covmap against OctoMap (pyoctomap) on the same beams of a real log.

Maps a CARMEN log (by default the Intel Research Lab's, 910 scans of 180
beams) at 5 cm twice, side by side: covmap's CoverageMap.integrate_log with
the default laser model, and an OctoMap OcTree inserting each scan's end
points as a point cloud from the scan's sensor position (all in the plane
z = resolution / 2; beams without echo, and echoes beyond the model's
maximum range, are cut at that range and clear only, as covmap does). It
prints both times, their ratio, and the share of the cells both maps know
on which they agree (occupied or not: covmap's ML coverage at least 0.5
against OctoMap's isNodeOccupied).

    pip install pyoctomap
    python tools/compare_octomap.py [LOG] [--resolution 0.05] [--repeat 3]

Run it from the repository (the log defaults to ../shared/data/carmen/).
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

import numpy as np

import covmap

DEFAULT_LOG = Path(__file__).resolve().parents[2] / "shared" / "data" / "carmen" / "intel-corrected.log.gz"


def aligned_grid(log: covmap.Log, resolution: float, reach: float) -> covmap.Grid:
    """A grid over the log whose cell edges fall on OctoMap's voxel edges
    (multiples of the resolution from 0)."""
    bounds = log.extent(reach)
    assert bounds is not None
    x0, y0, x1, y1 = bounds
    ox, oy = math.floor(x0 / resolution - 1) * resolution, math.floor(y0 / resolution - 1) * resolution
    cols = math.ceil((x1 - ox) / resolution) + 1
    rows = math.ceil((y1 - oy) / resolution) + 1
    return covmap.Grid(origin=(ox, oy), resolution=resolution, shape=(rows, cols))


def octomap_of(log: covmap.Log, resolution: float, max_range: float):  # type: ignore[no-untyped-def]
    """The OcTree of the log's beams, and the seconds inserting them took."""
    import pyoctomap

    tree = pyoctomap.OcTree(resolution)
    z = resolution / 2
    ox, oy, otheta = log.sensor_offset
    clouds = []
    for pose, ranges in zip(log.poses, log.ranges):
        x, y, theta = pose
        sx = x + math.cos(theta) * ox - math.sin(theta) * oy
        sy = y + math.sin(theta) * ox + math.cos(theta) * oy
        keep = ~np.isnan(ranges)
        r = np.minimum(ranges[keep], log.max_range_m)
        a = theta + otheta + log.bearings[keep]
        points = np.column_stack([sx + r * np.cos(a), sy + r * np.sin(a), np.full(r.size, z)])
        clouds.append((points, np.array([sx, sy, z])))
    start = time.perf_counter()
    for points, origin in clouds:
        tree.insertPointCloud(points, origin, max_range=max_range)
    return tree, time.perf_counter() - start


def agreement(cmap: covmap.CoverageMap, tree, resolution: float) -> tuple[float, int]:  # type: ignore[no-untyped-def]
    """The share of cells both maps know on which they agree, and how many
    cells that is."""
    grid = cmap.grid
    known = cmap.ros_occupancy(unknown_within_nats=0.0) >= 0
    occupied = cmap.ml() >= 0.5
    x0, y0, _, _ = grid.bounds
    agree = both = 0
    for row, col in zip(*np.nonzero(known)):
        node = tree.search([x0 + (col + 0.5) * resolution, y0 + (row + 0.5) * resolution, resolution / 2])
        if node is None:
            continue
        both += 1
        agree += int(tree.isNodeOccupied(node) == occupied[row, col])
    return agree / max(both, 1), both


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("log", nargs="?", type=Path, default=DEFAULT_LOG)
    p.add_argument("--resolution", type=float, default=0.05)
    p.add_argument("--reach", type=float, default=10.0, help="the grid holds every beam this far (m)")
    p.add_argument("--repeat", type=int, default=3, help="timed runs of each, the fastest counts")
    args = p.parse_args()
    log = covmap.Log.from_carmen(args.log)
    model = covmap.LaserModel()
    grid = aligned_grid(log, args.resolution, args.reach)
    covmap_s, octomap_s = math.inf, math.inf
    for _ in range(args.repeat):
        cmap = covmap.CoverageMap(grid)
        start = time.perf_counter()
        cmap.integrate_log(log, model)
        covmap_s = min(covmap_s, time.perf_counter() - start)
        tree, seconds = octomap_of(log, args.resolution, model.max_range_m)
        octomap_s = min(octomap_s, seconds)
    share, both = agreement(cmap, tree, args.resolution)
    rows, cols = grid.shape
    print(f"log            {args.log.name}: {len(log)} scans of {log.beams} beams")
    print(f"grid           {rows} x {cols} cells (rows x columns) of {args.resolution:g} m")
    print(f"covmap         {covmap_s:.3f} s (CoverageMap.integrate_log, fastest of {args.repeat})")
    print(f"octomap        {octomap_s:.3f} s (OcTree.insertPointCloud per scan, fastest of {args.repeat})")
    print(f"ratio          {octomap_s / covmap_s:.1f}x")
    print(f"agreement      {share:.4f} of the {both} cells both maps know")


if __name__ == "__main__":
    main()
