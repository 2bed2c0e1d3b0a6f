"""What an exploration run reports (:func:`covmap.explore`,
:class:`covmap.Exploration`): the native module builds these dataclasses
from the run; they pickle (a result's pickled state checked on load,
:mod:`covmap._state`), and compare by identity (they hold arrays)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from covmap import _state


if TYPE_CHECKING:
    import numpy.typing as npt

    from covmap._custom import CustomStrategy
    from covmap._native import CoverageMap, Grid, OccupancyGrid, Strategy

__all__ = ["ExplorationErrors", "ExplorationResult", "Step", "Timing"]

REAL_TIME_SPEED_M_S = 0.5


def real_time_factor(path_length_m: float, seconds: float, speed_m_s: float) -> float:
    """How many times faster than real time a run of ``seconds`` was for a
    robot driving ``path_length_m`` at ``speed_m_s`` (a positive, finite
    number, else :class:`~covmap.InvalidParameterError`): ``inf`` for a run
    that took no measurable time."""
    if isinstance(speed_m_s, bool) or not isinstance(speed_m_s, (int, float, np.floating, np.integer)) or not (
        0.0 < speed_m_s < float("inf")
    ):
        from covmap._errors import InvalidParameterError, quoted

        raise InvalidParameterError(
            f"invalid parameter `speed_m_s` = {quoted(speed_m_s)}: expected a positive, finite speed (m/s)"
        )
    driving_s = path_length_m / float(speed_m_s)
    return driving_s / seconds if seconds > 0.0 else float("inf")
"""The robot speed a run's wall time is compared against by default, metres
per second (the issue's goal: far faster than a robot driving at 0.5 m/s)."""


@dataclass(frozen=True)
class Timing:
    """Wall time of a run's loop, seconds, by what it was spent on. Not part
    of the run's outcome: the same seed gives the same run with other
    timings."""

    planning_s: float
    """Choosing goals and checking termination."""
    sensing_s: float
    """Scanning and driving (the simulated sensor and robot)."""
    integration_s: float
    """Integrating scans and contacts into the maps."""

    @property
    def total_s(self) -> float:
        """The three together."""
        return self.planning_s + self.sensing_s + self.integration_s


@dataclass(frozen=True)
class ExplorationErrors:
    """Mean absolute errors of the maps' estimates of coverage against the
    exact ground truth over the evaluation cells. The scan counts have none:
    a count says how often a cell was seen, not how much of it is covered."""

    coverage_map: float
    """The coverage map's mean map."""
    occupancy: float
    """The occupancy grid's probability of occupancy."""


@dataclass(frozen=True, eq=False)
class Step:
    """What one step of an exploration did (:meth:`covmap.Exploration.step`)."""

    index: int
    """The step's number, from 0."""
    goal: npt.NDArray[np.float64]
    """The goal the strategy chose, ``(x, y, theta)``."""
    path: npt.NDArray[np.float64]
    """The path planned to it on the map: cell centres, ``(K, 2)``."""
    reached: bool
    """Whether the robot got to the goal (not after a contact or at the path limit)."""
    contact: tuple[float, float] | None
    """Where the robot touched an obstacle the map did not show, if it did."""
    travelled_m: float
    """Distance driven in this step, metres."""
    scans: int
    """Scans taken in this step."""
    pose: npt.NDArray[np.float64]
    """The robot's pose after the step, ``(x, y, theta)``."""


@dataclass(frozen=True, eq=False)
class ExplorationResult:
    """Everything an exploration run reports (:func:`covmap.explore`).

    Per-cell arrays are ``(rows, cols)`` arrays of :attr:`grid`, indexed
    ``[row, col]``.
    """

    strategy: Strategy | CustomStrategy
    """The strategy that chose the goals."""
    seed: int
    """The seed of every random draw."""
    start: npt.NDArray[np.float64]
    """Where the robot started, ``(x, y, theta)`` (drawn from the seed when
    none was given)."""
    grid: Grid
    """The grid of the maps: the world's bounds plus a margin."""
    termination: str | None
    """How the run ended: ``"certain"`` (every cell of the reachable region
    certain), ``"stagnated"`` (certain or stagnated), ``"no_goal"`` (the
    strategy has no goal left), ``"limit"`` (``max_path_m`` or
    ``max_steps``); ``None`` for a run still going on."""
    path_length_m: float
    """Distance driven, metres."""
    scans: int
    """Scans taken."""
    steps: int
    """Steps taken (goals driven to)."""
    contacts: int
    """Contacts with obstacles the map did not show."""
    trajectory: npt.NDArray[np.float64]
    """Every pose in order, the start first: ``(K, 3)`` of ``(x, y, theta)``;
    consecutive poses are joined by straight drives."""
    scanned: npt.NDArray[np.bool_]
    """Whether a scan was taken at each pose of :attr:`trajectory`: ``(K,)``."""
    trace: dict[str, npt.NDArray[np.generic]]
    """Per-step figures, one entry a step: ``"path_length_m"`` and
    ``"scans"`` so far, ``"uncertain_fraction"`` (of the evaluation cells,
    entropy above epsilon), ``"contact"`` (bool), ``"planning_s"``."""
    counts: npt.NDArray[np.float32]
    """How many beams intercepted each cell (discounted as the counting
    strategy asks; undiscounted for the others)."""
    map: CoverageMap
    """The coverage map built."""
    occupancy: OccupancyGrid
    """The occupancy grid built from the same beams."""
    truth: npt.NDArray[np.float64]
    """The exact coverage of every cell by the world's obstacles."""
    evaluation_cells: npt.NDArray[np.bool_]
    """The cells the run is judged on, from the true world alone and the
    same for every strategy: the reachable free space (cell centres at least
    the robot's radius from every obstacle, connected to the start), every
    cell within the robot's radius of it, and every cell holding some
    obstacle within the robot's radius plus the sensor model's end band of
    it (free cells behind an obstacle, which no reading sees, are left
    out)."""
    epsilon: float
    """Entropy above which a cell is uncertain, nats."""
    high_entropy_fraction: float
    """Table I's measure: the fraction of the evaluation cells whose entropy
    on the coverage map is above :attr:`epsilon` at the end."""
    coverage_error: ExplorationErrors
    """The maps' mean absolute errors on the evaluation cells."""
    seconds: float
    """Wall time of the whole run, the setup (ground truth, evaluation cells)
    included, seconds."""
    timing: Timing
    """Wall time of the loop by what it was spent on."""

    @property
    def uncertain_cells(self) -> npt.NDArray[np.bool_]:
        """The evaluation cells whose entropy is above :attr:`epsilon`: the
        cells :attr:`high_entropy_fraction` counts."""
        return self.evaluation_cells & (self.map.entropy().astype(np.float64) > self.epsilon)

    @property
    def scan_poses(self) -> npt.NDArray[np.float64]:
        """The poses scans were taken from: ``(S, 3)``."""
        return self.trajectory[self.scanned]

    def real_time_factor(self, speed_m_s: float = REAL_TIME_SPEED_M_S) -> float:
        """How many times faster than real time the run was for a robot
        driving its path at ``speed_m_s``: the driving time over the run's
        wall time (``inf`` for a run that took no measurable time)."""
        return real_time_factor(self.path_length_m, self.seconds, speed_m_s)

    def __setstate__(self, state: Any) -> None:
        _state.restore(self, state, _result_fields())

    def __repr__(self) -> str:
        return (
            f"<ExplorationResult: {self.strategy!r}, seed {self.seed}, {self.termination}, "
            f"{self.path_length_m:.2f} m, {self.scans} scans, {self.steps} steps, "
            f"{100.0 * self.high_entropy_fraction:.2f} % uncertain>"
        )


def outcome_fields() -> dict[str, _state.Check]:
    """The checks of what a run's result and its summary share: how it
    ended, its figures and its timing (:mod:`covmap._state`)."""
    from covmap._custom import CustomStrategy
    from covmap._native import Strategy

    count = _state.integer(0, 2**63 - 1)
    seconds = _state.number(0.0)
    fraction = _state.number(0.0, 1.0)
    return {
        "strategy": _state.instance((Strategy, CustomStrategy)),
        "seed": _state.integer(0, 2**64 - 1),
        "termination": _state.one_of(_state.TERMINATIONS),
        "path_length_m": _state.number(0.0),
        "scans": count,
        "steps": count,
        "contacts": count,
        "trace": _state.trace,
        "epsilon": _state.number(0.0),
        "high_entropy_fraction": fraction,
        "coverage_error": _state.fields_of(ExplorationErrors, {"coverage_map": fraction, "occupancy": fraction}),
        "seconds": seconds,
        "timing": _state.fields_of(Timing, {"planning_s": seconds, "sensing_s": seconds, "integration_s": seconds}),
    }


def _result_fields() -> dict[str, _state.Check]:
    from covmap._native import CoverageMap, Grid, OccupancyGrid

    cells = _state.grid_shape

    def poses(state: Any) -> tuple[int | None, ...]:
        return (None, 3)

    def one_a_pose(state: Any) -> tuple[int | None, ...]:
        trajectory = state.get("trajectory")
        return (len(trajectory) if isinstance(trajectory, np.ndarray) else None,)

    return {
        **outcome_fields(),
        "start": _state.array(np.float64, lambda _: (3,), finite=True),
        "grid": _state.instance(Grid),
        "trajectory": _state.array(np.float64, poses, finite=True),
        "scanned": _state.array(np.bool_, one_a_pose),
        "counts": _state.array(np.float32, cells, finite=True, within=(0.0, math.inf)),
        "map": _state.all_of(_state.instance(CoverageMap), _state.on_grid),
        "occupancy": _state.all_of(_state.instance(OccupancyGrid), _state.on_grid),
        "truth": _state.array(np.float64, cells, within=(0.0, 1.0)),
        "evaluation_cells": _state.array(np.bool_, cells),
    }
