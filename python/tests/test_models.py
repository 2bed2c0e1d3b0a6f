from __future__ import annotations

import math
import pickle
from typing import Any

import numpy as np
import pytest

import covmap

SONAR_PARAMETERS = [
    "max_range_m",
    "band_m",
    "sigma_min",
    "sigma_per_m",
    "sigma_end",
    "xi_min",
    "xi_per_m",
    "end_weight",
    "opening_angle_rad",
]


def test_defaults_come_from_the_core() -> None:
    sonar = covmap.SonarModel()
    assert sonar.max_range_m == 5.0
    assert sonar.band_m == pytest.approx(0.2)
    assert sonar.opening_angle_rad == pytest.approx(math.radians(15.0))
    laser = covmap.LaserModel()
    assert laser.max_range_m == 30.0
    assert not hasattr(laser, "opening_angle_rad")
    assert list(sonar.to_dict()) == SONAR_PARAMETERS
    assert list(laser.to_dict()) == SONAR_PARAMETERS[:-1]


def test_one_override_keeps_the_other_defaults() -> None:
    default = covmap.SonarModel()
    narrow = covmap.SonarModel(opening_angle_rad=0.1)
    assert narrow.opening_angle_rad == 0.1
    assert narrow != default
    assert {k: v for k, v in narrow.to_dict().items() if k != "opening_angle_rad"} == {
        k: v for k, v in default.to_dict().items() if k != "opening_angle_rad"
    }


@pytest.mark.parametrize(
    "kwargs",
    [
        {"max_range_m": 0.0},
        {"max_range_m": math.nan},
        {"max_range_m": 1e300},
        {"band_m": -0.1},
        {"sigma_min": 0.0},
        {"sigma_per_m": -1.0},
        {"sigma_end": 0.01},
        {"xi_min": 0.0},
        {"xi_per_m": math.inf},
        {"end_weight": 1.5},
        {"end_weight": math.nan},
        {"opening_angle_rad": 0.0},
        {"opening_angle_rad": math.pi},
    ],
)
def test_invalid_parameters_raise(kwargs: dict[str, float]) -> None:
    with pytest.raises(covmap.InvalidParameterError) as info:
        covmap.SonarModel(**kwargs)
    assert isinstance(info.value, ValueError)
    # The message starts with the parameter at fault.
    assert str(info.value).startswith(f"invalid parameter `{next(iter(kwargs))}`"), info.value
    if "opening_angle_rad" not in kwargs:
        with pytest.raises(covmap.InvalidParameterError):
            covmap.LaserModel(**kwargs)


def test_unknown_parameter_is_a_type_error() -> None:
    with pytest.raises(TypeError):
        covmap.LaserModel(opening_angle_rad=0.2)  # type: ignore[call-arg]
    with pytest.raises(TypeError):
        covmap.SonarModel(5.0)  # type: ignore[call-arg]


@pytest.mark.parametrize("cls", [covmap.SonarModel, covmap.LaserModel])
def test_dict_repr_pickle_round_trips(cls: Any) -> None:
    m = cls(sigma_min=0.07, xi_per_m=0.01)
    assert cls.from_dict(m.to_dict()) == m
    assert eval(repr(m), {cls.__name__: cls}) == m
    assert pickle.loads(pickle.dumps(m)) == m
    assert hash(cls(sigma_min=0.07, xi_per_m=0.01)) == hash(m)
    assert m != cls()
    with pytest.raises(TypeError):
        cls.from_dict({"no_such_parameter": 1.0})


@pytest.mark.parametrize("cls", [covmap.SonarModel, covmap.LaserModel])
@pytest.mark.parametrize(
    ("removed", "off"),
    [("posterior_floor", 0.0), ("end_attribution", 0.0), ("free_yield", 0.0), ("no_echo_reach", 1.0),
     ("no_echo_weight", 1.0)],
)
def test_a_removed_parameter_is_read_only_at_its_off_value(cls: Any, removed: str, off: float) -> None:
    """A dict stored before the parameter's removal names it at its default
    then (its off value): ignored. Any other value describes a model covmap
    no longer builds; and the parameter is no keyword any more."""
    stored = {**cls().to_dict(), removed: off}
    assert cls.from_dict(stored) == cls()
    with pytest.raises(covmap.InvalidParameterError, match=f"`{removed}`.*removed"):
        cls.from_dict({**stored, removed: 0.5})
    with pytest.raises(TypeError):
        cls(**{removed: off})
    assert removed not in cls.PARAMETERS


def test_kernel_shape_sum_and_meaning(model: Any) -> None:
    k = model.kernel(1.0, 2.0)
    assert k is not None
    assert k.shape == (16,) and k.dtype == np.float32
    assert float(k.sum()) == pytest.approx(1.0, abs=1e-5)
    assert np.all(k > 0)
    assert k[0] > k[-1], "the beam passed through: empty is likelier"
    behind = model.kernel(2.0 + 1.5 * 0.05, 2.0)
    assert behind is not None and behind[-1] > behind[0], "just behind the end point: covered"
    assert model.kernel(2.0 + model.band_m + 0.06, 2.0) is None, "beyond the band: not updated"
    small = model.kernel(1.0, 2.0, resolution=0.1, bins=8)
    assert small is not None and small.shape == (8,)


def test_kernel_end_cell_peaks_at_the_covered_fraction() -> None:
    # The beam ends 0.3 cells past the centre: the far 20 % of the cell is covered.
    k = covmap.LaserModel().kernel(2.0, 2.0 + 0.3 * 0.05)
    assert k is not None
    assert int(np.argmax(k)) == 3  # bin value 3/15 = 0.2


def test_kernel_rejects_bad_bins_and_resolution(model: Any) -> None:
    for bins in (1, 257, -4):
        with pytest.raises(covmap.InvalidParameterError):
            model.kernel(1.0, 2.0, bins=bins)
    with pytest.raises(covmap.InvalidParameterError):
        model.kernel(1.0, 2.0, resolution=0.0)
    for d_l, d in ((float("nan"), 2.0), (1.0, float("nan")), (-0.1, 2.0), (1.0, float("inf"))):
        with pytest.raises(covmap.InvalidParameterError):
            model.kernel(d_l, d)
