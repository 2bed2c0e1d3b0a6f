"""Where a coverage run's uncertain cells are: in rooms the robot never
entered, or in the rooms it did (cells it could not settle), and of those,
how many are split between two neighbouring bins or hold evidence in
conflict.

Runs the coverage strategy with the 24-sonar ring and defaults on buildings
(default: the first six development buildings, seed 0, at most 3000 m) and
prints, per run, the evaluation cells left uncertain (entropy above epsilon)
as percentages of the evaluation cells:

- in rooms never entered: inside a room or hall the trajectory never entered
  (doors closed on the map, the issue's first cause);
- elsewhere, and of those (the second cause, cells that do not settle):
  - split: 90 % or more of the histogram on two neighbouring bins (a coverage
    known to a bin's width, its entropy near ln 2);
  - conflict: 10 % or more on each of the lowest and the highest quarter of
    the bins, and less on the middle half than on either (two modes, free
    and covered evidence against each other; a broad histogram is neither).

The 90 % and 10 % are this script's definitions of the two kinds, for
counting; nothing in covmap uses them.

    python tools/uncertain_by_cause.py [--buildings NAME,...] [--max-path-m M]
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

import covmap
from covmap import buildings as B


@dataclass(frozen=True)
class Split:
    """One run's uncertain cells by where they are, in percent of its
    evaluation cells (``elsewhere`` includes ``split`` and ``conflict``)."""

    building: str
    never_entered: float
    elsewhere: float
    split: float
    conflict: float
    rooms_never_entered: int
    run: str
    uncertain: float


def inside(points: npt.NDArray[np.float64], floor: npt.NDArray[np.float64]) -> npt.NDArray[np.bool_]:
    """Whether each of ``points`` (n x 2) lies on a room's ``floor``: its
    axis-aligned rectangles, one ``[x_min, y_min, x_max, y_max]`` a row."""
    x, y = points[:, 0], points[:, 1]
    result = np.zeros(len(points), dtype=bool)
    for x0, y0, x1, y1 in np.asarray(floor, dtype=float).reshape(-1, 4):
        result |= (x >= x0) & (x <= x1) & (y >= y0) & (y <= y1)
    return result


def kinds(histograms: npt.NDArray[np.float32]) -> tuple[npt.NDArray[np.bool_], npt.NDArray[np.bool_]]:
    """Which of ``histograms`` (n x bins) are split between two neighbouring
    bins, and which hold evidence in conflict (see the module documentation)."""
    h = np.asarray(histograms, dtype=np.float64)
    pairs = (h[:, :-1] + h[:, 1:]).max(axis=1)
    quarter = max(1, h.shape[1] // 4)
    low, high = h[:, :quarter].sum(axis=1), h[:, -quarter:].sum(axis=1)
    middle = 1.0 - low - high
    conflict = (low >= 0.1) & (high >= 0.1) & (middle < np.minimum(low, high))
    return pairs >= 0.9, conflict & ~(pairs >= 0.9)


def split(building: covmap.Building, max_path_m: float) -> Split:
    """Explore ``building`` with the coverage strategy (at most
    ``max_path_m``) and split its uncertain cells."""
    result = covmap.explore(building.world, covmap.Strategy.coverage(), max_path_m=max_path_m)
    grid = result.grid
    uncertain = result.uncertain_cells.reshape(grid.shape)
    ys, xs = np.nonzero(uncertain)
    centres = np.column_stack(
        [grid.origin[0] + (xs + 0.5) * grid.resolution, grid.origin[1] + (ys + 0.5) * grid.resolution]
    )
    missed = set(building.rooms_never_entered(result.trajectory))
    in_missed = np.zeros(len(centres), dtype=bool)
    for room in building.rooms:
        if room.name in missed:
            in_missed |= inside(centres, room.floor)
    histograms = np.asarray(result.map.histograms).reshape(grid.shape[0], grid.shape[1], -1)[ys, xs]
    is_split, is_conflict = kinds(histograms)
    percent = 100.0 / int(result.evaluation_cells.sum())
    return Split(
        building=building.name,
        never_entered=percent * int(in_missed.sum()),
        elsewhere=percent * int((~in_missed).sum()),
        split=percent * int((~in_missed & is_split).sum()),
        conflict=percent * int((~in_missed & is_conflict).sum()),
        rooms_never_entered=len(missed),
        run=f"{result.path_length_m:.0f} m, {result.termination}",
        uncertain=100.0 * result.high_entropy_fraction,
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument(
        "--buildings", default=None, help="buildings by name, comma-separated (default: 6 development buildings)"
    )
    parser.add_argument("--max-path-m", type=float, default=3000.0)
    args = parser.parse_args()
    if args.buildings:
        found = B.buildings(args.buildings.split(","))
    else:
        found = B.building_set("development", count=6, plans=False)
    print(
        "building | uncertain [%] | in rooms never entered | elsewhere | of those, split | in conflict"
        " | rooms never entered | run"
    )
    print("--- | --- | --- | --- | --- | --- | --- | ---")
    for building in found:
        s = split(building, args.max_path_m)
        print(
            f"{s.building} | {s.uncertain:.2f} | {s.never_entered:.2f} | {s.elsewhere:.2f} | {s.split:.2f}"
            f" | {s.conflict:.2f} | {s.rooms_never_entered} | {s.run}"
        )


if __name__ == "__main__":
    main()
