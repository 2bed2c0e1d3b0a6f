"""The bad-input corpus: calls of covmap's public API with arguments no
caller should pass, each of which must either succeed or raise a
:class:`covmap.CovmapError`, never panic, abort, hang, allocate without
bound or raise an exception outside the hierarchy.

A case is a line of Python run by ``runner.py`` in a namespace that
``SETUP`` prepares (a small grid ``g``, maps ``m`` and ``o``, the corridor
world ``w``, models, sensors, a log, files under ``tmp``). Most cases are
generated: every argument of every public function and method, in turn,
takes each of ``BAD_VALUES`` while the others keep a valid value; and
every public callable, found by introspection (``public_callables``), is
called with too many arguments, without a required one, with an unknown
keyword and with an argument given twice (``arity_cases``). The rest
are written out: one or more reproducers per class of the issue that
brought this corpus (panics, aborts on allocation, headers trusted,
unbounded work, endless or blocking reads, errors outside the hierarchy,
rules that differ between places), with the exception class they must
raise.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

#: The namespace every case runs in (``tmp`` is a fresh directory).
SETUP = """
import math, os, pickle
import numpy as np
import covmap
g = covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(20, 30))
m = covmap.CoverageMap(g)
o = covmap.OccupancyGrid(g)
w = covmap.World.builtin("corridor")
small = covmap.World([[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]])
laser_model = covmap.LaserModel()
sonar_model = covmap.SonarModel()
laser = covmap.Laser(beams=9)
ring = covmap.SonarRing.ring(8)
planner = covmap.Planner()
robot = covmap.Robot()
P = (1.0, 1.0, 0.3)
R = np.array([1.0, 2.0, 0.5])
B = np.array([0.0, 1.0, 2.0])
POSES = np.array([[1.0, 1.0, 0.0], [1.2, 1.0, 0.1]])
log = covmap.Log(POSES, np.ones((2, 3)), B, max_range_m=5.0)
strategy = covmap.Strategy.coverage()
import covmap.buildings, covmap.experiments.benchmark
building = covmap.Building.generate(0, area_m2=60.0)
"""

#: Values no argument expects: extreme numbers, wrong types, sequences of
#: the wrong length or of a huge claimed length, arrays that claim far more
#: elements than their memory holds.
BAD_VALUES: dict[str, str] = {
    "zero": "0",
    "negative": "-1",
    "negative float": "-0.5",
    "nan": "math.nan",
    "inf": "math.inf",
    "-inf": "-math.inf",
    "1e308": "1e308",
    "-1e308": "-1e308",
    "2**63": "2**63",
    "2**64": "2**64",
    "-2**63-1": "-2**63 - 1",
    "10**400": "10**400",
    "str": "'x'",
    "bytes": "b'x'",
    "None": "None",
    "object": "object()",
    "empty tuple": "()",
    "one number": "(1.0,)",
    "four numbers": "(1.0, 2.0, 3.0, 4.0)",
    "nan tuple": "(math.nan, math.nan, math.nan)",
    "huge range": "range(2**62)",
    "huger range": "range(2**64)",
    "nested": "[[1.0], [2.0]]",
    "empty array": "np.zeros(0)",
    "int array": "np.arange(3)",
    "2-D array": "np.zeros((2, 2))",
    "broadcast array": "np.broadcast_to(1.0, (2**40,))",
    "broadcast rows": "np.broadcast_to(1.0, (2**38, 3))",
    "numpy nan": "np.float64('nan')",
    "numpy int64 max": "np.int64(2**63 - 1)",
    "dict": "{'a': 1}",
    "grid": "g",
    "map": "m",
}

#: Every public function and method: the expression called, and its
#: arguments as (name, a valid value, how it is passed: "pos" or "kw").
API: list[tuple[str, list[tuple[str, str, str]]]] = [
    ("covmap.Grid", [("origin", "(0.0, 0.0)", "kw"), ("resolution", "0.1", "kw"), ("shape", "(20, 30)", "kw")]),
    ("covmap.Grid.covering", [("bounds", "(0.0, 0.0, 3.0, 2.0)", "pos"), ("resolution", "0.1", "kw")]),
    ("g.contains", [("x", "1.0", "pos"), ("y", "1.0", "pos")]),
    ("g.world_to_cell", [("x", "1.0", "pos"), ("y", "1.0", "pos")]),
    ("g.cell_center", [("row", "1", "pos"), ("col", "1", "pos")]),
    ("laser_model.kernel", [("cell_distance", "1.0", "pos"), ("measured_distance", "1.0", "pos"), ("resolution", "0.05", "kw"), ("bins", "16", "kw")]),
    ("covmap.SonarModel.from_dict", [("d", "sonar_model.to_dict()", "pos")]),
    ("covmap.SonarModel", [(k, "None", "kw") for k in ("max_range_m", "band_m", "sigma_min", "sigma_per_m", "sigma_end", "xi_min", "xi_per_m", "end_weight", "opening_angle_rad")]),
    ("covmap.LaserModel", [(k, "None", "kw") for k in ("max_range_m", "band_m", "sigma_min", "sigma_per_m", "sigma_end", "xi_min", "xi_per_m", "end_weight")]),
    ("covmap.log_likelihood", [("map", "m", "pos"), ("truth", "np.zeros((20, 30))", "pos"), ("cells", "None", "kw")]),
    ("covmap.fit_sensor_model", [("log", "log", "pos"), ("truth", "np.zeros((20, 30))", "pos"), ("model", "laser_model", "pos"), ("grid", "g", "kw"), ("parameters", "['xi_min']", "kw"), ("bounds", "None", "kw"), ("max_evaluations", "2", "kw"), ("restarts", "1", "kw"), ("seed", "0", "kw"), ("bins", "16", "kw"), ("cells", "None", "kw"), ("occlude_no_echo", "False", "kw"), ("progress", "False", "kw")]),
    ("covmap.run_learn", [("model", "laser_model", "pos"), ("train_world", "'partial'", "kw"), ("test_world", "'partial'", "kw"), ("scans", "3", "kw"), ("step", "0.5", "kw"), ("resolution", "0.2", "kw"), ("train_seed", "0", "kw"), ("test_seed", "1", "kw"), ("max_evaluations", "1", "kw"), ("restarts", "1", "kw"), ("seed", "0", "kw"), ("parameters", "['xi_min']", "kw"), ("judged_only", "False", "kw"), ("occlude_no_echo", "True", "kw"), ("progress", "False", "kw")]),
    ("covmap.CoverageMap", [("grid", "g", "pos"), ("bins", "16", "pos")]),
    ("covmap.CoverageMap.from_histograms", [("grid", "g", "pos"), ("histograms", "m.histograms", "pos")]),
    ("m.histogram", [("row", "1", "pos"), ("col", "1", "pos")]),
    ("m.integrate", [("pose", "P", "pos"), ("ranges", "R", "pos"), ("bearings", "B", "pos"), ("model", "laser_model", "pos")]),
    ("m.integrate_log", [("log", "log", "pos"), ("model", "laser_model", "pos"), ("occlude_no_echo", "False", "kw"), ("progress", "False", "kw")]),
    ("m.save", [("path", "os.path.join(tmp, 'm.npz')", "pos")]),
    ("covmap.CoverageMap.load", [("path", "os.path.join(tmp, 'missing.npz')", "pos")]),
    ("m.ros_occupancy", [("source", "'ml'", "kw"), ("unknown_within_nats", "0.05", "kw")]),
    ("m.to_ros_map", [("yaml_path", "os.path.join(tmp, 'map.yaml')", "pos"), ("mode", "'trinary'", "kw"), ("occupied_thresh", "0.65", "kw"), ("free_thresh", "0.196", "kw"), ("source", "'ml'", "kw"), ("unknown_within_nats", "0.05", "kw")]),
    ("m.track_history", [("on", "False", "pos")]),
    ("covmap.Log", [("poses", "POSES", "pos"), ("ranges", "np.ones((2, 3))", "pos"), ("bearings", "B", "pos"), ("max_range_m", "5.0", "kw"), ("timestamps", "None", "kw"), ("sensor_offset", "(0.0, 0.0, 0.0)", "kw")]),
    ("covmap.Log.from_carmen", [("path", "os.path.join(tmp, 'missing.log')", "pos"), ("max_range_m", "None", "kw"), ("laser", "'front'", "kw")]),
    ("covmap.Log.from_sonar_text", [("poses_path", "os.path.join(tmp, 'p.txt')", "pos"), ("measurements_path", "os.path.join(tmp, 'z.txt')", "pos"), ("bearings_deg", "[0.0, 90.0]", "kw"), ("length_unit_m", "1.0", "kw"), ("angle_unit_rad", "1.0", "kw"), ("max_range_m", "5.0", "kw")]),
    ("covmap.Log.from_laser_scans", [("poses", "POSES", "pos"), ("ranges", "np.ones((2, 3))", "pos"), ("angle_min", "-0.5", "kw"), ("angle_increment", "0.5", "kw"), ("range_min", "0.1", "kw"), ("range_max", "5.0", "kw"), ("timestamps", "None", "kw")]),
    ("log.extent", [("reach_m", "1.0", "pos")]),
    ("log.with_sensor_offset", [("offset", "(0.1, 0.0, 0.0)", "pos")]),
    ("log.__getitem__", [("key", "slice(0, 1)", "pos")]),
    ("covmap.Log._from_state", [("state", "b'{}'", "pos")]),
    ("covmap.OccupancyGrid", [("grid", "g", "pos")]),
    ("o.integrate", [("pose", "P", "pos"), ("ranges", "R", "pos"), ("bearings", "B", "pos"), ("model", "laser_model", "pos")]),
    ("o.integrate_log", [("log", "log", "pos"), ("model", "laser_model", "pos"), ("progress", "False", "kw")]),
    ("o.to_ros_map", [("yaml_path", "os.path.join(tmp, 'occ.yaml')", "pos"), ("mode", "'trinary'", "kw"), ("occupied_thresh", "0.65", "kw"), ("free_thresh", "0.196", "kw")]),
    ("covmap.expected_information_gain", [("map", "m", "pos"), ("poses", "POSES", "pos"), ("bearings", "B", "pos"), ("model", "laser_model", "pos"), ("method", "'fast'", "pos"), ("range_step_m", "None", "kw"), ("stop_coverage", "'ml'", "kw")]),
    ("covmap.Planner", [(k, "None", "kw") for k in ("alpha", "robot_radius_m", "candidate_stride_m", "min_travel_m", "min_gain_nats", "blocked_coverage", "unknown_entropy_fraction", "unknown_is_free", "epsilon", "range_step_m", "stop_coverage")]),
    ("planner.next_viewpoint", [("map", "m", "pos"), ("pose", "P", "pos"), ("bearings", "B", "pos"), ("model", "laser_model", "pos")]),
    ("planner.status", [("map", "m", "pos"), ("pose", "P", "pos")]),
    ("planner.free_space", [("map", "m", "pos")]),
    ("planner.path_costs", [("map", "m", "pos"), ("pose", "P", "pos")]),
    ("covmap.World", [("polygons", "[[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0)]]", "pos"), ("materials", "None", "pos")]),
    ("covmap.World.builtin", [("name", "'corridor'", "pos")]),
    ("covmap.World.from_file", [("path", "os.path.join(tmp, 'missing.png')", "pos"), ("wall_thickness_m", "0.1", "kw"), ("resolution", "None", "kw"), ("origin", "None", "kw")]),
    ("w.coverage", [("grid", "g", "pos")]),
    ("w.cast", [("origins", "(1.0, 1.0)", "pos"), ("angles", "B", "pos"), ("max_range_m", "5.0", "pos"), ("return_incidence", "False", "kw")]),
    ("w.contains", [("x", "1.0", "pos"), ("y", "1.0", "pos")]),
    ("w.distance_to_obstacle", [("x", "1.0", "pos"), ("y", "1.0", "pos")]),
    ("covmap.World._from_geojson", [("text", "'{}'", "pos")]),
    ("covmap.Building.generate", [("seed", "0", "pos"), ("area_m2", "60.0", "kw"), ("clutter", "0.5", "kw"), ("glass", "0.2", "kw"), ("door_width_m", "(0.8, 1.2)", "kw"), ("corridor_width_m", "(1.5, 3.0)", "kw"), ("room_size_m", "(2.5, 6.0)", "kw"), ("wall_thickness_m", "(0.1, 0.2)", "kw")]),
    ("covmap.Building.from_world", [("world", "small", "pos"), ("name", "'small'", "pos")]),
    ("covmap.Building.builtin", [("name", "'partial'", "pos")]),
    ("covmap.Building.from_file", [("path", "os.path.join(tmp, 'missing.map')", "pos"), ("wall_thickness_m", "0.1", "kw"), ("resolution", "None", "kw"), ("origin", "None", "kw")]),
    ("covmap.Building.from_json", [("text", "building.to_json()", "pos")]),
    ("building.rooms_entered", [("trajectory", "POSES", "pos")]),
    ("building.rooms_never_entered", [("trajectory", "POSES", "pos")]),
    ("covmap.buildings.building", [("reference", "'generated:1:60'", "pos"), ("image_resolution", "None", "kw")]),
    ("covmap.buildings.building_set", [("name", "'default'", "pos"), ("count", "1", "kw"), ("plans", "False", "kw"), ("plans_dir", "None", "kw")]),
    ("covmap.buildings.buildings", [("references", "['partial']", "pos")]),
    ("covmap.buildings.split_of", [("name", "'corridor'", "pos")]),
    # A benchmark kept short by its limits, as the runs above.
    ("covmap.experiments.benchmark.run", [("buildings", "[building]", "pos"), ("strategies", "['frontier']", "kw"), ("sensors", "['sonar']", "kw"), ("seeds", "[0]", "kw"), ("executor", "None", "kw"), ("progress", "False", "kw"), ("max_steps", "2", "kw"), ("resolution", "0.2", "kw")]),
    ("covmap.experiments.benchmark.sensor_of", [("name", "'sonar'", "pos")]),
    ("laser.simulate", [("world", "w", "pos"), ("pose", "P", "pos"), ("seed", "0", "kw")]),
    ("laser.simulate_path", [("world", "w", "pos"), ("poses", "POSES", "pos"), ("seed", "0", "kw")]),
    ("laser.record", [("world", "w", "pos"), ("poses", "POSES", "pos"), ("seed", "0", "kw")]),
    ("ring.simulate", [("world", "w", "pos"), ("pose", "P", "pos"), ("seed", "0", "kw")]),
    ("ring.simulate_path", [("world", "w", "pos"), ("poses", "POSES", "pos"), ("seed", "0", "kw")]),
    ("covmap.SonarRing", [(k, "None", "kw") for k in ("bearings_rad", "opening_angle_rad", "max_range_m", "min_range_m", "rays_per_cone", "noise_std_m", "noise_std_per_m", "outlier_probability", "multipath_probability", "critical_angle_wall_rad", "critical_angle_glass_rad")]),
    ("covmap.SonarRing.ring", [("count", "8", "pos")]),
    ("ring.with_model", [("model", "sonar_model", "pos")]),
    ("covmap.Laser", [("beams", "None", "pos"), ("fov_rad", "None", "pos"), ("bearings_rad", "None", "kw"), ("max_range_m", "None", "kw"), ("noise_std_m", "None", "kw")]),
    ("covmap.Robot", [("radius_m", "0.25", "kw")]),
    ("robot.collides", [("world", "w", "pos"), ("pose", "(1.0, 1.0)", "pos")]),
    ("robot.move_collides", [("world", "w", "pos"), ("start", "(1.0, 1.0)", "pos"), ("goal", "(2.0, 1.0)", "pos")]),
    ("robot.free_travel", [("world", "w", "pos"), ("start", "(1.0, 1.0)", "pos"), ("goal", "(2.0, 1.0)", "pos")]),
    ("robot.clearance", [("world", "w", "pos"), ("points", "[(1.0, 1.0)]", "pos")]),
    ("covmap._native.write_atomic", [("path", "os.path.join(tmp, 'out.bin')", "pos"), ("data", "b'abc'", "pos")]),
    ("covmap.Strategy.coverage", [("alpha", "0.5", "pos")]),
    ("covmap.Strategy.counting", [("n", "50", "pos"), ("discount_beyond_m", "None", "pos")]),
    # A run kept short by each of its limits (steps, path), so that an
    # argument set to an extreme value cannot make it long.
    ("covmap.explore", [("world", "small", "pos"), ("strategy", "strategy", "pos"), ("start", "None", "kw"), ("seed", "0", "kw"), ("sensor", "None", "kw"), ("model", "None", "kw"), ("resolution", "0.1", "kw"), ("bins", "16", "kw"), ("epsilon", "0.65", "kw"), ("robot_radius_m", "0.1", "kw"), ("candidate_stride_m", "0.5", "kw"), ("scan_spacing_m", "0.25", "kw"), ("max_path_m", "1.0", "kw"), ("max_steps", "2", "kw"), ("occlude_no_echo", "True", "kw")]),
    ("covmap.Exploration", [("world", "small", "pos"), ("strategy", "strategy", "pos"), ("resolution", "0.1", "kw"), ("bins", "16", "kw"), ("max_path_m", "1.0", "kw"), ("max_steps", "2", "kw")]),
]

#: Arguments whose extreme values make a valid call run long without being
#: wrong (a seed is any integer): their values are drawn from the numbers.
_SLOW = {("covmap.explore", "resolution"), ("covmap.Exploration", "resolution")}


@dataclass(frozen=True)
class Case:
    """One call: ``code`` run in ``SETUP``'s namespace. ``expect`` is
    ``"either"`` (success or a CovmapError) or the name of the class the
    call must raise (a covmap class, or ``"TypeError"``); ``builtin`` a
    builtin exception it must also be, ``mentions`` text its message must
    hold. ``allows``: Python's own ``TypeError`` is accepted too, that of a
    call whose arguments do not bind (``"binding"``) or that of the
    conversion of the argument so named (an argument of the wrong class).
    ``alone``: run in a process of its own (it may take the interpreter
    down). ``needs``: an optional package the case needs (``rosbags``):
    skipped without it, failed under ``CI=true``."""

    id: str
    code: str
    expect: str = "either"
    builtin: str | None = None
    mentions: str | None = None
    alone: bool = False
    allows: str | None = None
    needs: str | None = None


def _call(function: str, args: list[tuple[str, str, str]]) -> str:
    positional = [v for _, v, how in args if how == "pos"]
    keywords = [f"{n}={v}" for n, v, how in args if how == "kw"]
    return f"{function}({', '.join(positional + keywords)})"


def generated() -> list[Case]:
    """Every argument of every API entry with every bad value."""
    cases = []
    for function, args in API:
        for i, (name, _, how) in enumerate(args):
            for label, value in BAD_VALUES.items():
                if (function, name) in _SLOW and label in ("zero", "1e308", "negative float"):
                    continue
                bad = list(args)
                bad[i] = (name, value, how)
                cases.append(Case(f"{function}({name}={label})", _call(function, bad), allows=name))
    return cases


#: The written cases: the issue's reproducers, and the hostile files.
WRITTEN: list[Case] = [
    # Rust panics reaching Python: sequences reserved by their len().
    Case("integrate ranges range(2**62)", "m.integrate((1., 1., 0.), range(2**62), np.zeros(3), covmap.LaserModel())", "ArrayShapeError", "ValueError", "65536", alone=True),
    Case("integrate ranges range(2**31)", "m.integrate((1., 1., 0.), range(2**31), np.zeros(3), covmap.LaserModel())", "ArrayShapeError", "ValueError", "ranges", alone=True),
    Case("integrate bearings lying __len__", "m.integrate(P, R, type('L', (list,), {'__len__': lambda s: 2**40})([0.0, 1.0, 2.0]), laser_model)", "ArrayShapeError", "ValueError", "bearings", alone=True),
    Case("pose range(2**62)", "m.integrate(range(2**62), R, B, laser_model)", "ArrayShapeError", "ValueError", "pose", alone=True),
    Case("point range(2**62)", "robot.collides(w, range(2**62))", "ArrayShapeError", "ValueError", "pose", alone=True),
    Case("poses rows range(2**62)", "laser.simulate_path(w, [range(2**62)])", "ArrayShapeError", "ValueError", "poses[0]", alone=True),
    Case("polygon vertices range(2**62)", "covmap.World([range(2**62)])", "CovmapError", None, None, alone=True),
    Case("broadcast ranges", "m.integrate(P, np.broadcast_to(1.0, (2**40,)), B, laser_model)", "ArrayShapeError", "ValueError", "ranges", alone=True),
    Case("broadcast histograms", "covmap.CoverageMap.from_histograms(g, np.broadcast_to(np.float32(1), (20, 30, 2**30)))", "ArrayShapeError", "ValueError", "histograms", alone=True),
    Case("broadcast log ranges", "covmap.Log(POSES, np.broadcast_to(1.0, (2, 2**40)), B, max_range_m=5.0)", "ArrayShapeError", "ValueError", "ranges", alone=True),
    # Out of memory raises instead of aborting (under the runner's limit).
    Case("occupancy grid of 46340 x 46340 cells", "covmap.OccupancyGrid(covmap.Grid(origin=(0., 0.), resolution=0.05, shape=(46340, 46340)))", "OutOfMemoryError", "MemoryError", "bytes", alone=True),
    Case("coverage map of 46340 x 46340 cells", "covmap.CoverageMap(covmap.Grid(origin=(0., 0.), resolution=0.05, shape=(46340, 46340)))", "OutOfMemoryError", "MemoryError", "bytes", alone=True),
    Case("ground truth of 46340 x 46340 cells", "w.coverage(covmap.Grid(origin=(0., 0.), resolution=0.05, shape=(46340, 46340)))", "OutOfMemoryError", "MemoryError", "ground truth", alone=True),
    Case("read-outs of a large map", "big = covmap.CoverageMap(covmap.Grid(origin=(0., 0.), resolution=0.05, shape=(8192, 8192)), 2)\nfor f in (big.ml, big.mean, big.entropy, big.observed, lambda: big.histograms, big.measurements, big.stagnated):\n    try:\n        f()\n    except covmap.OutOfMemoryError:\n        pass\nbig.track_history(True)", "OutOfMemoryError", "MemoryError", "bytes", alone=True),
    Case("occupancy read-outs of a large grid", "big = covmap.OccupancyGrid(covmap.Grid(origin=(0., 0.), resolution=0.05, shape=(8192, 8192)))\nhold = []\nwhile True:\n    hold += [big.probabilities(), big.log_odds(), big.counts(), big.observed()]", "OutOfMemoryError", "MemoryError", "bytes", alone=True),
    Case("exploration on cells of 1 mm", "covmap.explore(w, strategy, resolution=0.001, max_steps=1)", "OutOfMemoryError", "MemoryError", "bytes", alone=True),
    Case("fit against the ground truth of 46340 x 46340 cells", "covmap.fit_sensor_model(log, w, sonar_model, grid=covmap.Grid(origin=(0., 0.), resolution=0.05, shape=(46340, 46340)))", "OutOfMemoryError", "MemoryError", "ground truth", alone=True),
    # (3000 gzip members of one line of 100000 readings, each inflating 69
    # times, within the ratio a gzip log may inflate by.)
    Case("carmen log of more readings than memory holds", "import gzip, random\np = os.path.join(tmp, 'wide.log.gz')\nrng = random.Random(0)\nvalues = ['1'] * 100000\nfor i in range(0, 100000, 40):\n    values[i] = str(rng.randrange(10))\nmember = gzip.compress(('FLASER 100000 ' + ' '.join(values) + ' 0 0 0 0 0 0 1 h 1\\n').encode(), compresslevel=9)\nwith open(p, 'wb') as f:\n    for _ in range(3000):\n        f.write(member)\ncovmap.Log.from_carmen(p)", "FileFormatError", "ValueError", "memory", alone=True),
    # Decoders trust headers: a 74-byte PNG claiming 100000 x 100000 pixels.
    Case("png header of 100000 x 100000 pixels", "import struct, zlib\ndef chunk(t, d):\n    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))\np = os.path.join(tmp, 'huge.png')\nopen(p, 'wb').write(b'\\x89PNG\\r\\n\\x1a\\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 100000, 100000, 8, 0, 0, 0, 0)) + chunk(b'IDAT', zlib.compress(b'')) + chunk(b'IEND', b''))\ncovmap.World.from_file(p, resolution=0.05)", "FileFormatError", "ValueError", "huge.png", alone=True),
    Case("png of 2**30 pixels within deflate's bound", "import struct, zlib\ndef chunk(t, d):\n    return struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))\nz = zlib.compressobj(9)\nrow = bytes(32769)\ndata = b''.join(z.compress(row) for _ in range(32768)) + z.flush()\np = os.path.join(tmp, 'big.png')\nopen(p, 'wb').write(b'\\x89PNG\\r\\n\\x1a\\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', 32768, 32768, 8, 0, 0, 0, 0)) + chunk(b'IDAT', data) + chunk(b'IEND', b''))\ncovmap.World.from_file(p, resolution=0.05)", "OutOfMemoryError", "MemoryError", "big.png", alone=True),
    Case("checkerboard image of more rectangles than the bound", "p = os.path.join(tmp, 'board.pgm')\nside = 1450\nrow = bytes((0, 255)) * (side // 2)\nopen(p, 'wb').write(f'P5\\n{side} {side}\\n255\\n'.encode() + b''.join(row if r % 2 == 0 else row[1:] + row[:1] for r in range(side)))\ncovmap.World.from_file(p, resolution=1000.0)", "FileFormatError", "ValueError", "rectangles", alone=True),
    Case("pgm header of 100000 x 100000 pixels", "p = os.path.join(tmp, 'huge.pgm')\nopen(p, 'wb').write(b'P5\\n100000 100000\\n255\\n' + b'\\0' * 16)\ncovmap.World.from_file(p, resolution=0.05)", "FileFormatError", "ValueError", "huge.pgm", alone=True),
    Case("pgm header of 2**64 pixels", "p = os.path.join(tmp, 'h.pgm')\nopen(p, 'wb').write(b'P5\\n18446744073709551617 3\\n255\\n\\0\\0\\0')\ncovmap.World.from_file(p, resolution=0.05)", "FileFormatError", "ValueError", "h.pgm", alone=True),
    Case("truncated png", "p = os.path.join(tmp, 't.png')\nfrom PIL import Image\nImage.new('L', (20, 20), 255).save(p)\ndata = open(p, 'rb').read()\nopen(p, 'wb').write(data[:len(data) // 2])\ncovmap.World.from_file(p, resolution=0.05)", "FileFormatError", "ValueError", "t.png"),
    Case("corrupted png", "p = os.path.join(tmp, 'c.png')\nfrom PIL import Image\nImage.new('L', (20, 20), 255).save(p)\ndata = bytearray(open(p, 'rb').read())\ndata[40] ^= 0xFF\nopen(p, 'wb').write(bytes(data))\ncovmap.World.from_file(p, resolution=0.05)", "FileFormatError", "ValueError", "c.png"),
    Case("truncated map file", "p = os.path.join(tmp, 'm.npz')\nm.save(p)\ndata = open(p, 'rb').read()\nopen(p, 'wb').write(data[:len(data) // 2])\ncovmap.CoverageMap.load(p)", "FileFormatError", "ValueError", "m.npz"),
    Case("corrupted map file", "p = os.path.join(tmp, 'm2.npz')\nm.save(p)\ndata = bytearray(open(p, 'rb').read())\ndata[len(data) // 2] ^= 0xFF\nopen(p, 'wb').write(bytes(data))\ncovmap.CoverageMap.load(p)", "FileFormatError", "ValueError", "m2.npz"),
    Case("scan spacing finer than a tenth of a cell", "covmap.explore(w, strategy, scan_spacing_m=1e-9, max_steps=3)", "InvalidParameterError", "ValueError", "scan_spacing_m"),
    Case("truncated carmen log", "p = os.path.join(tmp, 't.log')\nopen(p, 'w').write('FLASER 3 1.0 1.0')\ncovmap.Log.from_carmen(p)", "FileFormatError", "ValueError", "t.log"),
    Case("carmen beam count 2**64", "p = os.path.join(tmp, 'n.log')\nopen(p, 'w').write('FLASER 18446744073709551616 1.0\\n')\ncovmap.Log.from_carmen(p)", "FileFormatError", "ValueError", "n.log"),
    Case("geojson garbage", "covmap.World._from_geojson('{\"type\": \"FeatureCollection\", \"features\": [' * 1000)", "FileFormatError", "ValueError"),
    # Endless streams and files that never open.
    Case("world from /dev/zero", "covmap.World.from_file('/dev/zero')", "CovmapError", None, "/dev/zero", alone=True),
    Case("map from /dev/zero", "covmap.CoverageMap.load('/dev/zero')", "CovmapError", None, "/dev/zero", alone=True),
    Case("carmen log from /dev/zero", "covmap.Log.from_carmen('/dev/zero')", "CovmapError", None, "/dev/zero", alone=True),
    Case("sonar text from /dev/zero", "covmap.Log.from_sonar_text('/dev/zero', '/dev/zero', bearings_deg=[0.0], max_range_m=5.0)", "CovmapError", None, "/dev/zero", alone=True),
    Case("world from a fifo", "p = os.path.join(tmp, 'fifo.png')\nos.mkfifo(p)\ncovmap.World.from_file(p)", "CovmapError", None, "fifo", alone=True),
    Case("map from a fifo", "p = os.path.join(tmp, 'fifo.npz')\nos.mkfifo(p)\ncovmap.CoverageMap.load(p)", "CovmapError", None, "fifo", alone=True),
    Case("carmen log from a fifo", "p = os.path.join(tmp, 'fifo.log')\nos.mkfifo(p)\ncovmap.Log.from_carmen(p)", "CovmapError", None, "fifo", alone=True),
    Case("world from a directory", "covmap.World.from_file(tmp)", "CovmapError"),
    Case("carmen log from a directory", "covmap.Log.from_carmen(tmp)", "CovmapError"),
    Case("huge sparse carmen log", "p = os.path.join(tmp, 'sparse.log')\nwith open(p, 'wb') as f:\n    f.truncate(2**40)\ncovmap.Log.from_carmen(p)", "CovmapError", None, "sparse.log", alone=True),
    Case("huge sparse map file", "p = os.path.join(tmp, 'sparse.npz')\nwith open(p, 'wb') as f:\n    f.truncate(2**40)\ncovmap.CoverageMap.load(p)", "CovmapError", None, "sparse.npz", alone=True),
    Case("carmen line without end", "p = os.path.join(tmp, 'long.log')\nopen(p, 'w').write('#' * (8 << 20))\ncovmap.Log.from_carmen(p)", "CovmapError", None, "long.log", alone=True),
    # Work that grows without bound: long edges, images at large resolution.
    Case("checkerboard scaled up", "squares = [[(x * 1e5, y * 1e5), ((x + 1) * 1e5, y * 1e5), ((x + 1) * 1e5, (y + 1) * 1e5), (x * 1e5, (y + 1) * 1e5)] for x in range(0, 64, 2) for y in range(0, 64, 2)]\nbig = covmap.World(squares)\nbig.cast((1.0, -1.0), [1.0], 1e7)", "either", alone=True),
    Case("image at 1000 m a pixel", "p = os.path.join(tmp, 'board.png')\nfrom PIL import Image\nim = Image.new('L', (256, 256), 255)\nfor x in range(0, 256, 2):\n    for y in range(0, 256, 2):\n        im.putpixel((x, y), 0)\nim.save(p)\nbig = covmap.World.from_file(p, resolution=1000.0)\nbig.cast((1.0, -1.0), [1.0], 1e7)", "either", alone=True),
    # Errors outside the hierarchy.
    Case("bins 2**63", "covmap.CoverageMap(g, 2**63)", "IntegerOverflowError", "OverflowError", "bins"),
    Case("bins 2**64 as numpy", "covmap.CoverageMap(g, np.uint64(2**64 - 1))", "IntegerOverflowError", "OverflowError", "bins"),
    Case("cell 2**63", "m.histogram(2**63, 0)", "CellOutOfBoundsError", "IndexError", "row 9223372036854775808"),
    Case("resolution str", "covmap.Grid(origin=(0., 0.), resolution='0.1', shape=(4, 4))", "InvalidTypeError", "TypeError", "resolution"),
    Case("shape of three", "covmap.Grid(origin=(0., 0.), resolution=0.1, shape=(4, 4, 4))", "ArrayShapeError", "ValueError", "shape"),
    Case("bounds of three", "covmap.Grid.covering((0., 0., 1.), resolution=0.1)", "ArrayShapeError", "ValueError", "bounds"),
    Case("grid of the wrong type", "covmap.CoverageMap('grid')", "TypeError", allows="grid"),
    Case("planner alpha str", "covmap.Planner(alpha='x')", "InvalidTypeError", "TypeError", "alpha"),
    Case("sensor setting str", "covmap.LaserModel(max_range_m='x')", "InvalidTypeError", "TypeError", "max_range_m"),
    Case("seed 2**64", "laser.simulate(w, P, seed=2**64)", "IntegerOverflowError", "OverflowError", "seed"),
    Case("float 10**400", "g.contains(10**400, 1.0)", "IntegerOverflowError", "OverflowError", "x"),
    # Rules that differ between places: what integrate refuses, the
    # simulated sensors refuse; bounds that overflow.
    Case("laser from a heading whose beams overflow", "covmap.Laser(bearings_rad=[1e308, 0.0]).simulate(w, (1.0, 1.0, 1e308))", "InvalidBearingError", "ValueError", "bearing"),
    Case("sonar ring from a heading whose beams overflow", "covmap.SonarRing(bearings_rad=[1e308, 0.0]).simulate_path(w, [(1.0, 1.0, 1e308)])", "InvalidBearingError", "ValueError", "bearing"),
    Case("integrate from a heading whose beams overflow", "m.integrate((1.0, 1.0, 1e308), [1.0, 1.0], [1e308, 0.0], laser_model)", "InvalidBearingError", "ValueError", "bearing"),
    Case("grid whose bounds overflow", "covmap.Grid(origin=(1.7e308, 0.0), resolution=1e300, shape=(1, 10000000))", "InvalidGridError", "ValueError", "overflow"),
    Case("covering bounds that overflow", "covmap.Grid.covering((-1e308, -1e308, 1e308, 1e308), resolution=1e300)", "InvalidGridError", "ValueError"),
    # Python package: sweeps and the command line.
    Case("dask client of 10**9 workers", "with covmap.dask_client(workers=10**9):\n    pass", "InvalidParameterError", "ValueError", "workers"),
    Case("dask client of a nan timeout", "with covmap.dask_client('tcp://127.0.0.1:9', timeout_s=math.nan):\n    pass", "InvalidParameterError", "ValueError", "timeout_s"),
    Case("dask client of a str timeout", "with covmap.dask_client('tcp://127.0.0.1:9', timeout_s='1'):\n    pass", "InvalidParameterError", "ValueError", "timeout_s"),
    Case("dask client of neither", "with covmap.dask_client():\n    pass", "InvalidTypeError", "TypeError"),
    Case("sweep of a bad progress", "covmap.sweep([{'world': 'corridor'}], progress='yes')", "InvalidTypeError", "TypeError", "progress"),
    Case("sweep of a bad executor", "covmap.sweep([{'world': 'corridor', 'strategy': 'coverage'}], executor=3)", "InvalidExecutorError", "ValueError"),
    Case("real-time factor of a str speed", "covmap.explore(small, strategy, resolution=0.1, max_steps=1).real_time_factor('fast')", "InvalidParameterError", "ValueError", "speed_m_s"),
    Case("real-time factor of an infinite speed", "covmap.explore(small, strategy, resolution=0.1, max_steps=1).real_time_factor(math.inf)", "InvalidParameterError", "ValueError", "speed_m_s"),
    Case("sweep of a non-list", "covmap.sweep(3)", "CovmapError"),
    Case("sweep spec of a bad seed", "covmap.sweep([{'world': 'corridor', 'seed': 2**64}])", "CovmapError"),
    Case("sweep spec of a bad key", "covmap.sweep([{'world': 'corridor', 'nonsense': 1}])", "InvalidSpecError", "ValueError"),
    Case("sweep spec of a bad world", "covmap.sweep([{'world': 3}])", "CovmapError"),
    # Buildings and the benchmark: typed errors naming the value, before anything runs.
    Case("building of an unknown name", "covmap.buildings.building('atlantis')", "UnknownWorldError", "ValueError", "atlantis"),
    Case("generated building of a bad seed", "covmap.buildings.building('generated:-1')", "InvalidParameterError", "ValueError", "seed"),
    Case("generated building of a door narrower than the robot", "covmap.Building.generate(0, door_width_m=(0.4, 0.45))", "InvalidParameterError", "ValueError", "door_width_m[0]"),
    Case("generated building whose rooms cannot fit", "covmap.Building.generate(0, area_m2=12.0)", "InvalidParameterError", "ValueError", "area_m2"),
    Case("generated building of nan rooms", "covmap.Building.generate(0, room_size_m=(math.nan, 4.0))", "InvalidParameterError", "ValueError", "room_size_m[0]"),
    Case("building set without seeds", "covmap.buildings.building_set('test', count=0)", "InvalidParameterError", "ValueError", "count"),
    Case("building set of an unknown name", "covmap.buildings.building_set('holdout')", "UnknownWorldError", "ValueError", "holdout"),
    Case("building from a directory", "covmap.Building.from_file(tmp)", "CovmapError"),
    Case("building from a fifo", "p = os.path.join(tmp, 'fifo.map')\nos.mkfifo(p)\ncovmap.Building.from_file(p)", "CovmapError", None, "fifo", alone=True),
    Case("building from /dev/zero", "covmap.Building.from_file('/dev/zero')", "CovmapError", None, "/dev/zero", alone=True),
    Case("benchmark of no buildings", "covmap.experiments.benchmark.run([], progress=False)", "InvalidValueError", "ValueError", "buildings"),
    Case("benchmark of an unknown strategy", "covmap.experiments.benchmark.run([building], strategies=['greedy'], progress=False)", "InvalidParameterError", "ValueError", "greedy"),
    # Strategies of one's own and goals of the caller's: typed errors naming
    # the value, the run as it was.
    Case("custom strategy of a goal off the map", "covmap.Exploration(small, covmap.Strategy.custom(lambda v: (1e9, 1e9)), resolution=0.1).step()", "InvalidGoalError", "ValueError", "outside the map"),
    Case("custom strategy of a nan goal", "covmap.Exploration(small, covmap.Strategy.custom(lambda v: (math.nan, 0.5)), resolution=0.1).step()", "InvalidGoalError", "ValueError", "finite"),
    Case("custom strategy of a goal in an obstacle", "covmap.Exploration(w, covmap.Strategy.custom(lambda v: (0.0, 0.0)), resolution=0.1).step()", "InvalidGoalError", "ValueError", "cannot reach"),
    Case("custom strategy of a str goal", "covmap.Exploration(small, covmap.Strategy.custom(lambda v: 'north'), resolution=0.1).step()", "InvalidTypeError", "TypeError", "str"),
    Case("custom strategy of a huge index", "covmap.Exploration(w, covmap.Strategy.custom(lambda v: 10**30), resolution=0.1).step()", "InvalidGoalError", "ValueError", "candidate"),
    Case("custom strategy of a goal of 10**6 numbers", "covmap.Exploration(small, covmap.Strategy.custom(lambda v: np.zeros(10**6)), resolution=0.1).step()", "InvalidGoalError", "ValueError", "shape"),
    Case("custom strategy of no function", "covmap.Strategy.custom(3)", "InvalidTypeError", "TypeError", "choose"),
    Case("custom strategy that does not pickle, in a sweep", "covmap.sweep([{'world': small, 'strategy': covmap.Strategy.custom(lambda v: None), 'resolution': 0.1}], progress=False)", "InvalidSpecError", "ValueError", "does not pickle"),
    Case("step to a goal off the map", "covmap.Exploration(small, strategy, resolution=0.1).step(goal=(1e9, 0.0, 0.0))", "InvalidGoalError", "ValueError", "outside the map"),
    Case("step to an infinite goal", "covmap.Exploration(small, strategy, resolution=0.1).step(goal=(math.inf, 0.0, 0.0))", "CovmapError"),
    Case("benchmark of a strategy of no kind", "covmap.experiments.benchmark.run([building], strategies=[3], progress=False)", "InvalidParameterError", "ValueError", "int"),
    # Recordings for the Rerun viewer: a path that cannot be written, refused before the run.
    Case("recording to a directory", "covmap.record(tmp, small, strategy, resolution=0.1, max_steps=1)", "FileIOError", "OSError", needs="rerun"),
    Case("recording into a missing folder", "covmap.record(os.path.join(tmp, 'no', 'r.rrd'), small, strategy, resolution=0.1, max_steps=1)", "FileIOError", "OSError", "no directory", needs="rerun"),
    Case("recording to a fifo", "p = os.path.join(tmp, 'r.rrd')\nos.mkfifo(p)\ncovmap.record(p, small, strategy, resolution=0.1, max_steps=1)", "FileIOError", "OSError", alone=True, needs="rerun"),
    Case("recording of a bad option", "covmap.record(os.path.join(tmp, 'r.rrd'), small, strategy, resolution=-1.0)", "InvalidParameterError", "ValueError", "resolution", needs="rerun"),
    # The Gymnasium environment: bad options and actions, typed errors, the episode as it was.
    Case("gym environment of a bad action kind", "import covmap.gym\ncovmap.gym.ExploreEnv(w, action='joystick')", "InvalidParameterError", "ValueError", "action", needs="gymnasium"),
    Case("gym environment of a nan alpha", "import covmap.gym\ncovmap.gym.ExploreEnv(w, alpha=math.nan)", "InvalidParameterError", "ValueError", "alpha", needs="gymnasium"),
    Case("gym action out of range", "import covmap.gym\ne = covmap.gym.ExploreEnv(w, size=8, resolution=0.1)\ne.reset(seed=0)\ne.step(10**30)", "InvalidActionError", "ValueError", "action", needs="gymnasium"),
    Case("gym action of a str", "import covmap.gym\ne = covmap.gym.ExploreEnv(w, size=8, resolution=0.2)\ne.reset(seed=0)\ne.step('left')", "InvalidActionError", "ValueError", needs="gymnasium"),
    Case("gym goal action of nan", "import covmap.gym\ne = covmap.gym.ExploreEnv(w, action='goal', size=8, resolution=0.2)\ne.reset(seed=0)\ne.step([math.nan, 0.5])", "InvalidActionError", "ValueError", needs="gymnasium"),
    Case("gym step before reset", "import covmap.gym\ncovmap.gym.ExploreEnv(w, size=8, resolution=0.2).step(0)", "InvalidActionError", "ValueError", "reset", needs="gymnasium"),
    Case("benchmark of too many runs", "covmap.experiments.benchmark.run([building] * 10**4, seeds=range(10**4), progress=False)", "InvalidValueError", "ValueError", "runs"),
]


#: The cases of issue 35's classes: writers that replaced what was not
#: theirs, work that grew with what a file claims, bare exceptions, foreign
#: executors, values accepted silently, pickles loaded unchecked, hostile
#: ROS bags. None writes outside ``tmp`` (a fresh directory), or under /dev.
HARDENED: list[Case] = [
    # 1. Writers refuse a target that is not a regular file, before writing.
    Case("save over a fifo", "import stat\np = os.path.join(tmp, 'w.npz')\nos.mkfifo(p)\ntry:\n    m.save(p)\nfinally:\n    assert stat.S_ISFIFO(os.lstat(p).st_mode)", "FileIOError", "OSError", "a FIFO"),
    Case("save over a symlink", "t = os.path.join(tmp, 'target.npz')\nopen(t, 'wb').write(b'kept')\np = os.path.join(tmp, 'link.npz')\nos.symlink(t, p)\ntry:\n    m.save(p)\nfinally:\n    assert os.path.islink(p) and open(t, 'rb').read() == b'kept'", "FileIOError", "OSError", "symlink"),
    Case("save over a dangling symlink", "p = os.path.join(tmp, 'dangling.npz')\nos.symlink(os.path.join(tmp, 'nothing'), p)\ntry:\n    m.save(p)\nfinally:\n    assert not os.path.exists(os.path.join(tmp, 'nothing'))", "FileIOError", "OSError", "symlink"),
    Case("save over a socket", "import socket, stat\np = os.path.join(tmp, 's.npz')\nwith socket.socket(socket.AF_UNIX) as s:\n    s.bind(p)\ntry:\n    m.save(p)\nfinally:\n    assert stat.S_ISSOCK(os.lstat(p).st_mode)", "FileIOError", "OSError", "a socket"),
    Case("map_server pair over a fifo image", "import stat\nd = os.path.join(tmp, 'pair')\nos.mkdir(d)\nos.mkfifo(os.path.join(d, 'm.pgm'))\ntry:\n    m.to_ros_map(os.path.join(d, 'm.yaml'))\nfinally:\n    assert sorted(os.listdir(d)) == ['m.pgm']", "FileIOError", "OSError", "m.pgm"),
    Case("occupancy pair over a directory yaml", "d = os.path.join(tmp, 'pair2')\nos.makedirs(os.path.join(d, 'o.yaml'))\ntry:\n    o.to_ros_map(os.path.join(d, 'o.yaml'))\nfinally:\n    assert sorted(os.listdir(d)) == ['o.yaml']", "FileIOError", "OSError", "a directory"),
    Case("write_atomic over a fifo", "p = os.path.join(tmp, 'w.bin')\nos.mkfifo(p)\ncovmap._native.write_atomic(p, b'x')", "FileIOError", "OSError", "not a regular file"),
    Case("figure over a fifo", "import matplotlib.figure, covmap.plot\np = os.path.join(tmp, 'f.png')\nos.mkfifo(p)\ncovmap.plot.save_figure(matplotlib.figure.Figure(), p)", "FileIOError", "OSError", "FIFO"),
    Case("sweep csv over a fifo", "from pathlib import Path\nfrom covmap._sweep_files import write_csv\np = os.path.join(tmp, 'r.csv')\nos.mkfifo(p)\nwrite_csv(Path(p), [])", "FileIOError", "OSError", "FIFO"),
    Case("covmap learn with its trace a fifo", "import covmap.cli\nd = os.path.join(tmp, 'learn')\nos.mkdir(d)\nos.mkfifo(os.path.join(d, 'trace.csv'))\nassert covmap.cli.main(['learn', '--scans', '5', '--evaluations', '1', '--out', d]) == 1\nassert os.listdir(d) == ['trace.csv']"),
    # 2. Work bounded by what a file holds.
    Case("gzip carmen log inflating a thousand times", "import gzip\np = os.path.join(tmp, 'bomb.log.gz')\nwith gzip.open(p, 'wb', compresslevel=9) as f:\n    for _ in range(100000):\n        f.write(b'#' * 1000 + b'\\n')\ncovmap.Log.from_carmen(p)", "FileFormatError", "ValueError", "more than 100 times", alone=True),
    Case("map file of 1000 entries on the same bytes", "import struct\np = os.path.join(tmp, 'many.npz')\nm.save(p)\nb = open(p, 'rb').read()\ncount, size, offset = struct.unpack_from('<HII', b, len(b) - 12)\nfirst = b[offset:offset + 46 + struct.unpack_from('<H', b, offset + 28)[0]]\ncd = first * 1000\nopen(p, 'wb').write(b[:offset] + cd + struct.pack('<IHHHHIIH', 0x06054b50, 0, 0, 1000, 1000, len(cd), offset, 0))\ncovmap.CoverageMap.load(p)", "FileFormatError", "ValueError", "more than the 5", alone=True),
    Case("map_server yaml nested 100000 deep", "d = os.path.join(tmp, 'deep')\nos.mkdir(d)\nopen(os.path.join(d, 'm.pgm'), 'wb').write(b'P5\\n2 2\\n255\\n\\0\\xff\\xff\\0')\nopen(os.path.join(d, 'm.yaml'), 'w').write('ignored: ' + '[' * 100000 + ']' * 100000 + '\\nimage: m.pgm\\nresolution: 0.1\\norigin: [0, 0, 0]\\n')\ncovmap.World.from_file(os.path.join(d, 'm.yaml'))", "FileFormatError", "ValueError", "flow collections", alone=True),
    Case("geojson nested 100000 deep", "covmap.World._from_geojson('{\"type\": \"FeatureCollection\", \"features\": [], \"x\": ' + '[' * 100000 + ']' * 100000 + '}')", "FileFormatError", "ValueError", alone=True),
    Case("sweep json nested 100000 deep", "from pathlib import Path\nfrom covmap._sweep_files import read_specs\np = Path(tmp, 'deep.json')\np.write_text('{\"runs\": ' + '[' * 100000 + ']' * 100000 + '}')\nread_specs(p)", "FileFormatError", "ValueError", "nested too deeply", alone=True),
    Case("sweep toml nested 100000 deep", "from pathlib import Path\nfrom covmap._sweep_files import read_specs\np = Path(tmp, 'deep.toml')\np.write_text('x = ' + '[' * 100000 + ']' * 100000 + '\\n')\nread_specs(p)", "FileFormatError", "ValueError", "nested too deeply", alone=True),
    Case("model json nested 100000 deep", "from covmap.cli._options import load_model\np = os.path.join(tmp, 'model.json')\nopen(p, 'w').write('{\"model\": ' + '{\"a\": ' * 100000 + '1' + '}' * 100000 + '}')\nload_model(p)", "InvalidValueError", "ValueError", "nested too deeply", alone=True),
    # 3. No bare exceptions.
    Case("log sliced with step 0", "log[::0]", "InvalidValueError", "ValueError", "step"),
    Case("log sliced by strings", "log['a':]", "InvalidTypeError", "TypeError", "slice"),
    Case("map read from its own integrate_log progress", "m.integrate_log(log, laser_model, progress=lambda done, total: m.ml())", "MapBusyError", "RuntimeError", "busy in this call"),
    Case("map integrated into from its own integrate_log progress", "m.integrate_log(log, laser_model, progress=lambda done, total: m.integrate(P, R, B, laser_model))", "MapBusyError", "RuntimeError", "busy in this call"),
    Case("map saved from its own integrate_log progress", "m.integrate_log(log, laser_model, progress=lambda done, total: m.save(os.path.join(tmp, 'busy.npz')))", "MapBusyError", "RuntimeError", "busy in this call"),
    Case("occupancy grid read from its own integrate_log progress", "o.integrate_log(log, laser_model, progress=lambda done, total: o.counts())", "MapBusyError", "RuntimeError", "busy in this call"),
    Case("sonar-text log without measurements", "from pathlib import Path\nfrom covmap.experiments import mapping\nmapping.read_log(Path(tmp, 'poses.txt'), log_format='sonar-text')", "InvalidParameterError", "ValueError", "measurements"),
    Case("covmap map sonar-text without --measurements", "import contextlib, io, covmap.cli\np = os.path.join(tmp, 'poses.txt')\nopen(p, 'w').write('1 2 3\\n')\nerr = io.StringIO()\nwith contextlib.redirect_stderr(err):\n    status = covmap.cli.main(['map', p, '--format', 'sonar-text', '--out', os.path.join(tmp, 'mapped')])\nassert status == 2 and 'measurements' in err.getvalue() and 'Traceback' not in err.getvalue()"),
    # 4. Foreign executors.
    Case("sweep on an executor whose submit returns None", "covmap.sweep([{'world': 'partial', 'strategy': 'frontier', 'max_steps': 1}], executor=type('E', (), {'submit': lambda self, *a: None})(), progress=False)", "InvalidExecutorError", "ValueError", "not a future"),
    Case("sweep on futures without add_done_callback", "class F:\n    def result(self):\n        return None\nclass E:\n    def submit(self, *a):\n        return F()\ncovmap.sweep([{'world': 'partial', 'strategy': 'frontier', 'max_steps': 1}], executor=E(), progress=False)", "InvalidExecutorError", "ValueError", "add_done_callback"),
    Case("sweep on futures that never complete", "class F:\n    def result(self):\n        raise AssertionError('never done')\n    def add_done_callback(self, f):\n        pass\n    def cancel(self):\n        raise RuntimeError('cannot cancel')\nclass E:\n    def submit(self, *a):\n        return F()\ncovmap.sweep([{'world': 'partial', 'strategy': 'frontier', 'max_steps': 1}], executor=E(), progress=False, timeout_s=0.1)", "SweepError", "RuntimeError", "TimeoutError"),
    Case("sweep of a nan timeout", "covmap.sweep([], timeout_s=math.nan)", "InvalidParameterError", "ValueError", "timeout_s"),
    Case("sweep of a bool timeout", "covmap.sweep([], timeout_s=True)", "InvalidParameterError", "ValueError", "timeout_s"),
    Case("sweep called by a script's module level without the main guard", "import sys, types\nsrc = 'import covmap\\ncovmap.sweep([{\"world\": \"partial\", \"strategy\": \"frontier\", \"max_steps\": 1}] * 2, progress=False)\\n'\npath = os.path.join(tmp, 'script.py')\nopen(path, 'w').write(src)\nmain = types.ModuleType('__main__')\nmain.__file__ = path\nsaved = sys.modules['__main__']\nsys.modules['__main__'] = main\ntry:\n    exec(compile(src, path, 'exec'), vars(main))\nfinally:\n    sys.modules['__main__'] = saved", "MainGuardError", "RuntimeError", "if __name__ == \"__main__\":"),
    # 5. Values accepted silently, ranges stated wrongly, huge values quoted whole.
    Case("explore with epsilon above ln(bins)", "covmap.explore(small, strategy, epsilon=3.0, max_steps=1)", "InvalidParameterError", "ValueError", "ln(16)"),
    Case("explore with max_steps=True", "covmap.explore(small, strategy, max_steps=True)", "InvalidTypeError", "TypeError", "max_steps"),
    Case("counting n=2**64 states the real range", "covmap.Strategy.counting(n=2**64)", "IntegerOverflowError", "OverflowError", "from 1 to 2**32 - 1"),
    Case("a huge integer is quoted in part", "covmap.Strategy.counting(n=10**5000)", "IntegerOverflowError", "OverflowError", "an integer of 16610 bits"),
    Case("a huge string is quoted in part", "covmap.World.builtin('x' * 10**6)", "UnknownWorldError", "ValueError", "(1000000 characters)"),
    Case("sweep file run with seed and seeds", "from pathlib import Path\nfrom covmap._sweep_files import read_specs\np = Path(tmp, 'both.json')\np.write_text('{\"runs\": [{\"world\": \"partial\", \"strategy\": \"frontier\", \"seed\": 1, \"seeds\": [2, 3]}]}')\nread_specs(p)", "FileFormatError", "ValueError", "seed and seeds"),
    Case("sweep start of shape (1, 3)", "covmap.sweep([{'world': 'partial', 'strategy': 'frontier', 'start': [[0.5, 0.5, 0.0]], 'max_steps': 1}], progress=False)", "InvalidSpecError", "ValueError", "(1, 3)"),
    Case("geojson world with a resolution", "p = os.path.join(tmp, 'sq.geojson')\nopen(p, 'w').write('{\"type\": \"Polygon\", \"coordinates\": [[[0, 0], [1, 0], [1, 1], [0, 0]]]}')\ncovmap.World.from_file(p, resolution=-1)", "InvalidParameterError", "ValueError", "resolution"),
    Case("image world with a wall thickness", "p = os.path.join(tmp, 'i.pgm')\nopen(p, 'wb').write(b'P5\\n2 2\\n255\\n\\0\\xff\\xff\\0')\ncovmap.World.from_file(p, resolution=0.1, wall_thickness_m=0.3)", "InvalidParameterError", "ValueError", "wall_thickness_m"),
    # 6. Pickles checked on load.
    Case("exploration result pickle tampered", "r = covmap.explore(small, strategy, resolution=0.1, max_steps=1)\nstate = dict(vars(r), truth=r.truth * 5)\nblank = covmap.ExplorationResult.__new__(covmap.ExplorationResult)\nblank.__setstate__(state)", "InvalidValueError", "ValueError", "truth"),
    Case("run summary pickle tampered", "s = covmap.sweep([{'world': 'partial', 'strategy': 'frontier', 'resolution': 0.1, 'max_steps': 1}], progress=False)[0]\nblank = covmap.RunSummary.__new__(covmap.RunSummary)\nblank.__setstate__(dict(vars(s), seed=-1))", "InvalidValueError", "ValueError", "seed"),
    # 7. Hostile ROS bags, both formats (bags.hostile writes them).
    *[
        Case(
            f"{fmt} bag: {kind}",
            f"from pathlib import Path\nfrom bags import hostile\ncovmap.Log.from_bag(hostile(Path(tmp), {kind!r}, {fmt!r}), odom_topic={None if kind == 'tf loop' else '/odom'!r})",
            "FileFormatError",
            "ValueError",
            alone=kind in ("huge size", "deep metadata"),
            needs="rosbags",
        )
        for fmt in ("ros1", "ros2")
        for kind in ("truncated", "wrong type", "huge size", "stamps back", "tf loop", "deep metadata")
    ],
]


#: An instance of each native class with public methods, for the arity
#: cases of its methods (a name of ``SETUP``'s namespace, or an expression).
INSTANCES: dict[str, str] = {
    "Grid": "g",
    "SonarModel": "sonar_model",
    "LaserModel": "laser_model",
    "CoverageMap": "m",
    "OccupancyGrid": "o",
    "Log": "log",
    "Planner": "planner",
    "World": "w",
    "Building": "building",
    "SonarRing": "ring",
    "Laser": "laser",
    "Robot": "robot",
    "Exploration": "covmap.Exploration(small, strategy, resolution=0.1, max_path_m=1.0, max_steps=2)",
}

#: The package's public modules besides the native one: the functions and
#: classes of their ``__all__`` (or, without one, the public names they
#: define) are its API. Every module of ``covmap.experiments`` is added.
PUBLIC_MODULES = ["covmap", "covmap.plot", "covmap.cli", "covmap.buildings"]


@dataclass(frozen=True)
class PublicCallable:
    """A public callable of the Python API: ``expression`` reaches it in
    ``SETUP``'s namespace once ``module`` (if any) is imported; ``name`` is
    what its errors must mention; ``signature`` is as ``expression`` is
    called; ``no_constructor``: a native class that cannot be created."""

    module: str | None
    expression: str
    name: str
    signature: Any
    no_constructor: bool = False


def public_callables() -> list[PublicCallable]:
    """Every public callable of the Python API, found by introspection: the
    native module's functions, classes and their public methods, static and
    class methods; the functions and classes (with theirs) of
    ``PUBLIC_MODULES`` and ``covmap.experiments``. A native class with
    public methods needs an instance in ``INSTANCES``."""
    import importlib
    import inspect
    import pkgutil
    import types

    import covmap
    import covmap._native as native
    import covmap.experiments

    found: list[PublicCallable] = []
    seen: set[int] = set()

    def add(target: Any, entry: PublicCallable) -> None:
        if id(target) not in seen:
            seen.add(id(target))
            found.append(entry)

    def members(cls: type, module: str | None, prefix: str, instance: str | None) -> None:
        for name, member in vars(cls).items():
            if name.startswith("_"):
                continue
            if isinstance(member, (staticmethod, classmethod)):
                add(member, PublicCallable(module, f"{prefix}.{name}", name, inspect.signature(getattr(cls, name))))
            elif isinstance(member, types.FunctionType):
                signature = inspect.signature(member)
                if instance is None:  # a Python class's method, called on the class
                    add(member, PublicCallable(module, f"{prefix}.{name}", name, signature))
                else:
                    bound = signature.replace(parameters=list(signature.parameters.values())[1:])
                    add(member, PublicCallable(module, f"{instance}.{name}", name, bound))

    for name, value in vars(native).items():
        if name.startswith("_"):
            continue
        # Reached from covmap where it exports them.
        reach = f"covmap.{name}" if getattr(covmap, name, None) is value else f"covmap._native.{name}"
        if isinstance(value, type):
            no_constructor = getattr(value, "__text_signature__", None) is None
            add(value, PublicCallable(None, reach, name, inspect.signature(value), no_constructor))
            methods = [n for n, m in vars(value).items() if isinstance(m, types.FunctionType) and not n.startswith("_")]
            if methods and name not in INSTANCES:
                raise LookupError(f"no instance of covmap.{name} for its methods' arity cases: add one to INSTANCES")
            members(value, None, reach, INSTANCES.get(name))
        elif callable(value):
            add(value, PublicCallable(None, reach, name, inspect.signature(value)))

    modules = list(PUBLIC_MODULES)
    modules += [f"covmap.experiments.{m.name}" for m in pkgutil.iter_modules(covmap.experiments.__path__)]
    for module_name in modules:
        module = importlib.import_module(module_name)
        names = getattr(module, "__all__", None)
        if names is None:
            names = [n for n, v in vars(module).items() if not n.startswith("_") and getattr(v, "__module__", None) == module_name]
        for name in names:
            value = getattr(module, name)
            if not str(getattr(value, "__module__", "")).startswith("covmap"):
                continue
            reach = f"{module_name}.{name}"
            if isinstance(value, type):
                if issubclass(value, BaseException) or value.__module__ == native.__name__:
                    continue  # exceptions are raised, not called; native classes are above
                add(value, PublicCallable(module_name, reach, name, inspect.signature(value)))
                members(value, module_name, reach, None)
            elif isinstance(value, types.FunctionType):
                add(value, PublicCallable(module_name, reach, name, inspect.signature(value)))
    return found


def arity_cases() -> list[Case]:
    """Every public callable called with too many arguments, without a
    required one, with an unknown keyword and with an argument given twice
    (those of the four its signature allows; and a native class without a
    constructor, called at all): each must raise Python's ``TypeError``
    naming the callable, as any Python callable does. The arguments are
    placeholders: the binding fails before any is looked at."""
    import inspect

    P = inspect.Parameter
    cases = []
    for c in public_callables():
        params = list(c.signature.parameters.values())
        positional = [p for p in params if p.kind in (P.POSITIONAL_ONLY, P.POSITIONAL_OR_KEYWORD)]
        required = [p for p in params if p.default is P.empty and p.kind not in (P.VAR_POSITIONAL, P.VAR_KEYWORD)]
        calls: list[tuple[str, str]] = []
        if c.no_constructor:
            calls.append(("no arguments", ""))
        if not any(p.kind is P.VAR_POSITIONAL for p in params):
            calls.append(("too many arguments", ", ".join(["None"] * (len(positional) + 1))))
        if required:
            calls.append(("missing argument", ""))
        if not any(p.kind is P.VAR_KEYWORD for p in params):
            given = [f"{p.name}=None" if p.kind is P.KEYWORD_ONLY else "None" for p in required]
            calls.append(("unknown keyword", ", ".join([*given, "not_an_argument=None"])))
        twice = next((p for p in params if p.kind is P.POSITIONAL_OR_KEYWORD), None)
        if twice is not None:
            calls.append(("argument given twice", f"None, {twice.name}=None"))
        head = f"import {c.module}\n" if c.module else ""
        for label, arguments in calls:
            code = f"{head}{c.expression}({arguments})"
            cases.append(Case(f"{c.expression}({label})", code, "TypeError", None, c.name, allows="binding"))
    return cases


def cases() -> list[Case]:
    """The whole corpus."""
    return generated() + WRITTEN + HARDENED + arity_cases()
