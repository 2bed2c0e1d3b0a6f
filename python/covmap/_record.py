"""Runs and maps recorded for the Rerun viewer (the ``rerun`` extra:
``pip install 'covmap[rerun]'``; open a recording with ``rerun FILE.rrd``):
:func:`covmap.record` for an exploration, :func:`record_log` for a mapped
log (``covmap map LOG --record``), :func:`record_map` for a saved posterior
(``covmap view FILE.npz --record``).

A recording draws everything in the map's picture: one pixel a cell, x to
the right and y up (the image's row 0 is the map's top row), under the
entity ``map``:

- ``map/coverage``: the maximum-likelihood coverage, white free to black
  covered, cells no evidence reached in :data:`covmap.plot.UNKNOWN_COLOR`
  (unknown is not free);
- ``map/entropy``: the cells' entropy, dark certain to bright uncertain;
- ``map/outline``: the true obstacles' outlines (where the world is known);
- ``robot/pose`` (a point and an arrow of its heading), ``robot/path``;
- ``robot/beams``: the beams of a scan from the robot's pose (for an
  exploration, a scan simulated at the step's end pose, seeded by the step:
  the loop does not keep its readings; for a log, the log's own scan);
- ``plan/goal``, ``plan/candidates`` (the candidate viewpoints, coloured by
  expected gain, dark to bright);
- ``stats/uncertain_share``, ``stats/path_m``: scalars.

Timelines: ``step`` (an exploration's steps; a log's scans on ``scan``) and
``path_cm`` (the path driven so far, centimetres).

The file is written atomically when the recording ends (the recording is
kept in memory until then): a path where something other than a regular
file is, or that cannot be written, is refused before anything runs
(:class:`covmap.FileIOError`).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

import numpy as np

from covmap._errors import FileIOError, InvalidTypeError, MissingDependencyError

if TYPE_CHECKING:
    import numpy.typing as npt

    from covmap._exploration import ExplorationResult
    from covmap._exploration import Step
    from covmap._native import CoverageMap, Exploration, Grid, Log, Strategy, World
    from covmap._custom import CustomStrategy

__all__ = ["Recorder", "exploration_frame", "record", "record_log", "record_map"]

APPLICATION_ID = "covmap"
"""The recordings' application id in the viewer."""

MAX_BEAMS_DRAWN = 4096
"""The most beams a scan draws (a laser's 361 and a ring's 24 all)."""


def _rerun() -> Any:
    try:
        import rerun
    except ImportError as e:
        raise MissingDependencyError(
            "recording for the Rerun viewer needs rerun-sdk: pip install 'covmap[rerun]'"
        ) from e
    return rerun


def _target(path: str | os.PathLike[str]) -> str:
    """``path`` checked as a recording's target, before anything runs."""
    from covmap._native import check_write_target

    if not isinstance(path, (str, os.PathLike)):
        raise InvalidTypeError(f"a recording's path must be a path, got {type(path).__name__}")
    check_write_target(path)
    folder = os.path.dirname(os.path.abspath(os.fspath(path)))
    if not os.path.isdir(folder):
        raise FileIOError(f"{os.fspath(path)}: cannot write a recording there: no directory {folder}")
    return os.fspath(path)


class Recorder:
    """A recording of a map's picture over time (see the module
    documentation), written to ``path`` by :meth:`close` (or at the end of
    a ``with`` block; not if the block raised)."""

    def __init__(self, path: str | os.PathLike[str], grid: Grid, world: World | None = None) -> None:
        rr = _rerun()
        self._path = _target(path)
        self._rr = rr
        self._grid = grid
        self._stream = rr.RecordingStream(APPLICATION_ID)
        # The run's own timelines only: no wall-clock time of logging.
        self._stream.set_log_time_enabled(False)
        self._memory = self._stream.memory_recording()
        self._closed = False
        self._path_points: list[npt.NDArray[np.float64]] = []
        if world is not None:
            rings = [np.vstack([r, r[:1]]) for r in world.polygons]
            rings += [np.vstack([h, h[:1]]) for holes in world.holes for h in holes]
            self._stream.log("map/outline", rr.LineStrips2D([self._pixels(r) for r in rings], colors=[(255, 140, 0)]), static=True)

    def __enter__(self) -> Recorder:
        return self

    def __exit__(self, error: type[BaseException] | None, *exc: object) -> None:
        # A block that raised writes nothing: the file stays as it was.
        if error is None:
            self.close()
        else:
            self._closed = True

    def _pixels(self, xy: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """World coordinates ``(K, 2)`` as the picture's pixel coordinates."""
        g = self._grid
        p = np.asarray(xy, dtype=np.float64).reshape(-1, 2)
        x0, y0 = g.origin
        return np.column_stack([(p[:, 0] - x0) / g.resolution, g.rows - (p[:, 1] - y0) / g.resolution])

    def time(self, timeline: str, index: int, path_m: float) -> None:
        """Set the time of what is logged next: ``index`` on ``timeline``
        and the path driven so far."""
        self._stream.set_time(timeline, sequence=int(index))
        self._stream.set_time("path_cm", sequence=int(round(path_m * 100)))

    def maps(self, cmap: CoverageMap) -> None:
        """The map's layers, as pictures."""
        from covmap.plot import UNKNOWN_COLOR
        from matplotlib.colors import to_rgb

        rr = self._rr
        ml = np.flipud(cmap.ml())
        seen = np.flipud(cmap.observed())
        grey = ((1.0 - ml) * 255).astype(np.uint8)
        rgb = np.repeat(grey[:, :, None], 3, axis=2)
        rgb[~seen] = (np.array(to_rgb(UNKNOWN_COLOR)) * 255).astype(np.uint8)
        self._stream.log("map/coverage", rr.Image(rgb))
        entropy = np.flipud(cmap.entropy()) / np.log(cmap.bins)
        self._stream.log("map/entropy", rr.Image((np.clip(entropy, 0, 1) * 255).astype(np.uint8)))

    def robot(self, pose: npt.ArrayLike, trajectory: npt.ArrayLike | None = None) -> None:
        """The robot's pose and (given) its path so far."""
        rr = self._rr
        x, y, theta = (float(v) for v in np.asarray(pose, dtype=np.float64)[:3])
        here = self._pixels([[x, y]])[0]
        arrow = np.array([np.cos(theta), -np.sin(theta)]) * 0.5 / self._grid.resolution
        self._stream.log("robot/pose", rr.Points2D([here], radii=3.0, colors=[(220, 20, 20)]))
        self._stream.log("robot/heading", rr.Arrows2D(origins=[here], vectors=[arrow], colors=[(220, 20, 20)]))
        if trajectory is not None:
            t = np.asarray(trajectory, dtype=np.float64)
            self._stream.log("robot/path", rr.LineStrips2D([self._pixels(t[:, :2])], colors=[(220, 20, 20)]))

    def beams(self, pose: npt.ArrayLike, ranges: npt.ArrayLike, bearings: npt.ArrayLike) -> None:
        """A scan's beams from ``pose`` (readings that are not finite are
        left out)."""
        rr = self._rr
        x, y, theta = (float(v) for v in np.asarray(pose, dtype=np.float64)[:3])
        r = np.asarray(ranges, dtype=np.float64)[:MAX_BEAMS_DRAWN]
        b = np.asarray(bearings, dtype=np.float64)[: len(r)]
        ok = np.isfinite(r)
        ends = np.column_stack([x + r[ok] * np.cos(theta + b[ok]), y + r[ok] * np.sin(theta + b[ok])])
        start = self._pixels([[x, y]])[0]
        strips = [np.vstack([start, e]) for e in self._pixels(ends)]
        self._stream.log("robot/beams", rr.LineStrips2D(strips, colors=[(40, 120, 220)]))

    def plan(self, goal: npt.ArrayLike | None, poses: npt.ArrayLike, gains: npt.ArrayLike) -> None:
        """The chosen goal and the candidates, coloured by expected gain."""
        rr = self._rr
        p = np.asarray(poses, dtype=np.float64).reshape(-1, 3)
        g = np.asarray(gains, dtype=np.float64)
        top = float(g.max()) if len(g) and g.max() > 0 else 1.0
        shade = (np.clip(g / top, 0, 1) * 200 + 55).astype(np.uint8)
        colors = np.column_stack([shade, shade, np.full_like(shade, 40)])
        self._stream.log("plan/candidates", rr.Points2D(self._pixels(p[:, :2]), radii=1.5, colors=colors))
        if goal is not None:
            self._stream.log("plan/goal", rr.Points2D(self._pixels(np.asarray(goal)[:2]), radii=4.0, colors=[(20, 180, 20)]))

    def scalar(self, name: str, value: float) -> None:
        """A figure over time, under ``stats/``."""
        self._stream.log(f"stats/{name}", self._rr.Scalars(float(value)))

    def close(self) -> None:
        """End the recording and write the file (atomically)."""
        from covmap._native import write_atomic

        if self._closed:
            return
        self._closed = True
        self._stream.flush()
        write_atomic(self._path, self._memory.drain_as_bytes())


def exploration_frame(rec: Recorder, run: Exploration, step: Step | None, sensor: Any, world: World) -> None:
    """The run now, on the ``step`` timeline: the maps, the robot and its
    path, a scan's beams, the step's goal, the candidate viewpoints the
    coverage strategy weighs next (their expected gains), the figures."""
    rec.time("step", run.steps, run.path_length_m)
    rec.maps(run.map)
    rec.robot(run.pose, run.trajectory)
    ranges, bearings = sensor.simulate(world, tuple(run.pose), seed=run.steps)
    rec.beams(run.pose, ranges, bearings)
    candidates = run.viewpoints().candidates if not run.done else None
    rec.plan(
        None if step is None else step.goal,
        np.empty((0, 3)) if candidates is None else candidates.poses,
        np.empty(0) if candidates is None else candidates.gains,
    )
    rec.scalar("path_m", run.path_length_m)
    rec.scalar("uncertain_share", run.uncertain_fraction)


def record(
    path: str | os.PathLike[str],
    world: World,
    strategy: Strategy | CustomStrategy,
    **options: Any,
) -> ExplorationResult:
    """Explore ``world`` with ``strategy`` (``options``: the keywords of
    :func:`covmap.explore`) and record the start and every step to
    ``path``; returns the run's result, the same as :func:`covmap.explore`
    gives. Each frame also draws the candidate viewpoints the coverage
    strategy weighs next (a plan more a step). The path is checked, and
    every option, before the first step."""
    from covmap._native import Exploration, SonarRing

    target = _target(path)
    run = Exploration(world, strategy, **options)
    sensor = options.get("sensor") or SonarRing()
    with Recorder(target, run.map.grid, world) as rec:
        run.begin()
        exploration_frame(rec, run, None, sensor, world)
        while (step := run.step()) is not None:
            exploration_frame(rec, run, step, sensor, world)
    return run.result()


def record_log(
    path: str | os.PathLike[str],
    log: Log,
    cmap: CoverageMap,
    *,
    every: int = 1,
) -> None:
    """A recorded log and the map built from it: every ``every``-th scan
    (on the ``scan`` timeline) the robot's pose, its path so far and the
    scan's beams; the map's layers once, at the last scan."""
    if isinstance(every, bool) or not isinstance(every, int) or every < 1:
        from covmap._errors import InvalidParameterError

        raise InvalidParameterError(f"invalid parameter `every` = {every!r}: expected an integer of at least 1")
    poses, ranges, bearings = log.poses, log.ranges, log.bearings
    ox, oy, ot = log.sensor_offset
    c, s = np.cos(poses[:, 2]), np.sin(poses[:, 2])
    sensor = np.column_stack([poses[:, 0] + ox * c - oy * s, poses[:, 1] + ox * s + oy * c, poses[:, 2] + ot])
    travelled = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(poses[:, :2], axis=0).T))])
    with Recorder(path, cmap.grid) as rec:
        for i in range(0, len(poses), every):
            rec.time("scan", i, float(travelled[i]))
            rec.robot(poses[i], poses[: i + 1])
            rec.beams(sensor[i], ranges[i], bearings[i] if bearings.ndim == 2 else bearings)
        last = len(poses) - 1
        rec.time("scan", last, float(travelled[last]) if len(poses) else 0.0)
        rec.maps(cmap)


def record_map(path: str | os.PathLike[str], cmap: CoverageMap) -> None:
    """A saved posterior's layers, as one frame."""
    with Recorder(path, cmap.grid) as rec:
        rec.time("step", 0, 0.0)
        rec.maps(cmap)
