"""The exploration benchmark's file: one CSV row a run
(:func:`write_csv`), read back as the runs (:func:`read_csv`), so that the
views of a benchmark (``covmap benchmark --report``) need not run it
again."""

from __future__ import annotations

import csv
import io
from typing import TYPE_CHECKING

from covmap.experiments.benchmark import SENSORS, Benchmark, BenchmarkRun

if TYPE_CHECKING:
    from pathlib import Path

__all__ = ["CSV_FIELDS", "csv_text", "read_csv", "write_csv"]


CSV_FIELDS = (
    "building",
    "split",
    "strategy",
    "sensor",
    "seed",
    "termination",
    "uncertain_fraction",
    "rooms",
    "rooms_never_entered",
    "rooms_never_entered_names",
    "path_length_m",
    "scans",
    "steps",
    "contacts",
    "error_coverage_map",
    "error_occupancy",
    "evaluation_area_m2",
    "seconds",
    "real_time_factor",
)
"""The columns of :func:`csv_text`, one row a run."""


def csv_text(b: Benchmark) -> str:
    """One CSV row a run, columns :data:`CSV_FIELDS`."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(CSV_FIELDS)
    for r in b.runs:
        writer.writerow(
            [
                r.building,
                r.split,
                r.strategy,
                r.sensor,
                r.seed,
                r.termination,
                repr(r.uncertain_fraction),
                "" if r.rooms is None else r.rooms,
                r.rooms_missed,
                ";".join(r.rooms_never_entered),
                repr(r.path_length_m),
                r.scans,
                r.steps,
                r.contacts,
                repr(r.error_coverage_map),
                repr(r.error_occupancy),
                repr(r.evaluation_area_m2),
                repr(r.seconds),
                f"{r.real_time_factor:.1f}",
            ]
        )
    return out.getvalue()


def read_csv(path: Path) -> Benchmark:
    """The benchmark whose runs :func:`write_csv` wrote to ``path`` (its
    options are not in the file): the views and the figure of an earlier
    run, without running it again. A file that is not such a CSV raises
    :class:`~covmap.FileFormatError` naming the file and the row."""
    from covmap._errors import FileFormatError
    from covmap._read import read_small_file

    def bad(place: str, reason: str) -> FileFormatError:
        error = FileFormatError(f"{path}: {place}: {reason}")
        error.filename, error.place, error.reason = str(path), place, reason
        return error

    try:
        text = read_small_file(path).decode("utf-8")
    except UnicodeDecodeError as e:
        raise bad("content", str(e)) from None
    rows = list(csv.reader(io.StringIO(text)))
    if not rows or tuple(rows[0]) != CSV_FIELDS:
        raise bad("header", f"expected the columns {', '.join(CSV_FIELDS)}")
    runs = []
    for number, row in enumerate(rows[1:], start=2):
        if len(row) != len(CSV_FIELDS):
            raise bad(f"row {number}", f"expected {len(CSV_FIELDS)} values, got {len(row)}")
        v = dict(zip(CSV_FIELDS, row))
        try:
            runs.append(
                BenchmarkRun(
                    building=v["building"],
                    split=v["split"],
                    strategy=v["strategy"],
                    sensor=v["sensor"],
                    seed=int(v["seed"]),
                    termination=v["termination"],
                    uncertain_fraction=float(v["uncertain_fraction"]),
                    rooms=int(v["rooms"]) if v["rooms"] else None,
                    rooms_never_entered=tuple(v["rooms_never_entered_names"].split(";"))
                    if v["rooms_never_entered_names"]
                    else (),
                    path_length_m=float(v["path_length_m"]),
                    scans=int(v["scans"]),
                    steps=int(v["steps"]),
                    contacts=int(v["contacts"]),
                    error_coverage_map=float(v["error_coverage_map"]),
                    error_occupancy=float(v["error_occupancy"]),
                    evaluation_area_m2=float(v["evaluation_area_m2"]),
                    seconds=float(v["seconds"]),
                )
            )
        except ValueError as e:
            raise bad(f"row {number}", str(e)) from None
        if runs[-1].sensor not in SENSORS:
            raise bad(f"row {number}", f"unknown sensor {runs[-1].sensor!r}")
    return Benchmark(runs, {})


def write_csv(b: Benchmark, path: Path) -> Path:
    """Write :func:`csv_text` to ``path`` atomically; returns the path."""
    from covmap._native import write_atomic

    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, csv_text(b).encode())
    return path
