"""Strategies written in Python (:meth:`covmap.Strategy.custom`).

A :class:`CustomStrategy` holds a function ``choose(view)``. Before each
step of a run (:func:`covmap.explore`, :class:`covmap.Exploration`,
:func:`covmap.sweep`, the benchmark) the run calls it with a
:class:`StrategyView` of what the built-in strategies see, and drives one
step to the goal it returns (``Exploration.step(goal=...)``), or ends when
it returns ``None``:

- a goal is a pose ``(x, y, theta)`` (or ``(x, y)``: the robot's heading
  kept) that the robot can reach on its map, or the index of one of
  ``view.candidates``;
- ``None`` (or ``"done"``) ends the run, by the paper's rule where it holds
  (``"certain"``, ``"stagnated"``), else ``"no_goal"``.

A goal the robot cannot go to raises :class:`~covmap.InvalidGoalError`, an
answer of the wrong type :class:`~covmap.InvalidTypeError`, and an error
that ``choose`` raises passes on unchanged; in every case the run is as it
was (after its first scans). The built-in strategies stay in Rust; the
same choice can be made there through the core's ``ExplorationStrategy``
trait (``examples/custom_strategy.rs``).

>>> import covmap
>>> def nearest(view):
...     c = view.candidates.candidates
...     return None if len(c) == 0 else int(c.costs.argmin())
>>> run = covmap.Exploration(covmap.World.builtin("corridor"), covmap.Strategy.custom(nearest), max_steps=2)
>>> [step.index for step in run]
[0, 1]
>>> run.result().strategy.name
'nearest'
"""

from __future__ import annotations

import math
import numbers
from functools import cached_property
from typing import TYPE_CHECKING, Any, Callable, Union

import numpy as np

from covmap._errors import InvalidGoalError, InvalidParameterError, InvalidTypeError, quoted

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

    from covmap._native import CoverageMap, Exploration, Grid, OccupancyGrid, Plan

__all__ = ["CustomStrategy", "StrategyView"]

Goal = Union[None, str, int, "npt.ArrayLike"]
"""What ``choose`` returns: a pose, a candidate's index, or ``None``."""


class StrategyView:
    """What a custom strategy sees before a step: the run's maps (copies),
    where the robot is, what it can reach, the candidate viewpoints the
    coverage strategy weighs, and whether the paper's rule holds. Every
    part is read from the run when first asked for and kept: the view is
    the run as it stood when ``choose`` was called."""

    def __init__(self, exploration: Exploration, alpha: float) -> None:
        self._run = exploration
        self._alpha = alpha
        self.pose: npt.NDArray[np.float64] = exploration.pose
        """Where the robot is, ``(x, y, theta)``."""
        self.steps: int = exploration.steps
        """Steps taken so far."""
        self.scans: int = exploration.scans
        """Scans taken so far."""
        self.path_length_m: float = exploration.path_length_m
        """Metres driven so far."""
        self.uncertain_fraction: float = exploration.uncertain_fraction
        """The share of the evaluation cells above ``epsilon`` now."""
        self.grid: Grid = exploration.grid
        """The grid of the maps."""

    @cached_property
    def map(self) -> CoverageMap:
        """The coverage map built so far (a copy)."""
        return self._run.map

    @cached_property
    def occupancy(self) -> OccupancyGrid:
        """The occupancy grid built from the same beams (a copy)."""
        return self._run.occupancy

    @cached_property
    def region(self) -> npt.NDArray[np.bool_]:
        """The region the robot can reach on its coverage map: bool
        ``(rows, cols)``, the cells the paper's rule is checked on."""
        return self._run.region()

    @cached_property
    def rule(self) -> str | None:
        """Whether the paper's rule holds on :attr:`region`: ``"certain"``,
        ``"stagnated"``, or ``None`` while some cell is neither."""
        return self._run.rule()

    @cached_property
    def candidates(self) -> Plan:
        """The candidate viewpoints the coverage strategy weighs (a
        ``Plan``: ``candidates.poses``, ``.gains`` in nats, ``.costs`` in
        metres of path, ``.utilities`` by eq. 14 for the strategy's
        ``alpha``; ``pose`` the planner's own choice). The costliest part of
        the view: computed only when asked for."""
        return self._run.viewpoints(alpha=self._alpha)

    def path_to(self, goal: Sequence[float] | npt.NDArray[np.floating[Any]]) -> npt.NDArray[np.float64] | None:
        """The path a step to ``goal`` would take (cell centres, ``(K, 2)``),
        ``None`` where the robot cannot reach it."""
        return self._run.path_to(goal)

    def __repr__(self) -> str:
        x, y, theta = (float(v) for v in self.pose)
        return f"<StrategyView: step {self.steps}, pose ({x:.2f}, {y:.2f}, {theta:.2f}), {self.path_length_m:.1f} m>"


class CustomStrategy:
    """A strategy written in Python: ``choose(view)`` picks each goal (see
    the module documentation). Build one with :meth:`covmap.Strategy.custom`.
    Two compare equal when their functions, names and ``alpha`` are; it
    pickles when ``choose`` does (a function defined at the top level of a
    module), which :func:`covmap.sweep` needs."""

    def __init__(self, choose: Callable[[StrategyView], Goal], *, name: str | None = None, alpha: float = 0.5) -> None:
        if not callable(choose):
            raise InvalidTypeError(
                f"choose must be a function of a StrategyView that returns a goal, got {type(choose).__name__}"
            )
        if name is None:
            name = str(getattr(choose, "__name__", "custom"))
        if not isinstance(name, str) or not 0 < len(name) <= 100:
            raise InvalidParameterError(
                f"invalid parameter `name` = {quoted(name)}: expected a name of 1 to 100 characters"
            )
        if isinstance(alpha, bool) or not isinstance(alpha, numbers.Real):
            raise InvalidTypeError(f"alpha must be a number, got {type(alpha).__name__}")
        if not 0.0 <= float(alpha) <= 1.0:
            raise InvalidParameterError(f"invalid parameter `alpha` = {quoted(alpha)}: expected a weight in [0, 1]")
        self._choose: Callable[[StrategyView], Goal] = choose
        self._name: str = name
        self._alpha: float = float(alpha)

    @property
    def choose(self) -> Callable[[StrategyView], Goal]:
        """The function that picks each goal."""
        return self._choose

    @property
    def name(self) -> str:
        """What results call it."""
        return self._name

    @property
    def alpha(self) -> float:
        """The weight of information against travel in the utilities of the
        candidates it sees (eq. 14)."""
        return self._alpha

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, CustomStrategy):
            return NotImplemented
        return (self._choose, self._name, self._alpha) == (other._choose, other._name, other._alpha)

    def __hash__(self) -> int:
        return hash((CustomStrategy, self._name, self._alpha))

    def __repr__(self) -> str:
        return f"Strategy.custom({getattr(self._choose, '__qualname__', repr(self._choose))}, name={self._name!r})"

    def __reduce__(self) -> tuple[Any, ...]:
        return (_custom, (self._choose, self._name, self._alpha))


def _custom(choose: Callable[[StrategyView], Goal], name: str, alpha: float) -> CustomStrategy:
    return CustomStrategy(choose, name=name, alpha=alpha)


def goal_of(answer: Goal, view: StrategyView) -> tuple[float, float, float] | None:
    """The goal ``answer`` names (see the module documentation) as ``(x, y,
    theta)``, or ``None``: done."""
    if answer is None or (isinstance(answer, str) and answer == "done"):
        return None
    if isinstance(answer, (bool, np.bool_)):
        raise InvalidTypeError("a custom strategy's goal is a pose, a candidate's index or None, got a bool")
    if isinstance(answer, (numbers.Integral, np.integer)):
        poses = view.candidates.candidates.poses
        k = int(answer)
        if not 0 <= k < len(poses):
            raise InvalidGoalError(
                f"candidate {k} of {len(poses)}: a custom strategy's index must name one of view.candidates"
            )
        x, y, theta = (float(v) for v in poses[k])
        return x, y, theta
    if isinstance(answer, (str, bytes)) or not hasattr(answer, "__len__") and not hasattr(answer, "__array__"):
        raise InvalidTypeError(
            f"a custom strategy's goal is a pose (x, y[, theta]), a candidate's index or None, got {type(answer).__name__}"
        )
    try:
        values = np.asarray(answer, dtype=np.float64)
    except (TypeError, ValueError):
        raise InvalidTypeError(
            f"a custom strategy's goal is a pose of numbers (x, y[, theta]), got {quoted(answer)}"
        ) from None
    if values.shape not in ((2,), (3,)):
        raise InvalidGoalError(f"a custom strategy's goal is (x, y) or (x, y, theta), got shape {values.shape}")
    if not all(math.isfinite(v) for v in values):
        raise InvalidGoalError(f"a custom strategy's goal must be finite, got {quoted(answer)}")
    theta = float(values[2]) if values.shape == (3,) else float(view.pose[2])
    return float(values[0]), float(values[1]), theta


def decide(exploration: Exploration, strategy: CustomStrategy) -> tuple[float, float, float] | None:
    """Ask ``strategy`` for the next goal of ``exploration`` (called by the
    run before a step it was given no goal for)."""
    view = StrategyView(exploration, strategy.alpha)
    return goal_of(strategy.choose(view), view)
