"""Whether a map depends on the order of its scans, over a whole run.

Runs the coverage strategy with the 24-sonar ring and defaults on a
building (default: ``generated:4:250``, a development building, at most
3000 m), simulates a scan at each of the run's scan poses again (the scan
at pose ``i`` with seed ``i``), integrates those scans into fresh maps
with ``CoverageMap.integrate`` in three orders (forwards, backwards and
shuffled with seed 0) and prints, per order, the mean map's error against
the truth and the evaluation cells left uncertain, and, against the
forward map, the largest difference of the mean maps, the evaluation cells
whose mean moved by more than 0.1, and the cells whose ML blocks
(coverage above 0.5) in one map and not the other.

    python tools/scan_order.py [--building NAME] [--max-path-m M]
"""

from __future__ import annotations

import argparse
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

import covmap
from covmap import buildings as B


@dataclass(frozen=True)
class Order:
    """One order's map, and how far it is from the forward order's."""

    name: str
    error: float
    uncertain_percent: float
    largest_difference: float
    moved_percent: float
    blocked_differs: int


def maps_in_orders(building: covmap.Building, max_path_m: float) -> tuple[covmap.Exploration, dict[str, covmap.CoverageMap]]:
    """Explore ``building`` and integrate its scans anew in three orders."""
    exploration = covmap.Exploration(building.world, covmap.Strategy.coverage(), max_path_m=max_path_m)
    exploration.run()
    poses = np.asarray(exploration.result().scan_poses)
    ring = covmap.SonarRing()
    scans = [ring.simulate(building.world, tuple(p), seed=i) for i, p in enumerate(poses)]
    model = covmap.SonarModel()
    orders = {
        "forwards": np.arange(len(poses)),
        "backwards": np.arange(len(poses))[::-1],
        "shuffled": np.random.default_rng(0).permutation(len(poses)),
    }
    maps = {}
    for name, order in orders.items():
        map_ = covmap.CoverageMap(exploration.grid)
        for i in order:
            ranges, bearings = scans[i]
            map_.integrate(tuple(poses[i]), ranges, bearings, model)
        maps[name] = map_
    return exploration, maps


def compare(exploration: covmap.Exploration, maps: dict[str, covmap.CoverageMap], truth: npt.NDArray[np.float64]) -> list[Order]:
    """Each map's figures, against the first one's."""
    shape = exploration.grid.shape
    evaluation = np.asarray(exploration.evaluation_cells).reshape(shape)
    first = next(iter(maps.values()))
    mean0 = np.asarray(first.mean()).reshape(shape)
    blocked0 = np.asarray(first.ml()).reshape(shape) > 0.5
    result = []
    for name, map_ in maps.items():
        mean = np.asarray(map_.mean()).reshape(shape)
        entropy = np.asarray(map_.entropy()).reshape(shape)
        moved = np.abs(mean - mean0)
        result.append(
            Order(
                name=name,
                error=float(np.abs(mean - truth)[evaluation].mean()),
                uncertain_percent=100.0 * float((entropy[evaluation] > 0.65).mean()),
                largest_difference=float(moved.max()),
                moved_percent=100.0 * float((moved[evaluation] > 0.1).mean()),
                blocked_differs=int(((np.asarray(map_.ml()).reshape(shape) > 0.5) != blocked0).sum()),
            )
        )
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=(__doc__ or "").split("\n\n")[0])
    parser.add_argument("--building", default="generated:4:250")
    parser.add_argument("--max-path-m", type=float, default=3000.0)
    args = parser.parse_args()
    (building,) = B.buildings([args.building])
    exploration, maps = maps_in_orders(building, args.max_path_m)
    truth = building.world.coverage(exploration.grid)
    print(f"{building.name}: {exploration.scans} scans, {exploration.path_length_m:.0f} m")
    print("order | mean-map error | uncertain [%] | largest |mean difference| | cells moved > 0.1 [%] | cells blocked in one map only")
    print("--- | --- | --- | --- | --- | ---")
    for o in compare(exploration, maps, truth):
        print(
            f"{o.name} | {o.error:.4f} | {o.uncertain_percent:.2f} | {o.largest_difference:.2e}"
            f" | {o.moved_percent:.2f} | {o.blocked_differs}"
        )


if __name__ == "__main__":
    main()
