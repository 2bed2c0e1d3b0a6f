# Stubs of the native module covmap._native (built from crates/covmap-py). The
# signatures are written by hand; the docstrings are the module's own, written
# in by python/tools/gen_stubs.py and checked by python/tests/test_stubs.py.
# One file, longer than the others: stubtest checks the native module against
# one stub module, and every class of the module is declared here.
"""Native core of covmap (coverage maps, Stachniss and Burgard 2003). Import
from ``covmap`` instead.
"""

from collections.abc import Callable, Sequence
from os import PathLike
from typing import Any, ClassVar, Literal, final, overload, type_check_only

import numpy as np
import numpy.typing as npt
from typing_extensions import Self

from covmap._custom import CustomStrategy, StrategyView
from covmap._exploration import ExplorationResult, Step
from covmap.experiments.fig3 import Fig3Result

__all__ = [
    "__version__",
    "DEFAULT_BINS",
    "MIN_BINS",
    "MAX_BINS",
    "Grid",
    "SonarModel",
    "LaserModel",
    "CoverageMap",
    "OccupancyGrid",
    "Log",
    "STAGNATION_MEASUREMENTS",
    "STAGNATION_NATS",
    "MAP_FILE_VERSION",
    "expected_information_gain",
    "Planner",
    "Plan",
    "Candidates",
    "ExplorationStatus",
    "World",
    "Building",
    "Room",
    "Door",
    "SonarRing",
    "Laser",
    "Robot",
    "run_fig3",
    "run_learn",
    "log_likelihood",
    "fit_sensor_model",
    "SensorFit",
    "Strategy",
    "DEFAULT_DISCOUNT_BEYOND_M",
    "explore",
    "Exploration",
]

__version__: str
DEFAULT_BINS: int
MIN_BINS: int
MAX_BINS: int
STAGNATION_MEASUREMENTS: int
STAGNATION_NATS: float
MAP_FILE_VERSION: int
DEFAULT_DISCOUNT_BEYOND_M: float
_EXPLORE_DEFAULTS: dict[str, Any]

_Readings = npt.NDArray[np.float64] | npt.NDArray[np.float32] | Sequence[float]
_Ranges = npt.NDArray[np.float64] | npt.NDArray[np.float32]
_Progress = bool | Callable[[int, int], object]
_Pose = Sequence[float] | npt.NDArray[np.floating[Any]]
_Model = SonarModel | LaserModel
_Poses = npt.NDArray[np.float64] | npt.NDArray[np.float32] | Sequence[Sequence[float]]
_Points = npt.NDArray[np.float64] | Sequence[Sequence[float]]
_Point = Sequence[float] | npt.NDArray[np.floating[Any]]
_Path = str | PathLike[str]
_HistoryState = tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]
_Sensor = SonarRing | Laser

@final
class Grid:
    """A regular grid of square cells.

    ``origin`` is the world position (metres) of the lower-left corner of cell
    ``(row 0, col 0)``, ``resolution`` the side of a cell (metres), ``shape`` the
    number of cells as ``(rows, cols)``. Rows run along y and columns along x:
    cell ``(row, col)`` covers ``[ox + col*r, ox + (col+1)*r) x [oy + row*r,
    oy + (row+1)*r)``, and every per-cell array of this package is indexed
    ``[row, col]``. A resolution below 1e-6 m, more than 2**31 cells, or a
    corner more than 2**32 cells from zero raises ``InvalidGridError``.
    """

    def __new__(
        cls, *, origin: tuple[float, float], resolution: float, shape: tuple[int, int]
    ) -> Grid: ...
    @staticmethod
    def covering(bounds: tuple[float, float, float, float], *, resolution: float) -> Grid:
        """The grid covering ``bounds = (x_min, y_min, x_max, y_max)`` (metres),
        rounded up to whole cells of side ``resolution``.
        """
    @property
    def origin(self) -> tuple[float, float]:
        """World position of the lower-left corner, metres."""
    @property
    def resolution(self) -> float:
        """Side of a cell, metres."""
    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)``."""
    @property
    def rows(self) -> int:
        """Number of rows (cells along y)."""
    @property
    def cols(self) -> int:
        """Number of columns (cells along x)."""
    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """``(x_min, y_min, x_max, y_max)`` of the covered rectangle, metres."""
    def contains(self, x: float, y: float) -> bool:
        """Whether the world point lies in a cell of the grid: the rectangle with
        its upper edges excluded, up to rounding (a point on an upper edge may
        round into the last cell).
        """
    def world_to_cell(self, x: float, y: float) -> tuple[int, int] | None:
        """The ``(row, col)`` of the cell containing a world point, or ``None``
        outside the grid.
        """
    def cell_center(self, row: int, col: int) -> tuple[float, float]:
        """World position ``(x, y)`` of a cell's centre, metres (the cell need not
        lie inside the grid: a negative index counts on past the first row or
        column).
        """
    def __eq__(self, value: object, /) -> bool: ...
    def __ne__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    def __getnewargs_ex__(self) -> tuple[tuple[()], dict[str, Any]]:
        """Pickle and copy support: the keyword arguments that rebuild the grid."""

@type_check_only
class _RangeModel:
    """What both sensor models have: the range model's parameters and the
    methods over them."""

    PARAMETERS: ClassVar[tuple[str, ...]]
    """The names of the model's parameters, in the order of its keyword
    arguments (the core's declaration of them)."""
    # generated: properties(LaserModel)
    @property
    def max_range_m(self) -> float:
        """Readings at or beyond this distance mean "no echo", metres."""
    @property
    def band_m(self) -> float:
        """How far behind the end point cells are updated (as covered), metres."""
    @property
    def sigma_min(self) -> float:
        """Standard deviation of the coverage mean at zero distance, outside the end band."""
    @property
    def sigma_per_m(self) -> float:
        """Growth of that standard deviation per metre of distance `s = min(d_l, d)`."""
    @property
    def sigma_end(self) -> float:
        """The constant standard deviation inside the end band (the largest of all)."""
    @property
    def xi_min(self) -> float:
        """Weight of the uniform component at zero distance (must be positive)."""
    @property
    def xi_per_m(self) -> float:
        """Growth of the uniform weight per metre of distance `s = min(d_l, d)`."""
    @property
    def end_weight(self) -> float:
        """How strongly an echo marks the cells at and behind its end point
        (the end band and the band behind it), in `[0, 1]`: their kernels
        are mixed with the uniform prior by this weight. 1 (the
        default): the paper's kernels. A sonar's echo comes from somewhere
        on the arc of its cone, so most cells of the arc are not what it
        hit; a weight below 1 says so, where 1 marks the whole arc covered.
        """
    # end generated
    def kernel(
        self,
        cell_distance: float,
        measured_distance: float,
        *,
        resolution: float = 0.05,
        bins: int = 16,
    ) -> npt.NDArray[np.float32] | None:
        """The kernel a map multiplies into a cell at ``cell_distance`` (metres)
        for a reading of ``measured_distance`` (metres), on a grid of
        ``resolution`` (metres) with ``bins`` bins: a float32 array of shape
        ``(bins,)`` summing to 1, or ``None`` where the cell is not updated.
        A NaN, infinite or negative distance raises ``InvalidParameterError``.
        """
    def to_dict(self) -> dict[str, float]:
        """The parameters as a dict of keyword arguments."""
    @classmethod
    def from_dict(cls, d: dict[str, float]) -> Self:
        """The model with the parameters of ``d`` (missing ones take the defaults).
        The parameters covmap removed (``posterior_floor``, ``end_attribution``,
        ``free_yield`` at 0; ``no_echo_reach``, ``no_echo_weight`` at 1: each at its
        old default) may appear and are ignored; any other value of them raises
        ``InvalidParameterError``.
        """
    def __eq__(self, value: object, /) -> bool: ...
    def __ne__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...
    def __getnewargs_ex__(self) -> tuple[tuple[()], dict[str, float]]:
        """Pickle and copy support: the keyword arguments that rebuild the model."""

@final
class SonarModel(_RangeModel):
    """The sonar inverse model: a range model spread over a cone.

    Every cell whose centre lies within half the opening angle of the beam axis
    and no further than the reach of the reading is updated, with its centre's
    Euclidean distance from the sensor. Distances are in metres, angles in
    radians. Arguments left out (or ``None``) take the defaults of a
    Polaroid-class ultrasound sensor (15 degree cone, 5 m); every parameter is
    validated, and an invalid one raises ``InvalidParameterError``.
    """

    def __new__(
        cls,
        *,
        # generated: keywords(SonarModel)
        max_range_m: float | None = None,
        band_m: float | None = None,
        sigma_min: float | None = None,
        sigma_per_m: float | None = None,
        sigma_end: float | None = None,
        xi_min: float | None = None,
        xi_per_m: float | None = None,
        end_weight: float | None = None,
        opening_angle_rad: float | None = None,
        # end generated
    ) -> SonarModel: ...
    # generated: properties(SonarModel - LaserModel)
    @property
    def opening_angle_rad(self) -> float:
        """Full opening angle of the cone, radians, in `(0, pi)`."""
    # end generated

@final
class LaserModel(_RangeModel):
    """The laser inverse model: a range model along a thin beam.

    Every cell the ray crosses up to the reach of the reading is updated once,
    with the distance of its centre projected on the ray. Distances are in
    metres. Arguments left out (or ``None``) take the defaults of a SICK-class
    laser (30 m, sharp readings); an invalid parameter raises
    ``InvalidParameterError``.
    """

    def __new__(
        cls,
        *,
        # generated: keywords(LaserModel)
        max_range_m: float | None = None,
        band_m: float | None = None,
        sigma_min: float | None = None,
        sigma_per_m: float | None = None,
        sigma_end: float | None = None,
        xi_min: float | None = None,
        xi_per_m: float | None = None,
        end_weight: float | None = None,
        # end generated
    ) -> LaserModel: ...

@final
class CoverageMap:
    """A grid whose every cell holds a histogram over how much of it is covered by
    obstacles (0 = empty, 1 = fully covered), starting at the uniform prior.

    ``bins`` (2 to 256) is the number of coverage values; bin ``b`` stands for
    coverage ``b / (bins - 1)``. Per-cell arrays are indexed ``[row, col]`` as
    in ``Grid``.
    """

    def __new__(cls, grid: Grid, bins: int = 16) -> CoverageMap: ...
    @classmethod
    def from_histograms(cls, grid: Grid, histograms: npt.NDArray[np.float32]) -> CoverageMap:
        """A map over ``grid`` from stored histograms: a float32 array of shape
        ``(rows, cols, bins)`` whose every histogram is finite, non-negative and
        sums to 1 within 1e-3 (``.histograms`` of another map, for instance).
        """
    @property
    def grid(self) -> Grid:
        """The grid."""
    @property
    def bins(self) -> int:
        """Bins per cell."""
    @property
    def bin_values(self) -> npt.NDArray[np.float64]:
        """The coverage value of each bin, ``b / (bins - 1)``: float64, ``(bins,)``."""
    @property
    def histograms(self) -> npt.NDArray[np.float32]:
        """A copy of all histograms: float32, ``(rows, cols, bins)``."""
    def histogram(self, row: int, col: int) -> npt.NDArray[np.float32]:
        """One cell's histogram: float32, ``(bins,)``."""
    def ml(self) -> npt.NDArray[np.float32]:
        """The maximum-likelihood map: each cell's most probable coverage value,
        float32, ``(rows, cols)``.
        """
    def mean(self) -> npt.NDArray[np.float32]:
        """The mean map: each cell's expected coverage, float32, ``(rows, cols)``."""
    def entropy(self) -> npt.NDArray[np.float32]:
        """The entropy map in nats (``ln(bins)`` at the prior, 0 when certain),
        float32, ``(rows, cols)``.
        """
    def observed(self) -> npt.NDArray[np.bool_]:
        """Which cells some evidence reached (a reading, or the robot touching an
        obstacle): those whose histogram is no longer the uniform prior, bool,
        ``(rows, cols)``. Unknown is a value of its own: an unobserved cell
        reads 0 on ``ml()``, as an empty cell does, and this tells them apart.
        """
    def integrate(
        self, pose: _Pose, ranges: _Readings, bearings: _Readings, model: _Model
    ) -> int:
        """Integrate one scan taken from ``pose = (x, y, theta)`` (metres, radians):
        reading ``ranges[i]`` (metres) along ``theta + bearings[i]`` (radians).
        ``ranges`` and ``bearings`` are 1-D float64 or float32 arrays (or sequences of
        numbers) of equal length; a reading at or beyond the model's maximum
        range means "no echo". ``model`` is a ``SonarModel`` or a
        ``LaserModel``. Returns the number of cell updates.

        Everything is checked before anything changes: after an error the map
        is exactly as it was. The update runs with the GIL released; touching
        the same map from another thread meanwhile raises ``RuntimeError``.
        """
    def integrate_log(
        self, log: Log, model: _Model, *, occlude_no_echo: bool = False, progress: _Progress = False
    ) -> int:
        """Integrate every scan of ``log`` (a ``Log``) with ``model``, in order;
        returns the number of cell updates. Each scan is taken from its sensor pose (the robot's
        pose with the log's sensor offset); dropped beams (NaN) are skipped; a
        reading without echo clears up to the lesser of the log's and the
        model's maximum range. With ``occlude_no_echo`` every echo reading
        goes first into a copy of the map (as much memory again); then every
        scan goes in read against the cells that copy holds covered and is
        certain of (entropy at most 0.65 nats, the default epsilon; the
        exploration loop's rule, with every echo known; the map does not
        depend on the order of the scans): a no-echo reading clears only
        what its line of sight reaches past them (through a wall the echoes
        found it is taken for a specular miss), and an echo off one of them
        marks only the cells at its bearing and the certain ones, not the
        rest of its arc (model.md, section 5). Every
        scan is checked first: a scan whose
        sensor pose lies outside the map raises (``PoseOutsideMapError``, the
        message naming the scan) and leaves the map exactly as it was.
        ``progress``: ``True`` shows a bar (tqdm's if installed), a callable
        is called as ``progress(done, total)``; if it raises (or Ctrl-C
        interrupts the bar), the error is raised once the scans are in and
        the map is left as it was (with a progress display the scans go into
        a copy, which takes as much memory again). Runs with the GIL
        released.
        """
    def save(self, path: str | PathLike[str], *, compress: bool = True) -> None:
        """Save the whole posterior (grid, bins, histograms, the entropy history
        if kept) to ``path``: a versioned ``.npz`` archive that
        ``numpy.load`` opens without covmap (``covmap_version``, ``grid`` =
        origin x, origin y, resolution, ``histograms`` (rows, cols, bins),
        ``history_entropies`` and ``history_counts``), each entry with a
        CRC-32; deflated (``compress``, as ``numpy.savez_compressed``
        writes) or stored as they are. Written atomically: a reader never
        sees half a file, and a failed write leaves ``path`` as it was
        (``FileIOError``). Runs with the GIL released.
        """
    def ros_occupancy(
        self, *, source: Literal["ml", "mean"] = "ml", unknown_within_nats: float = 0.05
    ) -> npt.NDArray[np.int8]:
        """The map as ``nav_msgs/OccupancyGrid`` data: int8 ``(rows, cols)``,
        ``source``'s coverage (``"ml"`` or ``"mean"``) in percent, ``-1``
        (unknown) for every cell whose entropy is still within
        ``unknown_within_nats`` of the prior's ``ln(bins)`` (0: only cells no
        evidence reached). Row 0 is the grid's row 0, as in the message.
        """
    def to_ros_map(
        self,
        yaml_path: str | PathLike[str],
        *,
        mode: Literal["trinary", "scale"] = "trinary",
        occupied_thresh: float = 0.65,
        free_thresh: float = 0.196,
        source: Literal["ml", "mean"] = "ml",
        unknown_within_nats: float = 0.05,
    ) -> None:
        """Write the map as ROS map_server / nav2 map_saver do: ``yaml_path``
        and the PGM of the same name beside it, from ``ros_occupancy(source=,
        unknown_within_nats=)``; ``mode`` ``"trinary"`` (black at or above
        ``occupied_thresh``, white at or below ``free_thresh``, grey between
        and unknown) or ``"scale"`` (grey by occupancy, unknown 205).
        ``World.from_file(yaml_path)`` reads the pair back. The pair is
        written together: both files whole to temporary files first, then
        renamed into place, the old pair kept if either fails
        (``FileIOError``); a ``yaml_path`` ending in ``.pgm`` is refused.
        """
    @staticmethod
    def load(path: str | PathLike[str]) -> CoverageMap:
        """The map ``save`` wrote to ``path``, bit for bit. A file that is not a
        whole, unchanged map file (empty, cut short, a byte changed, a newer
        version) raises ``FileFormatError``, one that cannot be read
        ``FileIOError``; never a wrong map. Runs with the GIL released.
        """
    def track_history(self, on: bool) -> None:
        """Keep (``True``) or stop keeping (``False``) each cell's entropy after
        its last measurements, for ``stagnated()`` and ``Planner.status``. A
        scan that updates a cell counts as one measurement of it. Off by
        default; turning it on (again) starts an empty history. Pickling and
        copying keep the history.
        """
    @property
    def tracks_history(self) -> bool:
        """Whether the entropy history is kept."""
    def measurements(self) -> npt.NDArray[np.uint32]:
        """How many scans updated each cell since the history was turned on:
        uint32, ``(rows, cols)`` (all zero while it is off).
        """
    def stagnated(self) -> npt.NDArray[np.bool_]:
        """Whether each cell's entropy changed by less than 0.001 nats over its
        last five measurements: bool, ``(rows, cols)`` (all ``False`` while the
        history is off or shorter).
        """
    def __reduce__(
        self,
    ) -> tuple[Any, tuple[Grid, npt.NDArray[np.float32]], _HistoryState | None]:
        """Pickle and copy support: rebuilt from the grid and the histograms,
        the entropy history (if kept) and the evidence behind the histograms
        (each cell's log-likelihoods, which hold more than the histograms
        do) restored by ``__setstate__``, so that a copy goes on as the
        original does.
        """
    def __setstate__(self, state: _HistoryState | None) -> None:
        """Unpickling support: restore the state ``__reduce__`` saves,
        ``(history, evidence)``: the entropy history, ``None`` or
        ``(entropies, counts)`` (float32 ``(rows, cols,
        STAGNATION_MEASUREMENTS + 1)`` and uint32 ``(rows, cols)``), kept
        tracking, and the evidence, float32 ``(rows, cols, bins)``, which must
        give the map's histograms. ``None`` or ``(entropies, counts)`` alone
        (what earlier versions saved) restore the history only. After an
        error the map is exactly as it was.
        """

@final
class Log:
    """A recorded drive: scan ``i`` taken at ``timestamps[i]`` from robot pose
    ``poses[i]`` (x, y metres, theta radians), reading ``ranges[i, k]``
    metres along ``bearings[k]`` (or ``bearings[i, k]``, bearings of each
    scan), radians from the heading of a sensor mounted at
    ``sensor_offset`` on the robot.

    A range at or above ``max_range_m`` has no echo; a NaN range is a beam
    without a reading (``from_laser_scans`` makes them of REP 117's NaN and
    ``-inf``), which integrating skips. The constructor itself refuses NaN,
    infinite and negative ranges. ``len(log)`` counts scans; ``log[a:b]`` is
    a log of those scans. Logs pickle.
    """

    def __new__(
        cls,
        poses: _Poses,
        ranges: _Ranges,
        bearings: _Readings | npt.NDArray[np.float64],
        *,
        max_range_m: float,
        timestamps: _Readings | None = None,
        sensor_offset: tuple[float, float, float] = (0.0, 0.0, 0.0),
    ) -> Log: ...
    @staticmethod
    def from_carmen(
        path: str | PathLike[str], *, max_range_m: float | None = None, laser: Literal["front", "rear"] = "front"
    ) -> Log:
        """The log in a CARMEN file (plain or gzip): ``FLASER``, ``ROBOTLASER1``
        or ``RAWLASER1`` scans (poses from ``ODOM`` interpolated for the
        last); with ``laser="rear"`` the rear laser's ``RLASER``,
        ``ROBOTLASER2`` or ``RAWLASER2`` scans and mounting instead.
        ``max_range_m`` overrides the log's maximum range. A malformed line
        raises ``FileFormatError`` naming the file and the line. Reads with
        the GIL released.
        """
    @staticmethod
    def from_sonar_text(
        poses_path: str | PathLike[str],
        measurements_path: str | PathLike[str],
        *,
        bearings_deg: _Readings,
        length_unit_m: float = 1.0,
        range_unit_m: float | None = None,
        angle_unit_rad: float = 1.0,
        min_range_m: float = 0.0,
        max_range_m: float,
        no_echo: float | None = None,
    ) -> Log:
        """The sonar log of two text files read in step: ``poses_path`` lines
        ``timestamp x y theta``, ``measurements_path`` lines ``timestamp r_0
        … r_{B-1}`` (plain or gzip). ``bearings_deg`` gives each column's
        sonar, degrees from the heading. The poses' ``x`` and ``y`` are in
        units of ``length_unit_m`` metres, the ranges in units of
        ``range_unit_m`` (default: ``length_unit_m``), the heading in
        ``angle_unit_rad`` radians. A reading equal to ``no_echo`` (in the
        file's units), or at or above ``max_range_m``, has no echo; one below
        ``min_range_m`` is dropped (NaN); a negative one is an error.
        """
    @staticmethod
    def from_laser_scans(
        poses: _Poses,
        ranges: _Ranges,
        *,
        angle_min: float,
        angle_increment: float,
        range_min: float,
        range_max: float,
        timestamps: _Readings | None = None,
    ) -> Log:
        """Scans as ROS ``sensor_msgs/LaserScan`` hands them: ``ranges`` (N, B)
        float32 or float64, beam ``k`` at ``angle_min + k angle_increment``.
        REP 117 is converted here: ``+inf`` and readings above ``range_max``
        have no echo; NaN, ``-inf`` and readings below ``range_min`` are
        dropped (NaN in ``ranges``). ``range_max`` is the log's maximum range.
        """
    @staticmethod
    def from_bag(
        path: str | PathLike[str],
        *,
        topic: str | None = None,
        odom_topic: str | None = None,
        base_frame: str | None = None,
        fixed_frame: str | None = None,
        max_range_m: float | None = None,
    ) -> Log:
        """The log of one sensor in a ROS 1 (``.bag``) or ROS 2 bag, read with
        the ``rosbags`` package (``pip install 'covmap[rosbags]'``): the
        ``sensor_msgs/LaserScan`` or ``sensor_msgs/Range`` messages on
        ``topic`` (default: the bag's only such topic), REP 117 converted as
        ``from_laser_scans`` does; the robot's poses from the
        ``nav_msgs/Odometry`` on ``odom_topic``, else from ``/tf``
        (``base_frame``, default ``base_link``, in ``fixed_frame``, default
        the tree's root), interpolated at each message's stamp; the sensor's
        mounting from ``/tf_static``. ``max_range_m`` overrides the messages'
        maximum range. A bag that cannot be read or lacks what is asked
        raises ``FileFormatError`` naming the file (see ``covmap._bag``).
        """
    @property
    def poses(self) -> npt.NDArray[np.float64]:
        """The robot's pose of every scan, float64, ``(N, 3)``."""
    @property
    def ranges(self) -> npt.NDArray[np.float64]:
        """Every range, metres, float64, ``(N, B)`` (NaN: a dropped beam)."""
    @property
    def bearings(self) -> npt.NDArray[np.float64]:
        """The bearings, radians from the sensor's heading, float64: ``(B,)``,
        or ``(N, B)`` for a log whose scans have bearings of their own.
        """
    @property
    def timestamps(self) -> npt.NDArray[np.float64]:
        """The time of every scan, seconds, float64, ``(N,)``."""
    @property
    def max_range_m(self) -> float:
        """The sensor's maximum range, metres: a reading at or above it has no echo."""
    @property
    def sensor_offset(self) -> tuple[float, float, float]:
        """Where the sensor sits on the robot, ``(x, y, theta)`` in the robot's frame."""
    @property
    def beams(self) -> int:
        """The number of beams a scan."""
    def extent(self, reach_m: float) -> tuple[float, float, float, float] | None:
        """``(x_min, y_min, x_max, y_max)`` covering every pose and every beam's
        end point, each beam cut at ``reach_m`` metres (no-echo beams end at
        the maximum range); ``None`` for an empty log.
        """
    def with_sensor_offset(self, offset: _Pose) -> Log:
        """This log with its sensor mounted at ``offset`` ``(x, y, theta)`` on
        the robot.
        """
    def __len__(self) -> int: ...
    def __getitem__(self, key: slice, /) -> Log: ...
    def __reduce__(self) -> tuple[Any, tuple[bytes]]:
        """Pickle support: rebuilt by ``Log._from_state`` from the core's
        serialised form (JSON bytes, every float64 exact).
        """
    @staticmethod
    def _from_state(state: bytes) -> Log:
        """Unpickling support: the log saved by ``__reduce__`` (validated)."""

@final
class OccupancyGrid:
    """A standard log-odds occupancy grid (every cell at p = 0.5 to start), fed by
    the same beams as a ``CoverageMap``, with the scan counts of those beams.

    A cell in front of the reading's end point is observed free (p = 0.35), the
    end point's cell occupied (p = 0.7), cells behind are not touched; log-odds
    are clamped to ``[-5, 5]``. Per-cell arrays are indexed ``[row, col]``.
    """

    def __new__(cls, grid: Grid) -> OccupancyGrid: ...
    @property
    def grid(self) -> Grid:
        """The grid."""
    def integrate(
        self, pose: _Pose, ranges: _Readings, bearings: _Readings, model: _Model
    ) -> None:
        """Integrate one scan; arguments and checks as ``CoverageMap.integrate``.
        After an error the grid is exactly as it was. The update runs with the
        GIL released.
        """
    def ros_occupancy(self) -> npt.NDArray[np.int8]:
        """The grid as ``nav_msgs/OccupancyGrid`` data: int8 ``(rows, cols)``,
        the probability of occupancy in percent, ``-1`` (unknown) where no
        evidence reached.
        """
    def to_ros_map(
        self,
        yaml_path: str | PathLike[str],
        *,
        mode: Literal["trinary", "scale"] = "trinary",
        occupied_thresh: float = 0.65,
        free_thresh: float = 0.196,
    ) -> None:
        """Write the grid as ROS map_server / nav2 map_saver do: ``yaml_path``
        and the PGM of the same name beside it, from ``ros_occupancy()``;
        ``mode`` as ``CoverageMap.to_ros_map``. ``World.from_file(yaml_path)``
        reads the pair back.
        """
    def integrate_log(self, log: Log, model: _Model, *, progress: _Progress = False) -> int:
        """Integrate every scan of ``log`` (a ``Log``) with ``model``, in order;
        returns the number of scans. Each scan is taken from its sensor pose (the robot's
        pose with the log's sensor offset); dropped beams (NaN) are skipped; a
        reading without echo clears up to the lesser of the log's and the
        model's maximum range. Every scan is checked first: a scan whose
        sensor pose lies outside the map raises (``PoseOutsideMapError``, the
        message naming the scan) and leaves the map exactly as it was.
        ``progress``: ``True`` shows a bar (tqdm's if installed), a callable
        is called as ``progress(done, total)``; if it raises (or Ctrl-C
        interrupts the bar), the error is raised once the scans are in and
        the grid is left as it was (with a progress display the scans go into
        a copy, which takes as much memory again). Runs with the GIL
        released.
        """
    def probabilities(self) -> npt.NDArray[np.float32]:
        """Probability of occupancy, float32, ``(rows, cols)``."""
    def log_odds(self) -> npt.NDArray[np.float32]:
        """Log-odds of occupancy, float32, ``(rows, cols)``."""
    def counts(self) -> npt.NDArray[np.float32]:
        """How many beams intercepted each cell (up to its end point), float32,
        ``(rows, cols)``.
        """
    def observed(self) -> npt.NDArray[np.bool_]:
        """Which cells some evidence reached (a beam intercepted them, or the
        robot touched an obstacle there): bool, ``(rows, cols)``. The others are
        unknown, whatever ``probabilities()`` reads there (0.5).
        """
    def __getnewargs__(self) -> tuple[Grid]:
        """Pickle and copy support: the grid, for ``__new__``."""
    def __getstate__(self) -> bytes:
        """Pickle and copy support: the model, log-odds and counts, as the
        core's serialised form (JSON bytes; every float32 value exact).
        """
    def __setstate__(self, state: bytes) -> None:
        """Unpickling support: restore the state saved by ``__getstate__``
        (validated: a valid model, one log-odds value within its limit and one
        finite, non-negative count per cell of this grid). After an error the
        grid is exactly as it was.
        """

def expected_information_gain(
    map: CoverageMap,
    poses: _Poses,
    bearings: _Readings,
    model: _Model,
    method: Literal["fast", "exact"] = "fast",
    *,
    range_step_m: float | None = None,
    stop_coverage: Literal["ml", "maximum_likelihood", "mean"] = "ml",
) -> npt.NDArray[np.float64]:
    """The expected information gain (nats) of scanning ``map`` from each of
    ``poses`` (float64 ``(N, 3)`` of ``(x, y, theta)``) with beams at
    ``bearings`` (radians, relative to each heading) through ``model``: float64
    ``(N,)`` (paper eq. 11-13).

    ``method`` is ``"fast"`` (the production evaluator) or ``"exact"`` (the
    equation as written, equal to rounding). Predicted readings are spaced
    ``range_step_m`` apart (default: the grid resolution; between 1/1024 of
    it and it), and
    a predicted beam is stopped by each cell's ``stop_coverage``: ``"ml"``
    (most probable coverage, the paper's choice) or ``"mean"``. A pose outside
    the map or not finite raises; the map is never changed. Runs with the GIL
    released, candidates in parallel.
    """

@final
class Planner:
    """The decision-theoretic exploration planner.

    A cell *blocks* when its coverage on the ML map exceeds
    ``blocked_coverage`` and is *unknown* while its entropy is at least
    ``unknown_entropy_fraction`` of the prior's; the robot (a disc of
    ``robot_radius_m``) keeps its disc clear of blocked cells and, unless
    ``unknown_is_free``, of unknown ones; paths are 8-connected between cell
    centres (from where the robot stands, it may also cross the unblocked
    cells its disc overlaps there). Candidates are the reachable free cells on a
    lattice of ``candidate_stride_m``, at least ``min_travel_m`` away, whose
    expected gain exceeds ``min_gain_nats``; the chosen one maximises
    ``alpha * gain / max gain - (1 - alpha) * cost / max cost`` (``alpha = 0``:
    nearest, ``1``: most informative). Exploration is done when every
    reachable cell has entropy below ``epsilon`` or has stagnated.
    ``range_step_m`` and ``stop_coverage`` configure the gain as in
    ``expected_information_gain``.

    Arguments left out (or ``None``) take the defaults, readable as
    attributes; an invalid one raises ``InvalidParameterError``.
    """

    def __new__(
        cls,
        *,
        alpha: float | None = None,
        robot_radius_m: float | None = None,
        candidate_stride_m: float | None = None,
        min_travel_m: float | None = None,
        min_gain_nats: float | None = None,
        blocked_coverage: float | None = None,
        unknown_entropy_fraction: float | None = None,
        unknown_is_free: bool | None = None,
        epsilon: float | None = None,
        range_step_m: float | None = None,
        stop_coverage: Literal["ml", "maximum_likelihood", "mean"] | None = None,
    ) -> Planner: ...
    @property
    def alpha(self) -> float:
        """Weight of information against travel, in ``[0, 1]``."""
    @property
    def robot_radius_m(self) -> float:
        """Radius of the disc robot, metres; paths keep a cell more (at least 5 cm)
        from blocked cells.
        """
    @property
    def candidate_stride_m(self) -> float:
        """Spacing of the candidate lattice, metres."""
    @property
    def min_travel_m(self) -> float:
        """Candidates closer than this along the path are not goals, metres."""
    @property
    def min_gain_nats(self) -> float | None:
        """Candidates whose expected gain is at most this are not goals, nats;
        ``None`` (the default): what making one cell at the prior certain is
        worth, ``ln(bins) - epsilon``, at least 1 nat (the exploration loop's rule).
        """
    @property
    def blocked_coverage(self) -> float:
        """Coverage on the ML map above which a cell blocks the robot."""
    @property
    def unknown_entropy_fraction(self) -> float:
        """A cell is unknown while its entropy is at least this fraction of the prior's."""
    @property
    def unknown_is_free(self) -> bool:
        """Whether the robot may plan through unknown cells."""
    @property
    def epsilon(self) -> float:
        """Entropy below which a cell counts as explored, nats."""
    @property
    def range_step_m(self) -> float | None:
        """Spacing of the predicted readings, metres (``None``: the grid resolution)."""
    @property
    def stop_coverage(self) -> Literal["ml", "mean"]:
        """Which coverage stops a predicted beam: ``"ml"`` or ``"mean"``."""
    def least_gain_nats(self, bins: int = 16) -> float:
        """The least expected gain a candidate must promise to be a goal on a
        map of ``bins`` bins, nats: ``min_gain_nats``, or by default what
        making one cell at the prior certain is worth, ``ln(bins) - epsilon``,
        at least 1 nat.
        """
    def next_viewpoint(
        self, map: CoverageMap, pose: _Pose, bearings: _Readings, model: _Model
    ) -> Plan:
        """Choose the next viewpoint for a robot at ``pose = (x, y, theta)`` on
        ``map``, scanning with beams at ``bearings`` through ``model``. Runs
        with the GIL released; the map is not changed.
        """
    def status(self, map: CoverageMap, pose: _Pose) -> ExplorationStatus:
        """How far exploration of ``map`` has come for a robot at ``pose``."""
    def free_space(self, map: CoverageMap) -> npt.NDArray[np.bool_]:
        """Where the robot's centre may be on ``map``: bool, ``(rows, cols)``."""
    def path_costs(self, map: CoverageMap, pose: _Pose) -> npt.NDArray[np.float64]:
        """The length of a shortest path from ``pose`` to every cell over the
        robot's free space, metres: float64, ``(rows, cols)``, ``inf`` where
        unreachable.
        """
    def __getnewargs_ex__(self) -> tuple[tuple[()], dict[str, Any]]:
        """Pickle and copy support: the keyword arguments that rebuild the planner."""

@final
class Plan:
    """The planner's answer: the chosen viewpoint, the path to it and every
    candidate considered.
    """

    @property
    def pose(self) -> npt.NDArray[np.float64] | None:
        """The chosen viewpoint ``(x, y, theta)``, float64 ``(3,)``; ``None`` when
        no candidate is worth visiting.
        """
    @property
    def path(self) -> npt.NDArray[np.float64]:
        """The path to it: cell centres from the robot's cell to the goal's,
        float64 ``(K, 2)`` (``K = 0`` without a goal).
        """
    @property
    def chosen(self) -> int | None:
        """Index of the chosen candidate in ``candidates``, or ``None``."""
    @property
    def gain(self) -> float | None:
        """Expected information gain of the chosen viewpoint, nats, or ``None``."""
    @property
    def cost(self) -> float | None:
        """Path length to the chosen viewpoint, metres, or ``None``."""
    @property
    def candidates(self) -> Candidates:
        """Every candidate considered."""

@final
class Candidates:
    """The candidates a ``Plan`` considered, one entry per candidate."""

    @property
    def poses(self) -> npt.NDArray[np.float64]:
        """Candidate poses ``(x, y, theta)``: float64 ``(M, 3)``."""
    @property
    def gains(self) -> npt.NDArray[np.float64]:
        """Expected information gain of each, nats: float64 ``(M,)``."""
    @property
    def costs(self) -> npt.NDArray[np.float64]:
        """Path length from the robot to each, metres: float64 ``(M,)``."""
    @property
    def utilities(self) -> npt.NDArray[np.float64]:
        """Eq. 14's utility of each (``-inf`` for those that are no goal):
        float64 ``(M,)``.
        """
    def __len__(self) -> int: ...

@final
class ExplorationStatus:
    """How far exploration has come (``Planner.status``)."""

    @property
    def reachable_cells(self) -> int:
        """Cells connected to the robot through cells not blocked."""
    @property
    def certain_cells(self) -> int:
        """Of those, cells with entropy below epsilon."""
    @property
    def stagnated_cells(self) -> int:
        """Of the rest, cells whose entropy stagnated."""
    @property
    def done(self) -> bool:
        """Whether every reachable cell is certain or stagnated."""
    def __eq__(self, value: object, /) -> bool: ...
    def __ne__(self, value: object, /) -> bool: ...

@final
class Building:
    """A building: a ``World`` with its rooms and doors, so that an
    exploration can be judged room by room (``rooms_never_entered``).

    Make one with a static method: ``Building.generate(seed, ...)`` (a
    seeded floor plan), ``Building.from_file(path)`` (a real plan, a
    map_server pair), ``Building.builtin(name)`` or
    ``Building.from_world(world, name)``. Buildings pickle.
    """

    @staticmethod
    def generate(
        seed: int,
        *,
        area_m2: float = 200.0,
        clutter: float = 0.5,
        glass: float = 0.2,
        door_width_m: tuple[float, float] = (0.8, 1.2),
        corridor_width_m: tuple[float, float] = (1.5, 3.0),
        room_size_m: tuple[float, float] = (2.5, 6.0),
        wall_thickness_m: tuple[float, float] = (0.1, 0.2),
    ) -> Building:
        """The building of ``seed`` (0 to 2**64 - 1): corridors (straight, L
        or T) with rooms along them, rooms behind rooms, open halls with
        pillars, doors ``door_width_m`` wide, furniture that never blocks a
        door, pillars along corridors, slanted walls and glass fronts.
        ``area_m2``: the floor area, walls included (550 is AMROffice's
        size); ``clutter``: furniture, from 0 (none) to 1 (a piece per 2.5
        square metres); ``glass``: the share of glass room fronts; the
        ranges ``(least, most)`` of door, corridor and room widths and wall
        thicknesses, metres. Every room is reachable by a disc of 0.25 m
        from the first corridor. The same seed and parameters give the same
        building on every machine. A parameter out of its range (NaN, a
        negative size, a door narrower than the robot, rooms that cannot
        hold the widest door, an area too small for a corridor and two
        rooms) raises ``InvalidParameterError`` naming it.
        """
    @staticmethod
    def from_world(world: World, name: str = "world") -> Building:
        """``world`` as a building named ``name``, its rooms found by the rule
        for plans: the parts of the free space where the robot may start
        that passages narrower than 1.3 m (doorways) separate, each at
        least 0.25 square metres beyond 0.65 m from every obstacle (its
        core); a run enters one when the robot's centre crosses its core.
        Doors are not listed.
        """
    @staticmethod
    def builtin(name: str) -> Building:
        """A built-in world as a building (``World.builtin``; rooms by the
        rule of ``from_world``), named by its name.
        """
    @staticmethod
    def from_file(
        path: _Path,
        *,
        wall_thickness_m: float | None = None,
        resolution: float | None = None,
        origin: tuple[float, float] | None = None,
    ) -> Building:
        """A world file as a building (``World.from_file``, the same
        arguments; rooms by the rule of ``from_world``), named by the
        file's name.
        """
    @property
    def name(self) -> str:
        """Its name: ``"generated:SEED"`` (``"generated:SEED:AREA"`` for
        another area than the default), a plan's file name, a built-in
        world's name.
        """
    @property
    def world(self) -> World:
        """The world: walls, furniture, pillars and glass."""
    @property
    def rooms(self) -> list[Room]:
        """The rooms, corridors and halls, in order (doors name them by index)."""
    @property
    def doors(self) -> list[Door]:
        """The doors."""
    @property
    def floor_area_m2(self) -> float:
        """The area of the rooms' floors, square metres."""
    def rooms_entered(self, trajectory: _Points) -> npt.NDArray[np.bool_]:
        """Whether the robot's centre, driving straight from each point of
        ``trajectory`` (``(K, 2)`` points or ``(K, 3)`` poses, as
        ``ExplorationResult.trajectory``) to the next, entered each room:
        a bool array, one a room.
        """
    def rooms_never_entered(self, trajectory: _Points) -> list[str]:
        """The names of the rooms and halls (not corridors) that
        ``trajectory`` never entered (see ``rooms_entered``).
        """
    def to_json(self) -> str:
        """The building as JSON text (its world as GeoJSON, its rooms and
        doors); ``Building.from_json`` reads it back.
        """
    @staticmethod
    def from_json(text: str) -> Building:
        """A building from ``to_json``'s text; ``FileFormatError`` for text
        that is not one.
        """
    def __reduce__(self) -> tuple[Any, tuple[str]]:
        """Pickle and copy support: rebuilt by ``Building.from_json``."""

@final
class Room:
    """A room, corridor or hall of a ``Building``: its name, its kind and its
    floor (axis-aligned rectangles between its walls' faces).
    """

    @property
    def name(self) -> str:
        """Its name, unique in the building (``"room 3"``, ``"corridor 1"``,
        ``"region 2"``).
        """
    @property
    def kind(self) -> str:
        """``"room"``, ``"corridor"`` or ``"hall"``."""
    @property
    def floor(self) -> npt.NDArray[np.float64]:
        """The floor: ``(K, 4)`` float64 rectangles ``(x_min, y_min, x_max,
        y_max)``, metres.
        """
    @property
    def area_m2(self) -> float:
        """The floor's area, square metres."""

@final
class Door:
    """A door of a ``Building``: an opening in a wall between two rooms."""

    @property
    def center(self) -> tuple[float, float]:
        """The middle of the opening, ``(x, y)``, metres."""
    @property
    def width_m(self) -> float:
        """The opening's clear width, metres."""
    @property
    def wall_angle_rad(self) -> float:
        """The direction of the wall it is in, radians (0: along x)."""
    @property
    def rooms(self) -> tuple[int, int]:
        """The indices in ``Building.rooms`` of the two rooms it joins."""

@final
class World:
    """A set of obstacle polygons in the plane (metres); everything outside them
    is free space, and overlapping polygons are their union.

    ``polygons`` is a list of vertex arrays, each of shape ``(N, 2)`` (float64
    numpy arrays or sequences of ``(x, y)``), in either orientation, closed or
    not. ``materials`` (optional) gives each polygon's surface, ``"wall"``
    (the default) or ``"glass"``, which decides how it echoes ultrasound. A
    polygon that is not simple, has fewer than three distinct vertices or no
    area raises ``InvalidPolygonError`` naming its index.
    """

    def __new__(
        cls, polygons: Sequence[_Points], materials: Sequence[str] | None = None
    ) -> World: ...
    @staticmethod
    def builtin(name: str) -> World:
        """A built-in world by name (see ``World.builtin_names()``): ``"corridor"``
        (the paper's Fig. 3), ``"office"``, ``"partial"`` (Fig. 1). An unknown
        name raises ``UnknownWorldError``.
        """
    @staticmethod
    def builtin_names() -> list[str]:
        """The names of the built-in worlds."""
    @staticmethod
    def from_file(
        path: _Path,
        *,
        wall_thickness_m: float | None = None,
        resolution: float | None = None,
        origin: tuple[float, float] | None = None,
    ) -> World:
        """A world from a file, by its extension:

        - ``.json``, ``.geojson``: GeoJSON polygons in metres (a feature's
          ``properties.material`` is ``"wall"`` or ``"glass"``);
        - ``.map``: the ``LINES`` of an ARIA map, each a wall
          ``wall_thickness_m`` thick (default 0.1 m);
        - ``.yaml``, ``.yml``: a ROS map_server YAML file and its image;
        - ``.pgm``, ``.png``: an occupancy image (dark = occupied) of
          ``resolution`` metres per pixel, its lower-left corner at ``origin``
          (default ``(0, 0)``); ``resolution`` is required.

        In an image, the pixels that are not free (occupancy below the
        YAML's ``free_thresh``, default 0.196) are obstacles: the occupied
        ones and the unknown grey ones, so that a robot never drives in
        space the map did not see; a map_server file in ``mode: scale``
        makes obstacles of the occupied pixels only.

        An option the file's format does not use (``resolution`` for a
        GeoJSON file, say) raises ``InvalidParameterError``: it would be
        ignored. A malformed file raises ``FileFormatError`` (a ``ValueError``) naming
        the file and the place; a file that cannot be read raises
        ``FileIOError`` (an ``OSError``).
        """
    def to_geojson(self) -> str:
        """The world as GeoJSON text (``World.from_file`` reads it back from a
        ``.geojson`` file).
        """
    @property
    def bounds(self) -> tuple[float, float, float, float]:
        """``(x_min, y_min, x_max, y_max)`` of all obstacles, metres (all zero when
        there are none).
        """
    @property
    def polygons(self) -> list[npt.NDArray[np.float64]]:
        """The exterior ring of each polygon: a list of float64 ``(N, 2)`` arrays."""
    @property
    def holes(self) -> list[list[npt.NDArray[np.float64]]]:
        """The holes of each polygon: a list (one per polygon) of lists of
        float64 ``(K, 2)`` arrays.
        """
    @property
    def materials(self) -> list[str]:
        """The material of each polygon, ``"wall"`` or ``"glass"``."""
    @property
    def polygon_area_m2(self) -> float:
        """The sum of the polygons' areas, square metres (overlaps counted twice;
        the union is ``coverage(grid).sum()`` times the cell area).
        """
    def __len__(self) -> int: ...
    def coverage(self, grid: Grid) -> npt.NDArray[np.float64]:
        """The exact fraction of every cell of ``grid`` inside the obstacles:
        float64, ``(rows, cols)``, in ``[0, 1]`` (the ground truth a coverage
        map estimates). Runs with the GIL released.
        """
    @overload
    def cast(
        self,
        origins: _Points | _Point,
        angles: _Readings,
        max_range_m: float,
        *,
        return_incidence: Literal[False] = False,
    ) -> npt.NDArray[np.float64]:
        """Cast rays from ``origins`` along ``angles`` (radians, counter-clockwise
        from +x) up to ``max_range_m``: the distance to the first surface of
        each, float64 ``(N,)``, ``max_range_m`` where nothing was hit.

        ``origins`` is a float64 array of shape ``(N, 2)`` (or one point
        ``(x, y)`` shared by every ray), ``angles`` a float64 array of shape
        ``(N,)``. With ``return_incidence=True`` the result is a pair
        ``(distances, incidence)``, ``incidence`` the angle between each ray and
        the surface normal in ``[0, pi/2]`` (NaN where nothing was hit).
        """
    @overload
    def cast(
        self,
        origins: _Points | _Point,
        angles: _Readings,
        max_range_m: float,
        *,
        return_incidence: Literal[True],
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]: ...
    def contains(self, x: float, y: float) -> bool:
        """Whether the point ``(x, y)`` lies inside an obstacle."""
    def distance_to_obstacle(self, x: float, y: float) -> float:
        """Distance from ``(x, y)`` to the nearest obstacle, metres: 0 inside
        one, infinite in an empty world. A coordinate that is not finite
        raises ``InvalidValueError``.
        """
    def __reduce__(self) -> tuple[Any, tuple[str]]:
        """Pickle and copy support: rebuilt by ``World._from_geojson`` from
        ``to_geojson()``.
        """
    @staticmethod
    def _from_geojson(text: str) -> World:
        """Unpickling support: the world of a GeoJSON text (``to_geojson``)."""

@type_check_only
class _RangeSensor:
    """What both simulated sensors have: their bearings, their range and
    simulated scans."""

    @property
    def bearings_rad(self) -> npt.NDArray[np.float64]:
        """Bearing of each beam relative to the heading, radians: float64
        ``(n,)`` (a ring's sensors are mounted at these bearings).
        """
    @property
    def bearings(self) -> npt.NDArray[np.float64]:
        """The same as ``bearings_rad``, under the name ``CoverageMap.integrate`` uses."""
    @property
    def max_range_m(self) -> float:
        """Readings at or beyond this are "no echo", metres."""
    def simulate(
        self, world: World, pose: _Pose, *, seed: int = 0
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """One scan of ``world`` from ``pose = (x, y, theta)``, every random draw
        from a generator seeded with ``seed``: ``(ranges, bearings)``, float64
        ``(n,)`` each, ready for ``CoverageMap.integrate(pose, ranges,
        bearings, model)`` with the sensor's model (``SonarModel()`` for a
        ``SonarRing``, ``LaserModel()`` for a ``Laser``). The same seed gives
        the same readings.
        """
    def simulate_path(
        self, world: World, poses: _Poses, *, seed: int = 0
    ) -> npt.NDArray[np.float64]:
        """One scan from each pose of ``poses`` (float64 ``(N, 3)``): the ranges
        as float64 ``(N, n)``. Scan ``i`` draws from its own stream ``i`` of
        ``seed`` (scan 0 equals ``simulate(world, poses[0], seed=seed)``), so
        the result depends on the seed alone; scans run in parallel.
        """
    def record(self, world: World, poses: _Poses, *, seed: int = 0) -> Log:
        """``simulate_path``'s scans as a ``Log``: scan ``i`` from
        ``poses[i]`` at time ``i`` seconds, this sensor's bearings and
        maximum range, ready for ``CoverageMap.integrate_log``.
        """
    def __eq__(self, value: object, /) -> bool: ...
    def __ne__(self, value: object, /) -> bool: ...

@final
class SonarRing(_RangeSensor):
    """A ring of simulated ultrasound sensors, all at the robot's centre.

    Sensor ``i`` looks along ``theta + bearings_rad[i]``. A reading casts
    ``rays_per_cone`` rays across the cone; a ray echoes when it meets a
    surface at an incidence no larger than the material's critical angle
    (walls ``critical_angle_wall_rad``, glass ``critical_angle_glass_rad``);
    the nearest echo is the reading. A cone with only specular misses returns a
    longer multipath reading with ``multipath_probability``, else no echo.
    Echoes get Gaussian noise of standard deviation ``noise_std_m +
    noise_std_per_m * range`` and are at least ``min_range_m``; with
    ``outlier_probability`` a reading is replaced by a short outlier. No echo
    reads exactly ``max_range_m``, as ``CoverageMap.integrate`` expects.

    Arguments left out (or ``None``) take the defaults: 24 sensors 15 degrees
    apart, the first straight ahead, with the cone and range of the default
    ``SonarModel``. Distances in metres, angles in radians; an invalid value
    raises ``InvalidParameterError`` (or ``InvalidValueError`` for a bearing).
    """

    def __new__(
        cls,
        *,
        bearings_rad: _Readings | None = None,
        opening_angle_rad: float | None = None,
        max_range_m: float | None = None,
        min_range_m: float | None = None,
        rays_per_cone: int | None = None,
        noise_std_m: float | None = None,
        noise_std_per_m: float | None = None,
        outlier_probability: float | None = None,
        multipath_probability: float | None = None,
        critical_angle_wall_rad: float | None = None,
        critical_angle_glass_rad: float | None = None,
    ) -> SonarRing: ...
    @staticmethod
    def ring(count: int) -> SonarRing:
        """``count`` sensors evenly spaced around the robot, the first straight
        ahead, with the default error model.
        """
    @staticmethod
    def front_eight() -> SonarRing:
        """The eight-sonar front array of the ``sonar-8ring`` data set: -90,
        -37.5, -22.5, -7.5, 7.5, 22.5, 37.5 and 90 degrees.
        """
    def with_model(self, model: SonarModel) -> SonarRing:
        """The same ring with the opening angle and maximum range of ``model``, so
        that the simulated cone is the one the map assumes.
        """
    @property
    def opening_angle_rad(self) -> float:
        """Full opening angle of each cone, radians."""
    @property
    def min_range_m(self) -> float:
        """The shortest reading the sensor produces, metres."""
    @property
    def rays_per_cone(self) -> int:
        """Rays cast across each cone."""
    @property
    def noise_std_m(self) -> float:
        """Standard deviation of the range noise at zero range, metres."""
    @property
    def noise_std_per_m(self) -> float:
        """Growth of that standard deviation per metre of range."""
    @property
    def outlier_probability(self) -> float:
        """Probability that a reading is replaced by a short outlier."""
    @property
    def multipath_probability(self) -> float:
        """Probability that a specular miss returns a longer multipath reading."""
    @property
    def critical_angle_wall_rad(self) -> float:
        """Largest angle of incidence at which a wall still echoes, radians."""
    @property
    def critical_angle_glass_rad(self) -> float:
        """Largest angle of incidence at which glass still echoes, radians."""
    def __getnewargs_ex__(self) -> tuple[tuple[()], dict[str, Any]]:
        """Pickle and copy support: the keyword arguments that rebuild the ring."""

@final
class Laser(_RangeSensor):
    """A simulated laser scanner: thin beams, small Gaussian noise.

    ``beams`` beams spread evenly over ``fov_rad`` centred on the heading, the
    first at ``-fov_rad / 2`` and the last at ``+fov_rad / 2`` (default 361
    beams over pi: half a degree apart), or beams at ``bearings_rad``. A hit at
    distance ``d`` reads ``d + noise_std_m * z``; a beam that meets nothing
    before ``max_range_m`` (default 30 m, the default ``LaserModel``'s) reads
    exactly ``max_range_m``. Every surface, glass included, reflects it.
    """

    def __new__(
        cls,
        beams: int | None = None,
        fov_rad: float | None = None,
        *,
        bearings_rad: _Readings | None = None,
        max_range_m: float | None = None,
        noise_std_m: float | None = None,
    ) -> Laser: ...
    @staticmethod
    def sick_180() -> Laser:
        """180 beams one degree apart from -90 degrees (to +89), the layout of
        the 180-beam CARMEN logs.
        """
    @staticmethod
    def sick_361() -> Laser:
        """361 beams half a degree apart from -90 to +90 degrees."""
    @property
    def noise_std_m(self) -> float:
        """Standard deviation of the range noise, metres."""
    def __getnewargs_ex__(self) -> tuple[tuple[()], dict[str, Any]]:
        """Pickle and copy support: the keyword arguments that rebuild the laser."""

@final
class Robot:
    """A disc-shaped robot of radius ``radius_m`` (metres; the default matches
    ``Planner``'s).

    Points are ``(x, y)`` in metres; where a pose ``(x, y, theta)`` is given
    instead, its heading is ignored (a disc looks the same either way).
    """

    def __new__(cls, *, radius_m: float = 0.25) -> Robot: ...
    @property
    def radius_m(self) -> float:
        """The disc's radius, metres."""
    def collides(self, world: World, pose: _Point) -> bool:
        """Whether the disc at ``pose`` overlaps or touches an obstacle of
        ``world``. A pose with a non-finite position collides.
        """
    def move_collides(self, world: World, start: _Point, goal: _Point) -> bool:
        """Whether driving straight from ``start`` to ``goal`` touches an
        obstacle (either end in contact counts).
        """
    def free_travel(self, world: World, start: _Point, goal: _Point) -> float:
        """How far the disc can drive straight from ``start`` towards ``goal``
        before it touches an obstacle, metres: the whole length when the way is
        free, 0 when it starts in contact. A coordinate that is not finite
        raises ``InvalidValueError``.
        """
    def clearance(self, world: World, points: _Points) -> npt.NDArray[np.float64]:
        """The gap between the disc at each of ``points`` (float64 ``(N, 2)``)
        and the nearest obstacle, metres: float64 ``(N,)``, negative where they
        overlap. A point that is not finite raises ``InvalidValueError``. Runs
        with the GIL released.
        """
    def __eq__(self, value: object, /) -> bool: ...
    def __ne__(self, value: object, /) -> bool: ...
    def __getnewargs_ex__(self) -> tuple[tuple[()], dict[str, Any]]:
        """Pickle and copy support: the keyword arguments that rebuild the robot."""

def run_fig3(seed: int = 0) -> Fig3Result:
    """Run the paper's Fig. 3 with ``seed``: 24 simulated sonars driven along a
    seeded path through the built-in ``corridor``, every scan integrated into
    a coverage map and an occupancy grid, both measured against the exact
    ground truth on the cells the readings reached.

    Returns a ``Fig3Result`` (of ``covmap.experiments.fig3``): ``grid``
    (``Grid``), ``poses`` (float64 ``(N, 3)``), ``readings`` and
    ``cells_reached`` (int), the per-cell maps ``truth`` (float64), ``ml``,
    ``mean``, ``entropy``, ``occupancy`` (float32) and ``reached`` (bool), each
    ``(rows, cols)``; the mean absolute errors ``mae_ml``, ``mae_mean``,
    ``mae_occupancy`` (``MapErrors`` of ``all`` and ``partial``: over all
    reached cells and over those a wall face cuts); and ``log_likelihood`` of
    the truth under the coverage map with ``log_likelihood_prior`` under the
    uniform prior. Runs with the GIL released.
    """
def log_likelihood(
    map: CoverageMap,
    truth: npt.NDArray[np.float64] | npt.NDArray[np.float32],
    *,
    cells: npt.NDArray[np.bool_] | None = None,
) -> float:
    """The log-probability of the ground truth ``truth`` (a float64 or float32
    array of shape ``(rows, cols)`` of coverage values in [0, 1]) under the
    map's histograms, summed over every cell or those where ``cells`` (a bool
    array of the same shape) is true. A truth value between two bin values
    is scored by linear interpolation of the two bins' probabilities; a cell
    at the uniform prior scores ``ln(1 / bins)``.
    """
def fit_sensor_model(
    log: Log,
    truth: World | npt.NDArray[np.float64] | npt.NDArray[np.float32],
    model: SonarModel | LaserModel,
    *,
    grid: Grid | None = None,
    parameters: Sequence[str] | None = None,
    bounds: Sequence[tuple[str, tuple[float, float]]] | dict[str, tuple[float, float]] | None = None,
    max_evaluations: int = 300,
    restarts: int = 2,
    seed: int = 0,
    bins: int = 16,
    cells: npt.NDArray[np.bool_] | None = None,
    occlude_no_echo: bool = False,
    progress: bool | Callable[[int, int], object] = False,
) -> SensorFit:
    """Fit ``model``'s parameters to a recorded drive by maximum likelihood: the
    model under whose map of ``log`` the ground truth scores highest
    (``log_likelihood``), found by Nelder-Mead over the parameters scaled to
    their bounds, from ``restarts`` starting points (the first ``model``
    itself, the others drawn around it from ``seed``), in parallel, with the
    GIL released. The result is the same whatever the thread count.

    ``truth`` is a ``World`` (its exact coverage on ``grid``) or a float
    array of shape ``(rows, cols)``; ``grid`` defaults to the world's bounds
    and 0.5 m at 5 cm (required with an array). ``parameters`` names the
    parameters fitted (default: all the model has but ``max_range_m``);
    ``bounds`` maps names to ``(low, high)`` replacing the defaults.
    ``max_evaluations`` bounds the maps built, the starting model's
    included. With ``occlude_no_echo`` the maps are built as
    ``CoverageMap.integrate_log(..., occlude_no_echo=True)`` builds them (as
    the exploration loop does); by default every no-echo reading clears its
    whole footprint. ``progress``: ``True`` for a bar over evaluations, or a
    callable ``(done, total)``.

    Unknown parameter names, bounds that exclude the starting model, a truth
    of the wrong shape or an empty log raise ``InvalidParameterError`` (or the
    array errors) before any map is built.
    """
def run_learn(
    model: SonarModel | LaserModel,
    *,
    train_world: str = "corridor",
    test_world: str = "office",
    scans: int = 300,
    step: float = 0.15,
    resolution: float = 0.05,
    train_seed: int = 0,
    test_seed: int = 1,
    max_evaluations: int = 300,
    restarts: int = 2,
    seed: int = 0,
    parameters: Sequence[str] | None = None,
    judged_only: bool = False,
    occlude_no_echo: bool = True,
    progress: bool | Callable[[int, int], object] = False,
) -> dict[str, Any]:
    """Learn the sensor model in simulation (``covmap learn``): simulate a
    training drive of ``scans`` scans through the built-in ``train_world``
    and a test drive through ``test_world`` (the 24-sonar ring for a
    ``SonarModel``, a 180-degree laser for a ``LaserModel``; each along
    shortest paths to seeded waypoints), fit ``model`` on the training drive
    (as ``fit_sensor_model``), and score the starting and the learned model
    on both drives. With ``judged_only`` the fit scores the training drive's
    judged cells only, not every cell of its grid. With ``occlude_no_echo``
    (the default) every map, the fit's and the scores', is built as the
    exploration loop builds its maps: each no-echo reading clears only what
    its line of sight reaches past the cells the map holds covered and is
    certain of
    (``CoverageMap.integrate_log``'s
    ``occlude_no_echo``), and the drives' occupancy grids take the same
    beams; ``False`` lets no-echo readings clear their whole footprint.
    Runs with the GIL released.

    Returns a dict: ``fit`` (``SensorFit``); ``drives``, one dict per drive
    (training first) of ``world``, ``log`` (``Log``), ``grid`` (``Grid``) and
    ``truth`` (float64 ``(rows, cols)``), ``reached`` (uint32 ``(rows,
    cols)``: how many of its scans' sound reached each cell in the true
    world), ``judged`` (bool: the cells the drive is judged on, reached and
    observable from its free space) and ``faced_walls`` (bool: the wall
    cells behind a face that 20 or more scans reached); ``default`` and
    ``learned``, one dict per drive of ``log_likelihood`` (of the truth,
    every cell), ``judged_log_likelihood`` (over the judged cells),
    ``mean_error`` (of the mean map, over the judged cells),
    ``free_error`` and ``obstacle_error`` (the same over the judged free and
    obstacle cells), ``occupancy_error`` (the occupancy grid's),
    ``cells_reached``, ``wall_coverage`` (the mean map's mean over the faced
    walls) and ``occupancy_wall`` (the occupancy grid's).
    """

@final
class SensorFit:
    """What ``fit_sensor_model`` found: ``model`` (the best model, the starting
    one if nothing scored higher), ``log_likelihood`` and
    ``initial_log_likelihood`` (the starting model's), ``evaluations`` (maps
    built), ``parameters`` (the fitted names), ``bounds`` and ``trace``
    (every evaluation in order, the starting model's first: a dict of the
    fitted parameters and ``log_likelihood``).
    """

    @property
    def model(self) -> SonarModel | LaserModel:
        """The best model found."""
    @property
    def log_likelihood(self) -> float:
        """The log-likelihood of the truth under the best model's map."""
    @property
    def initial_log_likelihood(self) -> float:
        """The same under the starting model's map."""
    @property
    def evaluations(self) -> int:
        """How many maps were built and scored."""
    @property
    def parameters(self) -> list[str]:
        """The names of the fitted parameters."""
    @property
    def bounds(self) -> dict[str, tuple[float, float]]:
        """The bounds each was searched within, ``{name: (low, high)}``."""
    @property
    def trace(self) -> list[dict[str, float]]:
        """Every evaluation in order: a dict of the fitted parameters and
        ``log_likelihood``.
        """
    def __reduce__(self) -> tuple[Any, tuple[bytes]]:
        """Pickle support: rebuilt by ``SensorFit._from_state`` from JSON bytes
        (every float64 exact).
        """
    @staticmethod
    def _from_state(state: bytes) -> SensorFit:
        """Unpickling support: the fit saved by ``__reduce__`` (checked)."""

def write_atomic(path: _Path, data: bytes) -> None:
    """Write ``data`` to ``path`` atomically: a temporary file of a short name of
    its own in the same directory, flushed to disk, then renamed over
    ``path``, so a reader never sees a partial file; on failure nothing is
    left behind. The directory must exist. A path where something other
    than a regular file is (a directory, a device, a FIFO, a socket, a
    symlink) is refused before anything is written, as is a file that cannot
    be written: ``FileIOError`` (an ``OSError``). Runs with the GIL released.
    """

def check_write_target(path: _Path) -> None:
    """Raise ``FileIOError`` unless ``write_atomic(path, ...)`` may write
    ``path``: nothing is there, or a regular file is (a directory, a device,
    a FIFO, a socket or a symlink is never replaced).
    """

def flow_collections(text: str) -> int:
    """How many flow collections that hold something a YAML ``text`` may
    open, at most: its ``[`` and ``{`` not closed at once (the bound of
    ``MAX_FLOW_COLLECTIONS`` that map_server files are held to).
    """

MAX_FLOW_COLLECTIONS: int

@final
class Strategy:
    """How an exploring robot chooses where to go next (``explore``,
    ``Exploration``). Build one with a static method:

    - ``Strategy.coverage(alpha=0.5)``: the paper's decision-theoretic choice
      (eq. 14) on the coverage map, ``alpha`` the weight of information
      against travel in ``[0, 1]``; done when every cell of the reachable
      region is certain (entropy below ``epsilon``) or has stagnated, or
      when no candidate is worth visiting (a goal whose scans did not deliver
      what it promised is not chosen again);
    - ``Strategy.counting(n=50, discount_beyond_m=None)``: extended scan
      counting, a cell explored once ``n`` beams intercepted it (a beam reading
      ``d`` beyond ``discount_beyond_m`` counts ``discount_beyond_m / d``;
      ``None``: every beam counts 1; Table I's row uses
      ``DEFAULT_DISCOUNT_BEYOND_M``); the robot goes to the nearest candidate
      that would intercept an unexplored cell;
    - ``Strategy.frontier()``: nearest-frontier exploration (Yamauchi 1997) on
      the occupancy grid.

    Strategies compare equal when their settings are equal, hash, pickle and
    show as the call that builds them.
    """

    @staticmethod
    def coverage(alpha: float = 0.5) -> Strategy:
        """The paper's decision-theoretic strategy (eq. 14) with weight ``alpha``
        in ``[0, 1]`` (0: the nearest candidate, 1: the most informative);
        another value, NaN included, raises ``InvalidParameterError``.
        """
    @staticmethod
    def counting(n: int = 50, discount_beyond_m: float | None = None) -> Strategy:
        """Extended scan counting to ``n`` (at least 1) interceptions, beams
        reading farther than ``discount_beyond_m`` (positive, finite; ``None``:
        no discount) counted ``discount_beyond_m / d``; a bad value raises
        ``InvalidParameterError``.
        """
    @staticmethod
    def frontier() -> Strategy:
        """Nearest-frontier exploration on the occupancy grid."""
    @staticmethod
    def custom(
        choose: Callable[[StrategyView], Any], *, name: str | None = None, alpha: float = 0.5
    ) -> CustomStrategy:
        """A strategy written in Python: ``choose(view)`` is called before each
        step with a ``StrategyView`` (the maps, the pose, the reachable
        region, the candidate viewpoints with their expected gains and path
        costs, whether the paper's rule holds) and returns the goal,
        ``(x, y, theta)`` or the index of a candidate, or ``None`` when it is
        done. ``name`` names it in results (default: ``choose``'s name);
        ``alpha`` weighs the candidates' utilities it sees (eq. 14). Returns
        a ``CustomStrategy``, which ``explore``, ``Exploration``, ``sweep``
        and the benchmark take beside the built-in strategies (``sweep``
        needs a ``choose`` that pickles: a function defined at the top level
        of a module).
        """
    @property
    def name(self) -> Literal["coverage", "counting", "frontier"]:
        """``"coverage"``, ``"counting"`` or ``"frontier"``."""
    @property
    def alpha(self) -> float | None:
        """The weight of information against travel (``coverage``), else ``None``."""
    @property
    def n(self) -> int | None:
        """The interceptions that make a cell explored (``counting``), else ``None``."""
    @property
    def discount_beyond_m(self) -> float | None:
        """The discount range of ``counting``, metres (``None``: no discount, or
        another strategy).
        """
    def __reduce__(self) -> tuple[Any, tuple[Any, ...]]:
        """Pickle and copy support: the static method that builds the strategy
        and its arguments.
        """
    def __eq__(self, value: object, /) -> bool: ...
    def __ne__(self, value: object, /) -> bool: ...
    def __hash__(self) -> int: ...

def explore(
    world: World,
    strategy: Strategy | CustomStrategy,
    *,
    start: _Pose | None = None,
    seed: int = 0,
    sensor: _Sensor | None = None,
    model: _Model | None = None,
    resolution: float = 0.05,
    bins: int = 16,
    epsilon: float = 0.65,
    robot_radius_m: float = 0.25,
    candidate_stride_m: float = 0.5,
    scan_spacing_m: float = 0.25,
    max_path_m: float = 10000.0,
    max_steps: int = 20000,
    occlude_no_echo: bool = True,
) -> ExplorationResult:
    """Explore ``world`` (a ``World``) with ``strategy`` (a ``Strategy``) until
    the strategy is done or a limit is reached; returns an
    ``ExplorationResult``. Runs with the GIL released.

    The robot is a disc of ``robot_radius_m`` starting at ``start``
    (``(x, y, theta)``; ``None``: a free pose drawn from ``seed``, the
    centre of a cell keeping twice the radius from every obstacle in the
    free region the world encloses most of (not the outside of a
    building, nor a map's unknown), facing a random heading). It scans
    with ``sensor``
    (a ``SonarRing`` or a ``Laser``; ``None``: the 24-sonar ring) into a
    ``CoverageMap`` of ``bins`` bins over the world's bounds plus 0.5 m at
    ``resolution`` metres, and into an ``OccupancyGrid`` and scan counts
    fed the same beams, integrating with ``model`` (a ``SonarModel`` or a
    ``LaserModel``; ``None``: the sensor's default). Each step the strategy
    picks a goal on the maps (candidates ``candidate_stride_m`` apart), the
    robot follows the planned path through the true world, scanning every
    ``scan_spacing_m`` of travel and at the goal; where the map was wrong
    it stops at the obstacle, scans, and the contact is integrated as
    covered. Poses are exact (no localisation error). A cell is certain
    below ``epsilon`` nats. The run stops by the strategy's rule, or after
    ``max_path_m`` metres or ``max_steps`` steps. A reading with no echo
    clears only what its line of sight reaches past the cells the
    coverage map holds covered and is certain of, in every map, and an
    echo off such a cell marks only the cells at its bearing and the
    certain ones (``occlude_no_echo``, the default); with ``occlude_no_echo=False``
    it clears its whole footprint, the paper's reading (which settles
    more cells but erodes walls: docs/experiments.md, "The paper's
    no-echo reading in the loop").

    Every random draw (start, sensor noise) comes from ``seed``: the same
    seed gives the same run at any thread count. Every option is checked
    before anything runs: a bad value raises ``InvalidParameterError``
    naming it, a start in an obstacle ``InvalidStartError``, one off the
    map ``PoseOutsideMapError`` (all ``ValueError``).
    """

@final
class Exploration:
    """An exploration run to watch or steer step by step.

    ``Exploration(world, strategy, **options)`` takes the arguments of
    ``explore`` and checks them all, but runs nothing: each ``step()`` (GIL
    released) chooses a goal, drives there scanning on the way and returns a
    ``Step``, or ``None`` once the run is over. Iterating yields the steps.
    ``result()`` reports the run so far as an ``ExplorationResult``; stepping
    to the end gives the same result as ``explore`` with the same arguments.
    The maps read out (``map``, ``occupancy``) are copies. Touching the run
    from another thread while a step runs raises ``RuntimeError``.
    """

    def __new__(
        cls,
        world: World,
        strategy: Strategy | CustomStrategy,
        *,
        start: _Pose | None = None,
        seed: int = 0,
        sensor: _Sensor | None = None,
        model: _Model | None = None,
        resolution: float = 0.05,
        bins: int = 16,
        epsilon: float = 0.65,
        robot_radius_m: float = 0.25,
        candidate_stride_m: float = 0.5,
        scan_spacing_m: float = 0.25,
        max_path_m: float = 10000.0,
        max_steps: int = 20000,
        occlude_no_echo: bool = True,
    ) -> Exploration: ...
    def step(self, goal: _Pose | None = None) -> Step | None:
        """Take one step: a ``Step``, or ``None`` once the run is over. With
        ``goal`` (``(x, y, theta)``), a step to that goal, whatever the
        strategy: the path to it planned on the coverage map as the coverage
        strategy plans, then the drive, its scans and the scan at the goal.
        A goal that is not finite, lies off the map or that the robot cannot
        reach on its map raises ``InvalidGoalError`` and leaves the run as it
        was. Without it, a custom strategy's ``choose`` is asked (it may
        end the run: ``None``).
        """
    def begin(self) -> bool:
        """The first scans where the robot stands, if it has taken none (GIL
        released): what a step takes first, so that the maps, ``region()``
        and ``viewpoints()`` show the start before any step. Returns whether
        the run may take a step (``False`` once it is over; a limit reached
        ends it).
        """
    def run(self) -> ExplorationResult:
        """Step to the end of the run; returns ``result()``."""
    def finish(self) -> Literal["certain", "stagnated", "no_goal", "limit"]:
        """End the run now, on the caller's word: by the paper's rule where it
        holds (``"certain"``, ``"stagnated"``), else ``"no_goal"``. Returns
        how the run ended (as it was, for a run already over).
        """
    def region(self) -> npt.NDArray[np.bool_]:
        """The region the robot can reach on its coverage map now: bool ``(rows,
        cols)``, the cells the paper's rule is checked on.
        """
    def reachable(self) -> npt.NDArray[np.bool_]:
        """The cells the robot can reach on its coverage map now, where a
        step's goal may lie (``step(goal=...)`` accepts a goal in one):
        bool ``(rows, cols)``. ``region()`` holds more: the cells a scan from
        them reaches.
        """
    def rule(self) -> Literal["certain", "stagnated"] | None:
        """Whether the paper's rule holds now on ``region()``: ``"certain"``
        (every cell below ``epsilon``), ``"stagnated"`` (every cell certain or
        stagnated, some stagnated), ``None`` (some cell neither).
        """
    def viewpoints(self, alpha: float = 0.5) -> Plan:
        """The candidate viewpoints the coverage strategy weighs now: a ``Plan``
        whose ``candidates`` hold every candidate's pose, expected gain
        (nats), path cost (metres) and eq. 14's utility for ``alpha``, and
        whose ``pose`` is the planner's choice (GIL released). Planned as the
        loop plans, the candidates' gains kept from call to call where the
        map did not change under them: the plan a full computation gives.
        """
    def path_to(self, goal: _Pose) -> npt.NDArray[np.float64] | None:
        """The path a step to ``goal`` would take: cell centres from the
        robot's cell, ``(K, 2)``; ``None`` where the robot cannot reach it on
        its map.
        """
    def result(self) -> ExplorationResult:
        """The run so far as an ``ExplorationResult`` (its ``termination`` is
        ``None`` while the run goes on).
        """
    def __iter__(self) -> Self: ...
    def __next__(self) -> Step: ...
    @property
    def map(self) -> CoverageMap:
        """A copy of the coverage map built so far."""
    @property
    def occupancy(self) -> OccupancyGrid:
        """A copy of the occupancy grid built so far from the same beams."""
    @property
    def pose(self) -> npt.NDArray[np.float64]:
        """The robot's pose ``(x, y, theta)``: float64 ``(3,)``."""
    @property
    def trajectory(self) -> npt.NDArray[np.float64]:
        """Every pose so far, the start first: float64 ``(K, 3)``."""
    @property
    def done(self) -> bool:
        """Whether the run is over."""
    @property
    def termination(self) -> Literal["certain", "stagnated", "no_goal", "limit"] | None:
        """How the run ended (``"certain"``, ``"stagnated"``, ``"no_goal"``,
        ``"limit"``), or ``None`` while it goes on.
        """
    @property
    def steps(self) -> int:
        """Steps taken."""
    @property
    def scans(self) -> int:
        """Scans taken."""
    @property
    def path_length_m(self) -> float:
        """Distance driven, metres."""
    @property
    def uncertain_fraction(self) -> float:
        """Fraction of the evaluation cells whose entropy is above epsilon now."""
    @property
    def evaluation_cells(self) -> npt.NDArray[np.bool_]:
        """The cells the run is judged on: bool ``(rows, cols)`` (see
        ``ExplorationResult.evaluation_cells``).
        """
    @property
    def grid(self) -> Grid:
        """The grid of the maps."""
    @property
    def strategy(self) -> Strategy | CustomStrategy:
        """The strategy: a ``Strategy``, or the ``CustomStrategy`` given."""
