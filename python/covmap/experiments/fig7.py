"""The paper's Fig. 7: scan counting forced to a count ``n`` against the
decision-theoretic strategy, as path length over the fraction of evaluation
cells explored well enough (entropy below epsilon, 1 - Table I's measure).

Each counting run is a point; the mean per ``n`` makes the counting curve
(in the order of ``n``); the coverage runs' mean is a cross with its spread.
The paper's finding: if 85 % or more of the cells must be certain, coverage
maps travel less. :func:`path_at` reads the counting curve at a fraction
(linear interpolation between the means of consecutive ``n`` where the
curve first reaches it), :func:`crossings` where the counting curve reaches
the coverage runs' mean path length. :meth:`Fig7.reaching` reads the runs
on the way (the path at which each first had a fraction certain), which
tells the two halves of a coverage run apart: how soon it makes most of the
cells certain, and how far it drives for the last few.
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable

import numpy as np

from covmap._native import DEFAULT_DISCOUNT_BEYOND_M, Strategy
from covmap._sweep import RunSummary, SweepFailure, sweep
from covmap.experiments.table1 import mean_and_spread

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    from covmap._native import Building

DEFAULT_NS = (1, 2, 5, 10, 20, 35, 50, 70, 90, 110, 130)
"""The paper's counts ``n`` of scan counting."""

FRACTIONS = (0.85, 0.90, 0.95)
"""The fractions of certain cells the comparison is read at."""

CSV_FIELDS = (
    "strategy",
    "n",
    "alpha",
    "seed",
    "termination",
    "path_length_m",
    "certain_fraction",
    "high_entropy_fraction",
    "scans",
    "steps",
    "contacts",
    "seconds",
)
"""The columns of :func:`csv_text`, one row per run."""


@dataclass(frozen=True)
class Point:
    """A point of a curve: the mean certain fraction and path length of some runs."""

    label: str
    """What the runs were (``n = 5``, ``coverage``)."""
    certain: float
    """Mean fraction of the evaluation cells certain at the end."""
    certain_spread: float
    """Its sample standard deviation over the runs."""
    path_m: float
    """Mean path length, metres."""
    path_spread_m: float
    """Its sample standard deviation over the runs."""


def _point(label: str, runs: Sequence[RunSummary]) -> Point:
    certain, certain_spread = mean_and_spread([r.certain_fraction for r in runs])
    path, path_spread = mean_and_spread([r.path_length_m for r in runs])
    return Point(label, certain, certain_spread, path, path_spread)


@dataclass(frozen=True)
class Fig7:
    """The sweep of Fig. 7 in world ``world_name``."""

    world_name: str
    ns: list[int]
    seeds: list[int]
    alpha: float
    options: dict[str, Any]
    """The keywords every run was given beyond world, strategy and seed."""
    counting: list[RunSummary]
    """The counting runs, ``n`` by ``n``, the seeds within."""
    coverage: list[RunSummary]
    """The coverage runs, one a seed."""

    def counting_runs(self, n: int) -> list[RunSummary]:
        """The counting runs with count ``n``."""
        return [r for r in self.counting if r.strategy.n == n]

    @property
    def curve(self) -> list[Point]:
        """The counting curve: the mean of each ``n``'s runs, in the order of ``n``."""
        return [_point(f"n = {n}", self.counting_runs(n)) for n in self.ns]

    @property
    def cross(self) -> Point:
        """The coverage runs' mean and spread."""
        return _point(f"coverage, alpha {self.alpha:g}", self.coverage)

    def reaching(self, fraction: float) -> tuple[float | None, tuple[float, int] | None]:
        """On the way: the coverage runs' mean path when each first had
        ``fraction`` of its cells certain (:func:`reached_at`), and the
        counting ``n`` whose runs all got there soonest, as ``(mean path,
        n)``. ``None`` where some run of coverage (of every ``n``) never got
        there."""
        coverage = mean_reached_at(self.coverage, fraction)
        counting = [(path, n) for n in self.ns if (path := mean_reached_at(self.counting_runs(n), fraction)) is not None]
        return coverage, min(counting, default=None)


MAX_PATH_M = 2000.0
"""Where the sweep's runs stop, metres (unless told otherwise): the range
of the figure. Scan counting with a large ``n`` drives on for kilometres
on the corridor (the loop's own limit is a safety net of 10 km), and the
curve needs no more than this to show where it crosses coverage maps."""


def specs(
    world_name: str | Sequence[str | Building],
    *,
    ns: Sequence[int],
    seeds: Sequence[int],
    alpha: float,
    **options: Any,
) -> list[dict[str, Any]]:
    """The sweep's specs: coverage with ``alpha`` for each building and
    seed, then counting (discounted beyond
    :data:`~covmap.DEFAULT_DISCOUNT_BEYOND_M`) for each ``n`` from the
    largest down, each building and each seed. ``world_name``: one building
    (a name, see :func:`covmap.buildings.building`) or several (names or
    :class:`~covmap.Building` objects). Every run stops at :data:`MAX_PATH_M`
    unless ``options`` give ``max_path_m``.

    The order is the order the runs start in: the long runs (coverage's, a
    large ``n``'s) first and the short ones last, so that the cores finish
    together rather than one of them running a long run alone at the end.
    """
    options = {"max_path_m": MAX_PATH_M, **options}
    worlds = [world_name] if isinstance(world_name, str) else list(world_name)
    coverage = [
        {"world": w, "strategy": Strategy.coverage(alpha), "seed": s, **options} for w in worlds for s in seeds
    ]
    counting = [
        {"world": w, "strategy": Strategy.counting(n, DEFAULT_DISCOUNT_BEYOND_M), "seed": s, **options}
        for n in sorted(ns, reverse=True)
        for w in worlds
        for s in seeds
    ]
    return coverage + counting


def run(
    world_name: str | Sequence[str | Building] = "corridor",
    *,
    ns: Sequence[int] = DEFAULT_NS,
    seeds: Sequence[int] = (0, 1, 2, 3),
    alpha: float = 0.5,
    executor: Any = None,
    progress: bool | Callable[[int, RunSummary | SweepFailure], None] = True,
    **options: Any,
) -> Fig7:
    """Run the sweep of Fig. 7 (:func:`specs`; a failure's index is its
    spec's there) with :func:`covmap.sweep` on ``executor`` (``None``: the
    local cores): in one building, or over several (the benchmark's view,
    ``covmap fig7 --buildings``: every point the mean over the buildings
    and seeds). :class:`~covmap.InvalidValueError` for no ``ns``, no
    ``seeds`` or no buildings: the figure would have no curve or no runs."""
    worlds = [world_name] if isinstance(world_name, str) else list(world_name)
    if not ns or not seeds or not worlds:
        from covmap._errors import InvalidValueError

        raise InvalidValueError(
            f"fig7 needs at least one n and one seed, and a building, got ns={list(ns)}, seeds={list(seeds)}, "
            f"buildings={worlds}"
        )
    all_specs = specs(worlds, ns=ns, seeds=seeds, alpha=alpha, **options)
    summaries = sweep(all_specs, executor=executor, progress=progress)
    first = len(seeds) * len(worlds)
    coverage, counting = summaries[:first], summaries[first:]
    # Counting in the order of ``ns`` (the specs run the largest first),
    # the buildings and seeds within (the sort keeps their order).
    counting.sort(key=lambda r: ns.index(r.strategy.n))
    label = world_name if isinstance(world_name, str) else _label(worlds)
    return Fig7(label, list(ns), list(seeds), alpha, dict(options), counting, coverage)


def _label(worlds: Sequence[str | Building]) -> str:
    """A name for the buildings of a sweep: their names, or how many."""
    names = [w if isinstance(w, str) else w.name for w in worlds]
    return ", ".join(names) if len(names) <= 3 else f"{len(names)} buildings"


def path_at(curve: Sequence[Point], fraction: float) -> float | None:
    """The counting curve's path length where its certain fraction first
    reaches ``fraction``, interpolated linearly between consecutive points
    (``None``: never reached)."""
    if not curve:
        return None
    if curve[0].certain >= fraction:
        return curve[0].path_m
    for a, b in zip(curve, curve[1:]):
        if a.certain < fraction <= b.certain:
            t = (fraction - a.certain) / (b.certain - a.certain)
            return a.path_m + t * (b.path_m - a.path_m)
    return None


def reached_at(run: RunSummary, fraction: float) -> float | None:
    """The run's path length, metres, at the end of its first step after
    which at least ``fraction`` of its evaluation cells were certain (from
    its trace; ``None``: never)."""
    certain = 1.0 - np.asarray(run.trace["uncertain_fraction"], dtype=float)
    hits = np.flatnonzero(certain >= fraction)
    return float(run.trace["path_length_m"][hits[0]]) if hits.size else None


def mean_reached_at(runs: Sequence[RunSummary], fraction: float) -> float | None:
    """The mean of :func:`reached_at` over ``runs`` (``None`` if one of
    them never got there, or there are none)."""
    paths = [reached_at(r, fraction) for r in runs]
    if not paths or any(p is None for p in paths):
        return None
    return sum(p for p in paths if p is not None) / len(paths)


def crossings(curve: Sequence[Point], path_m: float) -> list[float]:
    """The certain fractions at which the counting curve passes the path
    length ``path_m`` (the coverage runs' mean), interpolated linearly
    between consecutive points, in the order of ``n``."""
    found = []
    for a, b in zip(curve, curve[1:]):
        da, db = a.path_m - path_m, b.path_m - path_m
        if da == 0.0:
            found.append(a.certain)
        elif da * db < 0.0:
            t = da / (da - db)
            found.append(a.certain + t * (b.certain - a.certain))
    if curve and curve[-1].path_m == path_m:
        found.append(curve[-1].certain)
    return found


def _pct(x: float) -> str:
    return f"{100.0 * x:.1f} %"


def report(f: Fig7) -> str:
    """The sweep as text: the counting curve, the coverage cross, where they
    cross, and both strategies' path lengths at :data:`FRACTIONS`."""
    lines = [
        f"Fig. 7, {f.world_name}, {len(f.seeds)} seed{'s' if len(f.seeds) != 1 else ''} "
        f"({', '.join(map(str, f.seeds))}); certain: evaluation cells with entropy below epsilon",
    ]
    if f.options:
        lines.append("options: " + ", ".join(f"{k}={v!r}" for k, v in sorted(f.options.items())))
    lines.append(f"{'runs':<22} {'certain (mean ± sd)':>22} {'path [m] (mean ± sd)':>24}")
    for p in [*f.curve, f.cross]:
        label = f"counting {p.label}" if p.label.startswith("n =") else p.label
        lines.append(
            f"{label:<22} {100 * p.certain:>11.1f} ± {100 * p.certain_spread:>5.1f} % "
            f"{p.path_m:>13.1f} ± {p.path_spread_m:>7.1f}"
        )
    cross = f.cross
    found = crossings(f.curve, cross.path_m)
    if found:
        lines.append(
            f"the counting curve passes the coverage runs' mean path ({cross.path_m:.1f} m) at "
            + ", ".join(_pct(x) for x in found)
            + " certain"
        )
    else:
        lines.append(f"the counting curve never passes the coverage runs' mean path ({cross.path_m:.1f} m)")
    best = max(f.curve, key=lambda p: p.certain)
    for fraction in FRACTIONS:
        counting = path_at(f.curve, fraction)
        counting_text = (
            f"counting {counting:.1f} m (interpolated along the curve)"
            if counting is not None
            else f"counting never reaches it (at most {_pct(best.certain)}, {best.label})"
        )
        coverage_text = (
            f"coverage {cross.path_m:.1f} m"
            if cross.certain >= fraction
            else f"coverage does not reach it (mean {_pct(cross.certain)})"
        )
        verdict = ""
        if counting is not None and cross.certain >= fraction:
            verdict = "; coverage travels less" if cross.path_m < counting else "; counting travels less"
        elif cross.certain >= fraction:
            verdict = "; only coverage reaches it"
        lines.append(f"at {100 * fraction:.0f} % certain: {counting_text}; {coverage_text}{verdict}")
    lines.append("on the way (the path at which a run first had the fraction certain, mean over the seeds):")
    for fraction in FRACTIONS:
        on_way, soonest = f.reaching(fraction)
        coverage_text = f"coverage {on_way:.1f} m" if on_way is not None else "not every coverage run gets there"
        counting_text = (
            f"counting {soonest[0]:.1f} m (n = {soonest[1]}, the soonest)"
            if soonest is not None
            else "no n whose every run gets there"
        )
        lines.append(f"  {100 * fraction:.0f} %: {coverage_text}; {counting_text}")
    return "\n".join(lines)


def csv_text(f: Fig7) -> str:
    """One CSV row per run, columns :data:`CSV_FIELDS`."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(CSV_FIELDS)
    for r in [*f.counting, *f.coverage]:
        s = r.strategy
        writer.writerow(
            [
                s.name,
                "" if s.n is None else s.n,
                "" if s.alpha is None else repr(s.alpha),
                r.seed,
                r.termination,
                repr(r.path_length_m),
                repr(r.certain_fraction),
                repr(r.high_entropy_fraction),
                r.scans,
                r.steps,
                r.contacts,
                f"{r.seconds:.3f}",
            ]
        )
    return out.getvalue()


def write_csv(f: Fig7, path: Path) -> Path:
    """Write :func:`csv_text` to ``path`` atomically; returns the path."""
    from covmap._native import write_atomic

    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, csv_text(f).encode())
    return path
