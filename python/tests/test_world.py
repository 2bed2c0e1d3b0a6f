"""Worlds: construction, ground-truth coverage, ray casts, files."""

from __future__ import annotations

import errno
import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

import covmap

UNIT_SQUARE = np.array([[0.23, 0.37], [1.23, 0.37], [1.23, 1.37], [0.23, 1.37]])
"""A 1 m x 1 m square whose sides fall inside cells of a 0.1 m grid."""


def block(x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]], dtype=np.float64)


def test_unit_square_coverage_sums_to_its_area() -> None:
    world = covmap.World(polygons=[UNIT_SQUARE])
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(20, 20))
    coverage = world.coverage(grid)
    assert coverage.shape == (20, 20) and coverage.dtype == np.float64
    assert abs(coverage.sum() * 0.01 - 1.0) < 1e-9
    assert coverage.min() >= 0.0 and coverage.max() <= 1.0
    # The cell holding the corner (0.23, 0.37): covered over [0.23, 0.3) x [0.37, 0.4).
    assert coverage[3, 2] == pytest.approx(0.7 * 0.3, abs=1e-9)
    assert coverage[8, 8] == pytest.approx(1.0, abs=1e-12)
    assert coverage[0, 0] == 0.0


def test_coverage_rows_run_along_y() -> None:
    # A strip across the top of the grid only.
    world = covmap.World([block(0.0, 0.8, 2.0, 1.0)])
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(10, 20))
    coverage = world.coverage(grid)
    np.testing.assert_allclose(coverage[8:], 1.0)
    np.testing.assert_allclose(coverage[:8], 0.0)


def test_triangle_coverage_is_exact() -> None:
    world = covmap.World([[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0)]])
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=1.0, shape=(2, 2))
    np.testing.assert_array_equal(world.coverage(grid), [[0.5, 1.0], [0.0, 0.5]])


def test_overlapping_polygons_count_once() -> None:
    world = covmap.World([block(0, 0, 2, 2), block(1, 1, 3, 3)])
    grid = covmap.Grid(origin=(-0.5, -0.5), resolution=0.25, shape=(16, 16))
    assert world.coverage(grid).sum() * 0.25**2 == pytest.approx(7.0, abs=1e-9)
    assert world.polygon_area_m2 == pytest.approx(8.0)


def test_cast_against_hand_computed_geometry() -> None:
    square = covmap.World([block(2.0, -0.5, 3.0, 0.5)])
    distances = square.cast(np.array([[0.0, 0.0]]), np.array([0.0]), 10.0)
    assert distances.dtype == np.float64 and distances.shape == (1,)
    assert distances[0] == pytest.approx(2.0, abs=1e-12)
    # A wall face x = 2 from y = -5 to 5: at 45 degrees the ray travels 2 sqrt(2)
    # and meets the face at 45 degrees; backwards it meets nothing.
    wall = covmap.World([block(2.0, -5.0, 3.0, 5.0)])
    origins = np.zeros((3, 2))
    angles = np.array([math.pi / 4, math.pi, 0.0])
    distances, incidence = wall.cast(origins, angles, 10.0, return_incidence=True)
    np.testing.assert_allclose(distances, [2 * math.sqrt(2), 10.0, 2.0], atol=1e-12)
    assert incidence[0] == pytest.approx(math.pi / 4, abs=1e-12)
    assert math.isnan(incidence[1])
    assert incidence[2] == pytest.approx(0.0, abs=1e-12)


def test_cast_shares_one_origin_between_rays() -> None:
    world = covmap.World([block(2.0, -5.0, 3.0, 5.0)])
    angles = np.array([0.0, 0.3, -0.3])
    shared = world.cast((0.0, 0.0), angles, 10.0)
    np.testing.assert_array_equal(shared, world.cast(np.zeros((3, 2)), angles, 10.0))
    np.testing.assert_allclose(shared, 2.0 / np.cos(angles), rtol=1e-12)


def test_queries_and_attributes() -> None:
    world = covmap.World([block(2.0, -1.0, 3.0, 1.0), UNIT_SQUARE], materials=["glass", "wall"])
    assert len(world) == 2
    assert world.materials == ["glass", "wall"]
    assert world.bounds == pytest.approx((0.23, -1.0, 3.0, 1.37))
    assert world.contains(2.5, 0.0) and not world.contains(1.5, 0.0)
    assert world.distance_to_obstacle(1.5, -0.5) == pytest.approx(0.5)
    assert world.distance_to_obstacle(2.5, 0.0) == 0.0
    exterior = world.polygons[0]
    assert exterior.shape == (4, 2) and exterior.dtype == np.float64
    assert world.holes == [[], []]


def test_builtin_worlds() -> None:
    names = covmap.World.builtin_names()
    assert names == ["corridor", "office", "partial"]
    corridor = covmap.World.builtin("corridor")
    # The documented geometry: the centre line y = 1.3 is free, the west wall's
    # inner face is x = 0.
    assert not any(corridor.contains(x, 1.3) for x in np.linspace(0.3, 16.5, 50))
    assert corridor.cast((2.0, 1.3), [math.pi], 10.0)[0] == pytest.approx(2.0, abs=1e-9)
    partial = covmap.World.builtin("partial")
    assert partial.bounds == pytest.approx((2.04, -1.0, 2.5, 1.0))


def test_unknown_builtin_name() -> None:
    with pytest.raises(covmap.UnknownWorldError, match="corridor, office, partial") as info:
        covmap.World.builtin("atlantis")
    assert isinstance(info.value, ValueError) and isinstance(info.value, covmap.CovmapError)


@pytest.mark.parametrize(
    ("polygons", "materials", "cls"),
    [
        ([UNIT_SQUARE, [(0.0, 0.0), (1.0, 0.0)]], None, covmap.InvalidPolygonError),
        ([[(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 1.0)]], None, covmap.InvalidPolygonError),
        ([[(0.0, 0.0), (1.0, 0.0), (math.nan, 1.0)]], None, covmap.InvalidPolygonError),
        ([UNIT_SQUARE], ["wall", "glass"], covmap.LengthMismatchError),
        ([UNIT_SQUARE], ["Glass"], covmap.InvalidParameterError),
        ([UNIT_SQUARE.astype(np.int64)], None, covmap.ArrayDtypeError),
        ([np.zeros((4, 3))], None, covmap.ArrayShapeError),
        ([[(0.0, 0.0, 1.0), (1.0, 0.0, 1.0), (1.0, 1.0, 1.0)]], None, covmap.ArrayShapeError),
    ],
    ids=["two vertices", "bow tie", "nan vertex", "materials length", "material name", "int dtype", "3 columns",
         "triples"],
)
def test_bad_polygons_raise(polygons: list, materials: list[str] | None, cls: type[Exception]) -> None:
    with pytest.raises(cls) as info:
        covmap.World(polygons, materials=materials)
    assert isinstance(info.value, covmap.CovmapError)


def test_invalid_polygon_is_named_by_index() -> None:
    with pytest.raises(covmap.InvalidPolygonError, match="polygon 1"):
        covmap.World([UNIT_SQUARE, [(0.0, 0.0), (1.0, 0.0)]])


def test_bad_rays_raise() -> None:
    world = covmap.World([UNIT_SQUARE])
    with pytest.raises(covmap.InvalidValueError, match="index 1"):
        world.cast(np.array([[0.0, 0.0], [math.nan, 0.0]]), np.zeros(2), 5.0)
    with pytest.raises(covmap.InvalidValueError):
        world.cast((0.0, 0.0), np.array([0.0, math.inf]), 5.0)
    with pytest.raises(covmap.LengthMismatchError):
        world.cast(np.zeros((3, 2)), np.zeros(2), 5.0)
    with pytest.raises(covmap.InvalidParameterError):
        world.cast((0.0, 0.0), np.zeros(2), 0.0)
    with pytest.raises(covmap.ArrayDtypeError):
        world.cast((0.0, 0.0), np.zeros(2, dtype=np.float16), 5.0)
    with pytest.raises(covmap.ArrayShapeError):
        world.cast(np.zeros(3), np.zeros(2), 5.0)


def test_geojson_round_trip(tmp_path: Path) -> None:
    world = covmap.World([block(2.0, -1.0, 3.0, 1.0), UNIT_SQUARE], materials=["glass", "wall"])
    path = tmp_path / "w.geojson"
    path.write_text(world.to_geojson())
    again = covmap.World.from_file(path)
    assert again.materials == world.materials
    for a, b in zip(again.polygons, world.polygons):
        np.testing.assert_array_equal(a, b)
    json_path = tmp_path / "w.json"
    json_path.write_text(world.to_geojson())
    assert len(covmap.World.from_file(str(json_path))) == 2


def test_malformed_geojson_names_the_file(tmp_path: Path) -> None:
    path = tmp_path / "broken.geojson"
    path.write_text('{"type": "FeatureCollection", "features": [')
    with pytest.raises(covmap.FileFormatError) as info:
        covmap.World.from_file(path)
    e = info.value
    assert isinstance(e, ValueError) and isinstance(e, covmap.CovmapError)
    assert str(path) in str(e)
    assert e.filename == str(path)
    assert e.place == "line 1, column 43"
    degenerate = tmp_path / "flat.geojson"
    degenerate.write_text('{"type": "Polygon", "coordinates": [[[0,0],[1,1],[2,2],[0,0]]]}')
    with pytest.raises(covmap.FileFormatError, match="flat.geojson"):
        covmap.World.from_file(degenerate)


def test_missing_and_unknown_files(tmp_path: Path) -> None:
    with pytest.raises(covmap.FileIOError) as info:
        covmap.World.from_file(tmp_path / "missing.map")
    assert isinstance(info.value, OSError)
    assert info.value.errno == errno.ENOENT
    assert info.value.filename == str(tmp_path / "missing.map")
    other = tmp_path / "world.txt"
    other.write_text("")
    with pytest.raises(covmap.FileFormatError, match="unknown extension"):
        covmap.World.from_file(other)


def test_aria_map_from_text(tmp_path: Path) -> None:
    path = tmp_path / "tiny.map"
    path.write_text("2D-Map\nNumLines: 2\nLINES\n0 0 4000 0\n4000 0 4000 3000\nDATA\n1 2\n")
    thin = covmap.World.from_file(path)
    thick = covmap.World.from_file(path, wall_thickness_m=0.3)
    assert len(thin) == 2
    assert thin.contains(2.0, 0.04) and not thin.contains(2.0, 0.1)
    assert thick.contains(2.0, 0.1)
    # Each wall is extended by half its thickness at both ends: t * (length + t).
    assert thin.polygon_area_m2 == pytest.approx(0.1 * 4.1 + 0.1 * 3.1)
    assert thick.polygon_area_m2 == pytest.approx(0.3 * 4.3 + 0.3 * 3.3)
    (tmp_path / "bad.map").write_text("2D-Map\nLINES\n0 0 10\n")
    with pytest.raises(covmap.FileFormatError, match="line 3"):
        covmap.World.from_file(tmp_path / "bad.map")


def test_occupancy_image_needs_a_resolution(tmp_path: Path) -> None:
    # 4 x 2 pixels: a dark run of two pixels on the top row.
    path = tmp_path / "tiny.pgm"
    path.write_bytes(b"P2\n4 2\n255\n255 0 0 255\n255 255 255 255\n")
    with pytest.raises(covmap.InvalidParameterError, match="resolution"):
        covmap.World.from_file(path)
    world = covmap.World.from_file(path, resolution=0.5, origin=(10.0, 0.0))
    assert world.bounds == pytest.approx((10.5, 0.5, 11.5, 1.0))


def test_aria_office_from_the_shared_data(shared_world: Callable[[str], Path]) -> None:
    world = covmap.World.from_file(shared_world("AMROffice.map"))
    assert len(world) == 243
    # LineMinPos -11682 -4183, LineMaxPos 5213 26519 (mm), widened by the walls.
    for got, want in zip(world.bounds, (-11.682, -4.183, 5.213, 26.519)):
        assert abs(got - want) <= 0.1, world.bounds


def test_stata_basement_from_the_shared_data(shared_world: Callable[[str], Path]) -> None:
    world = covmap.World.from_file(shared_world("stata_basement.yaml"))
    # 1730 x 1300 pixels of 0.0504 m, rotated by 3.14 rad about (25.9, 48.5).
    x0, y0, x1, y1 = world.bounds
    assert x1 <= 25.9 + 0.2 and x0 >= 25.9 - 1730 * 0.0504 - 0.2
    assert y1 <= 48.5 + 0.2 and y0 >= 48.5 - 1300 * 0.0504 - 0.2
    # Disjoint rectangles: the exact coverage adds up to their areas.
    grid = covmap.Grid.covering((x0 - 0.1, y0 - 0.1, x1 + 0.1, y1 + 0.1), resolution=0.1)
    covered = world.coverage(grid).sum() * 0.01
    assert covered == pytest.approx(world.polygon_area_m2, rel=1e-9)
