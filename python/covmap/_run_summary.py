"""What a sweep reports of each run: :class:`RunSummary`, made from an
:class:`~covmap.ExplorationResult` by :func:`summarise`, and the checks of
its pickled state (:mod:`covmap._state`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from covmap import _state
from covmap._errors import quoted
from covmap._exploration import REAL_TIME_SPEED_M_S, ExplorationErrors, Timing, real_time_factor

if TYPE_CHECKING:
    from collections.abc import Mapping

    import numpy.typing as npt

    from covmap._exploration import ExplorationResult
    from covmap._custom import CustomStrategy
    from covmap._native import Building, Strategy

__all__ = ["RunSummary", "explore_keywords", "summarise"]


def explore_keywords() -> tuple[str, ...]:
    """The keyword arguments :func:`covmap.explore` takes, in its order."""
    from covmap._native import _EXPLORE_DEFAULTS

    return tuple(_EXPLORE_DEFAULTS)


@dataclass(frozen=True, eq=False)
class RunSummary:
    """What one run of a sweep reports: everything of
    :class:`~covmap.ExplorationResult` that is small, under the same names,
    without the maps. Pickles; two summaries compare equal when their runs
    had the same outcome (the wall times, :attr:`seconds`, :attr:`timing`
    and the trace's ``"planning_s"``, are left out)."""

    index: int
    """The spec's position in the list given to :func:`sweep`."""
    world: str
    """The world: its name as the spec gave it, a ``Building``'s name, or the
    ``repr`` of the ``World`` given."""
    strategy: Strategy | CustomStrategy
    """The strategy that chose the goals."""
    seed: int
    """The seed of every random draw."""
    options: dict[str, Any]
    """The spec's further keywords of :func:`covmap.explore` (``seed``
    aside), as given (a ``start`` as a tuple of floats)."""
    start: tuple[float, float, float]
    """Where the robot started, ``(x, y, theta)``."""
    termination: str | None
    """How the run ended (see :attr:`covmap.ExplorationResult.termination`)."""
    path_length_m: float
    """Distance driven, metres."""
    scans: int
    """Scans taken."""
    steps: int
    """Steps taken."""
    contacts: int
    """Contacts with obstacles the map did not show."""
    epsilon: float
    """Entropy above which a cell is uncertain, nats."""
    high_entropy_fraction: float
    """The fraction of the evaluation cells whose entropy is above
    :attr:`epsilon` at the end (Table I's measure)."""
    coverage_error: ExplorationErrors
    """The maps' mean absolute errors on the evaluation cells."""
    seconds: float
    """Wall time of the whole run, seconds."""
    timing: Timing
    """Wall time of the loop by what it was spent on."""
    trace: dict[str, npt.NDArray[np.generic]] = field(repr=False)
    """Per-step figures (see :attr:`covmap.ExplorationResult.trace`)."""
    rooms: int | None = None
    """The rooms and halls of the building (its corridors aside) the run
    is judged on (:attr:`covmap.Building.rooms`); ``None`` for a world
    given without its rooms."""
    rooms_never_entered: tuple[str, ...] = ()
    """The names of those the robot never entered
    (:meth:`covmap.Building.rooms_never_entered`)."""
    evaluation_area_m2: float = 0.0
    """The area of the evaluation cells, square metres: what the run
    could observe."""

    @property
    def certain_fraction(self) -> float:
        """The fraction of the evaluation cells certain at the end: ``1 -
        high_entropy_fraction``."""
        return 1.0 - self.high_entropy_fraction

    def real_time_factor(self, speed_m_s: float = REAL_TIME_SPEED_M_S) -> float:
        """How many times faster than real time the run was for a robot
        driving its path at ``speed_m_s`` (see
        :meth:`covmap.ExplorationResult.real_time_factor`)."""
        return real_time_factor(self.path_length_m, self.seconds, speed_m_s)

    def _outcome(self) -> tuple[Any, ...]:
        return (
            self.index,
            self.world,
            self.strategy,
            self.seed,
            self.options,
            self.start,
            self.termination,
            self.path_length_m,
            self.scans,
            self.steps,
            self.contacts,
            self.epsilon,
            self.high_entropy_fraction,
            self.coverage_error,
            self.rooms,
            self.rooms_never_entered,
            self.evaluation_area_m2,
        )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RunSummary):
            return NotImplemented
        if self._outcome() != other._outcome():
            return False
        keys = self.trace.keys() - {"planning_s"}
        return keys == other.trace.keys() - {"planning_s"} and all(
            np.array_equal(self.trace[k], other.trace[k]) for k in keys
        )

    __hash__ = None  # type: ignore[assignment]

    def __setstate__(self, state: Any) -> None:
        _state.restore(self, state, _summary_fields())

    def __repr__(self) -> str:
        return (
            f"<RunSummary {self.index}: {self.world}, {self.strategy!r}, seed {self.seed}, {self.termination}, "
            f"{self.path_length_m:.2f} m, {100.0 * self.high_entropy_fraction:.2f} % uncertain>"
        )


def _summary_fields() -> dict[str, _state.Check]:
    """The checks of a pickled :class:`RunSummary` (:mod:`covmap._state`)."""
    from covmap._exploration import outcome_fields

    def start(value: Any, _: Any) -> str | None:
        finite = isinstance(value, tuple) and len(value) == 3 and all(type(v) is float and math.isfinite(v) for v in value)
        return None if finite else f"must be three finite floats (x, y, theta), got {quoted(value)}"

    def options(value: Any, _: Any) -> str | None:
        if not isinstance(value, dict) or not all(k in explore_keywords() for k in value):
            return f"must be a dict of covmap.explore keywords, got {quoted(value)}"
        return None

    def rooms(value: Any, _: Any) -> str | None:
        if value is None or (type(value) is int and 0 <= value <= 2**32 - 1):
            return None
        return f"must be None or an integer from 0 to 2**32 - 1, got {quoted(value)}"

    def rooms_never_entered(value: Any, state: Any) -> str | None:
        if not isinstance(value, tuple) or not all(type(v) is str for v in value):
            return f"must be a tuple of room names, got {quoted(value)}"
        judged = state.get("rooms") if isinstance(state, dict) else None
        if len(value) > (judged if type(judged) is int else 0):
            return f"names {len(value)} rooms, more than the {judged} judged"
        return None

    return {
        **outcome_fields(),
        "index": _state.integer(0, 2**63 - 1),
        "world": _state.instance(str),
        "options": options,
        "start": start,
        "rooms": rooms,
        "rooms_never_entered": rooms_never_entered,
        "evaluation_area_m2": _state.number(0.0),
    }


def summarise(
    index: int,
    world: str,
    options: Mapping[str, Any],
    result: ExplorationResult,
    building: Building | None = None,
) -> RunSummary:
    """The :class:`RunSummary` of ``result``, the run of spec ``index``
    (in ``building``, whose rooms it is judged on, if given)."""
    start = tuple(float(x) for x in result.start)
    rooms = None if building is None else sum(1 for r in building.rooms if r.kind != "corridor")
    never = () if building is None else tuple(building.rooms_never_entered(result.trajectory))
    cell_m2 = result.grid.resolution * result.grid.resolution
    return RunSummary(
        index=index,
        world=world,
        strategy=result.strategy,
        seed=result.seed,
        options=dict(options),
        start=(start[0], start[1], start[2]),
        termination=result.termination,
        path_length_m=result.path_length_m,
        scans=result.scans,
        steps=result.steps,
        contacts=result.contacts,
        epsilon=result.epsilon,
        high_entropy_fraction=result.high_entropy_fraction,
        coverage_error=result.coverage_error,
        seconds=result.seconds,
        timing=result.timing,
        trace={k: np.array(v) for k, v in result.trace.items()},
        rooms=rooms,
        rooms_never_entered=never,
        evaluation_area_m2=float(np.count_nonzero(result.evaluation_cells)) * cell_m2,
    )
