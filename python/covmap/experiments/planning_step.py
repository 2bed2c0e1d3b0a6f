"""One step of exploration in a simulated world: where to look next.

A sonar ring scans the world a few times from a start pose near one end of
its longest free passage; the scans are integrated into a coverage map, and
the :class:`covmap.Planner` weighs the expected information gain of every
reachable candidate viewpoint against the path to it (paper eq. 14).
:func:`covmap.plot.plot_planning_step` draws the step.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from covmap._native import CoverageMap, Grid, Plan, Planner, Robot, SonarModel, SonarRing, World

if TYPE_CHECKING:
    import numpy.typing as npt

SEARCH_RESOLUTION_M = 0.1
"""Cell size of the search for a start pose, metres."""
SEARCH_MARGIN_M = 2.0
"""Free margin around the world in that search, metres: passages that reach it
are open to the outside."""


def _runs(free: npt.NDArray[np.bool_]) -> list[tuple[int, int]]:
    """The ``[start, stop)`` column ranges of the runs of ``True`` in a row."""
    padded = np.concatenate(([False], free, [False])).astype(np.int8)
    edges = np.flatnonzero(np.diff(padded))
    return [(int(a), int(b)) for a, b in zip(edges[::2], edges[1::2])]


def start_pose(world: World, *, robot_radius_m: float = 0.25) -> tuple[float, float, float]:
    """A free pose near the west end of the world's main passage, heading east.

    Cells of 10 cm over the world's bounds (plus a 2 m margin) are free where
    a disc of ``robot_radius_m`` fits. Along each row, a run of free cells
    that touches neither side of the margin lies between obstacles. The
    longest such run marks the passage; of the band of rows around it whose
    runs are almost as long (90 %), the middle row is the passage's centre
    line, and the pose is its first free cell. A world with no enclosed run
    (a lone obstacle) gets the free cell nearest the middle of its bounds.
    """
    x0, y0, x1, y1 = world.bounds
    m = SEARCH_MARGIN_M
    grid = Grid.covering((x0 - m, y0 - m, x1 + m, y1 + m), resolution=SEARCH_RESOLUTION_M)
    rows, cols = grid.shape
    gx0, gy0 = grid.origin
    r = grid.resolution
    xs = gx0 + (np.arange(cols) + 0.5) * r
    ys = gy0 + (np.arange(rows) + 0.5) * r
    points = np.stack(np.meshgrid(xs, ys), axis=-1).reshape(-1, 2)
    free = (Robot(radius_m=robot_radius_m).clearance(world, points) > 0.0).reshape(rows, cols)
    # The longest enclosed run of each row: (length, first column).
    best = [max(((b - a, a) for a, b in _runs(free[i]) if a > 0 and b < cols), default=(0, 0)) for i in range(rows)]
    longest = max(length for length, _ in best)
    if longest == 0:
        cx, cy = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
        d2 = np.where(free.ravel(), (points[:, 0] - cx) ** 2 + (points[:, 1] - cy) ** 2, np.inf)
        k = int(np.argmin(d2))
        return float(points[k, 0]), float(points[k, 1]), 0.0
    top = max(range(rows), key=lambda i: (best[i][0], -abs(ys[i] - 0.5 * (y0 + y1))))
    lo = hi = top
    while lo > 0 and best[lo - 1][0] >= 0.9 * longest:
        lo -= 1
    while hi < rows - 1 and best[hi + 1][0] >= 0.9 * longest:
        hi += 1
    row = (lo + hi) // 2
    if best[row][0] == 0:  # defensive: the band is contiguous, its middle has a run
        row = top
    return float(xs[best[row][1]]), float(ys[row]), 0.0


@dataclass(frozen=True)
class Step:
    """What one planning step saw and chose."""

    world: World
    grid: Grid
    start: tuple[float, float, float]
    scans: int
    seed: int
    coverage_map: CoverageMap
    plan: Plan
    planner: Planner


def run(world: World, *, scans: int = 3, seed: int = 0, alpha: float = 0.5, resolution_m: float = 0.05) -> Step:
    """Scan ``world`` ``scans`` times from :func:`start_pose` with the default
    24-sonar ring (scan ``i`` from stream ``i`` of ``seed``), integrate the
    scans into a coverage map over the world's bounds plus 0.5 m, and plan
    the next viewpoint with ``alpha``."""
    x0, y0, x1, y1 = world.bounds
    grid = Grid.covering((x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5), resolution=resolution_m)
    planner = Planner(alpha=alpha)
    start = start_pose(world, robot_radius_m=planner.robot_radius_m)
    model = SonarModel()
    ring = SonarRing().with_model(model)
    cmap = CoverageMap(grid)
    ranges = ring.simulate_path(world, np.tile(np.array(start), (scans, 1)), seed=seed)
    for scan in ranges:
        cmap.integrate(start, scan, ring.bearings, model)
    plan = planner.next_viewpoint(cmap, start, ring.bearings, model)
    return Step(world=world, grid=grid, start=start, scans=scans, seed=seed, coverage_map=cmap, plan=plan, planner=planner)


def report(step: Step) -> str:
    """The chosen viewpoint and the candidates, as text."""
    plan = step.plan
    gains = plan.candidates.gains
    least = step.planner.least_gain_nats(step.coverage_map.bins)
    worth = int(np.count_nonzero(gains > least))
    x, y, theta = step.start
    lines = [
        f"start pose: ({x:.3f}, {y:.3f}, {theta:.3f}); {step.scans} sonar scans, seed {step.seed}",
        f"candidates: {len(gains)} ({worth} worth visiting, gain > {least:g} nats); "
        f"alpha {step.planner.alpha:g}",
    ]
    if plan.pose is None or plan.gain is None or plan.cost is None:
        lines.append("chosen viewpoint: none (no candidate is worth visiting)")
    else:
        gx, gy, gtheta = (float(v) for v in plan.pose)
        lines.append(
            f"chosen viewpoint: ({gx:.3f}, {gy:.3f}, {gtheta:.3f}), gain {plan.gain:.3f} nats, "
            f"cost {plan.cost:.3f} m, path of {len(plan.path)} cells"
        )
    return "\n".join(lines)
