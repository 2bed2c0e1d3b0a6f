"""How calls bind their arguments: a call that does not bind to the
signature, and an object argument of the wrong class, raise Python's own
``TypeError``, as numpy's and polars' calls do; a number covmap cannot
take raises covmap's error naming the argument, quoting the value and
stating the range the argument really takes. The corpus
(bad_input/corpus.py, ``arity_cases``) calls every public callable with
arguments that do not bind; these are the rest."""

from __future__ import annotations

import inspect
import math
import pickle
from typing import Any

import numpy as np
import pytest

import covmap
import covmap._native as native
from wrong_type import converted_argument


@pytest.fixture
def log() -> covmap.Log:
    poses = np.array([[1.0, 1.0, 0.0], [1.2, 1.0, 0.1]])
    return covmap.Log(poses, np.ones((2, 3)), np.array([0.0, 1.0, 2.0]), max_range_m=5.0)


def test_a_call_that_does_not_bind_raises_pythons_type_error(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    with pytest.raises(TypeError, match=r"CoverageMap\.integrate\(\) missing 3 required") as e:
        cmap.integrate((1.0, 1.0, 0.0))  # type: ignore[call-arg]
    assert type(e.value) is TypeError
    with pytest.raises(TypeError, match=r"Grid\.__new__\(\) got an unexpected keyword argument 'bogus'"):
        covmap.Grid(origin=(0, 0), resolution=0.05, shape=(2, 2), bogus=1)  # type: ignore[call-arg]
    with pytest.raises(TypeError, match=r"sweep\(\) missing 1 required positional argument: 'specs'"):
        covmap.sweep()  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="cannot create 'covmap._native.Plan' instances"):
        covmap.Plan()  # type: ignore[call-arg]


@pytest.mark.parametrize(
    ("call", "cls", "argument", "said"),
    [
        (lambda: covmap.Strategy.counting(n=2**64), covmap.IntegerOverflowError, "n", "18446744073709551616 is out of range: expected an integer from 1 to 2**32 - 1"),
        (lambda: covmap.Strategy.counting(n=0), covmap.InvalidParameterError, "n", "0 is out of range: expected an integer from 1 to 2**32 - 1"),
        (lambda: covmap.Strategy.counting(n=3.0), covmap.InvalidTypeError, "n", "expected an integer from 1 to 2**32 - 1, got float 3.0"),
        (lambda: covmap.explore(covmap.World.builtin("partial"), covmap.Strategy.frontier(), max_steps=True), covmap.InvalidTypeError, "max_steps", "got bool True"),
        (lambda: covmap.CoverageMap(covmap.Grid(origin=(0, 0), resolution=0.1, shape=(2, 2)), bins=300), covmap.InvalidParameterError, "bins", "300 is out of range: expected an integer from 2 to 256"),
        (lambda: covmap.SonarRing(rays_per_cone=5000), covmap.InvalidParameterError, "rays_per_cone", "expected an integer from 1 to 4096"),
        (lambda: covmap.Laser(beams=1), covmap.InvalidParameterError, "beams", "expected an integer from 2 to 2**16"),
        (lambda: covmap.SonarRing.ring(0), covmap.InvalidParameterError, "count", "expected an integer from 1 to 2**16"),
        (lambda: covmap.LaserModel(max_range_m=True), covmap.InvalidTypeError, "max_range_m", "got the bool True"),
        (lambda: covmap.Robot(radius_m=10**400), covmap.IntegerOverflowError, "radius_m", "expected a float64"),
        (lambda: covmap.Laser().simulate(covmap.World.builtin("partial"), (1.0, 1.0, 0.0), seed=-1), covmap.InvalidParameterError, "seed", "-1 is out of range: expected an integer from 0 to 2**64 - 1"),
    ],
)
def test_a_number_covmap_cannot_take_names_the_argument_and_the_real_range(
    call: Any, cls: type[Exception], argument: str, said: str
) -> None:
    with pytest.raises(cls) as e:
        call()
    assert str(e.value).startswith(f"argument '{argument}': ") and said in str(e.value)


def test_an_object_of_the_wrong_class_raises_pythons_type_error(grid: covmap.Grid) -> None:
    for call, argument in (
        (lambda: covmap.CoverageMap("grid"), "grid"),  # type: ignore[arg-type]
        (lambda: covmap.CoverageMap(grid).track_history("yes"), "on"),  # type: ignore[arg-type]
        (lambda: covmap.CoverageMap(grid).save(3), "path"),  # type: ignore[arg-type]
        (lambda: covmap.World.builtin(3), "name"),  # type: ignore[arg-type]
    ):
        with pytest.raises(TypeError) as e:
            call()
        assert converted_argument(e.value) == argument, e.value


def test_a_type_error_of_a_progress_callback_passes_unchanged(grid: covmap.Grid, log: covmap.Log) -> None:
    raised = TypeError("the callback's own error")

    def progress(done: int, total: int) -> None:
        raise raised

    cmap = covmap.CoverageMap(grid)
    with pytest.raises(TypeError) as e:
        cmap.integrate_log(log, covmap.LaserModel(), progress=progress)
    assert e.value is raised
    with pytest.raises(TypeError, match=r"takes exactly one argument") as e:
        cmap.integrate_log(log, covmap.LaserModel(), progress=math.sqrt)
    assert type(e.value) is TypeError


def test_covmap_errors_of_values_pass_unchanged(grid: covmap.Grid) -> None:
    with pytest.raises(covmap.ArrayDtypeError):
        covmap.CoverageMap(grid).integrate((1.0, 1.0, 0.0), np.ones(3, np.int64), np.zeros(3), covmap.LaserModel())


def _native_callables() -> list[tuple[str, Any]]:
    out = []
    for name, value in vars(native).items():
        if name.startswith("_"):
            continue
        if isinstance(value, type):
            out.append((name, value))
            out += [(f"{name}.{m}", getattr(value, m)) for m in vars(value) if not m.startswith("_") and callable(getattr(value, m))]
        elif callable(value):
            out.append((name, value))
    return out


@pytest.mark.parametrize(("name", "value"), _native_callables(), ids=[n for n, _ in _native_callables()])
def test_native_signatures_show_their_defaults(name: str, value: Any) -> None:
    """A default Python cannot show is written ``...``: every native
    callable's text signature spells its defaults out."""
    text = getattr(value, "__text_signature__", None)
    assert text is None or "..." not in text, f"{name}{text}"


def test_signatures_and_pickling_are_the_natives(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    assert str(inspect.signature(cmap.integrate)) == "(pose, ranges, bearings, model)"
    assert str(inspect.signature(covmap.CoverageMap)) == "(grid, bins=16)"
    assert str(inspect.signature(covmap.Strategy.counting)) == "(n=50, discount_beyond_m=None)"
    assert covmap.Grid.__text_signature__ == "(*, origin, resolution, shape)"
    assert pickle.loads(pickle.dumps(covmap.Robot(radius_m=0.3))) == covmap.Robot(radius_m=0.3)
    assert pickle.loads(pickle.dumps(covmap.sweep)) is covmap.sweep
