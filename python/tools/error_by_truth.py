"""Where a coverage run's map is wrong, by what the truth holds there: the
evaluation cells split into free cells, cells partly covered (wall faces,
corners) and cells fully covered (inside walls and furniture), each with
its mean absolute error, the cells held certain (entropy at most epsilon)
of a coverage more than one half off, and the cells left uncertain. Free
cells held certain and covered are counted by their distance from the
nearest obstacle as well (arcs across openings lie far from one, a wall
thickened by a cell at one cell). With the run's contacts (where the map
let the robot drive into an obstacle).

One run of the coverage strategy with the 24-sonar ring, as the
benchmark runs it; ``--clear-no-echo`` lets every no-echo reading clear its
whole footprint (the paper's reading) instead of only what its line of
sight reaches past the cells the map is certain are covered::

    python python/tools/error_by_truth.py generated:6:120
    python python/tools/error_by_truth.py generated:6:120 --clear-no-echo

docs/experiments.md, "The paper's no-echo reading in the loop", has what
it showed.
"""

from __future__ import annotations

import argparse

import numpy as np

import covmap
from covmap.buildings import building


def distance_from(mask: np.ndarray, most: int) -> np.ndarray:
    """Each cell's 4-connected distance, in cells, from the nearest cell of
    ``mask``; ``most`` for cells at that distance or farther."""
    distance = np.full(mask.shape, most, dtype=np.int64)
    reached = mask.copy()
    distance[reached] = 0
    for step in range(1, most):
        grown = reached.copy()
        grown[1:] |= reached[:-1]
        grown[:-1] |= reached[1:]
        grown[:, 1:] |= reached[:, :-1]
        grown[:, :-1] |= reached[:, 1:]
        distance[grown & ~reached] = step
        reached = grown
    return distance


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("building", help="a building's name (covmap.buildings.building): corridor, generated:S:A, a plan")
    parser.add_argument("--clear-no-echo", action="store_true", help="the paper's no-echo reading")
    parser.add_argument("--max-path-m", type=float, default=3000.0, help="the run's limit (default 3000, the benchmark's)")
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()

    b = building(args.building)
    r = covmap.explore(
        b.world,
        covmap.Strategy.coverage(0.5),
        seed=args.seed,
        max_path_m=args.max_path_m,
        occlude_no_echo=not args.clear_no_echo,
    )
    truth, cells = r.truth, r.evaluation_cells
    mean = r.map.mean().astype(np.float64)
    entropy = r.map.entropy().astype(np.float64)
    error = np.abs(mean - truth)
    certain = entropy <= r.epsilon
    print(
        f"{args.building}: {r.termination} after {r.path_length_m:.0f} m, "
        f"{100.0 * r.high_entropy_fraction:.2f} % uncertain, map error {r.coverage_error.coverage_map:.4f}, "
        f"{r.contacts} contacts"
    )
    print(f"{'truth':8s} {'cells':>7s} {'mean error':>10s} {'certain, > 0.5 off':>19s} {'uncertain':>9s}")
    for label, part in (
        ("free", cells & (truth == 0.0)),
        ("partly", cells & (truth > 0.0) & (truth < 1.0)),
        ("fully", cells & (truth >= 1.0)),
    ):
        print(
            f"{label:8s} {np.count_nonzero(part):7d} {error[part].mean():10.4f} "
            f"{np.count_nonzero(part & certain & (error > 0.5)):19d} {np.count_nonzero(part & ~certain):9d}"
        )
    most = 12
    distance = distance_from(truth > 0.0, most)
    held = cells & (truth == 0.0) & certain & (r.map.ml() > 0.5)
    counts = np.bincount(distance[held], minlength=most + 1)[1 : most + 1]
    shown = ", ".join(f"{d}: {n}" for d, n in enumerate(counts, start=1) if n)
    print(f"free cells held covered and certain, by cells from the nearest obstacle: {shown or 'none'}")


if __name__ == "__main__":
    main()
