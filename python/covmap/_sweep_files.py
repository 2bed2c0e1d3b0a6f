"""Sweeps to and from files: the specs of a sweep file (``.json`` or
``.toml``, for ``covmap sweep``) and the summaries as CSV, one row per spec."""

from __future__ import annotations

import csv
import io
import json
from typing import TYPE_CHECKING, Any

from covmap._errors import CovmapError, MissingDependencyError
from covmap._sweep import RunSummary, SweepFailure

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

__all__ = ["CSV_FIELDS", "csv_text", "read_specs", "write_csv"]


CSV_FIELDS = (
    "index",
    "world",
    "strategy",
    "seed",
    "options",
    "termination",
    "path_length_m",
    "high_entropy_fraction",
    "scans",
    "steps",
    "contacts",
    "error_coverage_map",
    "error_occupancy",
    "seconds",
    "error",
)
"""The columns of :func:`csv_text`, one row per spec."""


def _option_text(value: Any) -> Any:
    if isinstance(value, (bool, int, float, str)) or value is None:
        return value
    if isinstance(value, tuple):
        return list(value)
    return repr(value)


def csv_text(results: Sequence[RunSummary | None], failures: Sequence[SweepFailure] = ()) -> str:
    """One CSV row per spec, columns :data:`CSV_FIELDS`: a run's figures, or
    for a failed run its index and the error."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(CSV_FIELDS)
    rows: dict[int, RunSummary | SweepFailure] = {f.index: f for f in failures}
    rows.update({r.index: r for r in results if r is not None})
    for index in sorted(rows):
        r = rows[index]
        if isinstance(r, SweepFailure):
            writer.writerow([index, *([""] * (len(CSV_FIELDS) - 2)), f"{r.error_type}: {r.message}"])
            continue
        writer.writerow(
            [
                r.index,
                r.world,
                repr(r.strategy),
                r.seed,
                json.dumps({k: _option_text(v) for k, v in sorted(r.options.items())}),
                r.termination,
                repr(r.path_length_m),
                repr(r.high_entropy_fraction),
                r.scans,
                r.steps,
                r.contacts,
                repr(r.coverage_error.coverage_map),
                repr(r.coverage_error.occupancy),
                f"{r.seconds:.3f}",
                "",
            ]
        )
    return out.getvalue()


def write_csv(
    path: Path, results: Sequence[RunSummary | None], failures: Sequence[SweepFailure] = ()
) -> Path:
    """Write :func:`csv_text` to ``path`` atomically; returns the path."""
    from covmap._native import write_atomic

    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomic(path, csv_text(results, failures).encode())
    return path


def _file_error(path: Path, place: str, reason: str) -> Exception:
    from covmap._errors import FileFormatError

    error = FileFormatError(f"{path}: {place}: {reason}")
    error.filename, error.place, error.reason = str(path), place, reason
    return error


def read_specs(path: Path) -> list[dict[str, Any]]:
    """The specs of a sweep file (``.json`` or ``.toml``), for :func:`sweep`.

    The file holds ``runs``, a list of specs, and optionally ``defaults``,
    keys every run takes unless it gives them itself (a JSON file may also be
    a bare list of specs). A run (or the defaults) may give ``seeds``, a
    list of seeds, in place of ``seed``: one spec each, in that order; a
    table that gives both is refused (one would be dropped), and a run's
    ``seed`` or ``seeds`` replaces either of the defaults'.
    Strategies are written as names or tables (``strategy = { name =
    "counting", n = 50, discount_beyond_m = 2.0 }``), worlds as building
    names (built-in, ``generated:SEED[:AREA]``, a world file). A malformed file raises :class:`~covmap.FileFormatError` naming
    the file and the place; the specs themselves are checked by
    :func:`sweep`.

    TOML needs Python 3.11 (``tomllib``) or the ``tomli`` package."""
    from covmap._read import read_small_file, too_deep

    data = read_small_file(path)
    suffix = path.suffix.lower()
    deep = too_deep(data, "toml" if suffix == ".toml" else "json")
    if deep is not None:
        raise _file_error(path, "content", deep)
    try:
        if suffix == ".json":
            document: Any = json.loads(data)
        elif suffix == ".toml":
            try:
                import tomllib as toml
            except ImportError:
                try:
                    import tomli as toml  # type: ignore[no-redef,import-not-found,unused-ignore]
                except ImportError:
                    raise MissingDependencyError(
                        "reading TOML needs Python 3.11 or the tomli package (pip install tomli)"
                    ) from None
            document = toml.loads(data.decode("utf-8"))
        else:
            raise _file_error(path, "name", f"expected a .json or .toml file, got {suffix or 'no suffix'}")
    except (ValueError, UnicodeDecodeError) as e:
        if isinstance(e, CovmapError):
            raise
        raise _file_error(path, "content", str(e)) from None
    except RecursionError:
        raise _file_error(path, "content", "nested too deeply") from None
    if isinstance(document, list):
        document = {"runs": document}
    if not isinstance(document, dict):
        raise _file_error(path, "top level", f"expected a table with runs, got {type(document).__name__}")
    unknown = set(document) - {"runs", "defaults"}
    if unknown:
        raise _file_error(path, "top level", f"unknown keys {sorted(unknown)}: expected runs and defaults")
    runs, defaults = document.get("runs"), document.get("defaults", {})
    if not isinstance(runs, list) or not runs:
        raise _file_error(path, "runs", "expected a list of runs, at least one")
    if not isinstance(defaults, dict):
        raise _file_error(path, "defaults", f"expected a table, got {type(defaults).__name__}")
    if "seed" in defaults and "seeds" in defaults:
        raise _file_error(path, "defaults", "seed and seeds both given: give one")
    specs: list[dict[str, Any]] = []
    for number, run in enumerate(runs):
        if not isinstance(run, dict):
            raise _file_error(path, f"run {number}", f"expected a table, got {type(run).__name__}")
        if "seed" in run and "seeds" in run:
            raise _file_error(path, f"run {number}", "seed and seeds both given: give one")
        spec = dict(defaults)
        if "seed" in run or "seeds" in run:  # the run's seeds replace the defaults'
            spec.pop("seed", None)
            spec.pop("seeds", None)
        spec.update(run)
        seeds = spec.pop("seeds", None)
        if seeds is None:
            specs.append(spec)
            continue
        if not isinstance(seeds, list) or not seeds:
            raise _file_error(path, f"run {number}", "seeds must be a non-empty list of seeds")
        specs.extend({**spec, "seed": seed} for seed in seeds)
    return specs
