"""Where the sensor-model fit of ``covmap learn`` gains its likelihood, and
what it gives up for it.

Runs ``covmap.run_learn`` (the training and the test drive of ``covmap
learn``, the fit), then scores maps of both drives' logs built with the
starting model, the learned model, and the learned model with each fitted
parameter put back to its starting value, one at a time. Each map's
log-likelihood of the truth is split over classes of cells defined from the
true world and the drive alone:

- ``free, reached``: free cells (true coverage 0) that the drive's sound
  reached and a robot could observe (the drive's judged cells);
- ``free, unreached``: free cells no reading's sound reached (behind walls,
  in rooms the drive never looked into), which only footprints wider or
  longer than the sound cross;
- ``surface, reached``: judged cells that hold some obstacle (wall faces);
- ``faced walls``: the wall cells behind a face that 20 or more scans
  reached (the measure of the issue's "walls survive" goal);
- ``other``: every other cell (wall insides no face leads to, and the rest).

The classes partition the grid, so each row's classes sum to its total.
Also printed: the mean map's coverage over the faced walls and its mean
absolute error over the judged cells. Prints Markdown tables; asserts
nothing.

    python python/tools/learn_breakdown.py [--evaluations 300] [--parameters a,b,...]
"""

from __future__ import annotations

import argparse
from typing import Any

import numpy as np

import covmap


def classes(drive: dict[str, Any]) -> dict[str, np.ndarray]:
    """The cell classes of one drive (module docstring), a partition."""
    truth, reached, judged, walls = drive["truth"], drive["reached"], drive["judged"], drive["faced_walls"]
    free_reached = judged & (truth == 0)
    free_unreached = (reached == 0) & (truth == 0)
    surface = judged & (truth > 0) & ~walls
    taken = free_reached | free_unreached | surface | walls
    return {
        "free, reached": free_reached,
        "free, unreached": free_unreached,
        "surface, reached": surface,
        "faced walls": walls,
        "other": ~taken,
    }


def score(drive: dict[str, Any], model: Any, cells: dict[str, np.ndarray]) -> dict[str, float]:
    """Log-likelihood of the truth by class, faced walls' mean, judged error."""
    cmap = covmap.CoverageMap(drive["grid"])
    cmap.integrate_log(drive["log"], model)
    mean, truth = cmap.mean(), drive["truth"]
    row = {name: covmap.log_likelihood(cmap, truth, cells=mask) for name, mask in cells.items()}
    row["total"] = sum(row.values())
    row["walls' mean"] = float(mean[drive["faced_walls"]].mean())
    row["error"] = float(np.abs(mean - truth)[drive["judged"]].mean())
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--evaluations", type=int, default=300, help="the fit's evaluations (default 300)")
    parser.add_argument("--parameters", default=None, help="comma-separated parameters to fit (default: all)")
    args = parser.parse_args()
    start = covmap.SonarModel()
    parameters = args.parameters.split(",") if args.parameters else None
    report = covmap.run_learn(start, max_evaluations=args.evaluations, parameters=parameters)
    learned = report["fit"].model.to_dict()
    initial = start.to_dict()
    fitted = [name for name in learned if learned[name] != initial[name]]
    models = [("starting model", start), ("learned model", report["fit"].model)]
    for name in fitted:
        reset = dict(learned)
        reset[name] = initial[name]
        models.append((f"learned, `{name}` back to {initial[name]:.3g}", covmap.SonarModel.from_dict(reset)))
    print("learned: " + ", ".join(f"`{n}` {initial[n]:.3g} -> {learned[n]:.3g}" for n in fitted))
    for drive, label in zip(report["drives"], ["training", "test"]):
        cells = classes(drive)
        print(f"\n{label} drive ({drive['world']}): cells " + ", ".join(f"{n} {int(m.sum())}" for n, m in cells.items()))
        columns = [*cells, "total", "walls' mean", "error"]
        print("| model | " + " | ".join(columns) + " |")
        print("| --- " * (len(columns) + 1) + "|")
        for name, model in models:
            row = score(drive, model, cells)
            values = [f"{row[c]:.0f}" for c in [*cells, "total"]] + [f"{row[c]:.3f}" for c in ["walls' mean"]]
            values.append(f"{row['error']:.4f}")
            print(f"| {name} | " + " | ".join(values) + " |")


if __name__ == "__main__":
    main()
