"""The exploration benchmark: strategies x sensors x buildings x seeds, every
run through :func:`covmap.sweep` (the local cores or Dask), each run's
figures (one CSV row a run, :mod:`covmap.experiments.benchmark_files`) and
a summary per strategy and sensor (median and spread over the runs).

What a run reports (:class:`BenchmarkRun`): the share of the evaluation
cells left uncertain, the rooms never entered (by the generator's room
list; for a plan by the rule of :meth:`covmap.Building.from_world`), path
length, scans, steps, contacts, how it ended, the maps' errors against the
truth, wall time and the real-time factor (how many times faster than a
robot driving the path at 0.5 m/s).

Two configurations (:data:`CONFIGURATIONS`): ``"default"``, what a
newcomer runs in a few minutes on two cores (four small development
buildings, the four strategies, sonar), and ``"full"``, the baseline every
strategy is judged against (24 test buildings of three sizes and the real
plans with sonar, the eight small ones with the laser too). Every random draw comes from the seeds: the same
configuration gives the same figures (wall times aside) locally and on any
number of Dask workers.
"""

from __future__ import annotations

import math
import statistics
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

from covmap._errors import InvalidParameterError, InvalidTypeError, InvalidValueError
from covmap._native import DEFAULT_DISCOUNT_BEYOND_M, Laser, SonarRing, Strategy
from covmap._exploration import REAL_TIME_SPEED_M_S, real_time_factor
from covmap._sweep import RunSummary, SweepFailure, sweep
from covmap.buildings import split_of

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from covmap._custom import CustomStrategy
    from covmap._native import Building

    StrategyLike = str | Strategy | CustomStrategy

__all__ = [
    "CONFIGURATIONS",
    "LASER_MAX_EXTENT_M2",
    "LASER_MAX_PATH_M",
    "MAX_PATH_M",
    "MAX_RUNS",
    "SENSORS",
    "SIZE_CLASSES_M2",
    "STRATEGIES",
    "Benchmark",
    "BenchmarkRun",
    "Configuration",
    "StrategySummary",
    "run",
    "sensor_of",
    "specs",
    "speed_table",
    "strategy_of",
    "summary_table",
]

STRATEGIES: dict[str, Strategy] = {
    "coverage": Strategy.coverage(0.5),
    "counting n=1": Strategy.counting(1),
    "counting n=50": Strategy.counting(50, DEFAULT_DISCOUNT_BEYOND_M),
    "frontier": Strategy.frontier(),
}
"""The strategies of the benchmark by label: Table I's rows (coverage maps
with alpha 0.5, scan counting to 1 and to 50 discounted beyond 2 m) and
nearest frontiers. The benchmark also takes strategies as objects, a
``Strategy`` or a strategy of one's own (``Strategy.custom``): labelled by
their name (``"custom:NAME"`` for a custom one)."""

SENSORS = ("sonar", "laser")
"""The sensors by name: the 24-sonar ring and the 361-beam SICK laser."""


MAX_RUNS = 1_000_000
"""The most runs a benchmark may have."""


def _length(values: Any, what: str) -> int:
    """How many ``values`` hold: a list (not a str) of at most
    :data:`MAX_RUNS`, else a typed error naming ``what``."""
    if isinstance(values, str) or not hasattr(values, "__len__"):
        raise InvalidTypeError(f"{what} must be a list, got {type(values).__name__}")
    try:
        return len(values)
    except OverflowError:
        raise InvalidValueError(f"{what}: more than {MAX_RUNS}") from None


def sensor_of(name: str) -> SonarRing | Laser:
    """The simulated sensor of ``name`` (:data:`SENSORS`)."""
    if not isinstance(name, str):
        raise InvalidTypeError(f"a sensor is named by a str ({', '.join(SENSORS)}), got {type(name).__name__}")
    if name == "sonar":
        return SonarRing()
    if name == "laser":
        return Laser.sick_361()
    raise InvalidParameterError(f"unknown sensor {name!r}: expected one of {', '.join(SENSORS)}")


@dataclass(frozen=True)
class Configuration:
    """A benchmark configuration: which buildings, sensors and seeds, and
    the runs' limits."""

    buildings: str
    """The building set (:func:`covmap.buildings.building_set`)."""
    count: int
    """Generated buildings in the set."""
    plans: bool
    """Whether the set's plans are in it."""
    sensors: tuple[str, ...]
    """The sensors."""
    seeds: tuple[int, ...]
    """The runs' seeds (the start and the sensor noise), one run each."""
    sensor_options: dict[str, dict[str, Any]] = field(default_factory=dict)
    """Per sensor, the keywords of :func:`covmap.explore` its runs are
    given (their limits)."""
    max_extent_m2: dict[str, float] = field(default_factory=dict)
    """Per sensor, the largest building it runs in (the area of the
    world's bounding box, square metres); every building where none is
    given."""


MAX_PATH_M = 3000.0
"""The benchmark's path limit, metres: a run still going at 3 km ends as
``"limit"``. Counting to 50 drives 2.6 km in a 120 square-metre building
and goes on for many kilometres in larger ones (20 m a square metre);
coverage maps and frontiers end by their own rule well before it
(docs/experiments.md, the benchmark's limits). A step or path limit, never a wall-clock one: a run's end
must not depend on the machine."""

LASER_MAX_PATH_M = 300.0
"""The full benchmark's path limit of the laser's runs, metres. The
coverage strategy plans each step of the 361-beam laser for about 1 s (a
120 square-metre building) to 10 s (550 square metres) on one core: a run
to its own end takes some 320 steps, 455 m and 6 minutes in a small
building, hours in a large one; counting to 50 drives 1.4 km in 2700 steps
(docs/experiments.md, the benchmark's limits)."""

LASER_MAX_EXTENT_M2 = 200.0
"""The largest building the full benchmark runs the laser in (bounding box,
square metres): the small ones, for the reason of :data:`LASER_MAX_PATH_M`."""

CONFIGURATIONS: dict[str, Configuration] = {
    "default": Configuration("default", 4, False, ("sonar",), (0,), {"sonar": {"max_path_m": MAX_PATH_M}}),
    "full": Configuration(
        "test",
        24,
        True,
        ("sonar", "laser"),
        (0,),
        {"sonar": {"max_path_m": MAX_PATH_M}, "laser": {"max_path_m": LASER_MAX_PATH_M}},
        {"laser": LASER_MAX_EXTENT_M2},
    ),
}
"""The benchmark's configurations: ``"default"`` (four small development
buildings, sonar) and ``"full"`` (24 test buildings and the real plans with
sonar; the laser in the eight small ones, at most
:data:`LASER_MAX_PATH_M` a run)."""


@dataclass(frozen=True)
class BenchmarkRun:
    """One run of the benchmark: where, how, and its figures (a row of the
    CSV, :func:`read_csv` reads it back). Two runs compare equal when their
    outcomes are the same (the wall time aside)."""

    building: str
    """The building's name."""
    split: str
    """``"development"``, ``"test"`` or ``"-"`` (:func:`covmap.buildings.split_of`)."""
    strategy: str
    """The strategy's label (:data:`STRATEGIES`)."""
    sensor: str
    """The sensor's name."""
    seed: int
    """The run's seed."""
    termination: str
    """How it ended (:attr:`covmap.ExplorationResult.termination`)."""
    uncertain_fraction: float
    """The share of the evaluation cells uncertain at the end."""
    rooms: int | None
    """The rooms and halls it is judged on (``None``: no room list)."""
    rooms_never_entered: tuple[str, ...]
    """The names of those it never entered."""
    path_length_m: float
    """Distance driven, metres."""
    scans: int
    """Scans taken."""
    steps: int
    """Steps taken."""
    contacts: int
    """Contacts with obstacles the map did not show."""
    error_coverage_map: float
    """The coverage map's mean absolute error against the truth."""
    error_occupancy: float
    """The occupancy grid's."""
    evaluation_area_m2: float
    """The area of the evaluation cells, square metres."""
    seconds: float = field(compare=False)
    """Wall time, seconds."""

    @classmethod
    def of(cls, strategy: str, sensor: str, s: RunSummary) -> BenchmarkRun:
        """The figures of the sweep's run ``s`` of ``strategy`` with ``sensor``."""
        return cls(
            building=s.world,
            split=split_of(s.world),
            strategy=strategy,
            sensor=sensor,
            seed=s.seed,
            termination=str(s.termination),
            uncertain_fraction=s.high_entropy_fraction,
            rooms=s.rooms,
            rooms_never_entered=s.rooms_never_entered,
            path_length_m=s.path_length_m,
            scans=s.scans,
            steps=s.steps,
            contacts=s.contacts,
            error_coverage_map=s.coverage_error.coverage_map,
            error_occupancy=s.coverage_error.occupancy,
            evaluation_area_m2=s.evaluation_area_m2,
            seconds=s.seconds,
        )

    @property
    def rooms_missed(self) -> int:
        """How many rooms and halls the robot never entered."""
        return len(self.rooms_never_entered)

    @property
    def real_time_factor(self) -> float:
        """How many times faster than a robot driving the path at 0.5 m/s."""
        return real_time_factor(self.path_length_m, self.seconds, REAL_TIME_SPEED_M_S)


@dataclass(frozen=True)
class Benchmark:
    """The runs of a benchmark, in the order of its specs."""

    runs: list[BenchmarkRun]
    options: dict[str, Any]
    """The keywords of :func:`covmap.explore` every run was given (limits,
    resolution)."""
    sensor_options: dict[str, dict[str, Any]] = field(default_factory=dict)
    """Per sensor, the further keywords its runs were given."""

    def summaries(self) -> list[StrategySummary]:
        """A :class:`StrategySummary` per strategy and sensor, in the order
        of :data:`STRATEGIES` and the sensors."""
        keys: list[tuple[str, str]] = []
        for r in self.runs:
            if (r.strategy, r.sensor) not in keys:
                keys.append((r.strategy, r.sensor))
        order = list(STRATEGIES)
        keys.sort(key=lambda k: (order.index(k[0]) if k[0] in order else len(order), SENSORS.index(k[1])))
        return [
            StrategySummary.of(s, n, [r for r in self.runs if (r.strategy, r.sensor) == (s, n)]) for s, n in keys
        ]


def _quartiles(values: Sequence[float]) -> tuple[float, float, float]:
    """The median and the lower and upper quartiles (the median of one
    value for all three)."""
    if len(values) == 1:
        return values[0], values[0], values[0]
    q1, q2, q3 = statistics.quantiles(values, n=4, method="inclusive")
    return q2, q1, q3


@dataclass(frozen=True)
class StrategySummary:
    """One strategy with one sensor over a benchmark's runs: medians with
    their interquartile range (the spread), and counts."""

    strategy: str
    sensor: str
    runs: int
    uncertain: tuple[float, float, float]
    """The uncertain share: median, lower and upper quartile."""
    path_m: tuple[float, float, float]
    """Path length, metres: median and quartiles."""
    rooms_never_entered: tuple[float, float, float]
    """Rooms never entered: median and quartiles."""
    real_time_factor: tuple[float, float, float]
    """Real-time factor: median and quartiles."""
    error_coverage_map: float
    """The median of the coverage map's mean absolute error."""
    at_most_one_percent: int
    """Runs that left at most 1 % of their evaluation cells uncertain."""
    every_room: int
    """Runs that entered every room."""
    terminations: dict[str, int]
    """How many runs ended how."""

    @classmethod
    def of(cls, strategy: str, sensor: str, runs: Sequence[BenchmarkRun]) -> StrategySummary:
        """The summary of ``runs``, all of ``strategy`` with ``sensor``."""
        endings: dict[str, int] = {}
        for r in runs:
            endings[r.termination] = endings.get(r.termination, 0) + 1
        return cls(
            strategy=strategy,
            sensor=sensor,
            runs=len(runs),
            uncertain=_quartiles([r.uncertain_fraction for r in runs]),
            path_m=_quartiles([r.path_length_m for r in runs]),
            rooms_never_entered=_quartiles([float(r.rooms_missed) for r in runs]),
            real_time_factor=_quartiles([r.real_time_factor for r in runs]),
            error_coverage_map=statistics.median(r.error_coverage_map for r in runs),
            at_most_one_percent=sum(r.uncertain_fraction <= 0.01 for r in runs),
            every_room=sum(r.rooms_missed == 0 for r in runs),
            terminations=endings,
        )


def specs(
    buildings: Sequence[Building],
    *,
    strategies: Sequence[StrategyLike] = tuple(STRATEGIES),
    sensors: Sequence[str] = ("sonar",),
    seeds: Sequence[int] = (0,),
    sensor_options: Mapping[str, Mapping[str, Any]] | None = None,
    max_extent_m2: Mapping[str, float] | None = None,
    **options: Any,
) -> list[dict[str, Any]]:
    """The sweep's specs: every building, with every sensor, strategy and
    seed (``options``: further keywords of :func:`covmap.explore`, the same
    for every run; ``sensor_options``: per sensor, more of them, for its
    runs; ``max_extent_m2``: per sensor, the largest building it runs in,
    by the area of the world's bounding box); the largest buildings first,
    so that the long runs start first and the cores end together. At most
    :data:`MAX_RUNS` runs;
    a building that is no :class:`~covmap.Building`, an unknown strategy or
    sensor raise before any spec is made."""
    from covmap._native import Building

    sizes = [
        _length(values, what)
        for what, values in (("buildings", buildings), ("strategies", strategies), ("sensors", sensors), ("seeds", seeds))
    ]
    if sizes[0] * sizes[1] * sizes[2] * sizes[3] > MAX_RUNS:
        raise InvalidValueError(f"{' x '.join(map(str, sizes))} runs: expected at most {MAX_RUNS}")
    for b in buildings:
        if not isinstance(b, Building):
            raise InvalidTypeError(f"buildings must be Buildings (covmap.buildings.building), got {type(b).__name__}")
    chosen = [strategy_of(s) for s in strategies]
    for name in sensors:
        sensor_of(name)
    def extent(b: Building) -> float:
        x0, y0, x1, y1 = b.world.bounds
        return (x1 - x0) * (y1 - y0)

    per_sensor = {} if sensor_options is None else {k: dict(v) for k, v in sensor_options.items()}
    largest = {} if max_extent_m2 is None else dict(max_extent_m2)
    order = sorted(range(len(buildings)), key=lambda i: -extent(buildings[i]))
    return [
        {
            "world": buildings[i],
            "strategy": strategy,
            "seed": seed,
            "sensor": sensor_of(sensor),
            **options,
            **per_sensor.get(sensor, {}),
        }
        for i in order
        for sensor in sensors
        if extent(buildings[i]) <= largest.get(sensor, math.inf)
        for _, strategy in chosen
        for seed in seeds
    ]


def strategy_of(strategy: StrategyLike) -> tuple[str, Strategy | CustomStrategy]:
    """A benchmark's strategy and its label: a label of :data:`STRATEGIES`,
    or a ``Strategy`` or ``Strategy.custom`` object (labelled by its name;
    one of :data:`STRATEGIES` by its label there). Anything else raises
    :class:`~covmap.InvalidParameterError`; a custom strategy that does not
    pickle is refused by :func:`covmap.sweep` before anything runs."""
    from covmap._custom import CustomStrategy

    if isinstance(strategy, str):
        if strategy not in STRATEGIES:
            raise InvalidParameterError(
                f"unknown strategy {strategy[:80]!r}: expected one of {', '.join(STRATEGIES)}, "
                "a Strategy or Strategy.custom(...)"
            )
        return strategy, STRATEGIES[strategy]
    if isinstance(strategy, CustomStrategy):
        return f"custom:{strategy.name}", strategy
    if isinstance(strategy, Strategy):
        for label, known in STRATEGIES.items():
            if known == strategy:
                return label, strategy
        return repr(strategy).removeprefix("Strategy."), strategy
    raise InvalidParameterError(
        f"a benchmark's strategy is a label ({', '.join(STRATEGIES)}), a Strategy or Strategy.custom(...), "
        f"got {type(strategy).__name__}"
    )


def run(
    buildings: Sequence[Building],
    *,
    strategies: Sequence[StrategyLike] = tuple(STRATEGIES),
    sensors: Sequence[str] = ("sonar",),
    seeds: Sequence[int] = (0,),
    sensor_options: Mapping[str, Mapping[str, Any]] | None = None,
    max_extent_m2: Mapping[str, float] | None = None,
    executor: Any = None,
    progress: bool | Callable[[int, RunSummary | SweepFailure], None] = True,
    **options: Any,
) -> Benchmark:
    """Run the benchmark (:func:`specs`) with :func:`covmap.sweep` on
    ``executor`` (``None``: the local cores; a ``dask.distributed.Client``;
    see :func:`covmap.dask_client`), ``progress`` as :func:`covmap.sweep`
    takes it. No buildings, strategies, sensors or seeds raise
    :class:`~covmap.InvalidValueError` before anything runs: a benchmark
    without runs says nothing. A run that raises ends in
    :class:`~covmap.SweepError` once all have ended."""
    for what, values in (("buildings", buildings), ("strategies", strategies), ("sensors", sensors), ("seeds", seeds)):
        if _length(values, what) == 0:
            raise InvalidValueError(f"the benchmark needs at least one of its {what}, got none")
    all_specs = specs(
        buildings,
        strategies=strategies,
        sensors=sensors,
        seeds=seeds,
        sensor_options=sensor_options,
        max_extent_m2=max_extent_m2,
        **options,
    )
    summaries = sweep(all_specs, executor=executor, progress=progress)
    runs = []
    for spec, summary in zip(all_specs, summaries):
        label, _ = strategy_of(spec["strategy"])
        sensor = "laser" if isinstance(spec["sensor"], Laser) else "sonar"
        runs.append(BenchmarkRun.of(label, sensor, summary))
    per_sensor = {} if sensor_options is None else {k: dict(v) for k, v in sensor_options.items()}
    return Benchmark(runs, dict(options), per_sensor)


def _spread(q: tuple[float, float, float], scale: float, digits: int) -> str:
    median, low, high = (v * scale for v in q)
    return f"{median:.{digits}f} [{low:.{digits}f}, {high:.{digits}f}]"


def summary_table(b: Benchmark) -> str:
    """The summary per strategy and sensor as text: the median and the
    interquartile range ``[lower, upper]`` of the uncertain share, the path
    length, the rooms never entered and the real-time factor; how many runs
    left at most 1 % uncertain and entered every room; how the runs
    ended."""
    header = (
        "strategy",
        "sensor",
        "runs",
        "uncertain [%]",
        "path [m]",
        "rooms missed",
        "<= 1 %",
        "all rooms",
        "real time x",
        "error",
        "ended",
    )
    lines = [header]
    for s in b.summaries():
        lines.append(
            (
                s.strategy,
                s.sensor,
                str(s.runs),
                _spread(s.uncertain, 100.0, 2),
                _spread(s.path_m, 1.0, 0),
                _spread(s.rooms_never_entered, 1.0, 0),
                f"{s.at_most_one_percent}/{s.runs}",
                f"{s.every_room}/{s.runs}",
                _spread(s.real_time_factor, 1.0, 0),
                f"{s.error_coverage_map:.4f}",
                ", ".join(f"{k} {n}" for k, n in sorted(s.terminations.items())),
            )
        )
    widths = [max(len(line[i]) for line in lines) for i in range(len(header))]
    buildings = sorted({r.building for r in b.runs})
    text = [
        f"Benchmark: {len(b.runs)} runs on {len(buildings)} building{'s' if len(buildings) != 1 else ''}; "
        "median [lower quartile, upper quartile] over the runs"
    ]
    if b.options:
        text.append("options: " + ", ".join(f"{k}={v!r}" for k, v in sorted(b.options.items())))
    for sensor, options in sorted(b.sensor_options.items()):
        if options:
            text.append(f"{sensor}: " + ", ".join(f"{k}={v!r}" for k, v in sorted(options.items())))
    for i, line in enumerate(lines):
        text.append("  ".join(cell.ljust(w) for cell, w in zip(line, widths)).rstrip())
        if i == 0:
            text.append("  ".join("-" * w for w in widths))
    text.append(
        "uncertain: evaluation cells with entropy above epsilon at the end; rooms missed: rooms and halls the "
        "robot never entered; real time x: how many times faster than driving the path at 0.5 m/s; error: the "
        "coverage map's mean absolute error against the truth (median)"
    )
    return "\n".join(text)


SIZE_CLASSES_M2 = ((0.0, 200.0), (200.0, 400.0), (400.0, 700.0), (700.0, math.inf))
"""The classes of building sizes of :func:`speed_table`, by the area of a
run's evaluation cells (what it could observe), square metres: the
AMROffice plan's is 559, the built-in corridor's 106."""


def speed_table(b: Benchmark) -> str:
    """The real-time factor by strategy, sensor and building size
    (:data:`SIZE_CLASSES_M2`): the median over the runs of each class, and
    how many runs it holds."""
    def label(low: float, high: float) -> str:
        return f"{low:.0f}+ m^2" if math.isinf(high) else f"{low:.0f}-{high:.0f} m^2"

    header = ("strategy", "sensor", *(label(lo, hi) for lo, hi in SIZE_CLASSES_M2))
    lines = [header]
    for s in b.summaries():
        runs = [r for r in b.runs if (r.strategy, r.sensor) == (s.strategy, s.sensor)]
        cells = []
        for low, high in SIZE_CLASSES_M2:
            factors = [r.real_time_factor for r in runs if low <= r.evaluation_area_m2 < high]
            cells.append(f"{statistics.median(factors):.0f}x ({len(factors)})" if factors else "-")
        lines.append((s.strategy, s.sensor, *cells))
    widths = [max(len(line[i]) for line in lines) for i in range(len(header))]
    text = [
        "Real-time factor (driving the path at 0.5 m/s over the run's wall time): the median by the size of "
        "the run's evaluation cells (runs)"
    ]
    for i, line in enumerate(lines):
        text.append("  ".join(cell.ljust(w) for cell, w in zip(line, widths)).rstrip())
        if i == 0:
            text.append("  ".join("-" * w for w in widths))
    return "\n".join(text)
