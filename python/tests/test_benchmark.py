"""The exploration benchmark (``covmap.experiments.benchmark``, ``covmap
benchmark``) and its views, Table I and Fig. 7 over buildings, and ``covmap
explore`` on world files."""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path

import numpy as np
import pytest

import covmap
from cli_helpers import PNG_SIGNATURE, run_cli
from covmap.experiments import benchmark, benchmark_files, fig7, table1

#: Two small buildings, kept short: the benchmark's machinery, not its figures.
SMALL = ("generated:1:60", "generated:2:60")
LIMITS = {"max_steps": 6, "resolution": 0.1}


@pytest.fixture(scope="module")
def small() -> list[covmap.Building]:
    return [covmap.buildings.building(name) for name in SMALL]


@pytest.fixture(scope="module")
def bench(small: list[covmap.Building]) -> benchmark.Benchmark:
    return benchmark.run(
        small, strategies=["frontier", "counting n=1"], sensors=["sonar", "laser"], progress=False, **LIMITS
    )


def test_every_run_reports_its_figures(bench: benchmark.Benchmark, small: list[covmap.Building]) -> None:
    assert len(bench.runs) == 2 * 2 * 2
    assert {r.building for r in bench.runs} == set(SMALL)
    assert {(r.strategy, r.sensor) for r in bench.runs} == {
        (s, n) for s in ("frontier", "counting n=1") for n in ("sonar", "laser")
    }
    for r in bench.runs:
        b = small[SMALL.index(r.building)]
        assert r.split == "development"
        assert r.rooms == sum(1 for room in b.rooms if room.kind != "corridor")
        assert 0 <= r.rooms_missed <= r.rooms
        assert set(r.rooms_never_entered) <= {room.name for room in b.rooms}
        assert 0.0 <= r.uncertain_fraction <= 1.0 and r.evaluation_area_m2 > 20.0
        assert r.termination in ("limit", "no_goal", "stagnated", "certain")
        assert r.real_time_factor > 0.0
    rows = list(csv.DictReader(io.StringIO(benchmark_files.csv_text(bench))))
    assert len(rows) == len(bench.runs) and list(rows[0]) == list(benchmark_files.CSV_FIELDS)
    assert {row["sensor"] for row in rows} == {"sonar", "laser"}


def test_the_csv_reads_back_as_the_runs(bench: benchmark.Benchmark, tmp_path: Path) -> None:
    path = benchmark_files.write_csv(bench, tmp_path / "b.csv")
    back = benchmark_files.read_csv(path)
    assert back.runs == bench.runs
    assert [r.seconds for r in back.runs] == [r.seconds for r in bench.runs]
    assert benchmark.summary_table(back).splitlines()[2:] == benchmark.summary_table(bench).splitlines()[3:]
    bad = tmp_path / "bad.csv"
    bad.write_text("a,b\n1,2\n")
    with pytest.raises(covmap.FileFormatError, match="header"):
        benchmark_files.read_csv(bad)
    text = path.read_text().splitlines()
    bad.write_text("\n".join([text[0], text[1].replace(",sonar,", ",radar,", 1)]) + "\n")
    with pytest.raises(covmap.FileFormatError, match="row 2"):
        benchmark_files.read_csv(bad)
    with pytest.raises(covmap.FileIOError):
        benchmark_files.read_csv(tmp_path / "missing.csv")


def test_the_summary_has_a_row_per_strategy_and_sensor(bench: benchmark.Benchmark) -> None:
    summaries = bench.summaries()
    assert [(s.strategy, s.sensor) for s in summaries] == [
        ("counting n=1", "sonar"),
        ("counting n=1", "laser"),
        ("frontier", "sonar"),
        ("frontier", "laser"),
    ]
    for s in summaries:
        runs = [r for r in bench.runs if (r.strategy, r.sensor) == (s.strategy, s.sensor)]
        values = sorted(r.uncertain_fraction for r in runs)
        assert s.runs == 2 and s.uncertain[0] == pytest.approx(np.median(values))
        assert s.uncertain[1] <= s.uncertain[0] <= s.uncertain[2]
        assert sum(s.terminations.values()) == 2
    text = benchmark.summary_table(bench)
    assert "counting n=1" in text and "median [lower quartile, upper quartile]" in text
    assert "max_steps=6" in text
    speed = benchmark.speed_table(bench)
    assert "0-200 m^2" in speed and "frontier" in speed


def test_the_same_benchmark_gives_the_same_runs(bench: benchmark.Benchmark, small: list[covmap.Building]) -> None:
    again = benchmark.run(
        small, strategies=["frontier", "counting n=1"], sensors=["sonar", "laser"], progress=False, **LIMITS
    )
    assert again.runs == bench.runs


def test_the_figure_is_written(bench: benchmark.Benchmark, tmp_path: Path) -> None:
    path = covmap.plot.plot_benchmark(bench, tmp_path / "b.png")
    assert path.read_bytes()[:8] == PNG_SIGNATURE


def test_configurations() -> None:
    default = benchmark.CONFIGURATIONS["default"]
    assert default.buildings == "default" and default.sensors == ("sonar",)
    full = benchmark.CONFIGURATIONS["full"]
    assert full.buildings == "test" and full.plans and set(full.sensors) == {"sonar", "laser"}
    assert full.count >= 24
    assert list(benchmark.STRATEGIES) == ["coverage", "counting n=1", "counting n=50", "frontier"]


def test_bad_benchmarks_are_refused_before_anything_runs(small: list[covmap.Building]) -> None:
    for keywords in ({"strategies": []}, {"sensors": []}, {"seeds": []}):
        with pytest.raises(covmap.InvalidValueError):
            benchmark.run(small, progress=False, **keywords)  # type: ignore[arg-type]
    with pytest.raises(covmap.InvalidValueError, match="buildings"):
        benchmark.run([], progress=False)
    with pytest.raises(covmap.InvalidParameterError, match="greedy"):
        benchmark.run(small, strategies=["greedy"], progress=False)
    with pytest.raises(covmap.InvalidParameterError, match="radar"):
        benchmark.run(small, sensors=["radar"], progress=False)
    with pytest.raises(covmap.InvalidSpecError, match="max_steps"):
        benchmark.run(small, progress=False, max_steps=0)


def test_a_sweep_spec_names_a_building() -> None:
    [summary] = covmap.sweep(
        [{"world": "generated:3:60", "strategy": "frontier", "resolution": 0.1, "max_steps": 3}], progress=False
    )
    assert summary.world == "generated:3:60" and summary.rooms is not None
    with pytest.raises(covmap.InvalidSpecError, match="atlantis"):
        covmap.sweep([{"world": "atlantis", "strategy": "frontier"}], progress=False)


def test_table1_and_fig7_are_views_over_buildings() -> None:
    t = table1.run_buildings(list(SMALL), seeds=[0], progress=False, max_steps=2, resolution=0.1)
    assert [len(row.runs) for row in t.rows] == [2] * len(table1.METHODS)
    assert {r.building for row in t.rows for r in row.runs} == set(SMALL)
    assert "generated:1:60, generated:2:60" in table1.table(t)
    f = fig7.run(list(SMALL), ns=[1, 2], seeds=[0], progress=False, max_steps=2, resolution=0.1)
    assert len(f.coverage) == 2 and len(f.counting) == 4
    assert [r.strategy.n for r in f.counting] == [1, 1, 2, 2]
    assert f.world_name == "generated:1:60, generated:2:60"


def test_benchmark_command(tmp_path: Path) -> None:
    result = run_cli(
        "benchmark",
        "--buildings",
        ",".join(SMALL),
        "--strategies",
        "frontier",
        "--max-steps",
        "3",
        "--resolution",
        "0.1",
        "--out",
        str(tmp_path),
    )
    assert result.returncode == 0, result.stderr
    assert "frontier" in result.stdout and "median" in result.stdout
    assert "run 2/2" in result.stderr or "2/2" in result.stderr
    rows = list(csv.DictReader(io.StringIO((tmp_path / "benchmark.csv").read_text())))
    assert sorted(r["building"] for r in rows) == sorted(SMALL)
    assert (tmp_path / "benchmark.png").read_bytes()[:8] == PNG_SIGNATURE
    assert "Real-time factor" in result.stdout
    # The views of the run again, from its CSV, nothing run.
    again = run_cli("benchmark", "--report", str(tmp_path / "benchmark.csv"), "--out", str(tmp_path / "report"))
    assert again.returncode == 0, again.stderr
    rows_of = lambda text: [line for line in text.splitlines() if line.startswith("frontier")]  # noqa: E731
    assert rows_of(again.stdout) == rows_of(result.stdout) and len(rows_of(result.stdout)) == 2
    assert (tmp_path / "report" / "benchmark.png").read_bytes()[:8] == PNG_SIGNATURE


def test_the_benchmark_command_lets_no_echo_readings_clear_on_request(tmp_path: Path) -> None:
    """``--clear-no-echo`` runs the same buildings with every no-echo
    reading clearing its whole footprint: the option is shown with the
    summary, and the same run maps otherwise."""
    args = ["benchmark", "--buildings", "corridor", "--strategies", "coverage", "--max-steps", "12"]
    errors = []
    for clear in (False, True):
        out = tmp_path / ("clearing" if clear else "default")
        result = run_cli(*args, *(["--clear-no-echo"] if clear else []), "--out", str(out))
        assert result.returncode == 0, result.stderr
        assert ("occlude_no_echo=False" in result.stdout) == clear
        (row,) = csv.DictReader(io.StringIO((out / "benchmark.csv").read_text()))
        errors.append(float(row["error_coverage_map"]))
    assert errors[0] != errors[1]


def test_the_benchmark_command_maps_with_a_learned_model(tmp_path: Path) -> None:
    """``--model`` (a ``covmap learn`` file) is the model the runs of its
    sensor map with: the same runs give other maps; a model of a sensor the
    benchmark does not run, or of a parameter covmap removed, is refused
    before anything runs."""
    import json

    learned = tmp_path / "model.json"
    learned.write_text(json.dumps({"sensor": "sonar", "model": {**covmap.SonarModel(end_weight=0.5).to_dict()}}))
    args = ["benchmark", "--buildings", SMALL[0], "--strategies", "frontier", "--max-steps", "3", "--resolution", "0.1"]
    errors = []
    for model in (None, learned):
        out = tmp_path / ("default" if model is None else "learned")
        result = run_cli(*args, *([] if model is None else ["--model", str(model)]), "--out", str(out))
        assert result.returncode == 0, result.stderr
        assert ("end_weight=0.5" in result.stdout) == (model is not None)
        (row,) = csv.DictReader(io.StringIO((out / "benchmark.csv").read_text()))
        errors.append(float(row["error_coverage_map"]))
    assert errors[0] != errors[1]
    removed = tmp_path / "removed.json"
    removed.write_text(json.dumps({"sensor": "sonar", "model": {"no_echo_weight": 0.5}}))
    for model, extra, message in ((learned, ["--sensors", "laser"], "a sonar model"), (removed, [], "no_echo_weight")):
        out = tmp_path / "refused"
        result = run_cli(*args, *extra, "--model", str(model), "--out", str(out))
        assert result.returncode in (1, 2) and message in result.stderr and "Traceback" not in result.stderr, result.stderr
        assert not out.exists()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["benchmark", "--buildings", "atlantis"], "atlantis"),
        (["benchmark", "--sensors", "radar"], "radar"),
        (["benchmark", "--strategies", "greedy"], "greedy"),
        (["benchmark", "--buildings", "test", "--count", "5000"], "count"),
        (["explore", "--world", "generated:x"], "generated:x"),
        (["explore", "--world", "nowhere.map"], "nowhere.map"),
    ],
)
def test_bad_names_are_clean_errors(args: list[str], message: str, tmp_path: Path) -> None:
    result = run_cli(*args, "--out", str(tmp_path))
    assert result.returncode in (1, 2) and message in result.stderr, result.stderr
    assert "Traceback" not in result.stderr
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize("start", ["1,2,3,4", "a,b", "1", "nan,1"])
def test_a_bad_start_is_a_clean_error(start: str) -> None:
    result = run_cli("explore", "--start", start)
    assert result.returncode == 2 and "--start" in result.stderr and "Traceback" not in result.stderr


def test_explore_takes_a_world_file_and_saves_what_a_user_needs(tmp_path: Path) -> None:
    world_file = tmp_path / "building.geojson"
    b = covmap.Building.generate(3, area_m2=60)
    world_file.write_text(b.world.to_geojson())
    corridor = b.rooms[0].floor[0]
    x, y = (corridor[0] + corridor[2]) / 2, (corridor[1] + corridor[3]) / 2
    out = tmp_path / "out"
    result = run_cli(
        "explore",
        "--world",
        str(world_file),
        "--start",
        f"{x},{y}",
        "--resolution",
        "0.1",
        "--epsilon",
        "0.6",
        "--sensor",
        "laser",
        "--strategy",
        "frontier",
        "--max-steps",
        "3",
        "--frames",
        "2",
        "--out",
        str(out),
    )
    assert result.returncode == 1, result.stderr  # at the step limit
    assert f"({x:.3f} m, {y:.3f} m, 0.000 rad)" in result.stdout
    assert "rooms never entered" in result.stdout
    assert "H > 0.6 nats" in result.stdout
    posterior = covmap.CoverageMap.load(out / "building-frontier.npz")
    assert posterior.grid.resolution == 0.1
    again = covmap.World.from_file(out / "building-frontier.yaml")
    assert len(again) > 0
    lines = (out / "building-frontier-trajectory.csv").read_text().splitlines()
    assert lines[0] == "x_m,y_m,theta_rad,scanned"
    first = [float(v) for v in lines[1].split(",")]
    assert first[:3] == [x, y, 0.0] and len(lines) >= 3


def test_per_sensor_limits_and_buildings(small: list[covmap.Building]) -> None:
    """The full configuration's shape: the laser only in buildings up to
    its extent, with its own step limit; the largest buildings first."""
    large = covmap.buildings.building("generated:1002:550")
    specs = benchmark.specs(
        [*small, large],
        strategies=["frontier"],
        sensors=["sonar", "laser"],
        sensor_options={"laser": {"max_steps": 150}},
        max_extent_m2={"laser": 100.0},
        max_path_m=3000.0,
    )
    worlds = [(s["world"].name, type(s["sensor"]).__name__, s.get("max_steps")) for s in specs]
    assert worlds[0] == ("generated:1002:550", "SonarRing", None)
    assert ("generated:1002:550", "Laser", 150) not in worlds
    assert sorted(w for w in worlds if w[1] == "Laser") == [("generated:1:60", "Laser", 150), ("generated:2:60", "Laser", 150)]
    assert all(s["max_path_m"] == 3000.0 for s in specs)
    full = benchmark.CONFIGURATIONS["full"]
    assert full.sensor_options["laser"]["max_path_m"] == benchmark.LASER_MAX_PATH_M
    assert full.max_extent_m2 == {"laser": benchmark.LASER_MAX_EXTENT_M2}


def test_a_dask_cluster_gives_the_same_benchmark(bench: benchmark.Benchmark, small: list[covmap.Building]) -> None:
    """The buildings travel to the workers (pickled with their rooms): the
    same runs, the same rooms never entered, on a local Dask cluster."""
    try:
        import distributed  # noqa: F401
    except ImportError:
        if os.environ.get("CI") == "true":
            pytest.fail("dask.distributed is not installed (CI=true: CI installs covmap[dask])")
        pytest.skip("dask.distributed is not installed: pip install 'covmap[dask]' to run the Dask tests")
    with covmap.dask_client(workers=2) as client:
        on_dask = benchmark.run(
            small,
            strategies=["frontier", "counting n=1"],
            sensors=["sonar", "laser"],
            executor=client,
            progress=False,
            **LIMITS,
        )
    assert on_dask.runs == bench.runs
