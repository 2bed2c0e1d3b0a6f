"""The paper's Table I: exploration with coverage maps against scan counting
(and nearest frontiers), over several seeds, beside the paper's figures."""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable

from covmap._native import DEFAULT_DISCOUNT_BEYOND_M, Strategy, explore
from covmap._sweep import RunSummary, SweepFailure, sweep

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    from covmap._exploration import ExplorationResult
    from covmap._native import Building, World


@dataclass(frozen=True)
class Method:
    """One row of Table I: a strategy, and the paper's figures for it (the
    paper has none for frontiers)."""

    label: str
    """The row's name."""
    strategy: Strategy
    """The strategy."""
    paper_path_m: float | None
    """The paper's path length, metres."""
    paper_uncertain: float | None
    """The paper's fraction of cells left uncertain."""


METHODS = (
    Method("coverage maps, alpha 0.5", Strategy.coverage(0.5), 89.1, 0.0),
    Method("counting n = 1", Strategy.counting(1), 26.6, 0.21),
    Method("counting n = 50, discounted", Strategy.counting(50, DEFAULT_DISCOUNT_BEYOND_M), 90.6, 0.015),
    Method("nearest frontier", Strategy.frontier(), None, None),
)
"""The rows of Table I, in the paper's order, frontiers added."""

CSV_FIELDS = (
    "method",
    "strategy",
    "seed",
    "termination",
    "path_length_m",
    "uncertain_fraction",
    "scans",
    "steps",
    "contacts",
    "error_coverage_map",
    "error_occupancy",
    "seconds",
    "real_time_factor",
    "building",
)
"""The columns of :func:`csv_text`, one row per run."""


@dataclass(frozen=True)
class Run:
    """One run of one method with one seed: its figures (the result itself
    is not kept, so that many runs stay small)."""

    method: Method
    seed: int
    termination: str | None
    path_length_m: float
    uncertain_fraction: float
    scans: int
    steps: int
    contacts: int
    error_coverage_map: float
    error_occupancy: float
    seconds: float
    real_time_factor: float
    building: str = ""
    """The building's name (empty for the world of :func:`run`)."""

    @classmethod
    def of_summary(cls, method: Method, s: RunSummary) -> Run:
        """The figures of a sweep's run of ``method``."""
        return cls(
            method=method,
            seed=s.seed,
            termination=s.termination,
            path_length_m=s.path_length_m,
            uncertain_fraction=s.high_entropy_fraction,
            scans=s.scans,
            steps=s.steps,
            contacts=s.contacts,
            error_coverage_map=s.coverage_error.coverage_map,
            error_occupancy=s.coverage_error.occupancy,
            seconds=s.seconds,
            real_time_factor=s.real_time_factor(),
            building=s.world,
        )

    @classmethod
    def of(cls, method: Method, result: ExplorationResult) -> Run:
        """The figures of ``result``, a run of ``method``."""
        return cls(
            method=method,
            seed=result.seed,
            termination=result.termination,
            path_length_m=result.path_length_m,
            uncertain_fraction=result.high_entropy_fraction,
            scans=result.scans,
            steps=result.steps,
            contacts=result.contacts,
            error_coverage_map=result.coverage_error.coverage_map,
            error_occupancy=result.coverage_error.occupancy,
            seconds=result.seconds,
            real_time_factor=result.real_time_factor(),
        )


def mean_and_spread(values: Sequence[float]) -> tuple[float, float]:
    """The mean and the sample standard deviation (0 for a single value)."""
    n = len(values)
    mean = sum(values) / n
    if n < 2:
        return mean, 0.0
    return mean, math.sqrt(sum((v - mean) ** 2 for v in values) / (n - 1))


@dataclass(frozen=True)
class Row:
    """A method's runs over the seeds."""

    method: Method
    runs: list[Run] = field(default_factory=list)

    def stat(self, name: str) -> tuple[float, float]:
        """Mean and spread of the runs' figure ``name``."""
        return mean_and_spread([float(getattr(r, name)) for r in self.runs])

    @property
    def terminations(self) -> dict[str, int]:
        """How many runs ended how."""
        counts: dict[str, int] = {}
        for r in self.runs:
            key = str(r.termination)
            counts[key] = counts.get(key, 0) + 1
        return counts


@dataclass(frozen=True)
class Table1:
    """Table I over ``seeds`` in world ``world_name``."""

    world_name: str
    seeds: list[int]
    rows: list[Row]
    options: dict[str, Any]
    """The keywords every run was given beyond the world, strategy and seed."""

    @property
    def runs(self) -> list[Run]:
        """Every run, row by row."""
        return [r for row in self.rows for r in row.runs]


def run(
    world: World,
    *,
    world_name: str = "world",
    seeds: Sequence[int] = (0, 1, 2),
    methods: Sequence[Method] = METHODS,
    progress: Callable[[Method, int, ExplorationResult], None] | None = None,
    **options: Any,
) -> Table1:
    """Run every method of ``methods`` with every seed of ``seeds`` in
    ``world`` (``options``: further keywords of :func:`covmap.explore`, the
    same for every run), calling ``progress(method, seed, result)`` after
    each run."""
    rows = []
    for method in methods:
        row = Row(method)
        for seed in seeds:
            result = explore(world, method.strategy, seed=seed, **options)
            row.runs.append(Run.of(method, result))
            if progress is not None:
                progress(method, seed, result)
        rows.append(row)
    return Table1(world_name, list(seeds), rows, dict(options))


def run_buildings(
    buildings: Sequence[str | Building],
    *,
    seeds: Sequence[int] = (0, 1, 2),
    methods: Sequence[Method] = METHODS,
    executor: Any = None,
    progress: bool | Callable[[int, RunSummary | SweepFailure], None] = True,
    **options: Any,
) -> Table1:
    """Table I as a view of the benchmark: every method with every seed
    in every building of ``buildings`` (names, see
    :func:`covmap.buildings.building`, or :class:`~covmap.Building` objects),
    all runs through :func:`covmap.sweep` on ``executor`` (``progress`` as
    it takes it); each row's figures over all buildings and seeds. No
    buildings or seeds raise :class:`~covmap.InvalidValueError`."""
    worlds = list(buildings)
    if not worlds or not seeds:
        from covmap._errors import InvalidValueError

        raise InvalidValueError(f"Table I needs a building and a seed, got buildings={worlds}, seeds={list(seeds)}")
    specs = [
        {"world": w, "strategy": m.strategy, "seed": s, **options} for m in methods for w in worlds for s in seeds
    ]
    summaries = iter(sweep(specs, executor=executor, progress=progress))
    rows = [Row(m, [Run.of_summary(m, next(summaries)) for _ in worlds for _ in seeds]) for m in methods]
    names = [w if isinstance(w, str) else w.name for w in worlds]
    label = ", ".join(names) if len(names) <= 3 else f"{len(names)} buildings"
    return Table1(label, list(seeds), rows, dict(options))


def _stat(value: tuple[float, float], scale: float, digits: int) -> str:
    mean, spread = value
    return f"{mean * scale:.{digits}f} ± {spread * scale:.{digits}f}"


def table(t: Table1) -> str:
    """Table I as text: for each method the mean ± spread (sample standard
    deviation over the seeds) of the path length and of the uncertain share of
    the evaluation cells, beside the paper's figures; then the maps' mean
    absolute errors, the wall time and how the runs ended."""
    header = (
        "method",
        "path [m]",
        "uncertain [%]",
        "paper",
        "error cov. map",
        "error occ. grid",
        "wall [s]",
        "ended",
    )
    lines = [header]
    for row in t.rows:
        m = row.method
        paper = (
            f"{m.paper_path_m:.1f} m / {100.0 * m.paper_uncertain:g} %"
            if m.paper_path_m is not None and m.paper_uncertain is not None
            else "-"
        )
        lines.append(
            (
                m.label,
                _stat(row.stat("path_length_m"), 1.0, 1),
                _stat(row.stat("uncertain_fraction"), 100.0, 2),
                paper,
                _stat(row.stat("error_coverage_map"), 1.0, 4),
                _stat(row.stat("error_occupancy"), 1.0, 4),
                _stat(row.stat("seconds"), 1.0, 1),
                ", ".join(f"{k} x{n}" for k, n in row.terminations.items()),
            )
        )
    widths = [max(len(line[i]) for line in lines) for i in range(len(header))]
    text = [
        f"Table I, {t.world_name}, {len(t.seeds)} seed{'s' if len(t.seeds) != 1 else ''} "
        f"({', '.join(map(str, t.seeds))}); mean ± sample standard deviation over the runs"
    ]
    if t.options:
        text.append("options: " + ", ".join(f"{k}={v!r}" for k, v in sorted(t.options.items())))
    for i, line in enumerate(lines):
        text.append("  ".join(cell.ljust(w) for cell, w in zip(line, widths)).rstrip())
        if i == 0:
            text.append("  ".join("-" * w for w in widths))
    text.append(
        "uncertain: evaluation cells with entropy above epsilon at the end; errors: mean absolute "
        "error against the exact coverage on those cells (coverage map: its mean map)"
    )
    return "\n".join(text)


def csv_text(t: Table1) -> str:
    """One CSV row per run, columns :data:`CSV_FIELDS`."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(CSV_FIELDS)
    for r in t.runs:
        writer.writerow(
            [
                r.method.label,
                repr(r.method.strategy),
                r.seed,
                r.termination,
                repr(r.path_length_m),
                repr(r.uncertain_fraction),
                r.scans,
                r.steps,
                r.contacts,
                repr(r.error_coverage_map),
                repr(r.error_occupancy),
                f"{r.seconds:.3f}",
                f"{r.real_time_factor:.1f}",
                r.building,
            ]
        )
    return out.getvalue()


def write_csv(t: Table1, path: Path) -> Path:
    """Write :func:`csv_text` to ``path`` atomically; returns the path."""
    from covmap._native import write_atomic

    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, csv_text(t).encode())
    return path
