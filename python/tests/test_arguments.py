"""Calls with the wrong arguments raise InvalidTypeError (covmap/_arguments.py
and the native constructors' guard); everything else about the callables is
as it was. The corpus (bad_input/corpus.py, ``arity_cases``) calls every
public callable with wrong arguments; these are the rest: what must pass
unchanged, and what the wrapping must keep."""

from __future__ import annotations

import copy
import inspect
import math
import pickle
import pydoc
import types
from typing import Any

import numpy as np
import pytest

import covmap
import covmap._native as native


@pytest.fixture
def log() -> covmap.Log:
    poses = np.array([[1.0, 1.0, 0.0], [1.2, 1.0, 0.1]])
    return covmap.Log(poses, np.ones((2, 3)), np.array([0.0, 1.0, 2.0]), max_range_m=5.0)


def test_a_wrong_call_raises_invalid_type_error_with_the_binding_message(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    with pytest.raises(covmap.InvalidTypeError, match=r"CoverageMap\.integrate\(\) missing 3 required") as e:
        cmap.integrate((1.0, 1.0, 0.0))  # type: ignore[call-arg]
    assert isinstance(e.value, TypeError)
    assert type(e.value.__cause__) is TypeError
    assert str(e.value.__cause__) == str(e.value)
    with pytest.raises(covmap.InvalidTypeError, match=r"Grid\.__new__\(\) got an unexpected keyword argument 'bogus'"):
        covmap.Grid(origin=(0, 0), resolution=0.05, shape=(2, 2), bogus=1)  # type: ignore[call-arg]
    with pytest.raises(covmap.InvalidTypeError, match=r"sweep\(\) missing 1 required positional argument: 'specs'"):
        covmap.sweep()  # type: ignore[call-arg]
    with pytest.raises(covmap.InvalidTypeError, match="cannot create 'covmap._native.Plan' instances"):
        covmap.Plan()  # type: ignore[call-arg]


def test_a_type_error_of_a_progress_callback_passes_unchanged(grid: covmap.Grid, log: covmap.Log) -> None:
    raised = TypeError("the callback's own error")

    def progress(done: int, total: int) -> None:
        raise raised

    cmap = covmap.CoverageMap(grid)
    with pytest.raises(TypeError) as e:
        cmap.integrate_log(log, covmap.LaserModel(), progress=progress)
    assert e.value is raised
    # A builtin callback called with the wrong arguments: a binding error
    # too, but not of covmap's call.
    with pytest.raises(TypeError, match=r"takes exactly one argument") as e:
        cmap.integrate_log(log, covmap.LaserModel(), progress=math.sqrt)
    assert type(e.value) is TypeError


def test_a_type_error_of_an_executor_passes_unchanged() -> None:
    raised = TypeError("the executor's own error")

    class Executor:
        def submit(self, *args: Any, **kwargs: Any) -> Any:
            raise raised

    with pytest.raises(TypeError) as e:
        covmap.sweep([{"world": "corridor", "strategy": "coverage", "max_steps": 1}], executor=Executor(), progress=False)
    assert e.value is raised


def test_covmap_errors_pass_unchanged(grid: covmap.Grid) -> None:
    with pytest.raises(covmap.InvalidTypeError, match="argument 'grid'") as e:
        covmap.CoverageMap("grid")  # type: ignore[arg-type]
    assert e.value.__cause__ is None
    with pytest.raises(covmap.ArrayDtypeError):
        covmap.CoverageMap(grid).integrate((1.0, 1.0, 0.0), np.ones(3, np.int64), np.zeros(3), covmap.LaserModel())


def _native_callables() -> list[tuple[str, Any]]:
    out = []
    for name, value in vars(native).items():
        if name.startswith("_"):
            continue
        if isinstance(value, type):
            out += [(f"{name}.{m}", getattr(value, m)) for m in vars(value) if not m.startswith("_") and callable(getattr(value, m))]
        elif callable(value):
            out.append((name, value))
    return out


@pytest.mark.parametrize(("name", "wrapped"), _native_callables(), ids=[n for n, _ in _native_callables()])
def test_a_wrapper_keeps_the_name_doc_and_signature(name: str, wrapped: Any) -> None:
    original = inspect.unwrap(wrapped)
    assert original is not wrapped, f"{name} is not wrapped"
    if isinstance(original, types.ClassMethodDescriptorType):
        original = original.__get__(None, wrapped.__self__)  # bound, as the wrapper is
    assert wrapped.__qualname__ == original.__qualname__ == name
    assert wrapped.__module__ == "covmap._native"
    assert wrapped.__doc__ == original.__doc__
    assert inspect.signature(wrapped) == inspect.signature(original)
    assert wrapped.__text_signature__ == original.__text_signature__
    # Pickled by reference, to the same object.
    assert pickle.loads(pickle.dumps(wrapped)) == wrapped


def test_methods_keep_their_signatures_bound_and_their_help(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    assert str(inspect.signature(cmap.integrate)) == "(pose, ranges, bearings, model)"
    assert str(inspect.signature(covmap.SonarModel.from_dict)) == "(d)"
    assert str(inspect.signature(covmap.World.builtin)) == "(name)"
    assert isinstance(inspect.getattr_static(covmap.World, "builtin"), staticmethod)
    assert isinstance(inspect.getattr_static(covmap.SonarModel, "from_dict"), classmethod)
    text = pydoc.render_doc(covmap.CoverageMap, renderer=pydoc.plaintext)
    assert "integrate(self, /, pose, ranges, bearings, model)" in text
    assert inspect.cleandoc(covmap.CoverageMap.integrate.__doc__ or "").splitlines()[0] in text


def test_constructors_are_as_they_were(grid: covmap.Grid) -> None:
    assert covmap.Grid.__text_signature__ == "(*, origin, resolution, shape)"
    assert str(inspect.signature(covmap.CoverageMap)) == "(grid, bins=16)"
    made = covmap.Grid.__new__(covmap.Grid, origin=(0.0, 0.0), resolution=0.05, shape=(40, 60))
    assert made == grid and isinstance(made, covmap.Grid)
    cmap = covmap.CoverageMap(grid, 4)
    for again in (pickle.loads(pickle.dumps(cmap)), copy.deepcopy(cmap)):
        assert isinstance(again, covmap.CoverageMap)
        assert np.array_equal(again.histograms, cmap.histograms)
    assert pickle.loads(pickle.dumps(covmap.Robot(radius_m=0.3))) == covmap.Robot(radius_m=0.3)


def test_the_package_functions_keep_their_signatures() -> None:
    assert list(inspect.signature(covmap.sweep).parameters) == ["specs", "executor", "progress"]
    assert list(inspect.signature(covmap.plot.plot_map).parameters)[:2] == ["values", "grid"]
    assert pickle.loads(pickle.dumps(covmap.sweep)) is covmap.sweep
    assert covmap.dask_client.__doc__ and "Dask" in covmap.dask_client.__doc__
