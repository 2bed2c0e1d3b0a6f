from __future__ import annotations

import copy
import math
import pickle
import threading
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest

import covmap

if TYPE_CHECKING:
    from conftest import ScanSource


@pytest.mark.parametrize("bins", [2, 16, 33, 256])
def test_prior_is_uniform_with_maximal_entropy(grid: covmap.Grid, bins: int) -> None:
    cmap = covmap.CoverageMap(grid, bins=bins)
    assert cmap.bins == bins and cmap.grid == grid
    h = cmap.histograms
    assert h.shape == (40, 60, bins) and h.dtype == np.float32
    np.testing.assert_allclose(h, 1.0 / bins)
    entropy = cmap.entropy()
    assert entropy.shape == (40, 60) and entropy.dtype == np.float32
    np.testing.assert_allclose(entropy, math.log(bins), rtol=1e-5)
    np.testing.assert_allclose(cmap.mean(), 0.5, atol=1e-5)
    np.testing.assert_array_equal(cmap.bin_values, np.arange(bins) / (bins - 1))


def test_default_bins(grid: covmap.Grid) -> None:
    assert covmap.CoverageMap(grid).bins == covmap.DEFAULT_BINS == 16


@pytest.mark.parametrize("bins", [-1, 0, 1, 257])
def test_bad_bins_raise(grid: covmap.Grid, bins: int) -> None:
    with pytest.raises(covmap.InvalidParameterError) as info:
        covmap.CoverageMap(grid, bins=bins)
    assert isinstance(info.value, ValueError)


def test_histograms_stay_normalised_and_positive(scanned_map: covmap.CoverageMap) -> None:
    h = scanned_map.histograms
    assert np.all(np.isfinite(h))
    assert np.all(h > 0.0)
    np.testing.assert_allclose(h.sum(axis=-1), 1.0, atol=1e-5)


def test_ml_mean_entropy_agree_with_the_histograms(scanned_map: covmap.CoverageMap) -> None:
    h = scanned_map.histograms.astype(np.float64)
    values = scanned_map.bin_values
    ml = scanned_map.ml()
    mean = scanned_map.mean()
    entropy = scanned_map.entropy()
    for array in (ml, mean, entropy):
        assert array.shape == scanned_map.grid.shape and array.dtype == np.float32
    np.testing.assert_array_equal(ml, values[np.argmax(h, axis=-1)].astype(np.float32))
    np.testing.assert_allclose(mean, (h * values).sum(axis=-1), atol=1e-5)
    np.testing.assert_allclose(entropy, -(h * np.log(h)).sum(axis=-1), atol=1e-4)
    assert entropy.min() >= 0.0 and entropy.max() <= math.log(scanned_map.bins) + 1e-5
    assert entropy.min() < 0.5 * math.log(scanned_map.bins), "the scans taught the map something"


def test_histogram_of_one_cell(scanned_map: covmap.CoverageMap) -> None:
    np.testing.assert_array_equal(scanned_map.histogram(12, 34), scanned_map.histograms[12, 34])
    for row, col in [(40, 0), (0, 60), (-1, 0), (0, -1)]:
        with pytest.raises(covmap.CellOutOfBoundsError) as info:
            scanned_map.histogram(row, col)
        assert isinstance(info.value, IndexError)


def test_returned_arrays_are_copies(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    h = cmap.histograms
    h[:] = 0.0
    cmap.histogram(0, 0)[:] = 0.0
    np.testing.assert_allclose(cmap.histograms, 1.0 / 16)


def test_one_laser_beam(grid: covmap.Grid) -> None:
    cmap = covmap.CoverageMap(grid)
    # From (0.5, 1.025) along +x, ending at x = 2.04 in column 40.
    updates = cmap.integrate((0.5, 1.025, 0.0), np.array([1.54]), np.array([0.0]), covmap.LaserModel())
    assert updates == 33  # columns 10..42: to the end point plus the 0.1 m band
    ml = cmap.ml()
    assert np.all(ml[20, 10:40] == 0.0), "the beam passed: empty"
    assert ml[20, 41] == 1.0, "just behind the end point: covered"
    np.testing.assert_allclose(cmap.entropy()[21], math.log(16), rtol=1e-6)  # untouched row


def test_sequences_and_strided_arrays_give_the_same_map(
    scans: ScanSource, grid: covmap.Grid, model: Any
) -> None:
    pose, ranges, bearings = next(scans(grid, 1, seed=3))
    a = covmap.CoverageMap(grid)
    a.integrate(pose, ranges, bearings, model)
    b = covmap.CoverageMap(grid)
    b.integrate(list(pose), ranges.tolist(), tuple(bearings.tolist()), model)
    c = covmap.CoverageMap(grid)
    strided_ranges = np.repeat(ranges, 2)[::2]
    strided_bearings = np.stack([bearings, bearings], axis=1)[:, 0]
    assert not strided_ranges.flags.c_contiguous and not strided_bearings.flags.c_contiguous
    c.integrate(np.array(pose), strided_ranges, strided_bearings, model)
    np.testing.assert_array_equal(a.histograms, b.histograms)
    np.testing.assert_array_equal(a.histograms, c.histograms)


def test_integration_is_deterministic(
    scans: ScanSource, grid: covmap.Grid, model: Any
) -> None:
    maps = [covmap.CoverageMap(grid) for _ in range(2)]
    for cmap in maps:
        for scan in scans(grid, 10, seed=11):
            cmap.integrate(*scan, model)
    np.testing.assert_array_equal(maps[0].histograms, maps[1].histograms)


def test_threads_update_their_own_maps(
    scans: ScanSource, grid: covmap.Grid, model: Any
) -> None:
    """The update runs with the GIL released; maps in different threads stay apart."""
    scan_list = list(scans(grid, 20, seed=5))
    expected = covmap.CoverageMap(grid)
    for scan in scan_list:
        expected.integrate(*scan, model)
    maps = [covmap.CoverageMap(grid) for _ in range(4)]

    def work(cmap: covmap.CoverageMap) -> None:
        for scan in scan_list:
            cmap.integrate(*scan, model)

    threads = [threading.Thread(target=work, args=(m,)) for m in maps]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for cmap in maps:
        np.testing.assert_array_equal(cmap.histograms, expected.histograms)


def test_from_histograms_and_pickle(scanned_map: covmap.CoverageMap) -> None:
    h = scanned_map.histograms
    rebuilt = covmap.CoverageMap.from_histograms(scanned_map.grid, h)
    assert rebuilt.bins == scanned_map.bins and rebuilt.grid == scanned_map.grid
    # Stored histograms are renormalised on the way in: equal to float32 rounding.
    np.testing.assert_allclose(rebuilt.histograms, h, atol=1e-6)
    for clone in (pickle.loads(pickle.dumps(scanned_map)), copy.deepcopy(scanned_map)):
        np.testing.assert_allclose(clone.histograms, h, atol=1e-6)
    assert "CoverageMap(Grid(" in repr(scanned_map)


def test_from_histograms_validates(grid: covmap.Grid) -> None:
    good = np.full((40, 60, 4), 0.25, dtype=np.float32)
    assert covmap.CoverageMap.from_histograms(grid, good).bins == 4
    with pytest.raises(covmap.ArrayShapeError):
        covmap.CoverageMap.from_histograms(grid, good[:, :59])
    with pytest.raises(covmap.ArrayShapeError):
        covmap.CoverageMap.from_histograms(grid, good.reshape(40 * 60, 4))
    with pytest.raises(covmap.ArrayDtypeError) as dtype_error:
        covmap.CoverageMap.from_histograms(grid, good.astype(np.float64))
    assert isinstance(dtype_error.value, TypeError)
    bad = good.copy()
    bad[3, 4, 0] = np.nan
    with pytest.raises(covmap.InvalidHistogramError) as info:
        covmap.CoverageMap.from_histograms(grid, bad)
    assert isinstance(info.value, ValueError)
    with pytest.raises(covmap.InvalidHistogramError):
        covmap.CoverageMap.from_histograms(grid, good * 2)
    with pytest.raises(covmap.InvalidParameterError):
        covmap.CoverageMap.from_histograms(grid, np.ones((40, 60, 1), dtype=np.float32))
