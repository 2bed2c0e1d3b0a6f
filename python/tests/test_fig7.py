"""The paper's Fig. 7 on the built-in corridor, as the issue expects it:
scan counting's path grows with n, and where 85 % or more of the cells must
be certain, coverage maps travel less than counting reaching the same
fraction at the run's end (which does not hold now: marked so, strictly),
and on the way, where the runs first have a fraction certain. Whole runs at
the exploration's 5 cm cells, in parallel on the local cores (about a
minute of two cores)."""

from __future__ import annotations

import pytest

from covmap.experiments import fig7

NS = (1, 5, 20)
"""Counts far enough apart that the seeds' spread does not hide their order."""

SEEDS = (0, 1, 2)


@pytest.fixture(scope="module")
def sweep() -> fig7.Fig7:
    return fig7.run("corridor", ns=NS, seeds=SEEDS, progress=False)


def figures(f: fig7.Fig7) -> str:
    """The curve and the cross, for an assertion's message."""
    points = [*f.curve, f.cross]
    return "; ".join(f"{p.label}: {p.path_m:.0f} m, {100 * p.certain:.1f} % certain" for p in points)


def test_every_run_ends_by_its_rule(sweep: fig7.Fig7) -> None:
    for run in sweep.counting + sweep.coverage:
        assert run.termination in {"certain", "stagnated", "no_goal"}, (run.strategy, run.seed, run.termination)


def test_counting_travels_farther_the_higher_its_count(sweep: fig7.Fig7) -> None:
    paths = [p.path_m for p in sweep.curve]
    assert paths == sorted(paths) and len(set(paths)) == len(paths), figures(sweep)


def test_coverage_maps_make_every_fraction_certain(sweep: fig7.Fig7) -> None:
    assert all(sweep.cross.certain >= fraction for fraction in fig7.FRACTIONS), figures(sweep)


@pytest.mark.xfail(
    strict=True,
    reason="Fig. 7's claim, read at the runs' ends, does not hold on the corridor since no-echo readings clear "
    "their line of sight (2026-12-07): the coverage runs end farther than counting travels to reach 85 % "
    "certain, having made 99 % of the cells certain early and driven the rest for the last ones (the full "
    "sweep's figures: BENCHMARKS.md, Fig. 7); strict, so that the day it holds again this fails and is put back",
)
def test_coverage_maps_travel_less_wherever_85_percent_or_more_must_be_certain(sweep: fig7.Fig7) -> None:
    cross = sweep.cross
    for fraction in fig7.FRACTIONS:
        assert cross.certain >= fraction, figures(sweep)
        counting = fig7.path_at(sweep.curve, fraction)
        # A curve that never reaches the fraction travels farther for any path.
        assert counting is None or cross.path_m < counting, (fraction, figures(sweep))
    # The reading: the counting runs that reach 85 % themselves.
    reaching = [r.path_length_m for r in sweep.counting if r.certain_fraction >= 0.85]
    assert reaching and cross.path_m < sum(reaching) / len(reaching), figures(sweep)


def test_on_the_way_coverage_maps_reach_85_percent_and_more_before_counting(sweep: fig7.Fig7) -> None:
    for fraction in fig7.FRACTIONS:
        coverage, counting = sweep.reaching(fraction)
        assert coverage is not None, (fraction, fig7.report(sweep))
        assert counting is None or coverage < counting[0], (fraction, fig7.report(sweep))


def test_a_runs_trace_ends_where_the_run_does(sweep: fig7.Fig7) -> None:
    """What ``reaching`` reads on the way is what the run reports at its end."""
    for run in sweep.counting + sweep.coverage:
        last_certain = 1.0 - float(run.trace["uncertain_fraction"][-1])
        assert abs(last_certain - run.certain_fraction) < 1e-12, (run.strategy, run.seed)
        assert float(run.trace["path_length_m"][-1]) == run.path_length_m, (run.strategy, run.seed)
