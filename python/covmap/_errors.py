"""The exceptions of covmap.

Every error covmap raises for bad input is a :class:`CovmapError`; those caused
by a bad value are also a :class:`ValueError` (a cell index out of range is an
:class:`IndexError`, an array of the wrong dtype a :class:`TypeError`, a file
that cannot be read an :class:`OSError`), so code that catches the builtin
keeps working. A robot that fails during an exploration run raises
:class:`RobotError`, a :class:`RuntimeError`. The native module raises these classes.
"""

from __future__ import annotations

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
    "InvalidParameterError",
    "InvalidPolygonError",
    "InvalidPoseError",
    "InvalidRangeError",
    "InvalidStartError",
    "InvalidTypeError",
    "InvalidValueError",
    "LengthMismatchError",
    "PoseOutsideMapError",
    "RobotError",
    "UnknownWorldError",
]


class CovmapError(Exception):
    """Base class of every covmap error."""


class InvalidGridError(CovmapError, ValueError):
    """A grid was described with an unusable geometry."""


class InvalidParameterError(CovmapError, ValueError):
    """A sensor-model or map parameter (or a bin count) is out of its valid range."""


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


class ArrayShapeError(CovmapError, ValueError):
    """An array argument has the wrong number of dimensions or the wrong shape."""


class ArrayDtypeError(CovmapError, TypeError):
    """An array argument has the wrong element type (covmap never converts silently)."""


class InvalidTypeError(CovmapError, TypeError):
    """An argument has the wrong type: a model that is neither a SonarModel
    nor a LaserModel, a pickled state of the wrong form, a seed that is not an
    integer, arguments that exclude each other."""


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
    ``filename`` as for any :class:`OSError`)."""
