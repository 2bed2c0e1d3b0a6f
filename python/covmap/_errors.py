"""The exceptions of covmap.

Every error covmap raises for bad input is a :class:`CovmapError`; those caused
by a bad value are also a :class:`ValueError` (a cell index out of range is an
:class:`IndexError`, an array of the wrong dtype a :class:`TypeError`, a file
that cannot be read an :class:`OSError`, an integer beyond 64 bits an
:class:`OverflowError`, a result that does not fit in memory a
:class:`MemoryError`), so code that catches the builtin keeps working. A robot that fails during an exploration run raises
:class:`RobotError`, a :class:`RuntimeError`; a sweep whose runs raised,
:class:`SweepError`, one too. The native module raises these classes.
"""

from __future__ import annotations

import re
from typing import Any

__all__ = [
    "ArrayDtypeError",
    "ArrayShapeError",
    "CellOutOfBoundsError",
    "CovmapError",
    "FileFormatError",
    "FileIOError",
    "InvalidBearingError",
    "InvalidGridError",
    "InvalidHistogramError",
    "InvalidHistoryError",
    "IntegerOverflowError",
    "InvalidParameterError",
    "InvalidPolygonError",
    "InvalidPoseError",
    "InvalidExecutorError",
    "InvalidRangeError",
    "InvalidSpecError",
    "InvalidStartError",
    "InvalidTypeError",
    "InvalidValueError",
    "LengthMismatchError",
    "MissingDependencyError",
    "OutOfMemoryError",
    "PoseOutsideMapError",
    "RobotError",
    "SchedulerError",
    "SweepError",
    "UnknownWorldError",
]


class CovmapError(Exception):
    """Base class of every covmap error."""

    def add_note(self, note: str) -> None:
        """Add ``note`` to the exception; the note with which the native
        module names an argument it could not convert (``while processing
        'resolution'``) goes into the message instead, so that the message
        itself names the argument."""
        match = _ARGUMENT_NOTE.fullmatch(note)
        if match is not None and len(self.args) == 1 and isinstance(self.args[0], str):
            self.args = (f"argument '{match.group(1)}': {self.args[0]}",)
            return
        # BaseException.add_note is Python 3.11's; before, notes are dropped.
        add = getattr(super(), "add_note", None)
        if add is not None:
            add(note)


_ARGUMENT_NOTE = re.compile(r"while processing '(\w+)'")


class InvalidGridError(CovmapError, ValueError):
    """A grid was described with an unusable geometry."""


class InvalidParameterError(CovmapError, ValueError):
    """A sensor-model or map parameter (or a bin count) is out of its valid range."""


class IntegerOverflowError(InvalidParameterError, OverflowError):
    """An integer argument lies beyond what covmap takes: most integers are
    64-bit signed (``-2**63`` to ``2**63 - 1``), seeds unsigned (up to
    ``2**64 - 1``); the message names the argument and the limit. An
    :class:`InvalidParameterError` (a :class:`ValueError`) and an
    :class:`OverflowError`, as Python's own conversions raise."""


class InvalidRangeError(CovmapError, ValueError):
    """A range reading is NaN, infinite or negative."""


class InvalidBearingError(CovmapError, ValueError):
    """A bearing is NaN or infinite, or so large that added to the heading it
    overflows."""


class InvalidPoseError(CovmapError, ValueError):
    """A pose has a non-finite component."""


class PoseOutsideMapError(CovmapError, ValueError):
    """A pose lies outside the map."""


class LengthMismatchError(CovmapError, ValueError):
    """Two inputs that must have the same length do not (ranges and bearings)."""


class CellOutOfBoundsError(CovmapError, IndexError):
    """A cell index lies outside the grid."""


class InvalidHistogramError(CovmapError, ValueError):
    """Histogram data handed in does not describe a valid map."""


class InvalidHistoryError(CovmapError, ValueError):
    """A stored entropy history holds an entropy no map can have (NaN, infinite,
    negative, or above the prior's ``ln(bins)``)."""




class OutOfMemoryError(CovmapError, MemoryError):
    """A map or a result needs more memory than can be had (a grid of many
    cells, a read-out of a large map); the message says what and how many
    bytes. Nothing was changed."""


class ArrayShapeError(CovmapError, ValueError):
    """An array argument has the wrong number of dimensions or the wrong shape."""


class ArrayDtypeError(CovmapError, TypeError):
    """An array argument has the wrong element type (covmap never converts silently)."""


class InvalidTypeError(CovmapError, TypeError):
    """An argument has the wrong type: a model that is neither a SonarModel
    nor a LaserModel, a pickled state of the wrong form, a seed that is not an
    integer, arguments that exclude each other. Also a call with the wrong
    arguments (too many, a missing one, an unknown keyword, one given twice),
    with Python's message naming the callable and the argument; a class that
    cannot be created (a result, such as ``Plan``), called."""


class InvalidPolygonError(CovmapError, ValueError):
    """A polygon is not a usable obstacle (too few vertices, a non-finite
    coordinate, no area, edges that cross); the message names its index."""


class InvalidValueError(CovmapError, ValueError):
    """One element of an input array is unusable (a NaN ray origin, an infinite angle)."""


class UnknownWorldError(CovmapError, ValueError):
    """No built-in world has the requested name; the message lists those that do."""


class InvalidStartError(CovmapError, ValueError):
    """An exploration cannot start where asked (the robot's disc overlaps an
    obstacle), or the robot fits nowhere to start; the message gives the
    position and the reason."""


class RobotError(CovmapError, RuntimeError):
    """The robot failed during an exploration run: its sensor or its drive
    could not do what the loop asked. Not caused by a bad argument: a
    :class:`RuntimeError`, not a :class:`ValueError`."""


class FileFormatError(CovmapError, ValueError):
    """A world or log file is malformed or degenerate.

    ``filename`` names the file, ``place`` where in it (a line, a feature, a
    pixel) and ``reason`` what is wrong there; the message says all three.
    """

    filename: str | None = None
    place: str | None = None
    reason: str | None = None


class FileIOError(CovmapError, OSError):
    """A file could not be read or written (``errno``, ``strerror`` and
    ``filename`` as for any :class:`OSError`; ``errno`` is ``None`` where
    covmap refused the file itself, a directory given for a file, say)."""

    def __str__(self) -> str:
        # OSError's text, once ``filename`` is set, is built from ``errno`` and
        # ``strerror`` alone: without an errno it would read
        # "[Errno None] ...", so the message (which names the file and the
        # reason) is the text then.
        if self.errno is None and len(self.args) == 1:
            return str(self.args[0])
        return super().__str__()


class InvalidSpecError(CovmapError, ValueError):
    """A spec of :func:`covmap.sweep` cannot run (an unknown key, a value of
    the wrong type or out of range, a world that does not pickle). ``index``
    is the spec's position in the list, ``reason`` what is wrong with it;
    the message says both."""

    def __init__(self, index: int, reason: str) -> None:
        super().__init__(f"spec {index}: {reason}")
        self.index = index
        self.reason = reason

    def __reduce__(self) -> tuple[type[InvalidSpecError], tuple[int, str]]:
        return type(self), (self.index, self.reason)


class InvalidExecutorError(CovmapError, ValueError):
    """An executor handed to :func:`covmap.sweep` cannot run its runs (no
    ``submit``, or a process pool that forks: covmap's thread pool does not
    survive a fork, and the children would wait for it forever)."""


class SchedulerError(CovmapError, OSError):
    """A Dask scheduler could not be reached at the address given (nothing
    listens there, or it did not answer in time)."""


class MissingDependencyError(CovmapError, ImportError):
    """An optional dependency a feature needs is not installed; the message
    says what to install (``pip install covmap[dask]`` for Dask)."""


class SweepError(CovmapError, RuntimeError):
    """Some runs of a sweep raised. Raised by :func:`covmap.sweep` after
    every run has ended, so that no result is lost: ``results`` holds one
    entry per spec in the specs' order (a ``RunSummary``, or ``None`` where
    the run failed), ``failures`` a ``SweepFailure`` per failed run (its
    spec's index, the exception's type name and message, and the exception
    itself)."""

    def __init__(self, results: list[Any], failures: list[Any]) -> None:
        shown = "; ".join(f"spec {f.index}: {f.error_type}: {f.message}" for f in failures[:5])
        more = f"; and {len(failures) - 5} more" if len(failures) > 5 else ""
        super().__init__(f"{len(failures)} of {len(results)} runs failed: {shown}{more}")
        self.results = results
        self.failures = failures

    def __reduce__(self) -> tuple[type[SweepError], tuple[list[Any], list[Any]]]:
        return type(self), (self.results, self.failures)
