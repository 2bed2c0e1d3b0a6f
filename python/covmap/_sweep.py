"""Many exploration runs at once: :func:`covmap.sweep` runs a list of specs
(each a dict of :func:`covmap.explore` arguments) on this machine's cores or
on any executor with ``concurrent.futures``' ``submit`` (a
``ProcessPoolExecutor``, a ``dask.distributed.Client``), and returns one
:class:`RunSummary` per spec, in the specs' order.

A spec holds ``world`` (a :class:`~covmap.World`, a
:class:`~covmap.Building`, or a building's name: a built-in world such as
``"corridor"``, ``"generated:SEED[:AREA]"``, a world file; see
:func:`covmap.buildings.building`), ``strategy`` (a :class:`~covmap.Strategy`;
or ``"coverage"``, ``"counting"``, ``"frontier"`` for the strategy's
defaults; or a dict such as ``{"name": "counting", "n": 50,
"discount_beyond_m": 2.0}`` or ``{"name": "coverage", "alpha": 0.25}``, the
keywords of the static method of that name), and any keywords of
:func:`covmap.explore` (``seed``, ``start``, ``sensor``, ``model``,
``resolution``, ``max_steps``, ...). Every spec is checked before any run
starts: an unknown key, a value of the wrong type or out of range, or a
spec that does not pickle raises :class:`~covmap.InvalidSpecError` naming
the spec's index and what is wrong.

Where the runs go:

- ``executor=None``: a process pool of one worker a local core (at most one
  a spec), each worker started fresh (``spawn``) with
  ``RAYON_NUM_THREADS=1``, so that a run's own parallelism is off and runs
  do not fight over the cores. A sweep of one spec (or a machine of one
  core) runs in this process, with the run's parallelism on.
- ``executor=`` anything with ``submit(fn, *args)`` returning a future with
  ``result()`` and ``add_done_callback``: every run goes there (only that
  public API is used; an executor without it is refused with
  :class:`~covmap.InvalidExecutorError`, see :mod:`covmap._executors`). In
  a process other than the caller's, a run sets ``RAYON_NUM_THREADS=1``
  unless it is set already (rayon reads it once, when covmap first uses its
  thread pool in that process), so one run uses one core; set the variable
  in the workers' environment to give each run more threads. A
  ``ProcessPoolExecutor`` must not fork (``mp_context`` ``spawn`` or
  ``forkserver``): the thread pool of a process that has used covmap does
  not survive a fork, and the children would hang, so a run in a worker
  forked from a process that had imported covmap refuses to start and the
  sweep raises :class:`~covmap.InvalidExecutorError`. :func:`dask_client`
  connects to a Dask scheduler or starts a local cluster (``pip install
  covmap[dask]``).

Worker processes are spawned, and each imports the caller's script again:
a script must call :func:`sweep` under ``if __name__ == "__main__":``
(otherwise every worker would call it again), which :func:`sweep` checks
before anything starts (:class:`~covmap.MainGuardError`, naming the line).
``timeout_s`` bounds the wait: runs not done within that many seconds of
the first submission are cancelled (the sweep's own worker processes
killed) and reported as failures (``TimeoutError``).

Every random draw of a run comes from its seed, and a run gives the same
result at any thread count: the same specs give equal summaries locally, in
a process pool and on Dask with any number of workers (summaries compare
without their wall times).

Failures: a run that raises does not stop the others. Once every run has
ended, :func:`sweep` raises :class:`~covmap.SweepError` if any failed; its
``results`` hold every summary in the specs' order (``None`` for a failed
run) and its ``failures`` a :class:`SweepFailure` per failed run with the
spec's index.
"""

from __future__ import annotations

import difflib
import math
import os
import pickle
from collections import abc
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Union

import numpy as np

from covmap import _executors
from covmap._errors import CovmapError, InvalidSpecError, SweepError, quoted
from covmap._run_summary import RunSummary, explore_keywords, summarise

if TYPE_CHECKING:
    from collections.abc import Mapping, Sequence

    from covmap._custom import CustomStrategy
    from covmap._native import Building, Strategy, World

__all__ = [
    "RunSummary",
    "SweepFailure",
    "prepare",
    "strategy_of",
    "summarise",
    "sweep",
]

SPEC_KEYS = ("world", "strategy")
"""The keys every spec must hold; the others are :func:`covmap.explore`'s
keywords."""

MAX_SEED = 2**64 - 1
"""The largest seed: seeds are unsigned 64-bit integers."""


@dataclass(frozen=True)
class SweepFailure:
    """A run of a sweep that raised."""

    index: int
    """The spec's position in the list given to :func:`sweep`."""
    error_type: str
    """The exception's class name."""
    message: str
    """The exception's message."""
    error: BaseException | None = field(default=None, compare=False)
    """The exception itself (``None`` if it could not be brought back)."""


Progress = Union[bool, Callable[[int, Union[RunSummary, SweepFailure]], None]]
"""``progress`` of :func:`sweep`: a bar (``True``), nothing (``False``), or
a callable given each run's index and summary (or failure) as it ends."""


@dataclass(frozen=True)
class _Run:
    """A spec, checked: what a worker needs to run it."""

    index: int
    world: World
    world_label: str
    strategy: Strategy | CustomStrategy
    seed: int
    options: dict[str, Any]
    building: Building | None = None


def strategy_of(value: Any) -> Strategy | CustomStrategy:
    """A strategy from a spec: a ``Strategy``; ``"coverage"``,
    ``"counting"`` or ``"frontier"`` (the defaults); a dict with
    ``"name"`` and the keywords of that static method; or a
    ``CustomStrategy`` that pickles (its runs go to other processes).
    Raises ``InvalidTypeError`` or ``InvalidParameterError`` naming what is
    wrong."""
    from covmap._custom import CustomStrategy
    from covmap._errors import InvalidParameterError, InvalidTypeError
    from covmap._native import Strategy

    if isinstance(value, Strategy):
        return value
    if isinstance(value, CustomStrategy):
        try:
            pickle.dumps(value)
        except Exception as e:  # noqa: BLE001 (pickling raises whatever the object's parts raise)
            raise InvalidParameterError(
                f"{value!r} does not pickle, and a sweep's runs go to other processes (local cores or Dask "
                f"workers): define choose at the top level of a module ({type(e).__name__}: {e})"
            ) from None
        return value
    builders: dict[str, Callable[..., Strategy]] = {
        "coverage": Strategy.coverage,
        "counting": Strategy.counting,
        "frontier": Strategy.frontier,
    }
    if isinstance(value, str):
        name, keywords = value, {}
    elif isinstance(value, dict):
        keywords = dict(value)
        name = keywords.pop("name", None)
        if not isinstance(name, str):
            raise InvalidTypeError(f"a strategy dict needs a \"name\" ({', '.join(builders)}), got {quoted(value)}")
    else:
        raise InvalidTypeError(
            f"strategy must be a Strategy, a name ({', '.join(builders)}) or a dict with a name, got {type(value).__name__}"
        )
    if name not in builders:
        raise InvalidParameterError(f"unknown strategy {quoted(name)}: expected one of {', '.join(builders)}")
    try:
        return builders[name](**keywords)
    except TypeError as e:  # an unknown keyword among them, or a value of the wrong type
        raise InvalidTypeError(f"strategy {quoted(name)}: {e}") from None


def _world_of(value: Any) -> tuple[World, str, Building | None]:
    from covmap.buildings import spec_world

    return spec_world(value)


def _seed_of(value: Any) -> int:
    from covmap._errors import InvalidParameterError, InvalidTypeError

    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise InvalidTypeError(f"seed must be an integer, got {type(value).__name__}")
    if not 0 <= int(value) <= MAX_SEED:
        raise InvalidParameterError(f"invalid parameter `seed` = {quoted(value)}: expected 0 to 2**64 - 1")
    return int(value)


def _start_of(value: Any) -> tuple[float, float, float] | None:
    """A spec's ``start``: ``None``, or ``(x, y, theta)`` (any sequence or
    1-D array of three numbers; nothing is flattened or dropped)."""
    from covmap._errors import ArrayShapeError

    if value is None:
        return None
    start = np.asarray(value, dtype=np.float64)
    if start.shape != (3,):
        raise ArrayShapeError(f"start must be (x, y, theta), three numbers, got shape {start.shape}")
    return (float(start[0]), float(start[1]), float(start[2]))


def prepare(specs: Sequence[Mapping[str, Any]]) -> list[_Run]:
    """Check every spec (see the module's documentation) without running any;
    raises :class:`~covmap.InvalidSpecError` for the first bad one."""
    from covmap._native import Exploration

    if isinstance(specs, (str, bytes)) or not hasattr(specs, "__len__"):
        from covmap._errors import InvalidTypeError

        raise InvalidTypeError(f"specs must be a list of dicts, got {type(specs).__name__}")
    keywords = explore_keywords()
    allowed = (*SPEC_KEYS, *keywords)
    runs: list[_Run] = []
    # The native check builds a run (ground truth, evaluation cells): once per
    # world and options, whatever the strategy and seed.
    checked: set[tuple[int, str]] = set()
    worlds: dict[str, tuple[World, Building | None]] = {}
    for index, spec in enumerate(specs):
        if not isinstance(spec, abc.Mapping):
            raise InvalidSpecError(index, f"expected a dict of covmap.explore arguments, got {type(spec).__name__}")
        for key in spec:
            if key not in allowed:
                near = difflib.get_close_matches(str(key), allowed, n=1)
                hint = f" (did you mean {near[0]!r}?)" if near else ""
                raise InvalidSpecError(
                    index, f"unknown key {quoted(key)}{hint}; a spec takes {', '.join(allowed)}"
                )
        for key in SPEC_KEYS:
            if key not in spec:
                raise InvalidSpecError(index, f"no {key!r}: every spec needs a world and a strategy")
        try:
            name = spec["world"]
            if isinstance(name, str) and name in worlds:
                (world, building), label = worlds[name], name
            else:
                world, label, building = _world_of(name)
                if isinstance(name, str):
                    worlds[name] = (world, building)
            strategy = strategy_of(spec["strategy"])
            seed = _seed_of(spec.get("seed", 0))
            options = {k: v for k, v in spec.items() if k not in (*SPEC_KEYS, "seed")}
            if "start" in options:
                options["start"] = _start_of(options["start"])
            same_check = (id(world), repr(sorted(options.items())))
            if same_check not in checked:
                Exploration(world, strategy, seed=seed, **options)
                checked.add(same_check)
        except (CovmapError, TypeError, ValueError) as e:
            raise InvalidSpecError(index, f"{type(e).__name__}: {e}") from e
        runs.append(_Run(index, world, label, strategy, seed, options, building))
    return runs


def _run_pickled(payload: bytes, caller_pid: int) -> RunSummary:
    """Run one pickled :class:`_Run` (in a worker, or in the caller's process)."""
    if os.getpid() != caller_pid:
        _executors.refuse_forked_worker()
        # Before covmap's first parallel call in this process: one thread a run.
        os.environ.setdefault(_executors.THREADS_VARIABLE, "1")
    from covmap._native import explore

    run: _Run = pickle.loads(payload)
    result = explore(run.world, run.strategy, seed=run.seed, **run.options)
    return summarise(run.index, run.world_label, run.options, result, run.building)


def _one_thread() -> None:
    """The initializer of :func:`sweep`'s own worker processes."""
    os.environ[_executors.THREADS_VARIABLE] = "1"


class _Bar:
    """The default progress display: a bar of the runs."""

    def __init__(self, total: int) -> None:
        from covmap._progress import Progress as Display

        self.display = Display(total, "run")

    def __call__(self, index: int, outcome: RunSummary | SweepFailure) -> None:
        if isinstance(outcome, SweepFailure):
            self.display.update(f"spec {index} failed: {outcome.error_type}")
        else:
            self.display.update(
                f"spec {index}: {outcome.path_length_m:.1f} m, "
                f"{100.0 * outcome.high_entropy_fraction:.1f} % uncertain, {outcome.seconds:.1f} s"
            )

    def close(self) -> None:
        self.display.__exit__()


def _failure(index: int, error: BaseException) -> SweepFailure:
    try:
        pickle.dumps(error)
        kept: BaseException | None = error
    except Exception:
        kept = None
    return SweepFailure(index, type(error).__name__, str(error), kept)


def sweep(
    specs: Sequence[Mapping[str, Any]],
    *,
    executor: Any = None,
    progress: Progress = True,
    timeout_s: float | None = None,
) -> list[RunSummary]:
    """Run every spec of ``specs`` (dicts of :func:`covmap.explore`
    arguments; see :mod:`covmap._sweep`) and return their summaries in the
    specs' order.

    ``executor=None`` runs them on this machine's cores, one run a core, in
    worker processes of their own; otherwise every run is submitted to
    ``executor`` (a ``ProcessPoolExecutor`` that does not fork, a
    ``dask.distributed.Client``, anything with ``submit``). ``progress``: a
    bar on standard error (``True``), nothing (``False``), or a callable
    given each run's index and :class:`RunSummary` (or
    :class:`SweepFailure`) as it ends. ``timeout_s``: the most seconds to
    wait for the runs, from the first submission (``None``: no limit); runs
    not done by then are cancelled (the sweep's own worker processes
    killed) and fail with ``TimeoutError``.

    Every spec is checked first (:class:`~covmap.InvalidSpecError` names the
    first bad one; nothing runs), and so is the call: new worker processes
    import the caller's script again, so a script must call ``sweep`` under
    ``if __name__ == "__main__":`` (:class:`~covmap.MainGuardError`
    otherwise). Runs that raise are collected: after every run has ended,
    :class:`~covmap.SweepError` carries the summaries of the others and the
    failures with their specs' indexes.
    """
    if not (isinstance(progress, bool) or callable(progress)):
        from covmap._errors import InvalidTypeError

        raise InvalidTypeError(f"progress must be True, False or a callable, got {type(progress).__name__}")
    _check_timeout(timeout_s)
    runs = prepare(specs)
    if executor is not None:
        _executors.check_executor(executor)
    payloads = []
    for run in runs:
        try:
            payloads.append(pickle.dumps(run))
        except Exception as e:
            raise InvalidSpecError(run.index, f"does not pickle, so no worker can run it: {e}") from e
    if not runs:
        return []
    workers = min(_executors.local_cores(), len(runs))
    # One run, or one core, runs here (its own parallelism on), unless a
    # timeout asks for a process that can be stopped. The main guard is
    # checked whatever the cores, so that a script runs on every machine.
    in_this_process = executor is None and workers == 1 and timeout_s is None
    if executor is None or _starts_processes(executor):
        _executors.check_main_guard("covmap.sweep")
    results: list[RunSummary | None] = [None] * len(runs)
    failures: list[SweepFailure] = []
    bar = _Bar(len(runs)) if progress is True else None
    report = bar if bar is not None else (progress if callable(progress) else None)

    def record(index: int, outcome: RunSummary | SweepFailure) -> None:
        if isinstance(outcome, RunSummary):
            results[index] = outcome
        else:
            failures.append(outcome)
        if report is not None:
            report(index, outcome)

    try:
        if in_this_process:
            for run, payload in zip(runs, payloads):
                try:
                    summary = _run_pickled(payload, os.getpid())
                except Exception as e:
                    record(run.index, _failure(run.index, e))
                else:
                    record(run.index, summary)
        else:
            for index in _run_on(executor, workers, payloads, record, timeout_s):
                message = f"no result within {timeout_s:g} s: the run was cancelled"
                record(index, SweepFailure(index, "TimeoutError", message))
    finally:
        if bar is not None:
            bar.close()
    if failures:
        failures.sort(key=lambda f: f.index)
        raise SweepError(list(results), failures)
    return [r for r in results if r is not None]


def _check_timeout(timeout_s: Any) -> None:
    if timeout_s is None:
        return
    if isinstance(timeout_s, bool) or not isinstance(timeout_s, (int, float)) or not 0.0 < timeout_s < math.inf:
        from covmap._errors import InvalidParameterError

        raise InvalidParameterError(
            f"invalid parameter `timeout_s` = {quoted(timeout_s)}: expected None or a positive, finite number of seconds"
        )


def _starts_processes(executor: Any) -> bool:
    """Whether ``executor`` runs its calls in processes it starts here (a
    ``ProcessPoolExecutor``), which import the caller's script again."""
    from concurrent.futures import ProcessPoolExecutor

    return isinstance(executor, ProcessPoolExecutor)


def _run_on(
    executor: Any,
    workers: int,
    payloads: list[bytes],
    record: Callable[[int, RunSummary | SweepFailure], None],
    timeout_s: float | None,
) -> list[int]:
    """Run every payload on ``executor`` (``None``: a pool of ``workers``
    spawned processes of this sweep's own), recording each outcome as it
    ends; returns the indexes of the runs not done within ``timeout_s``."""

    def ended(outcome: _executors.Outcome) -> None:
        index, summary, error = outcome
        if error is not None:
            record(index, _failure(index, error))
        elif isinstance(summary, RunSummary):
            record(index, summary)
        else:
            record(index, SweepFailure(index, "TypeError", f"the executor returned {type(summary).__name__}"))

    calls = [(payload, os.getpid()) for payload in payloads]
    # Looked up now, so that a test may stand in for the worker function.
    function = _run_pickled
    if executor is not None:
        return _executors.gather(executor, function, calls, ended, timeout_s)
    pool = _executors.LocalPool(workers, _one_thread)
    finished = False
    try:
        late = _executors.gather(pool.executor, function, calls, ended, timeout_s)
        finished = not late
        return late
    finally:
        pool.close(finished=finished)
