"""Buildings: the seeded generator, plans as buildings, building names and
the split, rooms entered, worlds from map_server images (unknown pixels)
and where a seeded start lies."""

from __future__ import annotations

import inspect
import pickle
from pathlib import Path
from typing import Callable

import numpy as np
import pytest

import covmap
from covmap import buildings


def test_the_same_seed_gives_the_same_building() -> None:
    a = covmap.Building.generate(5)
    b = covmap.Building.generate(5)
    assert a.to_json() == b.to_json()
    assert all(np.array_equal(p, q) for p, q in zip(a.world.polygons, b.world.polygons))
    assert a.to_json() != covmap.Building.generate(6).to_json()
    assert a.name == "generated:5"
    assert covmap.Building.generate(5, area_m2=300).name == "generated:5:300"
    back = pickle.loads(pickle.dumps(a))
    assert back.to_json() == a.to_json() and back.name == a.name
    assert covmap.Building.from_json(a.to_json()).to_json() == a.to_json()


def test_the_documented_defaults_are_the_generators() -> None:
    """The signature's defaults make the building the defaults make."""
    defaults = {
        name: p.default
        for name, p in inspect.signature(covmap.Building.generate).parameters.items()
        if p.default is not inspect.Parameter.empty
    }
    assert defaults == {
        "area_m2": 200.0,
        "clutter": 0.5,
        "glass": 0.2,
        "door_width_m": (0.8, 1.2),
        "corridor_width_m": (1.5, 3.0),
        "room_size_m": (2.5, 6.0),
        "wall_thickness_m": (0.1, 0.2),
    }
    assert covmap.Building.generate(3, **defaults).to_json() == covmap.Building.generate(3).to_json()


@pytest.mark.parametrize("seed", [0, 1, 1000, 1001])
def test_rooms_doors_and_materials(seed: int) -> None:
    b = covmap.Building.generate(seed, area_m2=250)
    kinds = {r.kind for r in b.rooms}
    assert "corridor" in kinds and "room" in kinds and kinds <= {"room", "corridor", "hall"}
    assert len({r.name for r in b.rooms}) == len(b.rooms)
    for door in b.doors:
        i, j = door.rooms
        hall = "hall" in (b.rooms[i].kind, b.rooms[j].kind)
        low, high = (2.0, 3.5) if hall else (0.8, 1.2)
        assert low - 1e-9 <= door.width_m <= high + 1e-9, door
        # The opening is free: the robot's disc fits in its middle.
        assert b.world.distance_to_obstacle(*door.center) >= 0.25
    for room in b.rooms:
        assert room.floor.shape[1] == 4 and room.area_m2 > 0
    assert 0.6 * 250 < b.floor_area_m2 < 250
    assert set(b.world.materials) <= {"wall", "glass"}
    assert len(b.world) > len(b.rooms)


def test_glass_and_clutter_follow_their_parameters() -> None:
    bare = covmap.Building.generate(2, area_m2=300, clutter=0.0, glass=0.0)
    full = covmap.Building.generate(2, area_m2=300, clutter=1.0, glass=1.0)
    assert "glass" not in bare.world.materials
    assert full.world.materials.count("glass") >= len([r for r in full.rooms if r.kind == "room"]) // 2
    assert len(full.world) > len(bare.world)


def test_every_room_is_entered_by_a_drive_through_its_door() -> None:
    """A drive from the first corridor's middle to each door and into the
    room beyond enters that room; a drive along the corridor enters none."""
    b = covmap.Building.generate(7)
    corridor = b.rooms[0].floor[0]
    middle = ((corridor[0] + corridor[2]) / 2, (corridor[1] + corridor[3]) / 2)
    entered = b.rooms_entered(np.array([middle]))
    assert entered[0] and not entered[1:].any()
    assert b.rooms_never_entered([middle]) == [r.name for r in b.rooms if r.kind != "corridor"]
    poses = np.array([[middle[0], middle[1], 0.0]])
    assert np.array_equal(b.rooms_entered(poses), entered)
    for door in b.doors:
        i, j = door.rooms
        room = b.rooms[j]
        f = room.floor[0]
        inside = ((f[0] + f[2]) / 2, (f[1] + f[3]) / 2)
        path = [door.center, inside]
        assert b.rooms_entered(path)[j], (door, room)


def test_plans_are_buildings_with_rooms_by_the_rule() -> None:
    corridor = covmap.Building.builtin("corridor")
    assert corridor.name == "corridor" and corridor.doors == []
    # Three rooms and the corridor; the east room's rotated box leaves
    # passages narrower than 1.3 m either side: five regions.
    assert [r.name for r in corridor.rooms] == [f"region {k}" for k in range(1, 6)]
    same = covmap.Building.from_world(covmap.World.builtin("corridor"), "c")
    assert same.name == "c" and len(same.rooms) == 5
    # Along the corridor's centre line: only the corridor's region.
    along = np.array([[1.0, 1.3], [16.0, 1.3]])
    assert corridor.rooms_entered(along).sum() == 1
    assert len(corridor.rooms_never_entered(along)) == 4


def test_references_name_buildings() -> None:
    assert buildings.building("generated:3").to_json() == covmap.Building.generate(3).to_json()
    b = buildings.building("generated:3:150")
    assert b.to_json() == covmap.Building.generate(3, area_m2=150).to_json()
    assert buildings.building("office").name == "office"
    assert buildings.building(b) is b
    assert buildings.building(covmap.World.builtin("partial")).name == "world"
    assert buildings.split_of("generated:3") == "development"
    assert buildings.split_of("generated:1003:550") == "test"
    assert buildings.split_of("generated:5000") == "-"
    assert buildings.split_of("corridor") == "development"
    assert buildings.split_of("AMROffice.map") == "test"
    assert buildings.split_of("mine.map") == "-"
    assert set(buildings.DEVELOPMENT_SEEDS).isdisjoint(buildings.TEST_SEEDS)


def test_building_sets() -> None:
    default = buildings.building_set("default")
    assert [b.name for b in default] == [f"generated:{s}:120" for s in range(4)]
    development = buildings.building_set("development", count=4)
    assert [b.name for b in development] == [
        "generated:0:120",
        "generated:1:250",
        "generated:2:550",
        "generated:3:120",
        "corridor",
        "office",
    ]
    test = buildings.building_set("test", count=2, plans=False)
    assert [b.name for b in test] == ["generated:1000:120", "generated:1001:250"]
    assert all(buildings.split_of(b.name) == "test" for b in test)
    found = buildings.buildings(["default", "corridor"], count=1)
    assert [b.name for b in found] == ["generated:0:120", "corridor"]


def test_the_test_set_holds_the_real_plans(shared_world: Callable[[str], Path]) -> None:
    folder = shared_world("AMROffice.map").parent
    test = buildings.building_set("test", count=1, plans_dir=folder)
    assert [b.name for b in test] == ["generated:1000:120", *buildings.TEST_PLANS]
    amr = test[1]
    # Rooms of the real plan by the rule: a dozen or more regions.
    assert len(amr.rooms) >= 10
    with pytest.raises(covmap.FileIOError, match="missing"):
        buildings.building_set("test", count=1, plans_dir=folder / "nowhere")


@pytest.mark.parametrize(
    ("keywords", "name"),
    [
        ({"area_m2": float("nan")}, "area_m2"),
        ({"area_m2": -10.0}, "area_m2"),
        ({"area_m2": 5.0}, "area_m2"),
        ({"clutter": 2.0}, "clutter"),
        ({"glass": -0.1}, "glass"),
        ({"door_width_m": (0.4, 1.0)}, "door_width_m[0]"),
        ({"door_width_m": (1.0, 0.8)}, "door_width_m[1]"),
        ({"corridor_width_m": (float("nan"), 2.0)}, "corridor_width_m[0]"),
        ({"room_size_m": (1.5, 4.0)}, "room_size_m[0]"),
        ({"wall_thickness_m": (-0.1, 0.1)}, "wall_thickness_m[0]"),
    ],
)
def test_bad_generator_parameters_are_named(keywords: dict[str, object], name: str) -> None:
    with pytest.raises(covmap.InvalidParameterError, match=name.replace("[", r"\[").replace("]", r"\]")):
        covmap.Building.generate(0, **keywords)  # type: ignore[arg-type]


def test_bad_names_and_files_are_typed_errors(tmp_path: Path) -> None:
    with pytest.raises(covmap.UnknownWorldError, match="atlantis"):
        buildings.building("atlantis")
    with pytest.raises(covmap.UnknownWorldError, match="generated:SEED"):
        buildings.building("generated:1:2:3")
    with pytest.raises(covmap.InvalidParameterError, match="generated:x"):
        buildings.building("generated:x")
    with pytest.raises(covmap.InvalidParameterError, match="area_m2"):
        buildings.building("generated:1:-5")
    with pytest.raises(covmap.FileIOError):
        buildings.building(str(tmp_path / "missing.map"))
    garbage = tmp_path / "garbage.yaml"
    garbage.write_text("image: [\n")
    with pytest.raises(covmap.FileFormatError, match="garbage.yaml"):
        covmap.Building.from_file(garbage)
    with pytest.raises(covmap.UnknownWorldError, match="atlantis"):
        buildings.building_set("atlantis")
    for count in (0, -1, 10**6, True):
        with pytest.raises(covmap.InvalidParameterError, match="count"):
            buildings.building_set("test", count=count)  # type: ignore[arg-type]
    with pytest.raises(covmap.InvalidTypeError):
        buildings.building(3)  # type: ignore[arg-type]
    with pytest.raises(covmap.FileFormatError):
        covmap.Building.from_json("{")


def write_map(path: Path, pixels: np.ndarray, resolution: float = 0.1) -> Path:
    """A map_server pair: ``pixels`` (rows from the top) as a PGM, and its YAML."""
    height, width = pixels.shape
    path.with_suffix(".pgm").write_bytes(f"P5\n{width} {height}\n255\n".encode() + pixels.astype(np.uint8).tobytes())
    path.write_text(
        f"image: {path.with_suffix('.pgm').name}\nresolution: {resolution}\norigin: [0.0, 0.0, 0.0]\n"
        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n"
    )
    return path


def test_unknown_pixels_are_obstacles_and_the_start_lies_in_the_known_free_space(tmp_path: Path) -> None:
    """A mapped room (white, 3 x 3 m, walls black) inside a large unknown
    (grey) area: the unknown is an obstacle, the seeded start lies in the
    room, never in the unmapped grey."""
    pixels = np.full((100, 100), 205)
    pixels[20:52, 20:52] = 0
    pixels[21:51, 21:51] = 254
    world = covmap.World.from_file(write_map(tmp_path / "map.yaml", pixels))
    assert world.contains(1.0, 1.0)  # unknown: an obstacle
    assert not world.contains(3.5, 6.5)  # the room's free space
    for seed in range(4):
        run = covmap.Exploration(world, covmap.Strategy.frontier(), seed=seed, resolution=0.1, max_steps=1)
        x, y = run.pose[:2]
        assert 2.1 < x < 5.1 and 4.9 < y < 7.9, (seed, run.pose)


def test_a_mapped_runs_map_server_pair_is_a_world_to_explore_again(tmp_path: Path) -> None:
    """The ML map of a run, saved as a map_server pair and read back: its
    unknown cells are obstacles, so the start lies inside the building."""
    b = covmap.Building.generate(4, area_m2=60)
    first = covmap.explore(b.world, covmap.Strategy.frontier(), seed=0, resolution=0.1)
    path = tmp_path / "mapped.yaml"
    first.map.to_ros_map(path)
    again = covmap.World.from_file(path)
    run = covmap.Exploration(again, covmap.Strategy.frontier(), seed=0, resolution=0.1, max_steps=1)
    x, y = run.pose[:2]
    x0, y0, x1, y1 = b.world.bounds
    assert x0 < x < x1 and y0 < y < y1
    assert not b.world.contains(x, y)


def test_the_stata_basement_start_lies_in_its_corridors(shared_world: Callable[[str], Path]) -> None:
    """The Stata basement's unmapped interior (grey) is an obstacle: the
    seeded start lies on free (white) pixels of the map."""
    from PIL import Image

    yaml = shared_world("stata_basement.yaml")
    world = covmap.World.from_file(yaml)
    image = np.asarray(Image.open(yaml.with_name("stata_basement.png")).convert("L"))
    resolution, origin_x, origin_y = 0.0504, 25.9, 48.5
    for seed in range(3):
        run = covmap.Exploration(world, covmap.Strategy.frontier(), seed=seed, resolution=0.1, max_steps=1)
        x, y = run.pose[:2]
        # The image is rotated by 3.14 rad about its origin.
        u, v = (origin_x - x) / resolution, (origin_y - y) / resolution
        row, col = image.shape[0] - 1 - int(v), int(u)
        assert image[row, col] > 250, (seed, x, y, image[row, col])
