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
  ``result()`` and ``add_done_callback``: every run goes there. In a process
  other than the caller's, a run sets ``RAYON_NUM_THREADS=1`` unless it is
  set already (rayon reads it once, when covmap first uses its thread pool
  in that process), so one run uses one core; set the variable in the
  workers' environment to give each run more threads. A
  ``ProcessPoolExecutor`` must not fork (``mp_context`` ``spawn`` or
  ``forkserver``): the thread pool of a process that has used covmap does
  not survive a fork, and the children would hang, so such a pool is
  refused with :class:`~covmap.InvalidExecutorError`. :func:`dask_client`
  connects to a Dask scheduler or starts a local cluster (``pip install
  covmap[dask]``).

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
import queue
from collections import abc
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Callable, Union

import numpy as np

from covmap._arguments import check_module
from covmap._errors import (
    CovmapError,
    InvalidExecutorError,
    InvalidSpecError,
    MissingDependencyError,
    SchedulerError,
    SweepError,
)
from covmap._exploration import REAL_TIME_SPEED_M_S, ExplorationErrors, Timing, real_time_factor

if TYPE_CHECKING:
    from collections.abc import Iterator, Mapping, Sequence

    import numpy.typing as npt

    from covmap._exploration import ExplorationResult
    from covmap._native import Building, Strategy, World

__all__ = [
    "RunSummary",
    "SweepFailure",
    "dask_client",
    "prepare",
    "strategy_of",
    "summarise",
    "sweep",
]

THREADS_VARIABLE = "RAYON_NUM_THREADS"
"""The environment variable rayon sizes its thread pool by, once, when covmap
first uses the pool in a process."""

SPEC_KEYS = ("world", "strategy")
"""The keys every spec must hold; the others are :func:`covmap.explore`'s
keywords."""

MAX_SEED = 2**64 - 1
"""The largest seed: seeds are unsigned 64-bit integers."""


def explore_keywords() -> tuple[str, ...]:
    """The keyword arguments :func:`covmap.explore` takes, in its order."""
    from covmap._native import _EXPLORE_DEFAULTS

    return tuple(_EXPLORE_DEFAULTS)


@dataclass(frozen=True, eq=False)
class RunSummary:
    """What one run of a sweep reports: everything of
    :class:`~covmap.ExplorationResult` that is small, under the same names,
    without the maps. Pickles; two summaries compare equal when their runs
    had the same outcome (the wall times, :attr:`seconds`, :attr:`timing`
    and the trace's ``"planning_s"``, are left out)."""

    index: int
    """The spec's position in the list given to :func:`sweep`."""
    world: str
    """The world: its name as the spec gave it, a ``Building``'s name, or the
    ``repr`` of the ``World`` given."""
    strategy: Strategy
    """The strategy that chose the goals."""
    seed: int
    """The seed of every random draw."""
    options: dict[str, Any]
    """The spec's further keywords of :func:`covmap.explore` (``seed``
    aside), as given (a ``start`` as a tuple of floats)."""
    start: tuple[float, float, float]
    """Where the robot started, ``(x, y, theta)``."""
    termination: str | None
    """How the run ended (see :attr:`covmap.ExplorationResult.termination`)."""
    path_length_m: float
    """Distance driven, metres."""
    scans: int
    """Scans taken."""
    steps: int
    """Steps taken."""
    contacts: int
    """Contacts with obstacles the map did not show."""
    epsilon: float
    """Entropy above which a cell is uncertain, nats."""
    high_entropy_fraction: float
    """The fraction of the evaluation cells whose entropy is above
    :attr:`epsilon` at the end (Table I's measure)."""
    coverage_error: ExplorationErrors
    """The maps' mean absolute errors on the evaluation cells."""
    seconds: float
    """Wall time of the whole run, seconds."""
    timing: Timing
    """Wall time of the loop by what it was spent on."""
    trace: dict[str, npt.NDArray[np.generic]] = field(repr=False)
    """Per-step figures (see :attr:`covmap.ExplorationResult.trace`)."""
    rooms: int | None = None
    """The rooms and halls of the building (its corridors aside) the run
    is judged on (:attr:`covmap.Building.rooms`); ``None`` for a world
    given without its rooms."""
    rooms_never_entered: tuple[str, ...] = ()
    """The names of those the robot never entered
    (:meth:`covmap.Building.rooms_never_entered`)."""
    evaluation_area_m2: float = 0.0
    """The area of the evaluation cells, square metres: what the run
    could observe."""

    @property
    def certain_fraction(self) -> float:
        """The fraction of the evaluation cells certain at the end: ``1 -
        high_entropy_fraction``."""
        return 1.0 - self.high_entropy_fraction

    def real_time_factor(self, speed_m_s: float = REAL_TIME_SPEED_M_S) -> float:
        """How many times faster than real time the run was for a robot
        driving its path at ``speed_m_s`` (see
        :meth:`covmap.ExplorationResult.real_time_factor`)."""
        return real_time_factor(self.path_length_m, self.seconds, speed_m_s)

    def _outcome(self) -> tuple[Any, ...]:
        return (
            self.index,
            self.world,
            self.strategy,
            self.seed,
            self.options,
            self.start,
            self.termination,
            self.path_length_m,
            self.scans,
            self.steps,
            self.contacts,
            self.epsilon,
            self.high_entropy_fraction,
            self.coverage_error,
            self.rooms,
            self.rooms_never_entered,
            self.evaluation_area_m2,
        )

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, RunSummary):
            return NotImplemented
        if self._outcome() != other._outcome():
            return False
        keys = self.trace.keys() - {"planning_s"}
        return keys == other.trace.keys() - {"planning_s"} and all(
            np.array_equal(self.trace[k], other.trace[k]) for k in keys
        )

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return (
            f"<RunSummary {self.index}: {self.world}, {self.strategy!r}, seed {self.seed}, {self.termination}, "
            f"{self.path_length_m:.2f} m, {100.0 * self.high_entropy_fraction:.2f} % uncertain>"
        )


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
    strategy: Strategy
    seed: int
    options: dict[str, Any]
    building: Building | None = None


def strategy_of(value: Any) -> Strategy:
    """A strategy from a spec: a ``Strategy``; ``"coverage"``,
    ``"counting"`` or ``"frontier"`` (the defaults); or a dict with
    ``"name"`` and the keywords of that static method. Raises
    ``InvalidTypeError`` or ``InvalidParameterError`` naming what is wrong."""
    from covmap._errors import InvalidParameterError, InvalidTypeError
    from covmap._native import Strategy

    if isinstance(value, Strategy):
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
            raise InvalidTypeError(f"a strategy dict needs a \"name\" ({', '.join(builders)}), got {value!r}")
    else:
        raise InvalidTypeError(
            f"strategy must be a Strategy, a name ({', '.join(builders)}) or a dict with a name, got {type(value).__name__}"
        )
    if name not in builders:
        raise InvalidParameterError(f"unknown strategy {name!r}: expected one of {', '.join(builders)}")
    try:
        return builders[name](**keywords)
    except InvalidTypeError as e:  # an unknown keyword among them, or a value of the wrong type
        raise InvalidTypeError(f"strategy {name!r}: {e}") from None


def _world_of(value: Any) -> tuple[World, str, Building | None]:
    from covmap.buildings import spec_world

    return spec_world(value)


def _seed_of(value: Any) -> int:
    from covmap._errors import InvalidParameterError, InvalidTypeError

    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise InvalidTypeError(f"seed must be an integer, got {type(value).__name__}")
    if not 0 <= int(value) <= MAX_SEED:
        raise InvalidParameterError(f"invalid parameter `seed` = {value}: expected 0 to 2**64 - 1")
    return int(value)


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
                    index, f"unknown key {key!r}{hint}; a spec takes {', '.join(allowed)}"
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
            if options.get("start") is not None:
                options["start"] = tuple(float(x) for x in np.asarray(options["start"], dtype=np.float64).ravel())
            same_check = (id(world), repr(sorted(options.items())))
            if same_check not in checked:
                Exploration(world, strategy, seed=seed, **options)
                checked.add(same_check)
        except (CovmapError, TypeError, ValueError) as e:
            raise InvalidSpecError(index, f"{type(e).__name__}: {e}") from e
        runs.append(_Run(index, world, label, strategy, seed, options, building))
    return runs


def summarise(
    index: int,
    world: str,
    options: Mapping[str, Any],
    result: ExplorationResult,
    building: Building | None = None,
) -> RunSummary:
    """The :class:`RunSummary` of ``result``, the run of spec ``index``
    (in ``building``, whose rooms it is judged on, if given)."""
    start = tuple(float(x) for x in result.start)
    rooms = None if building is None else sum(1 for r in building.rooms if r.kind != "corridor")
    never = () if building is None else tuple(building.rooms_never_entered(result.trajectory))
    cell_m2 = result.grid.resolution * result.grid.resolution
    return RunSummary(
        index=index,
        world=world,
        strategy=result.strategy,
        seed=result.seed,
        options=dict(options),
        start=(start[0], start[1], start[2]),
        termination=result.termination,
        path_length_m=result.path_length_m,
        scans=result.scans,
        steps=result.steps,
        contacts=result.contacts,
        epsilon=result.epsilon,
        high_entropy_fraction=result.high_entropy_fraction,
        coverage_error=result.coverage_error,
        seconds=result.seconds,
        timing=result.timing,
        trace={k: np.array(v) for k, v in result.trace.items()},
        rooms=rooms,
        rooms_never_entered=never,
        evaluation_area_m2=float(np.count_nonzero(result.evaluation_cells)) * cell_m2,
    )


def _run_pickled(payload: bytes, caller_pid: int) -> RunSummary:
    """Run one pickled :class:`_Run` (in a worker, or in the caller's process)."""
    if os.getpid() != caller_pid:
        # Before covmap's first parallel call in this process: one thread a run.
        os.environ.setdefault(THREADS_VARIABLE, "1")
    from covmap._native import explore

    run: _Run = pickle.loads(payload)
    result = explore(run.world, run.strategy, seed=run.seed, **run.options)
    return summarise(run.index, run.world_label, run.options, result, run.building)


def _one_thread() -> None:
    """The initializer of :func:`sweep`'s own worker processes."""
    os.environ[THREADS_VARIABLE] = "1"


def local_cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


def _check_executor(executor: Any) -> None:
    if not callable(getattr(executor, "submit", None)):
        raise InvalidExecutorError(
            f"executor must have a submit method (a concurrent.futures executor, a dask.distributed.Client), "
            f"got {type(executor).__name__}"
        )
    context = getattr(executor, "_mp_context", None)
    method = getattr(context, "get_start_method", None)
    if callable(method) and method() == "fork":
        raise InvalidExecutorError(
            "a ProcessPoolExecutor that forks would hang (covmap's thread pool does not survive a fork): "
            "pass mp_context=multiprocessing.get_context('spawn') or 'forkserver'"
        )


class _Bar:
    """The default progress display: a bar of the runs."""

    def __init__(self, total: int) -> None:
        from covmap.cli._progress import Progress as Display

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
    specs: Sequence[Mapping[str, Any]], *, executor: Any = None, progress: Progress = True
) -> list[RunSummary]:
    """Run every spec of ``specs`` (dicts of :func:`covmap.explore`
    arguments; see :mod:`covmap._sweep`) and return their summaries in the
    specs' order.

    ``executor=None`` runs them on this machine's cores, one run a core;
    otherwise every run is submitted to ``executor`` (a
    ``ProcessPoolExecutor`` that does not fork, a ``dask.distributed.Client``,
    anything with ``submit``). ``progress``: a bar on standard error
    (``True``), nothing (``False``), or a callable given each run's index and
    :class:`RunSummary` (or :class:`SweepFailure`) as it ends.

    Every spec is checked first (:class:`~covmap.InvalidSpecError` names the
    first bad one; nothing runs). Runs that raise are collected: after every
    run has ended, :class:`~covmap.SweepError` carries the summaries of the
    others and the failures with their specs' indexes.
    """
    if not (isinstance(progress, bool) or callable(progress)):
        from covmap._errors import InvalidTypeError

        raise InvalidTypeError(f"progress must be True, False or a callable, got {type(progress).__name__}")
    runs = prepare(specs)
    if executor is not None:
        _check_executor(executor)
    payloads = []
    for run in runs:
        try:
            payloads.append(pickle.dumps(run))
        except Exception as e:
            raise InvalidSpecError(run.index, f"does not pickle, so no worker can run it: {e}") from e
    results: list[RunSummary | None] = [None] * len(runs)
    failures: list[SweepFailure] = []
    if not runs:
        return []
    bar = _Bar(len(runs)) if progress is True else None
    report = bar if bar is not None else (progress if callable(progress) else None)
    try:
        workers = min(local_cores(), len(runs))
        if executor is None and workers == 1:
            for run, payload in zip(runs, payloads):
                outcome: RunSummary | SweepFailure
                try:
                    outcome = results[run.index] = _run_pickled(payload, os.getpid())
                except Exception as e:
                    outcome = _failure(run.index, e)
                    failures.append(outcome)
                if report is not None:
                    report(run.index, outcome)
        elif executor is None:
            import multiprocessing
            from concurrent.futures import ProcessPoolExecutor

            with ProcessPoolExecutor(
                workers, mp_context=multiprocessing.get_context("spawn"), initializer=_one_thread
            ) as pool:
                _gather(pool, payloads, results, failures, report)
        else:
            _gather(executor, payloads, results, failures, report)
    finally:
        if bar is not None:
            bar.close()
    if failures:
        failures.sort(key=lambda f: f.index)
        raise SweepError(list(results), failures)
    return [r for r in results if r is not None]


def _gather(
    executor: Any,
    payloads: list[bytes],
    results: list[RunSummary | None],
    failures: list[SweepFailure],
    report: Callable[[int, RunSummary | SweepFailure], None] | None,
) -> None:
    """Submit every payload to ``executor`` and collect the outcomes as they
    end (``add_done_callback``: the concurrent.futures and Dask futures both
    have it)."""
    done: queue.Queue[tuple[int, Any]] = queue.Queue()
    futures = []
    try:
        for index, payload in enumerate(payloads):
            future = executor.submit(_run_pickled, payload, os.getpid())
            futures.append(future)
            future.add_done_callback(lambda f, i=index: done.put((i, f)))
        for _ in payloads:
            index, future = done.get()
            try:
                summary = future.result()
            except Exception as e:
                failed = _failure(index, e)
            else:
                if isinstance(summary, RunSummary):
                    results[index] = summary
                    if report is not None:
                        report(index, summary)
                    continue
                failed = SweepFailure(index, "TypeError", f"the executor returned {type(summary).__name__}")
            failures.append(failed)
            if report is not None:
                report(index, failed)
    except BaseException:
        for future in futures:
            future.cancel()
        raise


#: The most worker processes :func:`dask_client` starts on this machine.
MAX_LOCAL_WORKERS = 1024


@contextmanager
def dask_client(
    address: str | None = None, *, workers: int | None = None, timeout_s: float = 10.0
) -> Iterator[Any]:
    """A ``dask.distributed.Client`` for :func:`sweep`, closed when the block
    ends: connected to the scheduler at ``address`` (``"tcp://host:8786"``),
    or, with ``workers``, to a local cluster of that many worker processes of
    one thread each, started here. A scheduler that does not answer within
    ``timeout_s`` raises :class:`~covmap.SchedulerError`; Dask missing,
    :class:`~covmap.MissingDependencyError`."""
    if (address is None) == (workers is None):
        from covmap._errors import InvalidTypeError

        raise InvalidTypeError("dask_client takes an address or a number of workers, not both or neither")
    if isinstance(timeout_s, bool) or not isinstance(timeout_s, (int, float)) or not 0 < timeout_s < math.inf:
        from covmap._errors import InvalidParameterError

        raise InvalidParameterError(
            f"invalid parameter `timeout_s` = {timeout_s!r}: expected a positive, finite number of seconds"
        )
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int) or not 1 <= workers <= MAX_LOCAL_WORKERS
    ):
        from covmap._errors import InvalidParameterError

        raise InvalidParameterError(
            f"invalid parameter `workers` = {workers!r}: expected from 1 to {MAX_LOCAL_WORKERS} workers"
        )
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise MissingDependencyError(
            "Dask is not installed: pip install 'covmap[dask]' (dask.distributed)"
        ) from None
    if workers is not None:
        with LocalCluster(
            n_workers=workers, processes=True, threads_per_worker=1, dashboard_address=None
        ) as cluster, Client(cluster) as client:
            yield client
        return
    try:
        client = Client(address, timeout=timeout_s)
    except (OSError, TimeoutError, ValueError) as e:
        raise SchedulerError(f"no Dask scheduler answered at {address!r} within {timeout_s:g} s: {e}") from None
    with client:
        yield client


check_module(__name__)  # calls with the wrong arguments raise InvalidTypeError
