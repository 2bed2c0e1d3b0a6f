"""Strategies written in Python (``Strategy.custom``) and steps to goals the
caller chose (``Exploration.step(goal=...)``): they run where the built-in
strategies run, make the built-in choice when they ask for it, and every
bad answer is a typed error with the run as it was."""

from __future__ import annotations

import pickle
from typing import Any

import numpy as np
import pytest

import covmap
from test_exploration import room

SHORT: dict[str, Any] = {"resolution": 0.1, "max_steps": 4}


def planners_choice(view: covmap.StrategyView) -> Any:
    """The coverage planner's own choice, or done."""
    return view.candidates.pose


def highest_utility(view: covmap.StrategyView) -> Any:
    """The candidate of the highest utility, by its index; done when no
    candidate is worth a goal."""
    c = view.candidates.candidates
    worth = np.isfinite(c.utilities)
    if not worth.any():
        return None
    return int(np.where(worth, c.utilities, -np.inf).argmax())


def test_the_planners_choice_asked_for_is_the_coverage_strategys_first_steps() -> None:
    world = room()
    own = covmap.Exploration(world, covmap.Strategy.coverage(0.5), seed=2, **SHORT)
    custom = covmap.Exploration(world, covmap.Strategy.custom(planners_choice), seed=2, **SHORT)
    own_steps, custom_steps = list(own), list(custom)
    assert len(own_steps) == len(custom_steps) == 4
    for a, b in zip(own_steps, custom_steps):
        np.testing.assert_array_equal(a.goal, b.goal)
        np.testing.assert_array_equal(a.path, b.path)
        assert (a.scans, a.reached) == (b.scans, b.reached)
    assert custom.steps == own.steps == 4 and custom.termination == own.termination == "limit"
    np.testing.assert_array_equal(custom.map.histograms, own.map.histograms)


def test_a_custom_strategy_explores_to_its_own_end_and_pickles() -> None:
    strategy = covmap.Strategy.custom(highest_utility)
    assert isinstance(strategy, covmap.CustomStrategy) and strategy.name == "highest_utility"
    result = covmap.explore(room(), strategy, seed=0, resolution=0.1, max_steps=200)
    assert result.strategy == strategy
    assert result.termination in ("certain", "stagnated", "no_goal")
    assert result.steps > 1 and result.high_entropy_fraction < 0.5
    again = pickle.loads(pickle.dumps(result))
    assert again.strategy == strategy and again.path_length_m == result.path_length_m
    assert "highest_utility" in repr(result)


def test_the_view_shows_what_the_strategies_see() -> None:
    seen: list[covmap.StrategyView] = []

    def look(view: covmap.StrategyView) -> Any:
        seen.append(view)
        return None

    run = covmap.Exploration(room(), covmap.Strategy.custom(look, name="look"), seed=0, resolution=0.1)
    assert run.step() is None and run.termination in ("no_goal", "certain", "stagnated")
    (view,) = seen
    assert view.steps == 0 and view.scans >= 1 and view.path_length_m == 0.0
    assert view.map.grid.shape == view.region.shape == view.grid.shape
    assert view.region.dtype == np.bool_ and view.region.any()
    assert view.rule in (None, "certain", "stagnated")
    c = view.candidates.candidates
    assert len(c) > 0 and c.poses.shape == (len(c), 3) and (c.gains >= 0).all() and (c.costs >= 0).all()
    path = view.path_to(view.candidates.pose)
    assert path is not None and path.shape[1] == 2
    assert view.path_to((1e6, 0.0, 0.0)) is None
    assert "step 0" in repr(view)


def test_a_step_to_a_goal_of_the_callers_own() -> None:
    run = covmap.Exploration(room(), covmap.Strategy.frontier(), seed=0, resolution=0.1)
    run.step()  # the first scans, a frontier step
    goal = run.viewpoints().pose
    step = run.step(goal=goal)
    assert step is not None and step.reached
    np.testing.assert_allclose(run.pose[:2], goal[:2], atol=1e-9)
    assert run.strategy == covmap.Strategy.frontier()
    assert run.finish() in ("certain", "stagnated", "no_goal") and run.done
    assert run.step(goal=goal) is None


def _state(run: covmap.Exploration) -> tuple[Any, ...]:
    return (run.steps, run.scans, tuple(run.pose), run.path_length_m, run.map.histograms.tobytes())


@pytest.mark.parametrize(
    ("answer", "error", "says"),
    [
        ((1e6, 1e6, 0.0), covmap.InvalidGoalError, "outside the map"),
        ((float("nan"), 1.0, 0.0), covmap.InvalidGoalError, "finite"),
        ((0.05, 0.05, 0.0), covmap.InvalidGoalError, "cannot reach"),
        ((1.0, 2.0, 3.0, 4.0), covmap.InvalidGoalError, "shape"),
        (10**6, covmap.InvalidGoalError, "candidate 1000000"),
        (-1, covmap.InvalidGoalError, "candidate -1"),
        ("north", covmap.InvalidTypeError, "str"),
        (True, covmap.InvalidTypeError, "bool"),
        (1.5, covmap.InvalidTypeError, "float"),
        ({"x": 1}, covmap.InvalidTypeError, "pose of numbers"),
    ],
)
def test_a_bad_answer_is_a_typed_error_and_the_run_as_it_was(answer: Any, error: type, says: str) -> None:
    answers = iter([None, answer])

    def first_good_then(view: covmap.StrategyView) -> Any:
        given = next(answers)
        return view.candidates.pose if given is None else given

    run = covmap.Exploration(room(), covmap.Strategy.custom(first_good_then), seed=0, resolution=0.1)
    assert run.step() is not None
    before = _state(run)
    with pytest.raises(error, match=says):
        run.step()
    assert _state(run) == before and not run.done


def test_a_bad_goal_given_to_a_step_is_a_typed_error_and_the_run_as_it_was() -> None:
    run = covmap.Exploration(room(), covmap.Strategy.coverage(), seed=0, resolution=0.1)
    run.step()
    before = _state(run)
    for goal, error in [
        ((1e6, 0.0, 0.0), covmap.InvalidGoalError),
        ((0.05, 0.05, 0.0), covmap.InvalidGoalError),
        ((1.0, 2.0), covmap.ArrayShapeError),
        ("here", covmap.ArrayDtypeError),
    ]:
        with pytest.raises(error):
            run.step(goal=goal)
        assert _state(run) == before


def test_an_error_of_the_strategys_own_passes_unchanged() -> None:
    raised = RuntimeError("the policy's own error")

    def broken(view: covmap.StrategyView) -> Any:
        raise raised

    run = covmap.Exploration(room(), covmap.Strategy.custom(broken), seed=0, resolution=0.1)
    with pytest.raises(RuntimeError) as e:
        run.step()
    assert e.value is raised
    assert run.steps == 0 and not run.done
    with pytest.raises(RuntimeError):
        covmap.explore(room(), covmap.Strategy.custom(broken), seed=0, resolution=0.1)


def test_the_loop_does_not_choose_for_a_strategy_it_cannot_call() -> None:
    with pytest.raises(covmap.InvalidTypeError, match="choose must be a function"):
        covmap.Strategy.custom(42)  # type: ignore[arg-type]
    with pytest.raises(covmap.InvalidParameterError, match="alpha"):
        covmap.Strategy.custom(highest_utility, alpha=2.0)
    with pytest.raises(covmap.InvalidParameterError, match="name"):
        covmap.Strategy.custom(highest_utility, name="")
    with pytest.raises(covmap.InvalidTypeError, match="Strategy.custom"):
        covmap.explore(room(), highest_utility)  # type: ignore[arg-type]


def test_a_custom_strategy_runs_in_a_sweep_beside_the_built_in_ones() -> None:
    world = room()
    strategy = covmap.Strategy.custom(highest_utility)
    specs = [
        {"world": world, "strategy": strategy, "seed": 1, **SHORT},
        {"world": world, "strategy": "frontier", "seed": 1, **SHORT},
    ]
    summaries = covmap.sweep(specs, progress=False)
    direct = covmap.explore(world, strategy, seed=1, **SHORT)
    assert summaries[0].strategy == strategy
    assert (summaries[0].path_length_m, summaries[0].scans) == (direct.path_length_m, direct.scans)
    assert pickle.loads(pickle.dumps(summaries[0])) == summaries[0]


def test_a_custom_strategy_that_does_not_pickle_is_refused_by_a_sweep() -> None:
    strategy = covmap.Strategy.custom(lambda view: None, name="inline")
    with pytest.raises(covmap.InvalidSpecError, match="does not pickle"):
        covmap.sweep([{"world": room(), "strategy": strategy, **SHORT}], progress=False)


def test_a_custom_strategy_runs_in_the_benchmark_beside_the_built_in_ones() -> None:
    from covmap.experiments import benchmark

    building = covmap.buildings.building("generated:1:60")
    strategy = covmap.Strategy.custom(highest_utility)
    bench = benchmark.run([building], strategies=[strategy, "frontier"], progress=False, **SHORT)
    assert [r.strategy for r in bench.runs] == ["custom:highest_utility", "frontier"]
    assert [s.strategy for s in bench.summaries()] == ["frontier", "custom:highest_utility"]
    direct = covmap.explore(building.world, strategy, seed=0, **SHORT)
    assert bench.runs[0].path_length_m == direct.path_length_m
    assert benchmark.strategy_of(covmap.Strategy.coverage(0.5)) == ("coverage", covmap.Strategy.coverage(0.5))
    with pytest.raises(covmap.InvalidParameterError, match="got int"):
        benchmark.strategy_of(3)  # type: ignore[arg-type]
