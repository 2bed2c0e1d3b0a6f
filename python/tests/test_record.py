"""Recordings for the Rerun viewer (``covmap.record``, ``--record`` of
``covmap explore``, ``covmap map`` and ``covmap view``), read back with
Rerun's own reader: the entities and the number of steps. No display."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import covmap
from cli_helpers import run_cli
from extras import need_extra
from test_exploration import room


rr = need_extra("rerun", "rerun", "the recording tests")

ROOM = room()


def contents(path: Path) -> dict[str, Any]:
    """Per entity of the recording: its rows' values on each timeline, and
    whether it is static."""
    from rerun.chunk import RrdReader

    out: dict[str, Any] = {}
    for chunk in RrdReader(path).stream():
        batch = chunk.to_record_batch()
        entry = out.setdefault(chunk.entity_path, {"static": chunk.is_static, "rows": 0, "timelines": {}, "names": set()})
        entry["rows"] += chunk.num_rows
        entry["names"] |= set(chunk.timeline_names)
        for timeline in set(chunk.timeline_names) & {"step", "scan", "path_cm"}:
            entry["timelines"].setdefault(timeline, []).extend(batch.column(timeline).to_pylist())
    return out


def test_an_exploration_is_recorded_step_by_step(tmp_path: Path) -> None:
    path = tmp_path / "run.rrd"
    result = covmap.record(path, ROOM, covmap.Strategy.coverage(), seed=1, resolution=0.1, max_steps=5)
    direct = covmap.explore(ROOM, covmap.Strategy.coverage(), seed=1, resolution=0.1, max_steps=5)
    assert (result.path_length_m, result.scans) == (direct.path_length_m, direct.scans)
    seen = contents(path)
    for entity in ("/map/coverage", "/map/entropy", "/robot/pose", "/robot/path", "/robot/beams", "/plan/candidates", "/plan/goal", "/stats/uncertain_share"):
        assert entity in seen, (entity, sorted(seen))
    assert seen["/map/outline"]["static"]
    assert set().union(*(e["names"] for e in seen.values())) == {"step", "path_cm"}  # no wall-clock time
    # The start and every step: one frame each, on the step timeline and by path.
    steps = sorted(set(seen["/map/entropy"]["timelines"]["step"]))
    assert steps == list(range(result.steps + 1))
    assert sorted(set(seen["/plan/goal"]["timelines"]["step"])) == list(range(1, result.steps + 1))
    path_cm = seen["/robot/pose"]["timelines"]["path_cm"]
    assert max(path_cm) == round(result.path_length_m * 100) and path_cm == sorted(path_cm)


def test_the_explore_command_records(tmp_path: Path) -> None:
    path = tmp_path / "run.rrd"
    done = run_cli("explore", "--world", "corridor", "--max-steps", "3", "--resolution", "0.1", "--record", str(path), "--out", str(tmp_path / "out"))
    assert done.returncode == 1 and "ended at a limit" in done.stdout, done.stderr  # 3 steps: a limit
    seen = contents(path)
    assert sorted(set(seen["/map/coverage"]["timelines"]["step"])) == [1, 2, 3]
    assert "/robot/beams" in seen and "/plan/candidates" in seen


def test_a_mapped_log_and_a_saved_posterior_are_recorded(tmp_path: Path) -> None:
    world = covmap.World.builtin("corridor")
    poses = np.array([[1.0 + 0.5 * i, 1.3, 0.0] for i in range(12)])
    log = covmap.SonarRing().record(world, poses, seed=0)
    cmap = covmap.CoverageMap(covmap.Grid.covering(world.bounds, resolution=0.1))
    cmap.integrate_log(log, covmap.SonarModel())
    from covmap._record import record_log, record_map

    record_log(tmp_path / "log.rrd", log, cmap, every=3)
    seen = contents(tmp_path / "log.rrd")
    assert sorted(set(seen["/robot/beams"]["timelines"]["scan"])) == [0, 3, 6, 9]
    assert "/map/coverage" in seen
    npz = tmp_path / "map.npz"
    cmap.save(npz)
    done = run_cli("view", str(npz), "--record", str(tmp_path / "view.rrd"), "--out", str(tmp_path / "view"))
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "view" / "map.png").is_file()
    assert {"/map/coverage", "/map/entropy"} <= set(contents(tmp_path / "view.rrd"))


def test_a_recording_that_cannot_be_written_is_refused_before_anything_runs(tmp_path: Path) -> None:
    (tmp_path / "folder.rrd").mkdir()
    with pytest.raises(covmap.FileIOError):
        covmap.record(tmp_path / "folder.rrd", ROOM, covmap.Strategy.coverage(), resolution=0.1, max_steps=2)
    with pytest.raises(covmap.FileIOError, match="no directory"):
        covmap.record(tmp_path / "absent" / "run.rrd", ROOM, covmap.Strategy.coverage(), resolution=0.1, max_steps=2)
    fifo = tmp_path / "fifo.rrd"
    os.mkfifo(fifo)
    with pytest.raises(covmap.FileIOError):
        covmap.record(fifo, ROOM, covmap.Strategy.coverage(), resolution=0.1, max_steps=2)
    assert fifo.is_fifo()
    with pytest.raises(covmap.InvalidTypeError):
        covmap.record(3, ROOM, covmap.Strategy.coverage())  # type: ignore[arg-type]


def test_without_rerun_the_error_says_what_to_install(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    import sys

    monkeypatch.setitem(sys.modules, "rerun", None)
    with pytest.raises(covmap.MissingDependencyError, match=r"covmap\[rerun\]"):
        covmap.record(tmp_path / "run.rrd", ROOM, covmap.Strategy.coverage(), resolution=0.1, max_steps=2)
    assert not (tmp_path / "run.rrd").exists()


def test_a_run_that_raises_writes_no_recording(tmp_path: Path) -> None:
    def broken(view: covmap.StrategyView) -> None:
        raise RuntimeError("the strategy's own error")

    path = tmp_path / "run.rrd"
    path.write_bytes(b"kept")
    with pytest.raises(RuntimeError):
        covmap.record(path, ROOM, covmap.Strategy.custom(broken), resolution=0.1, max_steps=3)
    assert path.read_bytes() == b"kept"
