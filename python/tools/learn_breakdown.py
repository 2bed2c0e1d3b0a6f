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
Also printed: the mean map's coverage over the faced walls, its mean
absolute error over the judged cells, and how many judged free cells no
reading updated (still exactly at the prior's mean 1/2).

The maps are built as the fit built them: no-echo readings occluded by the
map (``covmap learn``'s default) or, with ``--clear-no-echo``, clearing
their whole footprint. The starting and the learned model are also scored
in the other kind of map. Prints Markdown tables; asserts nothing.

    python python/tools/learn_breakdown.py [--evaluations 300] [--parameters a,b,...]
        [--test-seed 1] [--clear-no-echo]
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


def score(drive: dict[str, Any], model: Any, cells: dict[str, np.ndarray], occlude: bool) -> dict[str, float]:
    """Log-likelihood of the truth by class, faced walls' mean, judged
    error and judged free cells at the prior, in the map ``model`` builds
    (no-echo readings occluded by it if ``occlude``)."""
    cmap = covmap.CoverageMap(drive["grid"])
    cmap.integrate_log(drive["log"], model, occlude_no_echo=occlude)
    mean, truth = cmap.mean(), drive["truth"]
    row = {name: covmap.log_likelihood(cmap, truth, cells=mask) for name, mask in cells.items()}
    row["total"] = sum(row.values())
    row["walls' mean"] = float(mean[drive["faced_walls"]].mean())
    row["error"] = float(np.abs(mean - truth)[drive["judged"]].mean())
    row["free at prior"] = float((cells["free, reached"] & (np.abs(mean - 0.5) < 1e-6)).sum())
    return row


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--evaluations", type=int, default=300, help="the fit's evaluations (default 300)")
    parser.add_argument("--parameters", default=None, help="comma-separated parameters to fit (default: all)")
    parser.add_argument("--test-seed", type=int, default=1, help="seed of the test drive (default 1)")
    parser.add_argument(
        "--clear-no-echo", action="store_true", help="fit to maps whose no-echo readings clear their whole footprint"
    )
    args = parser.parse_args()
    start = covmap.SonarModel()
    parameters = args.parameters.split(",") if args.parameters else None
    occlude = not args.clear_no_echo
    report = covmap.run_learn(
        start,
        max_evaluations=args.evaluations,
        parameters=parameters,
        test_seed=args.test_seed,
        occlude_no_echo=occlude,
    )
    learned = report["fit"].model.to_dict()
    initial = start.to_dict()
    fitted = [name for name in learned if learned[name] != initial[name]]
    models = [("starting model", start, occlude), ("learned model", report["fit"].model, occlude)]
    other = "clearing" if occlude else "occluded"
    models += [(f"{name}, {other} maps", model, not occlude) for name, model, _ in models]
    for name in fitted:
        reset = dict(learned)
        reset[name] = initial[name]
        models.append((f"learned, `{name}` back to {initial[name]:.3g}", covmap.SonarModel.from_dict(reset), occlude))
    print("learned: " + ", ".join(f"`{n}` {initial[n]:.3g} -> {learned[n]:.3g}" for n in fitted))
    for drive, label in zip(report["drives"], ["training", "test"]):
        cells = classes(drive)
        print(f"\n{label} drive ({drive['world']}): cells " + ", ".join(f"{n} {int(m.sum())}" for n, m in cells.items()))
        columns = [*cells, "total", "walls' mean", "error", "free at prior"]
        print("| model | " + " | ".join(columns) + " |")
        print("| --- " * (len(columns) + 1) + "|")
        for name, model, occluded in models:
            row = score(drive, model, cells, occluded)
            values = [f"{row[c]:.0f}" for c in [*cells, "total"]] + [f"{row[c]:.3f}" for c in ["walls' mean"]]
            values += [f"{row['error']:.4f}", f"{row['free at prior']:.0f}"]
            print(f"| {name} | " + " | ".join(values) + " |")


if __name__ == "__main__":
    main()
