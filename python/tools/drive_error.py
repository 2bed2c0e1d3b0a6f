"""Where the mean-map error of a recorded sonar drive comes from: the
drives of ``covmap learn`` (the corridor with thick walls and pillars, and
the office), mapped with the default sonar model by the coverage map (its
no-echo readings occluded by the map, and clearing their whole footprint)
and by the occupancy grid baseline (clearing, as ``OccupancyGrid.integrate_log``
has it).

The judged cells (those the drive's sound reached, as the drive's figure
is judged) are split into classes, each with its cells and its share of
the mean error (the shares add up to the mean error):

- ``free, held covered``: free cells the map gives a coverage above one
  half (echo arcs marked where nothing returned them, walls drawn thick),
  also counted by their distance, in cells, from the nearest obstacle;
- ``free, at the prior``: free cells no reading changed;
- ``free, partly cleared``: the other free cells, with the median number of
  scans that reached them;
- ``surface``: judged cells that hold some obstacle (wall faces).

::

    python python/tools/drive_error.py [--scans 300]

docs/experiments.md, "Where the drive's error comes from", has what it
showed. Prints Markdown; asserts nothing.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

import numpy as np

import covmap

sys.path.insert(0, str(Path(__file__).resolve().parent))
from error_by_truth import distance_from  # noqa: E402

CLASSES = ("free, held covered", "free, at the prior", "free, partly cleared", "surface")


def classes(values: np.ndarray, truth: np.ndarray, judged: np.ndarray) -> dict[str, np.ndarray]:
    """The judged cells by class (module docstring): a partition of them."""
    free = judged & (truth == 0.0)
    held = free & (values > 0.5)
    prior = free & (np.abs(values - 0.5) < 1e-6)
    return {
        CLASSES[0]: held,
        CLASSES[1]: prior,
        CLASSES[2]: free & ~held & ~prior,
        CLASSES[3]: judged & (truth > 0.0),
    }


def shares(values: np.ndarray, truth: np.ndarray, judged: np.ndarray) -> dict[str, tuple[int, float]]:
    """Each class's cells and share of the mean error over the judged cells."""
    error = np.abs(values - truth)
    total = max(int(np.count_nonzero(judged)), 1)
    return {
        name: (int(np.count_nonzero(mask)), float(error[mask].sum()) / total)
        for name, mask in classes(values, truth, judged).items()
    }


def maps(drive: dict[str, Any]) -> dict[str, np.ndarray]:
    """The drive's maps: the coverage map's mean, occluded and clearing,
    and the occupancy grid's probabilities."""
    model = covmap.SonarModel()
    out = {}
    for label, occlude in (("coverage map, occluded", True), ("coverage map, clearing", False)):
        cmap = covmap.CoverageMap(drive["grid"])
        cmap.integrate_log(drive["log"], model, occlude_no_echo=occlude)
        out[label] = np.asarray(cmap.mean(), dtype=np.float64)
    grid = covmap.OccupancyGrid(drive["grid"])
    grid.integrate_log(drive["log"], model)
    out["occupancy grid, clearing"] = np.asarray(grid.probabilities(), dtype=np.float64)
    return out


def report(drive: dict[str, Any]) -> str:
    """The drive's Markdown tables."""
    truth = np.asarray(drive["truth"], dtype=np.float64)
    judged = np.asarray(drive["judged"], dtype=bool)
    reached = np.asarray(drive["reached"])
    most = 5
    distance = distance_from(truth > 0.0, most)
    lines = [
        f"{drive['world']} drive, {int(np.count_nonzero(judged))} judged cells",
        "",
        "| map | mean error | " + " | ".join(CLASSES) + " | held covered at 1 / 2-4 / 5+ cells | partly cleared: median scans |",
        "| --- " * (len(CLASSES) + 4) + "|",
    ]
    for label, values in maps(drive).items():
        row = shares(values, truth, judged)
        mask = classes(values, truth, judged)
        held = distance[mask[CLASSES[0]]]
        near = [np.count_nonzero(held == 1), np.count_nonzero((held >= 2) & (held <= 4)), np.count_nonzero(held >= most)]
        partly = reached[mask[CLASSES[2]]]
        median = float(np.median(partly)) if partly.size else 0.0
        cells = " | ".join(f"{n} cells, {share:.4f}" for n, share in row.values())
        error = sum(share for _, share in row.values())
        lines.append(f"| {label} | {error:.4f} | {cells} | {' / '.join(map(str, near))} | {median:.0f} |")
    return "\n".join(lines)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scans", type=int, default=300, help="scans a drive (default 300, covmap learn's)")
    args = parser.parse_args()
    # The drives only: one evaluation of the fit, whose result is not used.
    learned = covmap.run_learn(covmap.SonarModel(), scans=args.scans, max_evaluations=1, restarts=1)
    for drive in learned["drives"]:
        print(report(drive) + "\n")


if __name__ == "__main__":
    main()
