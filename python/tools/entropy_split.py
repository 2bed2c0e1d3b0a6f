"""Where a coverage run's steps take entropy from, quarter by quarter of its
path: the uncertain evaluation cells (what the run is judged on), the
uncertain cells outside them (within the region the stop rule judges, and
beyond it), and cells already certain (entropy below epsilon at the step's
start).

One run of the coverage strategy with the 24-sonar ring, stepped to its end;
after each step the map's entropy is compared with the step's start::

    python python/tools/entropy_split.py generated:13:250
    python python/tools/entropy_split.py corridor --max-path-m 2000

A run whose later quarters take most of their entropy from cells outside the
evaluation cells chases cells it is not asked to settle
(docs/experiments.md, "The line of sight landed").
"""

from __future__ import annotations

import argparse

import numpy as np

import covmap
from covmap.buildings import building


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("building", help="a building's name (covmap.buildings.building): corridor, generated:S:A, a plan")
    parser.add_argument("--seed", type=int, default=0, help="the run's seed (default 0)")
    parser.add_argument("--max-path-m", type=float, default=3000.0, help="the run's path limit (default 3000)")
    parser.add_argument("--epsilon", type=float, default=0.65, help="entropy below which a cell is certain")
    args = parser.parse_args()

    run = covmap.Exploration(
        building(args.building).world,
        covmap.Strategy.coverage(),
        seed=args.seed,
        max_path_m=args.max_path_m,
        epsilon=args.epsilon,
    )
    evaluation = run.evaluation_cells
    before = run.map.entropy().astype(np.float64)
    region = run.region()
    rows = []
    for _ in run:
        after = run.map.entropy().astype(np.float64)
        uncertain = before >= args.epsilon
        removed = before - after
        rows.append(
            (
                run.path_length_m,
                removed[uncertain & evaluation].sum(),
                removed[uncertain & ~evaluation & region].sum(),
                removed[uncertain & ~evaluation & ~region].sum(),
                removed[~uncertain].sum(),
                run.uncertain_fraction,
            )
        )
        before = after
        region = run.region()
    print(
        f"{args.building}, seed {args.seed}: ended {run.termination} at {run.path_length_m:.0f} m, "
        f"{100 * run.uncertain_fraction:.2f} % of the evaluation cells uncertain, {len(rows)} steps"
    )
    if not rows:
        return
    table = np.array(rows)
    length = table[-1, 0]
    for q in range(4):
        lo, hi = q * length / 4, (q + 1) * length / 4
        part = table[(table[:, 0] > lo) & (table[:, 0] <= hi)]
        if not len(part):
            continue
        taken = part[:, 1:5].sum(axis=0)
        total = taken.sum()
        shares = ", ".join(
            f"{name} {100 * x / total:5.1f} %"
            for name, x in zip(
                ("uncertain evaluation cells", "uncertain others in the stop region", "uncertain others beyond it", "certain"),
                taken,
            )
        )
        print(
            f"{lo:6.0f} to {hi:6.0f} m: {total:9.0f} nats removed: {shares}; "
            f"{100 * part[-1, 5]:.2f} % uncertain after"
        )


if __name__ == "__main__":
    main()
