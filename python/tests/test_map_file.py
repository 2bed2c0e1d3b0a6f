"""CoverageMap.save / CoverageMap.load: the posterior file as a user keeps
it: opened by numpy alone, loaded bit for bit, and refused (never misread)
when empty, cut short or changed."""

from __future__ import annotations

import errno
import os
from pathlib import Path

import numpy as np
import pytest

import covmap


def scanned_map(history: bool) -> covmap.CoverageMap:
    grid = covmap.Grid(origin=(-1.0, 0.5), resolution=0.1, shape=(20, 30))
    cmap = covmap.CoverageMap(grid, bins=12)
    cmap.track_history(history)
    for i in range(6):
        cmap.integrate((0.5 + 0.1 * i, 1.5, 0.2 * i), [0.7, 1.1, 5.0], [-0.3, 0.0, 0.3], covmap.SonarModel())
    return cmap


@pytest.mark.parametrize("history", [False, True])
def test_a_saved_map_loads_bit_for_bit(tmp_path: Path, history: bool) -> None:
    cmap = scanned_map(history)
    path = tmp_path / "map.npz"
    cmap.save(path)
    back = covmap.CoverageMap.load(path)
    assert back.grid == cmap.grid and back.bins == cmap.bins
    assert back.histograms.tobytes() == cmap.histograms.tobytes()
    assert back.tracks_history == history
    np.testing.assert_array_equal(back.measurements(), cmap.measurements())
    np.testing.assert_array_equal(back.stagnated(), cmap.stagnated())


def test_numpy_opens_the_file_without_covmap(tmp_path: Path) -> None:
    cmap = scanned_map(True)
    path = tmp_path / "map.npz"
    cmap.save(path)
    with np.load(path) as f:
        assert sorted(f.files) == ["covmap_version", "grid", "histograms", "history_counts", "history_entropies"]
        assert f["covmap_version"].tolist() == [covmap.MAP_FILE_VERSION]
        np.testing.assert_array_equal(f["grid"], [-1.0, 0.5, 0.1])
        assert f["histograms"].dtype == np.float32
        np.testing.assert_array_equal(f["histograms"], cmap.histograms)
        np.testing.assert_array_equal(f["history_counts"], cmap.measurements())


def test_changed_cut_and_empty_files_are_refused(tmp_path: Path) -> None:
    cmap = scanned_map(False)
    path = tmp_path / "map.npz"
    cmap.save(path)
    data = path.read_bytes()
    bad = tmp_path / "bad.npz"
    for name, content in [
        ("empty", b""),
        ("cut", data[: len(data) // 2]),
        ("cut end", data[:-1]),
        ("flipped", data[: len(data) // 2] + bytes([data[len(data) // 2] ^ 0x01]) + data[len(data) // 2 + 1 :]),
    ]:
        bad.write_bytes(content)
        with pytest.raises(covmap.FileFormatError, match="not a valid covmap map file") as caught:
            covmap.CoverageMap.load(bad)
        assert caught.value.filename == str(bad), name
    with pytest.raises(covmap.FileIOError):
        covmap.CoverageMap.load(tmp_path / "absent.npz")


def test_a_failed_save_leaves_nothing_behind(tmp_path: Path) -> None:
    cmap = scanned_map(False)
    with pytest.raises(covmap.FileIOError):
        cmap.save(tmp_path / "no such dir" / "map.npz")
    assert list(tmp_path.iterdir()) == []
    path = tmp_path / "map.npz"
    path.write_bytes(b"an older file")
    cmap.save(path)
    assert covmap.CoverageMap.load(path).histograms.tobytes() == cmap.histograms.tobytes()


def test_ros_occupancy_marks_unknown_and_known_cells() -> None:
    cmap = scanned_map(False)
    data = cmap.ros_occupancy(source="mean", unknown_within_nats=0.0)
    assert data.dtype == np.int8 and data.shape == cmap.grid.shape
    observed = cmap.observed()
    assert (data[~observed] == -1).all()
    np.testing.assert_array_equal(data[observed], np.round(cmap.mean()[observed] * 100).astype(np.int8))
    loose = cmap.ros_occupancy(unknown_within_nats=1.0)
    assert (loose == -1).sum() > (data == -1).sum()
    with pytest.raises(covmap.InvalidValueError):
        cmap.ros_occupancy(source="max")  # type: ignore[arg-type]
    with pytest.raises(covmap.InvalidParameterError):
        cmap.ros_occupancy(unknown_within_nats=-1.0)


@pytest.mark.parametrize("mode", ["trinary", "scale"])
def test_map_server_pairs_read_back_as_the_map(tmp_path: Path, mode: str) -> None:
    world = covmap.World.builtin("corridor")
    (x0, y0, x1, y1) = world.bounds
    grid = covmap.Grid.covering((x0 - 0.5, y0 - 0.5, x1 + 0.5, y1 + 0.5), resolution=0.1)
    poses = np.array([[1.0 + 0.5 * i, 1.3, 0.4 * i] for i in range(12)])
    log = covmap.Laser().record(world, poses, seed=1)
    maps = [covmap.CoverageMap(grid), covmap.OccupancyGrid(grid)]
    for m in maps:
        m.integrate_log(log, covmap.LaserModel())
        yaml = tmp_path / f"{type(m).__name__}-{mode}.yaml"
        m.to_ros_map(yaml, mode=mode)  # type: ignore[arg-type]
        assert f"mode: {mode}" in yaml.read_text()
        data = m.ros_occupancy()
        assert (data == -1).any() and (data >= 65).any()
        back = covmap.World.from_file(yaml)
        occupied = back.coverage(grid) > 0.5
        # In trinary mode every pixel that is not free is an obstacle, the
        # unknown ones among them (a robot never drives where the map saw
        # nothing); in scale mode a pixel reads as its value, the unknown
        # ones below the occupied threshold.
        free_thresh = float(yaml.read_text().split("free_thresh:")[1].split()[0])
        free = (data >= 0) & (data <= round(100 * free_thresh))  # map_saver's white
        expected = ~free if mode == "trinary" else data >= 65
        np.testing.assert_array_equal(occupied, expected)
    with pytest.raises(covmap.InvalidValueError):
        maps[1].to_ros_map(tmp_path / "x.yaml", mode="raw")  # type: ignore[arg-type]
    with pytest.raises(covmap.InvalidParameterError):
        maps[1].to_ros_map(tmp_path / "y.yaml", occupied_thresh=0.1, free_thresh=0.5)
    assert not (tmp_path / "x.yaml").exists() and not (tmp_path / "y.pgm").exists()


def test_to_ros_map_refuses_what_it_cannot_write_whole(tmp_path: Path) -> None:
    cmap = scanned_map(False)
    with pytest.raises(covmap.FileIOError, match="x.pgm"):
        cmap.to_ros_map(tmp_path / "x.pgm")
    assert list(tmp_path.iterdir()) == []
    (tmp_path / "d.yaml").mkdir()
    with pytest.raises(covmap.FileIOError, match="is a directory"):
        cmap.to_ros_map(tmp_path / "d.yaml")
    assert [p.name for p in tmp_path.iterdir()] == ["d.yaml"]
    for bad in (float("nan"), 1.5):
        with pytest.raises(covmap.InvalidParameterError, match="occupied_thresh"):
            cmap.to_ros_map(tmp_path / "t.yaml", occupied_thresh=bad)
    with pytest.raises(covmap.InvalidParameterError, match="free_thresh"):
        cmap.to_ros_map(tmp_path / "t.yaml", free_thresh=float("nan"))
    assert [p.name for p in tmp_path.iterdir()] == ["d.yaml"]


def test_file_io_errors_say_the_reason_and_the_file(tmp_path: Path) -> None:
    missing = tmp_path / "missing.log"
    for read in (covmap.Log.from_carmen, covmap.CoverageMap.load):
        with pytest.raises(covmap.FileIOError) as caught:
            read(missing)
        assert caught.value.errno == errno.ENOENT, read
        assert caught.value.filename == str(missing)
        assert str(caught.value) == f"[Errno {errno.ENOENT}] {os.strerror(errno.ENOENT)}: {str(missing)!r}"
        # Refused by covmap itself: no errno, the reason and the file in the text.
        with pytest.raises(covmap.FileIOError) as caught:
            read(tmp_path)
        assert caught.value.errno is None and caught.value.filename == str(tmp_path)
        assert "not a regular file" in str(caught.value) and str(tmp_path) in str(caught.value), read
        assert "None" not in str(caught.value)
