"""The state a pickle restores into covmap's result dataclasses
(:class:`~covmap.ExplorationResult`, :class:`~covmap.RunSummary`), checked
as the native classes check theirs (``Log``, ``CoverageMap``,
``SensorFit``, ``Strategy``): a field missing, unknown or of a value no run
gives raises :class:`~covmap.InvalidValueError` naming the class and the
field, before the object holds any of it.

Each class lists its fields with a check (:data:`Check`): a function of the
field's value and the whole state that says what is wrong, or ``None``.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from covmap._errors import InvalidValueError, quoted

if TYPE_CHECKING:
    from collections.abc import Mapping

Check = Callable[[Any, "Mapping[str, Any]"], "str | None"]
"""What is wrong with a field's value (given the whole state), or ``None``."""

TERMINATIONS = (None, "certain", "stagnated", "no_goal", "limit")
"""How a run can end (``None``: still going on)."""


def restore(obj: object, state: object, fields: Mapping[str, Check]) -> None:
    """Set the fields of the frozen dataclass ``obj`` from the pickled
    ``state`` once every check of ``fields`` passed; else raise
    :class:`~covmap.InvalidValueError` naming the field."""
    name = type(obj).__name__
    if not isinstance(state, dict) or set(state) != set(fields):
        got = sorted(map(str, state)) if isinstance(state, dict) else type(state).__name__
        raise InvalidValueError(f"not a saved {name}: expected the fields {sorted(fields)}, got {quoted(got)}")
    for field, check in fields.items():
        problem = check(state[field], state)
        if problem is not None:
            raise InvalidValueError(f"not a saved {name}: {field} {problem}")
    for field, value in state.items():
        object.__setattr__(obj, field, value)


def instance(cls: type | tuple[type, ...]) -> Check:
    """The value is a ``cls``."""

    def check(value: Any, _: Mapping[str, Any]) -> str | None:
        return None if isinstance(value, cls) else f"must be a {_names(cls)}, got {type(value).__name__}"

    return check


def _names(cls: type | tuple[type, ...]) -> str:
    return " or ".join(c.__name__ for c in (cls if isinstance(cls, tuple) else (cls,)))


def integer(low: int, high: int) -> Check:
    """An ``int`` (not a bool) from ``low`` to ``high``."""

    def check(value: Any, _: Mapping[str, Any]) -> str | None:
        if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
            return f"must be an integer from {low} to {high}, got {quoted(value)}"
        return None

    return check


def number(low: float, high: float = math.inf) -> Check:
    """A finite ``float`` (or ``int``, not a bool) from ``low`` to ``high``."""

    def check(value: Any, _: Mapping[str, Any]) -> str | None:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (low <= value <= high and math.isfinite(value)):
            return f"must be a finite number from {low} to {high}, got {quoted(value)}"
        return None

    return check


def one_of(values: tuple[Any, ...]) -> Check:
    """One of ``values``."""

    def check(value: Any, _: Mapping[str, Any]) -> str | None:
        return None if any(value == v and type(value) is type(v) for v in values) else f"must be one of {values}, got {quoted(value)}"

    return check


def array(dtype: type, shape: Callable[[Mapping[str, Any]], tuple[int | None, ...]], *, finite: bool = False, within: tuple[float, float] | None = None) -> Check:
    """A numpy array of ``dtype`` whose shape is ``shape(state)`` (``None``:
    any length), its values finite or within ``within`` if asked."""

    def check(value: Any, state: Mapping[str, Any]) -> str | None:
        expected = shape(state)
        if not isinstance(value, np.ndarray) or value.dtype != dtype:
            return f"must be a {np.dtype(dtype).name} array, got {type(value).__name__} {getattr(value, 'dtype', '')}".rstrip()
        if len(value.shape) != len(expected) or any(e is not None and e != n for e, n in zip(expected, value.shape)):
            return f"must have shape {expected}, got {value.shape}"
        if finite and not np.isfinite(value).all():
            return "must hold finite values only"
        if within is not None and value.size and not (np.all(value >= within[0]) and np.all(value <= within[1])):
            return f"must hold values from {within[0]} to {within[1]} only"
        return None

    return check


def grid_shape(state: Mapping[str, Any]) -> tuple[int | None, ...]:
    """The shape of the state's ``grid`` (any, if it is no grid: its own
    check says so)."""
    shape = getattr(state.get("grid"), "shape", (None, None))
    return tuple(shape)


def on_grid(value: Any, state: Mapping[str, Any]) -> str | None:
    """A map over the state's ``grid``."""
    if getattr(value, "grid", None) != state.get("grid"):
        return f"must be a map over the result's grid {quoted(state.get('grid'))}"
    return None


def trace(value: Any, state: Mapping[str, Any]) -> str | None:
    """Per-step figures: names to 1-D numeric arrays, one value a step."""
    steps = state.get("steps")
    if not isinstance(value, dict):
        return f"must be a dict of arrays, got {type(value).__name__}"
    for key, column in value.items():
        if not isinstance(key, str):
            return f"must be keyed by names, got {quoted(key)}"
        if not isinstance(column, np.ndarray) or column.dtype.kind not in "biuf" or column.shape != (steps,):
            return f"[{key!r}] must be a numeric array of one value a step ({steps}), got {quoted(column)}"
    return None


def all_of(*checks: Check) -> Check:
    """Every one of ``checks``, the first problem reported."""

    def check(value: Any, state: Mapping[str, Any]) -> str | None:
        for c in checks:
            problem = c(value, state)
            if problem is not None:
                return problem
        return None

    return check


def fields_of(cls: type, checks: Mapping[str, Check]) -> Check:
    """A ``cls`` dataclass whose fields pass ``checks``."""

    def check(value: Any, state: Mapping[str, Any]) -> str | None:
        if type(value) is not cls:
            return f"must be a {cls.__name__}, got {type(value).__name__}"
        for field, c in checks.items():
            problem = c(getattr(value, field, None), state)
            if problem is not None:
                return f".{field} {problem}"
        return None

    return check
