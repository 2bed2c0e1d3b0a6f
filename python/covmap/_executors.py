"""Calls run on executors for :func:`covmap.sweep`: its own pool of worker
processes, a Dask cluster (:func:`dask_client`), or any executor with
``concurrent.futures``' ``submit``, through their public API only
(``submit``; a future's ``result``, ``add_done_callback`` and ``cancel``).

What can go wrong with a foreign executor is refused with one clear
:class:`~covmap.InvalidExecutorError` instead of an error from the
clean-up: no ``submit``, a ``submit`` that returns something other than a
future (``None``), a future without ``add_done_callback``. A future that
never completes is waited for at most ``timeout_s``; a worker process
forked from one that runs covmap (whose thread pool does not survive the
fork, so that the run would wait for it forever) refuses to run
(:func:`refuse_forked_worker`).

New worker processes are spawned, and a spawned process imports the
caller's script again (as ``__mp_main__``): a script that calls
:func:`covmap.sweep` at module level without ``if __name__ ==
"__main__":`` would call it again in every worker, and every run would
fail with ``BrokenProcessPool``. :func:`check_main_guard` finds such a call
before anything starts and raises :class:`~covmap.MainGuardError` naming
the script, the line and the fix.
"""

from __future__ import annotations

import ast
import inspect
import math
import os
import queue
import sys
import time
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any, Callable

from covmap._errors import InvalidExecutorError, MainGuardError, MissingDependencyError, SchedulerError, quoted

if TYPE_CHECKING:
    from collections.abc import Iterator
    from types import FrameType, ModuleType

__all__ = [
    "MAX_LOCAL_WORKERS",
    "THREADS_VARIABLE",
    "Outcome",
    "check_executor",
    "check_main_guard",
    "dask_client",
    "gather",
    "LocalPool",
    "local_cores",
    "refuse_forked_worker",
]

THREADS_VARIABLE = "RAYON_NUM_THREADS"
"""The environment variable rayon sizes its thread pool by, once, when covmap
first uses the pool in a process."""

Outcome = tuple[int, Any, "BaseException | None"]
"""What :func:`gather` reports of one call: its index, its result (``None``
if it raised) and its exception (``None`` if it returned)."""

_forked = False
"""Whether this process was forked from one that had imported covmap."""


def _mark_forked() -> None:
    global _forked
    _forked = True


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_mark_forked)


def refuse_forked_worker() -> None:
    """Raise :class:`~covmap.InvalidExecutorError` in a worker process
    forked from a process that had imported covmap: covmap's thread pool
    does not survive a fork, and the run would wait for it forever."""
    if _forked:
        raise InvalidExecutorError(
            "this worker process was forked from one running covmap, whose thread pool does not survive a "
            "fork (the run would hang): give covmap.sweep a ProcessPoolExecutor with "
            "mp_context=multiprocessing.get_context('spawn') (or 'forkserver')"
        )


def local_cores() -> int:
    """The cores this process may run on."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return max(1, os.cpu_count() or 1)


def check_executor(executor: Any) -> None:
    """Raise :class:`~covmap.InvalidExecutorError` unless ``executor`` has a
    ``submit`` method."""
    if not callable(getattr(executor, "submit", None)):
        raise InvalidExecutorError(
            "executor must have a submit method (a concurrent.futures executor, a dask.distributed.Client), "
            f"got {type(executor).__name__}"
        )


def _is_main_guard(test: ast.expr) -> bool | None:
    """Whether ``test`` is ``__name__ == "__main__"`` (``True``), its
    negation with ``!=`` (``False``), or neither (``None``)."""
    if not (isinstance(test, ast.Compare) and len(test.ops) == 1 and len(test.comparators) == 1):
        return None
    sides = {type(test.left), type(test.comparators[0])}
    names = [n for n in (test.left, test.comparators[0]) if isinstance(n, ast.Name)]
    constants = [c for c in (test.left, test.comparators[0]) if isinstance(c, ast.Constant)]
    if sides != {ast.Name, ast.Constant} or names[0].id != "__name__" or constants[0].value != "__main__":
        return None
    if isinstance(test.ops[0], ast.Eq):
        return True
    return False if isinstance(test.ops[0], ast.NotEq) else None


def _guarded(tree: ast.Module, line: int) -> bool:
    """Whether ``line`` of the module ``tree`` runs only under ``if
    __name__ == "__main__":`` (or in the ``else`` of its negation)."""

    def within(statements: list[ast.stmt]) -> bool:
        return any(s.lineno <= line <= (s.end_lineno or s.lineno) for s in statements)

    for node in ast.walk(tree):
        if isinstance(node, ast.If):
            guard = _is_main_guard(node.test)
            if (guard is True and within(node.body)) or (guard is False and within(node.orelse)):
                return True
    return False


def _module_frame(main: ModuleType) -> FrameType | None:
    """The outermost frame running the main module's own code (its
    ``<module>`` frame), if the main module is still being run."""
    found = None
    frame = inspect.currentframe()
    while frame is not None:
        if frame.f_code.co_name == "<module>" and frame.f_globals is vars(main):
            found = frame
        frame = frame.f_back  # type: ignore[assignment]
    return found


def check_main_guard(what: str) -> None:
    """Raise :class:`~covmap.MainGuardError` if ``what`` (``"covmap.sweep"``)
    is being called by the main script's module-level code outside ``if
    __name__ == "__main__":``: a spawned worker process imports the script
    again, and would call it again. Nothing is checked where that cannot
    happen (an interactive session, ``python -c``, a call from a function
    the script's code did not call while it ran) or where the script's
    source cannot be read."""
    main = sys.modules.get("__main__")
    path = getattr(main, "__file__", None)
    if main is None or not isinstance(path, str):
        return
    frame = _module_frame(main)
    if frame is None:
        return
    try:
        with open(path, "rb") as f:
            tree = ast.parse(f.read(), filename=path)
    except (OSError, SyntaxError, ValueError):
        return
    line = frame.f_lineno
    if _guarded(tree, line):
        return
    raise MainGuardError(
        f"{path}, line {line}: {what} starts worker processes, which import this script again and would run "
        f"this line again; put the code that calls {what} under 'if __name__ == \"__main__\":'"
    )


def _cancel(futures: list[Any]) -> None:
    """Cancel what can be cancelled; a future that cannot says nothing."""
    for future in futures:
        try:
            future.cancel()
        except Exception:  # noqa: BLE001, S110 (a foreign future's cancel may fail in any way)
            pass


def gather(
    executor: Any,
    function: Callable[..., Any],
    calls: list[tuple[Any, ...]],
    report: Callable[[Outcome], None],
    timeout_s: float | None,
) -> list[int]:
    """Submit ``function(*args)`` for each ``args`` of ``calls`` to
    ``executor`` and ``report`` each :data:`Outcome` as it ends
    (``add_done_callback``), in the order they end. Returns the indexes of
    the calls not done within ``timeout_s`` seconds of the first submission
    (``None``: waits for all), cancelled. An executor whose ``submit``
    returns no future raises :class:`~covmap.InvalidExecutorError`, as does
    a worker's own (a forked worker's): the calls submitted are cancelled."""
    done: queue.Queue[int] = queue.Queue()
    futures: list[Any] = []
    start = time.monotonic()
    try:
        for index, args in enumerate(calls):
            future = executor.submit(function, *args)
            if not (callable(getattr(future, "add_done_callback", None)) and callable(getattr(future, "result", None))):
                raise InvalidExecutorError(
                    f"{type(executor).__name__}.submit returned {type(future).__name__}, not a future: "
                    "covmap.sweep needs one with result() and add_done_callback() "
                    "(a concurrent.futures.Future, a Dask future)"
                )
            futures.append(future)
            future.add_done_callback(lambda _, i=index: done.put(i))
        ended: set[int] = set()
        while len(ended) < len(calls):
            remaining = None if timeout_s is None else max(0.0, start + timeout_s - time.monotonic())
            try:
                index = done.get(timeout=remaining)
            except queue.Empty:
                late = [i for i in range(len(calls)) if i not in ended]
                _cancel([futures[i] for i in late])
                return late
            if index in ended:  # a callback called twice
                continue
            ended.add(index)
            try:
                outcome: Outcome = (index, futures[index].result(), None)
            except InvalidExecutorError:
                raise
            except Exception as e:  # noqa: BLE001 (a run's error is reported, not raised)
                outcome = (index, None, e)
            report(outcome)
        return []
    except BaseException:
        _cancel(futures)
        raise


class LocalPool:
    """A pool of ``workers`` spawned worker processes (not forked: covmap's
    thread pool does not survive a fork), each started by ``initializer``:
    a ``ProcessPoolExecutor``, which :meth:`close` can also stop with its
    runs unfinished (after a timeout, an error or Ctrl-C), killing its
    processes."""

    def __init__(self, workers: int, initializer: Callable[[], None]) -> None:
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor

        # The children this pool adds are its workers (ProcessPoolExecutor
        # names no public way to its processes before Python 3.14).
        self._before = set(multiprocessing.active_children())
        self.executor = ProcessPoolExecutor(
            workers, mp_context=multiprocessing.get_context("spawn"), initializer=initializer
        )

    def close(self, *, finished: bool) -> None:
        """Shut the pool down: once its runs are over if they are
        ``finished``, else at once, its worker processes killed."""
        import multiprocessing
        import time

        if finished:
            self.executor.shutdown(wait=True)
            return
        self.executor.shutdown(wait=False, cancel_futures=True)
        terminate = getattr(self.executor, "terminate_workers", None)  # Python 3.14
        if callable(terminate):
            terminate()
            return
        # Looked for again until none of the pool's workers is left (the
        # executor's own thread may still start one after a look), each
        # terminated, and killed outright once the 5 s it had are over; at
        # most 10 s in all.
        start = time.monotonic()
        while (workers := set(multiprocessing.active_children()) - self._before) and time.monotonic() - start < 10.0:
            late = time.monotonic() - start >= 5.0
            for child in workers:
                if late:
                    child.kill()
                else:
                    child.terminate()
            for child in workers:
                child.join(timeout=max(0.1, 5.0 - (time.monotonic() - start)))


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
    if workers is not None:
        check_main_guard("covmap.dask_client(workers=...)")
    if (address is None) == (workers is None):
        from covmap._errors import InvalidTypeError

        raise InvalidTypeError("dask_client takes an address or a number of workers, not both or neither")
    if isinstance(timeout_s, bool) or not isinstance(timeout_s, (int, float)) or not 0 < timeout_s < math.inf:
        from covmap._errors import InvalidParameterError

        raise InvalidParameterError(
            f"invalid parameter `timeout_s` = {quoted(timeout_s)}: expected a positive, finite number of seconds"
        )
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int) or not 1 <= workers <= MAX_LOCAL_WORKERS
    ):
        from covmap._errors import InvalidParameterError

        raise InvalidParameterError(
            f"invalid parameter `workers` = {quoted(workers)}: expected from 1 to {MAX_LOCAL_WORKERS} workers"
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
        raise SchedulerError(f"no Dask scheduler answered at {quoted(address)} within {timeout_s:g} s: {e}") from None
    with client:
        yield client
