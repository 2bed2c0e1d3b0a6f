"""covmap.sweep as a user calls it: the same summaries locally, in a process
pool and on a Dask cluster, the specs' order kept, bad specs refused before
anything runs, a failing run reported with its index and the others kept;
covmap sweep and covmap fig7 end to end on tiny settings."""

from __future__ import annotations

import csv
import io
import json
import math
import multiprocessing
import os
import pickle
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path
from typing import Any

import pytest

import covmap
import covmap._sweep as sweep_module
from cli_helpers import PNG_SIGNATURE, run_cli
from extras import need_extra
from test_exploration import room

ORIGINAL_RUN = sweep_module._run_pickled
"""The sweep's own worker function, before any test replaces it."""

SHORT: dict[str, Any] = {"resolution": 0.1, "max_steps": 4}
"""Short runs: a few steps of a small room at 10 cm cells."""


@pytest.fixture(scope="module")
def specs() -> list[dict[str, Any]]:
    """Four short runs of three strategies in the room, in a mixed order of
    seeds, so that an order lost or runs swapped shows."""
    world = room()
    return [
        {"world": world, "strategy": covmap.Strategy.counting(2), "seed": 3, **SHORT},
        {"world": world, "strategy": "frontier", "seed": 1, **SHORT},
        {"world": world, "strategy": {"name": "coverage", "alpha": 0.5}, "seed": 0, **SHORT},
        {"world": world, "strategy": {"name": "counting", "n": 1}, "seed": 2, **SHORT},
    ]


@pytest.fixture(scope="module")
def local(specs: list[dict[str, Any]]) -> list[covmap.RunSummary]:
    return covmap.sweep(specs, progress=False)


def need_dask() -> Any:
    """``distributed``, or a skip with a message (a failure under ``CI=true``:
    CI installs the extra)."""
    return need_extra("distributed", "dask", "the Dask tests")


def test_summaries_follow_the_specs_and_match_explore(
    specs: list[dict[str, Any]], local: list[covmap.RunSummary]
) -> None:
    assert [s.index for s in local] == [0, 1, 2, 3]
    assert [s.seed for s in local] == [3, 1, 0, 2]
    assert [s.strategy for s in local] == [
        covmap.Strategy.counting(2),
        covmap.Strategy.frontier(),
        covmap.Strategy.coverage(0.5),
        covmap.Strategy.counting(1),
    ]
    assert all(s.options == SHORT and s.world.startswith("<World") for s in local)
    # A summary is the run's result, small: the same figures as explore's.
    direct = covmap.explore(specs[1]["world"], covmap.Strategy.frontier(), seed=1, **SHORT)
    s = local[1]
    assert (s.termination, s.path_length_m, s.scans, s.steps, s.contacts) == (
        direct.termination,
        direct.path_length_m,
        direct.scans,
        direct.steps,
        direct.contacts,
    )
    assert s.high_entropy_fraction == direct.high_entropy_fraction and s.coverage_error == direct.coverage_error
    assert s.certain_fraction == 1.0 - direct.high_entropy_fraction
    assert s.start == tuple(direct.start)
    assert s.trace.keys() == direct.trace.keys() and len(s.trace["path_length_m"]) == direct.steps
    assert pickle.loads(pickle.dumps(s)) == s
    # Runs differ, and a summary of another run compares unequal.
    assert len({(r.path_length_m, r.scans) for r in local}) > 1 and local[0] != local[3]


def test_a_process_pool_gives_the_same_summaries(
    specs: list[dict[str, Any]], local: list[covmap.RunSummary]
) -> None:
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        pooled = covmap.sweep(specs, executor=pool, progress=False)
    assert pooled == local
    assert [s.seconds for s in pooled] != [0.0] * 4


def test_a_forking_pool_is_refused(specs: list[dict[str, Any]]) -> None:
    with ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork")) as pool:
        with pytest.raises(covmap.InvalidExecutorError, match="fork"):
            covmap.sweep(specs, executor=pool, progress=False)
    with pytest.raises(covmap.InvalidExecutorError, match="submit"):
        covmap.sweep(specs, executor=object(), progress=False)


class _NoFuture:
    """An executor whose submit returns None."""

    def submit(self, *args: Any) -> Any:
        return None


class _FutureWithoutCallback:
    """An executor whose futures have no add_done_callback (nor a working cancel)."""

    def submit(self, function: Any, *args: Any) -> Any:
        class Future:
            def result(self) -> Any:
                return function(*args)

            def cancel(self) -> bool:
                raise RuntimeError("cannot cancel")

        return Future()


class _NeverDone:
    """An executor whose futures never complete."""

    def __init__(self) -> None:
        self.cancelled = 0

    def submit(self, *args: Any) -> Any:
        executor = self

        class Future:
            def result(self) -> Any:
                raise AssertionError("a future that never completed was asked for its result")

            def add_done_callback(self, callback: Any) -> None:
                pass

            def cancel(self) -> bool:
                executor.cancelled += 1
                return True

        return Future()


def test_foreign_executors_without_futures_are_refused_with_the_cause(specs: list[dict[str, Any]]) -> None:
    with pytest.raises(covmap.InvalidExecutorError, match="_NoFuture.submit returned NoneType, not a future"):
        covmap.sweep(specs, executor=_NoFuture(), progress=False)
    with pytest.raises(covmap.InvalidExecutorError, match="add_done_callback"):
        covmap.sweep(specs, executor=_FutureWithoutCallback(), progress=False)


def test_runs_not_done_within_the_timeout_are_cancelled_and_reported(specs: list[dict[str, Any]]) -> None:
    never = _NeverDone()
    with pytest.raises(covmap.SweepError, match="4 of 4 runs failed") as caught:
        covmap.sweep(specs, executor=never, progress=False, timeout_s=0.2)
    assert [(f.index, f.error_type) for f in caught.value.failures] == [(i, "TimeoutError") for i in range(4)]
    assert "no result within 0.2 s" in caught.value.failures[0].message
    assert never.cancelled == 4
    for bad in (0, -1.0, math.nan, math.inf, "10", True):
        with pytest.raises(covmap.InvalidParameterError, match="timeout_s"):
            covmap.sweep(specs, progress=False, timeout_s=bad)


def test_the_sweeps_own_pool_is_stopped_at_the_timeout() -> None:
    """Runs of the whole corridor take minutes: the timeout ends them, the
    worker processes are killed, and the call returns at once."""
    import time

    slow = [{"world": "corridor", "strategy": "coverage", "seed": s} for s in range(2)]
    start = time.monotonic()
    with pytest.raises(covmap.SweepError) as caught:
        covmap.sweep(slow, progress=False, timeout_s=2.0)
    assert time.monotonic() - start < 30.0
    assert {f.error_type for f in caught.value.failures} == {"TimeoutError"}
    assert not [p for p in multiprocessing.active_children() if p.is_alive()]


SCRIPT = """
import covmap
specs = [{"world": "partial", "strategy": "frontier", "resolution": 0.1, "max_steps": 2, "seed": s} for s in range(2)]
GUARD
    print(len(covmap.sweep(specs, progress=False)), "runs")
"""


def test_a_script_without_the_main_guard_gets_one_clear_error(tmp_path: Path) -> None:
    import subprocess
    import sys

    results = {}
    for name, guard in (("unguarded", "if True:"), ("guarded", 'if __name__ == "__main__":')):
        script = tmp_path / f"{name}.py"
        script.write_text(SCRIPT.replace("GUARD", guard))
        results[name] = subprocess.run(
            [sys.executable, str(script)], capture_output=True, text=True, timeout=300, cwd=tmp_path, check=False
        )
    unguarded = results["unguarded"]
    assert unguarded.returncode == 1
    assert "MainGuardError" in unguarded.stderr and f"{tmp_path / 'unguarded.py'}, line 5" in unguarded.stderr
    assert 'if __name__ == "__main__":' in unguarded.stderr and "BrokenProcessPool" not in unguarded.stderr
    assert results["guarded"].returncode == 0 and "2 runs" in results["guarded"].stdout, results["guarded"].stderr


def test_the_sweep_module_needs_no_command_line() -> None:
    import subprocess
    import sys

    code = (
        "import sys, covmap\n"
        "covmap.sweep([{'world': 'partial', 'strategy': 'frontier', 'resolution': 0.1, 'max_steps': 1}])\n"
        "print(sorted(m for m in sys.modules if m.startswith('covmap.cli')))\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"


def test_a_dask_cluster_gives_the_same_summaries(
    specs: list[dict[str, Any]], local: list[covmap.RunSummary]
) -> None:
    distributed = need_dask()
    seen: list[int] = []
    with distributed.LocalCluster(
        n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        on_dask = covmap.sweep(specs, executor=client, progress=lambda i, s: seen.append(i))
        # One worker process a run at a time: each run's own parallelism off.
        threads = client.run(lambda: os.environ.get("RAYON_NUM_THREADS"))
    assert on_dask == local
    assert sorted(seen) == [0, 1, 2, 3]
    assert set(threads.values()) == {"1"}


def test_a_dead_scheduler_is_a_clear_error() -> None:
    need_dask()
    with pytest.raises(covmap.SchedulerError, match="tcp://127.0.0.1:9"):
        with covmap.dask_client("tcp://127.0.0.1:9", timeout_s=2.0):
            pass


@pytest.mark.parametrize(
    ("bad", "message"),
    [
        ({"max_step": 3}, r"spec 2: unknown key 'max_step' \(did you mean 'max_steps'\?\)"),
        ({"world": 3}, "spec 2: InvalidTypeError: world must be a World"),
        ({"world": "atlantis"}, "spec 2: UnknownWorldError"),
        ({"strategy": "spiral"}, "spec 2: InvalidParameterError: unknown strategy 'spiral'"),
        ({"strategy": {"name": "counting", "m": 2}}, "spec 2: InvalidTypeError: strategy 'counting'"),
        ({"strategy": {"name": "coverage", "alpha": 2.0}}, "spec 2: InvalidParameterError.*alpha"),
        ({"seed": -1}, "spec 2: InvalidParameterError.*seed"),
        ({"seed": 1.5}, "spec 2: InvalidTypeError: seed must be an integer"),
        ({"resolution": "fine"}, "spec 2: InvalidTypeError: argument 'resolution'"),
        ({"resolution": -0.1}, "spec 2: InvalidParameterError.*resolution"),
        ({"start": (2.0, 1.0, 0.0)}, "spec 2: InvalidStartError"),
        ({"start": [[0.5, 0.5, 0.0]]}, r"spec 2: ArrayShapeError: start must be \(x, y, theta\), three numbers, got shape \(1, 3\)"),
        ({"seed": 10**5000}, "spec 2: InvalidParameterError: invalid parameter `seed` = an integer of 16610 bits"),
        ({"sensor": "sonar"}, "spec 2: InvalidTypeError: sensor must be a SonarRing or a Laser"),
    ],
)
def test_a_bad_spec_is_refused_by_its_index_before_anything_runs(
    specs: list[dict[str, Any]], bad: dict[str, Any], message: str
) -> None:
    calls: list[int] = []
    broken = [dict(s) for s in specs]
    broken[2].update(bad)
    with pytest.raises(covmap.InvalidSpecError, match=message) as caught:
        covmap.sweep(broken, progress=lambda i, s: calls.append(i))
    assert caught.value.index == 2 and isinstance(caught.value, ValueError)
    assert calls == []


def test_specs_that_are_no_dicts_or_miss_a_key_are_refused(specs: list[dict[str, Any]]) -> None:
    with pytest.raises(covmap.InvalidSpecError, match="spec 1: expected a dict"):
        covmap.sweep([specs[0], ["corridor"]], progress=False)  # type: ignore[list-item]
    with pytest.raises(covmap.InvalidSpecError, match="spec 0: no 'strategy'"):
        covmap.sweep([{"world": "corridor"}], progress=False)
    assert covmap.sweep([], progress=False) == []


def test_a_run_that_raises_is_reported_and_the_others_kept(
    specs: list[dict[str, Any]], local: list[covmap.RunSummary], monkeypatch: pytest.MonkeyPatch
) -> None:
    # Every spec is checked before it runs, so a run raises only when the
    # robot fails: the worker function stands in for a robot failing in spec 1.
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        monkeypatch.setattr(sweep_module, "_run_pickled", _fails_for_spec_1)
        with pytest.raises(covmap.SweepError, match="1 of 4 runs failed: spec 1: RobotError") as caught:
            covmap.sweep(specs, executor=pool, progress=False)
    error = caught.value
    assert [f.index for f in error.failures] == [1]
    assert isinstance(error.failures[0].error, covmap.RobotError)
    kept = error.results
    assert kept[1] is None and [kept[i] for i in (0, 2, 3)] == [local[i] for i in (0, 2, 3)]
    again = pickle.loads(pickle.dumps(error))
    assert again.failures == error.failures and again.results == error.results


def _fails_for_spec_1(payload: bytes, caller_pid: int) -> covmap.RunSummary:
    """The sweep's worker function, raising as a broken robot would for spec 1."""
    run = pickle.loads(payload)
    if run.index == 1:
        raise covmap.RobotError("the sonar ring stopped answering")
    return ORIGINAL_RUN(payload, caller_pid)


def test_covmap_sweep_runs_a_toml_file(tmp_path: Path) -> None:
    spec_file = tmp_path / "study.toml"
    spec_file.write_text(
        "[defaults]\n"
        'world = "partial"\n'
        "resolution = 0.1\n"
        "max_steps = 2\n"
        "[[runs]]\n"
        'strategy = "frontier"\n'
        "seeds = [1, 0]\n"
        "[[runs]]\n"
        'strategy = { name = "counting", n = 3 }\n'
        "seed = 4\n"
    )
    out = tmp_path / "out" / "results.csv"
    result = run_cli("sweep", str(spec_file), "--out", str(out))
    assert result.returncode == 0, result.stderr
    rows = list(csv.DictReader(io.StringIO(out.read_text())))
    assert [(r["index"], r["strategy"], r["seed"]) for r in rows] == [
        ("0", "Strategy.frontier()", "1"),
        ("1", "Strategy.frontier()", "0"),
        ("2", "Strategy.counting(n=3, discount_beyond_m=None)", "4"),
    ]
    assert all(r["world"] == "partial" and float(r["path_length_m"]) >= 0.0 and r["error"] == "" for r in rows)
    assert json.loads(rows[0]["options"]) == {"max_steps": 2, "resolution": 0.1}
    assert f"wrote {out}" in result.stdout


@pytest.mark.parametrize(
    ("defaults", "run", "seeds"),
    [
        ({}, {"seed": 4}, [4]),
        ({"seed": 1}, {"seeds": [5, 6]}, [5, 6]),
        ({"seeds": [1, 2]}, {"seed": 7}, [7]),
        ({"seeds": [1, 2]}, {}, [1, 2]),
    ],
)
def test_a_runs_seed_or_seeds_replace_the_defaults(tmp_path: Path, defaults: dict[str, Any], run: dict[str, Any], seeds: list[int]) -> None:
    from covmap._sweep_files import read_specs

    spec_file = tmp_path / "study.json"
    spec_file.write_text(json.dumps({"defaults": {"world": "partial", **defaults}, "runs": [{"strategy": "frontier", **run}]}))
    assert [s.get("seed") for s in read_specs(spec_file)] == seeds


@pytest.mark.parametrize("where", ["defaults", "runs"])
def test_seed_and_seeds_in_one_table_are_refused(tmp_path: Path, where: str) -> None:
    from covmap._sweep_files import read_specs

    both = {"seed": 1, "seeds": [2, 3]}
    document = {"defaults": both, "runs": [{"world": "partial", "strategy": "frontier"}]}
    if where == "runs":
        document = {"runs": [{"world": "partial", "strategy": "frontier", **both}]}
    spec_file = tmp_path / "study.json"
    spec_file.write_text(json.dumps(document))
    with pytest.raises(covmap.FileFormatError, match="seed and seeds both given"):
        read_specs(spec_file)


def test_covmap_sweep_names_a_bad_spec_and_writes_nothing(tmp_path: Path) -> None:
    spec_file = tmp_path / "study.json"
    spec_file.write_text(json.dumps([{"world": "partial", "strategy": "frontier", "max_steps": 0}]))
    out = tmp_path / "results.csv"
    result = run_cli("sweep", str(spec_file), "--out", str(out))
    assert result.returncode == 2
    assert "spec 0:" in result.stderr and "max_steps" in result.stderr
    assert not out.exists()


def test_covmap_fig7_writes_its_figure_and_table(tmp_path: Path) -> None:
    result = run_cli(
        "fig7", "--world", "partial", "--ns", "1,3", "--seeds", "2", "--resolution", "0.1",
        "--max-steps", "3", "--out", str(tmp_path),
    )
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "fig7.png").read_bytes().startswith(PNG_SIGNATURE)
    rows = list(csv.DictReader(io.StringIO((tmp_path / "fig7.csv").read_text())))
    assert len(rows) == 2 * 2 + 2
    assert sorted({r["n"] for r in rows if r["strategy"] == "counting"}) == ["1", "3"]
    assert sum(r["strategy"] == "coverage" for r in rows) == 2
    for fraction in ("85 %", "90 %", "95 %"):
        assert fraction in result.stdout


def test_sweep_and_model_files_that_are_no_small_regular_files_are_refused(tmp_path: Path) -> None:
    """A FIFO is refused before it is opened (it would hang the reader),
    ``/dev/zero`` is no regular file, and a deeply nested file is a format
    error, not a RecursionError: for sweep specs and for fig2's model."""
    from covmap._sweep_files import read_specs
    from covmap.cli._options import load_model

    fifo = tmp_path / "specs.json"
    os.mkfifo(fifo)
    deep = tmp_path / "deep.json"
    deep.write_text("[" * 100_000 + "]" * 100_000)
    for path in (fifo, Path("/dev/zero")):
        with pytest.raises(covmap.FileIOError, match="not a regular file"):
            read_specs(path)
        with pytest.raises(covmap.FileIOError, match="not a regular file"):
            load_model(str(path))
    with pytest.raises(covmap.FileFormatError, match="nested too deeply"):
        read_specs(deep)
    with pytest.raises(covmap.InvalidValueError, match="nested too deeply"):
        load_model(str(deep))


def test_fig7_needs_an_n_and_a_seed() -> None:
    from covmap.experiments import fig7

    for ns, seeds in (([1], []), ([], [0])):
        with pytest.raises(covmap.InvalidValueError, match="at least one n and one seed"):
            fig7.run("corridor", ns=ns, seeds=seeds, progress=False)
