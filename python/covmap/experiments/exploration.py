"""One exploration run watched step by step, as ``covmap explore`` shows it:
the run, snapshots of its maps for an animation, and its summary table."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from covmap._errors import InvalidParameterError
from covmap._exploration import REAL_TIME_SPEED_M_S
from covmap._native import Exploration

if TYPE_CHECKING:
    from pathlib import Path

    import numpy.typing as npt

    from covmap._exploration import ExplorationResult, Step
    from covmap._native import Building, Strategy, World

MAX_FRAMES = 60
"""The most snapshots an animation of a run is drawn from (``covmap explore``
keeps its GIF small)."""

UNKNOWN_LEVEL = 255
"""The level of an unobserved cell in a :class:`Snapshot`'s ``ml``."""

LEVELS = 250
"""The level of an ML coverage of 1 in a :class:`Snapshot`'s ``ml`` (0 is 0)."""


@dataclass(frozen=True, eq=False)
class Snapshot:
    """The maps and the robot after one step of a run, small enough to keep
    a few dozen of: the ML map as ``uint8`` levels (``round(coverage *
    LEVELS)``, :data:`UNKNOWN_LEVEL` where no evidence reached the cell)."""

    step: int
    """Steps taken when the snapshot was taken (0: before the first)."""
    ml: npt.NDArray[np.uint8]
    """The ML map, ``(rows, cols)`` levels."""
    trajectory: npt.NDArray[np.float64]
    """The poses so far, ``(K, 3)``."""
    path_length_m: float
    """Distance driven so far, metres."""
    uncertain_fraction: float
    """Fraction of the evaluation cells still uncertain."""

    @property
    def ml_coverage(self) -> np.ma.MaskedArray[Any, np.dtype[np.float64]]:
        """The ML map as coverage in ``[0, 1]``, unobserved cells masked."""
        return np.ma.masked_array(self.ml / LEVELS, mask=self.ml == UNKNOWN_LEVEL)


@dataclass(frozen=True, eq=False)
class ExploreRun:
    """A run of ``covmap explore``: its world, its result, and at most
    :data:`MAX_FRAMES` snapshots spread over it, the last one at its end."""

    world_name: str
    """The world's name."""
    world: World
    """The world explored."""
    result: ExplorationResult
    """What the run reports."""
    frames: list[Snapshot]
    """Snapshots in order of their steps."""


def snapshot(run: Exploration) -> Snapshot:
    """The maps and robot of ``run`` now."""
    cmap = run.map
    levels = np.rint(cmap.ml() * LEVELS).astype(np.uint8)
    levels[~cmap.observed()] = UNKNOWN_LEVEL
    return Snapshot(
        step=run.steps,
        ml=levels,
        trajectory=run.trajectory,
        path_length_m=run.path_length_m,
        uncertain_fraction=run.uncertain_fraction,
    )


def spread(frames: list[Snapshot], count: int) -> list[Snapshot]:
    """At most ``count`` of ``frames``, evenly spread, the first and the last kept."""
    if len(frames) <= count:
        return list(frames)
    picks = np.unique(np.linspace(0, len(frames) - 1, count).round().astype(int))
    return [frames[i] for i in picks]


def run(
    world: World,
    strategy: Strategy,
    *,
    world_name: str = "world",
    frames: int = MAX_FRAMES,
    progress: Callable[[Exploration, Step], None] | None = None,
    **options: Any,
) -> ExploreRun:
    """Explore ``world`` with ``strategy`` step by step (``options`` are
    :func:`covmap.explore`'s keywords), calling ``progress(exploration,
    step)`` after each step and keeping at most ``frames`` (at least 2)
    snapshots for an animation. Every option is checked before the first
    step, as :func:`covmap.explore` checks them.

    Which steps are kept does not depend on how long the run turns out to
    be: every ``stride``-th step is kept, and when twice ``frames`` have been
    kept every other one is dropped and the stride doubles.
    """
    if not 2 <= frames:
        raise InvalidParameterError(f"invalid parameter `frames` = {frames}: expected at least 2")
    exploration = Exploration(world, strategy, **options)
    kept = [snapshot(exploration)]
    stride = 1
    for step in exploration:
        if progress is not None:
            progress(exploration, step)
        if exploration.steps % stride == 0:
            kept.append(snapshot(exploration))
            if len(kept) >= 2 * frames:
                kept = kept[::2]
                stride *= 2
    if kept[-1].step != exploration.steps:
        kept.append(snapshot(exploration))
    return ExploreRun(world_name, world, exploration.result(), spread(kept, frames))


def summary(run_: ExploreRun, speed_m_s: float = REAL_TIME_SPEED_M_S, *, building: Building | None = None) -> str:
    """The run's figures as a table: path, scans, steps, how it ended, the
    uncertain share of the evaluation cells, the rooms of ``building`` (if
    given) never entered, the maps' errors, wall time and how much faster
    than a robot driving at ``speed_m_s`` it ran."""
    r = run_.result
    t = r.timing
    rows = [
        ("world", run_.world_name),
        ("strategy", repr(r.strategy)),
        ("seed", str(r.seed)),
        ("start (x, y, theta)", f"({r.start[0]:.3f} m, {r.start[1]:.3f} m, {r.start[2]:.3f} rad)"),
        ("termination", str(r.termination)),
        ("path length", f"{r.path_length_m:.2f} m"),
        ("scans", str(r.scans)),
        ("steps", str(r.steps)),
        ("contacts", str(r.contacts)),
        ("evaluation cells", f"{int(r.evaluation_cells.sum())} of {r.grid.rows * r.grid.cols}"),
        (f"uncertain (H > {r.epsilon:g} nats)", f"{100.0 * r.high_entropy_fraction:.2f} % of the evaluation cells"),
        *(
            []
            if building is None
            else [
                (
                    "rooms never entered",
                    _rooms_text(building, building.rooms_never_entered(r.trajectory)),
                )
            ]
        ),
        ("map error, coverage map (mean)", f"{r.coverage_error.coverage_map:.4f}"),
        ("map error, occupancy grid", f"{r.coverage_error.occupancy:.4f}"),
        (
            "wall time",
            f"{r.seconds:.2f} s (planning {t.planning_s:.2f} s, sensing {t.sensing_s:.2f} s, "
            f"integration {t.integration_s:.2f} s)",
        ),
        (f"faster than real time at {speed_m_s:g} m/s", f"{r.real_time_factor(speed_m_s):.0f}x"),
    ]
    width = max(len(name) for name, _ in rows)
    return "\n".join(f"{name:<{width}}  {value}" for name, value in rows)


def _rooms_text(building: Building, never: list[str]) -> str:
    judged = sum(1 for r in building.rooms if r.kind != "corridor")
    names = f": {', '.join(never)}" if never else ""
    return f"{len(never)} of {judged}{names}"


TRAJECTORY_FIELDS = ("x_m", "y_m", "theta_rad", "scanned")
"""The columns of the trajectory CSV (:func:`save`)."""


def trajectory_csv(result: ExplorationResult) -> str:
    """The run's trajectory as CSV, columns :data:`TRAJECTORY_FIELDS`: every
    pose in order, the start first, and whether a scan was taken there."""
    lines = [",".join(TRAJECTORY_FIELDS)]
    for (x, y, theta), scanned in zip(result.trajectory.tolist(), result.scanned.tolist()):
        lines.append(f"{x!r},{y!r},{theta!r},{int(scanned)}")
    return "\n".join(lines) + "\n"


def save(run_: ExploreRun, out: Path, stem: str) -> list[Path]:
    """Save what a user needs to continue from the run into ``out``, each
    file written whole or not at all: ``<stem>.npz`` (the final posterior,
    :meth:`covmap.CoverageMap.load`), ``<stem>.yaml`` and ``<stem>.pgm``
    (the ML map as a ROS map_server pair: cells no evidence reached
    unknown) and ``<stem>-trajectory.csv`` (:func:`trajectory_csv`).
    Returns the paths."""
    from covmap._native import write_atomic

    out.mkdir(parents=True, exist_ok=True)
    r = run_.result
    posterior, yaml, pgm, trajectory = saved_paths(out, stem)
    r.map.save(posterior)
    r.map.to_ros_map(yaml)
    write_atomic(trajectory, trajectory_csv(r).encode())
    return [posterior, yaml, pgm, trajectory]


def saved_paths(out: Path, stem: str) -> list[Path]:
    """The files :func:`save` writes into ``out``: the posterior, the
    map_server pair and the trajectory."""
    return [out / f"{stem}.npz", out / f"{stem}.yaml", out / f"{stem}.pgm", out / f"{stem}-trajectory.csv"]
