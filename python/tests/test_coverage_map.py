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
    # Without a history, none is saved and none comes back; the evidence
    # behind the histograms (log-likelihoods, each cell's largest 0) is saved.
    assert not scanned_map.tracks_history
    _, args, state = scanned_map.__reduce__()
    history, evidence = state
    assert history is None
    assert evidence.dtype == np.float32 and evidence.shape == h.shape
    assert (evidence <= 0).all() and (evidence.max(axis=-1) == 0).all()
    assert args[0] == scanned_map.grid
    for clone in (pickle.loads(pickle.dumps(scanned_map)), copy.deepcopy(scanned_map)):
        np.testing.assert_array_equal(clone.histograms, h)
        assert not clone.tracks_history
        assert not clone.measurements().any()
    assert "CoverageMap(Grid(" in repr(scanned_map)


def settled_map(grid: covmap.Grid, model: Any, scans: ScanSource) -> covmap.CoverageMap:
    """A map with its entropy history: random scans, then the same scan
    repeated until the cells it reaches stagnate."""
    cmap = covmap.CoverageMap(grid)
    cmap.track_history(True)
    for pose, ranges, bearings in scans(grid, 10, seed=3):
        cmap.integrate(pose, ranges, bearings, model)
    pose, ranges, bearings = next(scans(grid, 1, seed=4, beams=90))
    for _ in range(25):
        cmap.integrate(pose, ranges, bearings, model)
    return cmap


def saved_history(cmap: covmap.CoverageMap) -> tuple[Any, Any]:
    """The (entropies, counts) history `__reduce__` saves for a tracked map."""
    history, _ = saved_state(cmap)
    assert history is not None
    entropies, counts = history
    return entropies, counts


def saved_state(cmap: covmap.CoverageMap) -> tuple[Any, Any]:
    """The (history, evidence) state `__reduce__` saves."""
    _, _, state = cmap.__reduce__()
    history, evidence = state
    return history, evidence


def test_pickle_and_copy_keep_the_entropy_history(
    grid: covmap.Grid, model: Any, scans: ScanSource
) -> None:
    cmap = settled_map(grid, model, scans)
    stagnated, measurements = cmap.stagnated(), cmap.measurements()
    assert stagnated.any() and not stagnated.all()
    assert measurements.max() > covmap.STAGNATION_MEASUREMENTS + 1
    clones = [pickle.loads(pickle.dumps(cmap)), copy.deepcopy(cmap), copy.copy(cmap)]
    for clone in clones:
        assert clone.tracks_history
        np.testing.assert_array_equal(clone.histograms, cmap.histograms)
        np.testing.assert_array_equal(clone.measurements(), measurements)
        np.testing.assert_array_equal(clone.stagnated(), stagnated)
    # Each copy's history goes on as the original's does.
    for pose, ranges, bearings in scans(grid, 5, seed=5):
        for m in (cmap, *clones):
            m.integrate(pose, ranges, bearings, model)
    assert cmap.measurements().sum() > measurements.sum()
    for clone in clones:
        np.testing.assert_array_equal(clone.histograms, cmap.histograms)
        np.testing.assert_array_equal(clone.measurements(), cmap.measurements())
        np.testing.assert_array_equal(clone.stagnated(), cmap.stagnated())


def test_reduce_saves_the_history_as_arrays(
    grid: covmap.Grid, model: Any, scans: ScanSource
) -> None:
    cmap = settled_map(grid, model, scans)
    entropies, counts = saved_history(cmap)
    assert entropies.dtype == np.float32
    assert entropies.shape == (*grid.shape, covmap.STAGNATION_MEASUREMENTS + 1)
    assert counts.dtype == np.uint32
    np.testing.assert_array_equal(counts, cmap.measurements())
    assert np.isfinite(entropies).all() and (entropies >= 0).all()
    assert entropies.max() <= math.log(cmap.bins) + 1e-6


def test_setstate_rejects_bad_state_and_leaves_the_map_unchanged(
    grid: covmap.Grid, model: Any, scans: ScanSource
) -> None:
    tracked = settled_map(grid, model, scans)
    entropies, counts = saved_history(tracked)
    nan = entropies.copy()
    nan[3, 4, 1] = np.nan
    negative = entropies.copy()
    negative[3, 4, 1] = -1.0
    bad: list[tuple[Any, type[Exception]]] = [
        ((entropies[:, :-1], counts), covmap.ArrayShapeError),
        ((entropies[..., :-1], counts), covmap.ArrayShapeError),
        ((entropies, counts[:-1]), covmap.ArrayShapeError),
        ((entropies.reshape(-1), counts), covmap.ArrayShapeError),
        ((entropies, counts[..., None]), covmap.ArrayShapeError),
        ((entropies.astype(np.float64), counts), covmap.ArrayDtypeError),
        ((entropies, counts.astype(np.int64)), covmap.ArrayDtypeError),
        ((entropies.tolist(), counts), covmap.ArrayDtypeError),
        ((nan, counts), covmap.InvalidHistoryError),
        ((negative, counts), covmap.InvalidHistoryError),
        ((entropies,), TypeError),
        ((entropies, counts, counts), TypeError),
        ([entropies, counts], TypeError),
    ]
    for cmap in (tracked, covmap.CoverageMap(grid)):
        histograms, measurements, stagnated = cmap.histograms, cmap.measurements(), cmap.stagnated()
        tracks = cmap.tracks_history
        for bad_state, error in bad:
            with pytest.raises(error):
                cmap.__setstate__(bad_state)
            assert cmap.tracks_history == tracks
            np.testing.assert_array_equal(cmap.histograms, histograms)
            np.testing.assert_array_equal(cmap.measurements(), measurements)
            np.testing.assert_array_equal(cmap.stagnated(), stagnated)
        cmap.__setstate__(None)
        assert cmap.tracks_history == tracks
    # The evidence: of the map's shape and dtype, finite, and giving the map's
    # histograms; with a history, neither is restored unless both are good.
    _, evidence = saved_state(tracked)
    nan_evidence = evidence.copy()
    nan_evidence[3, 4, 1] = np.nan
    other = covmap.CoverageMap(grid)
    _, other_evidence = saved_state(other)
    bad_evidence: list[tuple[Any, type[Exception]]] = [
        ((None, evidence[:, :-1]), covmap.ArrayShapeError),
        ((None, evidence.astype(np.float64)), covmap.ArrayDtypeError),
        ((None, nan_evidence), covmap.InvalidHistogramError),
        ((None, other_evidence), covmap.InvalidHistogramError),
        (((entropies, counts), other_evidence), covmap.InvalidHistogramError),
        (((nan, counts), evidence), covmap.InvalidHistoryError),
    ]
    untracked = covmap.CoverageMap.from_histograms(grid, tracked.histograms)
    for cmap in (tracked, untracked):
        histograms, measurements, tracks = cmap.histograms, cmap.measurements(), cmap.tracks_history
        for bad_state, error in bad_evidence:
            with pytest.raises(error):
                cmap.__setstate__(bad_state)
            assert cmap.tracks_history == tracks
            np.testing.assert_array_equal(cmap.histograms, histograms)
            np.testing.assert_array_equal(cmap.measurements(), measurements)
    # Refused, the state changed nothing: the map goes on as one rebuilt
    # from its histograms alone, not as the original.
    copy_alone = covmap.CoverageMap.from_histograms(grid, tracked.histograms)
    restored = copy.deepcopy(tracked)
    pose, ranges, bearings = next(scans(grid, 1, seed=4, beams=90))
    for m in (untracked, copy_alone, restored, tracked):
        for _ in range(30):
            m.integrate(pose, ranges, bearings, model)
    np.testing.assert_array_equal(untracked.histograms, copy_alone.histograms)
    np.testing.assert_array_equal(restored.histograms, tracked.histograms)
    # The typed errors are also the builtins callers catch.
    with pytest.raises(ValueError, match=r"history entropies must have shape"):
        tracked.__setstate__((entropies[:, :-1], counts))
    with pytest.raises(ValueError, match=r"invalid entropy history at cell 184"):
        tracked.__setstate__((nan, counts))
    with pytest.raises(TypeError, match=r"got a tuple of length 1"):
        tracked.__setstate__((entropies,))  # type: ignore[arg-type]


def test_setstate_restores_onto_a_map_without_history(
    grid: covmap.Grid, model: Any, scans: ScanSource
) -> None:
    source = settled_map(grid, model, scans)
    target = covmap.CoverageMap.from_histograms(grid, source.histograms)
    assert not target.tracks_history
    target.__setstate__(saved_history(source))
    assert target.tracks_history
    np.testing.assert_array_equal(target.measurements(), source.measurements())
    np.testing.assert_array_equal(target.stagnated(), source.stagnated())


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


def test_integrate_log_can_occlude_no_echo_readings_by_the_map() -> None:
    """With ``occlude_no_echo`` a no-echo reading stops at the wall the map
    holds covered and is certain of, and leaves what lies behind it as it
    was; a cell held covered but uncertain does not stop it."""
    grid = covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(10, 60))
    laser = covmap.LaserModel(max_range_m=5.0)
    poses = np.array([[0.05, 0.55, 0.0]] * 6)
    ranges = np.array([[2.0]] * 5 + [[5.0]])  # five echoes from a wall at 2 m, then a miss
    log = covmap.Log(poses, ranges, np.zeros(1), max_range_m=5.0)
    maps = {}
    for occlude in (False, True):
        m = covmap.CoverageMap(grid)
        m.integrate_log(log[:5], laser)
        m.integrate_log(log[5:], laser, occlude_no_echo=occlude)
        maps[occlude] = m.mean()
    walls = covmap.CoverageMap(grid)
    walls.integrate_log(log[:5], laser)
    behind = (5, slice(30, 50))  # the cells 3 to 5 m out: behind the wall's band
    assert np.array_equal(maps[True][behind], walls.mean()[behind])
    assert (maps[False][behind] < walls.mean()[behind]).all()
    # The face cell (the echoes' range on its edge: half covered, uncertain)
    # does not occlude, the certain cell behind it does.
    face, wall = walls.entropy()[5, 20], walls.entropy()[5, 21]
    assert face > 0.65 >= wall and walls.mean()[5, 21] > 0.5
    assert maps[True][5, 20] == pytest.approx(maps[False][5, 20], abs=1e-6)
    assert maps[True][5, 20] < walls.mean()[5, 20]
    assert maps[True][5, 22] == walls.mean()[5, 22] > maps[False][5, 22]
    # Occlusion changes nothing where no echo has marked the map yet.
    first = covmap.CoverageMap(grid)
    first.integrate_log(log[5:], laser, occlude_no_echo=True)
    plain = covmap.CoverageMap(grid)
    plain.integrate_log(log[5:], laser)
    assert np.array_equal(first.histograms, plain.histograms)
    # Within one log the echoes go in first: the miss is occluded by the
    # wall whether it came after the echoes or before them.
    after, before = covmap.CoverageMap(grid), covmap.CoverageMap(grid)
    after.integrate_log(log, laser, occlude_no_echo=True)
    before.integrate_log(covmap.Log(poses, ranges[::-1].copy(), np.zeros(1), max_range_m=5.0), laser, occlude_no_echo=True)
    np.testing.assert_allclose(after.histograms, before.histograms, atol=1e-6)
    assert np.array_equal(after.mean()[behind], walls.mean()[behind])
