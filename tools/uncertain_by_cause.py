"""Where a coverage run's uncertain cells are: in rooms the robot never
entered, or in the rooms it did (surfaces it could not settle).

Runs the coverage strategy with the 24-sonar ring and defaults on buildings
(default: the first six development buildings, seed 0, at most 3000 m) and
prints, per run, the evaluation cells left uncertain (entropy above epsilon)
split by where they lie: inside a room or hall never entered, or elsewhere.
Issue 38 names two causes of unfinished runs, doors closed on the maps
(rooms never entered) and cells that cannot be settled; this measures how
much of each run's uncertain share each accounts for.

    python tools/uncertain_by_cause.py [--buildings NAME,...] [--max-path-m M]
"""

from __future__ import annotations

import argparse

import numpy as np

import covmap
from covmap import buildings as B


def inside(points: np.ndarray, floor: np.ndarray) -> np.ndarray:
    """Whether each of ``points`` (n x 2) lies on a room's ``floor``: its
    axis-aligned rectangles, one ``[x_min, y_min, x_max, y_max]`` a row."""
    x, y = points[:, 0], points[:, 1]
    result = np.zeros(len(points), dtype=bool)
    for x0, y0, x1, y1 in np.asarray(floor, dtype=float).reshape(-1, 4):
        result |= (x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)
    return result


def split(building: covmap.Building, max_path_m: float) -> tuple[str, float, float, int, str, float]:
    """Explore ``building`` with the coverage strategy (at most
    ``max_path_m``); its name, the percentages of the evaluation cells left
    uncertain inside rooms never entered and elsewhere, the count of those
    rooms, the run's length and end, and its whole uncertain percentage."""
    result = covmap.explore(building.world, covmap.Strategy.coverage(), max_path_m=max_path_m)
    uncertain = result.uncertain_cells.reshape(result.grid.shape)
    grid = result.grid
    rows, cols = uncertain.shape
    ys, xs = np.nonzero(uncertain)
    centres = np.column_stack(
        [grid.origin[0] + (xs + 0.5) * grid.resolution, grid.origin[1] + (ys + 0.5) * grid.resolution]
    )
    missed = set(building.rooms_never_entered(result.trajectory))
    in_missed = np.zeros(len(centres), dtype=bool)
    for room in building.rooms:
        if room.name in missed:
            in_missed |= inside(centres, room.floor)
    total = int(result.evaluation_cells.sum())
    return (
        building.name,
        100.0 * in_missed.sum() / total,
        100.0 * (~in_missed).sum() / total,
        len(missed),
        f"{result.path_length_m:.0f} m, {result.termination}",
        100.0 * result.high_entropy_fraction,
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--buildings", default=None, help="buildings by name, comma-separated (default: 6 development buildings)")
    parser.add_argument("--max-path-m", type=float, default=3000.0)
    args = parser.parse_args()
    if args.buildings:
        found = B.buildings(args.buildings.split(","))
    else:
        found = B.building_set("development", count=6, plans=False)
    print("building | uncertain in rooms never entered [%] | uncertain elsewhere [%] | rooms never entered | run")
    print("--- | --- | --- | --- | ---")
    for building in found:
        name, missed, rest, rooms, run, _ = split(building, args.max_path_m)
        print(f"{name} | {missed:.2f} | {rest:.2f} | {rooms} | {run}")


if __name__ == "__main__":
    main()
