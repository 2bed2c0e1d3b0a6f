"""The Gymnasium environment (``covmap.gym``, the ``gym`` extra): it passes
Gymnasium's checker, its reward makes eq. 14 greedy, its episodes end by the
paper's rule or a limit, identical seeds give identical episodes in a
vectorised environment, and bad actions are typed errors with the episode
as it was."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import covmap
from extras import need_extra
from test_exploration import room


gymnasium = need_extra("gymnasium", "gym", "the environment's tests")
cgym = pytest.importorskip("covmap.gym")

#: A small world and short episodes: the environment's machinery, not its figures.
ROOM = room()
SHORT: dict[str, Any] = {"max_steps": 6, "size": 16}


def test_make_by_id_and_check_env() -> None:
    from gymnasium.utils.env_checker import check_env

    for action in ("lattice", "goal"):
        # The checker samples the whole action space: masked actions stay.
        env = gymnasium.make(cgym.ENV_ID, world=ROOM, action=action, masked="stay", **SHORT)
        check_env(env.unwrapped, skip_render_check=True)
        obs, info = env.reset(seed=3)
        assert env.observation_space.contains(obs)
        assert set(obs) == {"entropy", "coverage", "observed", "robot", "pose"}
        assert obs["robot"].sum() == 1.0 and obs["observed"].max() > 0
        env.close()
    # The module path form imports covmap.gym on the way.
    env = gymnasium.make("covmap.gym:covmap/Explore-v0", world=ROOM, **SHORT)
    assert isinstance(env.unwrapped, cgym.ExploreEnv)


def test_the_reward_is_entropy_removed_less_travel_and_eq14_is_its_greedy_choice() -> None:
    env = cgym.ExploreEnv(ROOM, action="goal", alpha=0.5, **SHORT)
    obs, info = env.reset(seed=0)
    run = env._run
    plan = run.viewpoints(0.5)
    c = plan.candidates
    worth = np.isfinite(c.utilities)
    lam = info["lam"]
    assert lam == pytest.approx(c.gains[worth].max() / c.costs[worth].max())
    # Eq. 14's utility orders the candidates as the expected reward does.
    expected = c.gains[worth] - lam * c.costs[worth]
    assert int(np.argmax(expected)) == int(np.argmax(c.utilities[worth]))
    before = float(run.map.entropy().astype(np.float64).sum())
    path_before = run.path_length_m
    obs, reward, terminated, truncated, info2 = env.step(info["paper_action"])
    after = float(run.map.entropy().astype(np.float64).sum())
    driven = run.path_length_m - path_before
    assert info2["entropy_removed"] == pytest.approx(before - after)
    assert reward == pytest.approx((before - after) - lam * driven)
    assert driven > 0 and before > after
    # The paper's action is the planner's choice (the coverage strategy's
    # goal, test_custom_strategy.py), as a fraction of the square.
    x0, y0, side = env._square()
    np.testing.assert_allclose(
        np.asarray(info["paper_action"], np.float64) * side + (x0, y0), plan.pose[:2], atol=1e-5 * side
    )


def test_an_episode_ends_by_the_rule_or_a_limit() -> None:
    # Eq. 14's goals, exactly: the goal actions.
    env = cgym.ExploreEnv(ROOM, action="goal", max_steps=300, size=16)
    result = cgym.episode(env, cgym.PaperPolicy(), seed=1)
    assert result["termination"] in ("certain", "stagnated", "no_goal")
    assert result["uncertain_share"] < 0.2 and result["steps"] > 1
    own = covmap.explore(ROOM, covmap.Strategy.coverage(0.5), seed=1, resolution=0.1)
    assert result["uncertain_share"] < own.high_entropy_fraction + 0.05
    short = cgym.episode(cgym.ExploreEnv(ROOM, max_steps=2, size=16), cgym.RandomPolicy(seed=0), seed=1)
    assert short["termination"] == "limit" and short["steps"] == 2


def test_identical_seeds_give_identical_episodes_in_a_vector_env() -> None:
    import functools

    make = functools.partial(cgym.ExploreEnv, ROOM, **SHORT)

    def rollout(vec: Any) -> list[Any]:
        obs, info = vec.reset(seed=[5, 5])
        policy = cgym.RandomPolicy(seed=2)
        out = []
        for _ in range(4):
            # Both copies take the same action: the first one's choice.
            a = policy(None, {"action_mask": info["action_mask"][0]})
            obs, reward, terminated, truncated, info = vec.step(np.array([a, a]))
            out.append((reward.tolist(), obs["entropy"].tobytes(), terminated.tolist(), truncated.tolist()))
        return out

    # Spawned, not forked: covmap's worker threads do not survive a fork.
    vec = gymnasium.vector.AsyncVectorEnv([make, make], context="spawn")
    try:
        first = rollout(vec)
        second = rollout(vec)
    finally:
        vec.close()
    assert first == second
    for reward, entropy, _, _ in first:
        assert reward[0] == reward[1]


def test_a_drawn_building_comes_from_the_split() -> None:
    env = cgym.ExploreEnv(area_m2=60.0, **SHORT)
    obs, info = env.reset(seed=4)
    again, _ = cgym.ExploreEnv(area_m2=60.0, **SHORT).reset(seed=4)
    for k in obs:
        np.testing.assert_array_equal(obs[k], again[k])
    other, _ = env.reset(seed=5)
    assert not np.array_equal(obs["observed"], other["observed"])


def _state(env: Any) -> tuple[Any, ...]:
    run = env._run
    return (run.steps, run.scans, tuple(run.pose), run.map.histograms.tobytes())


@pytest.mark.parametrize("action", [-1, 24, 10**30, 1.5, "north", True, None])
def test_a_bad_lattice_action_is_a_typed_error_and_the_episode_as_it_was(action: Any) -> None:
    env = cgym.ExploreEnv(ROOM, **SHORT)
    env.reset(seed=0)
    before = _state(env)
    with pytest.raises(covmap.InvalidActionError):
        env.step(action)
    assert _state(env) == before


def test_a_masked_action_is_refused() -> None:
    env = cgym.ExploreEnv(ROOM, lattice_radii_m=(1.0, 8.0), **SHORT)
    _, info = env.reset(seed=0)
    masked = np.flatnonzero(info["action_mask"] == 0)
    assert len(masked) >= 8  # the ring at 8 m lies off the map of a 4 x 3 m room
    before = _state(env)
    with pytest.raises(covmap.InvalidActionError, match="masked"):
        env.step(int(masked[0]))
    assert _state(env) == before


def test_a_masked_action_stays_when_asked_to() -> None:
    env = cgym.ExploreEnv(ROOM, lattice_radii_m=(1.0, 8.0), masked="stay", **SHORT)
    obs, info = env.reset(seed=0)
    before = _state(env)
    masked = int(np.flatnonzero(info["action_mask"] == 0)[0])
    obs2, reward, terminated, truncated, info2 = env.step(masked)
    assert info2["stayed"] and reward == 0.0 and _state(env) == before
    assert not (terminated or truncated)
    for k in obs:
        np.testing.assert_array_equal(obs[k], obs2[k])


def test_a_bad_goal_action_is_a_typed_error_and_the_episode_as_it_was() -> None:
    env = cgym.ExploreEnv(ROOM, action="goal", **SHORT)
    env.reset(seed=0)
    before = _state(env)
    for action in ([2.0, 0.5], [np.nan, 0.5], [0.1, 0.2, 0.3], "here"):
        with pytest.raises(covmap.InvalidActionError):
            env.step(action)
    with pytest.raises(covmap.InvalidGoalError):
        env.step(np.array([0.0, 0.0], np.float32))  # the map's corner, outside the room's walls
    assert _state(env) == before


@pytest.mark.parametrize(
    ("options", "names"),
    [
        ({"action": "joystick"}, "action"),
        ({"buildings": "holdout"}, "buildings"),
        ({"size": 0}, "size"),
        ({"lattice_radii_m": (1.0, -2.0)}, "lattice_radii_m"),
        ({"alpha": 0.0}, "alpha"),
        ({"max_steps": True}, "max_steps"),
        ({"resolution": float("nan")}, "resolution"),
        ({"render_mode": "human"}, "render_mode"),
        ({"epsilon": -1.0}, "epsilon"),
    ],
)
def test_bad_options_are_refused_when_the_environment_is_made(options: dict[str, Any], names: str) -> None:
    with pytest.raises(covmap.CovmapError, match=names):
        cgym.ExploreEnv(ROOM, **options)


def test_a_step_outside_an_episode_is_refused() -> None:
    env = cgym.ExploreEnv(ROOM, max_steps=1, size=16)
    with pytest.raises(covmap.InvalidActionError, match="reset"):
        env.step(0)
    _, info = env.reset(seed=0)
    env.step(info["paper_action"])
    with pytest.raises(covmap.InvalidActionError, match="ended"):
        env.step(info["paper_action"])


def test_render_draws_the_observation() -> None:
    env = cgym.ExploreEnv(ROOM, render_mode="rgb_array", **SHORT)
    env.reset(seed=0)
    picture = env.render()
    assert picture is not None and picture.shape == (16, 16, 3) and picture.dtype == np.uint8


def test_the_reference_figures_command_runs() -> None:
    from covmap.experiments import gym_baselines

    for action in ("lattice", "goal"):
        episodes, loop = gym_baselines.run(count=1, area_m2=60.0, max_steps=3, action=action, progress=False)
        assert [e.policy for e in episodes] == ["random", "paper"] and len(loop) == 1
        assert all(e.steps <= 3 and e.termination in ("limit", "no_goal", "certain", "stagnated") for e in episodes)
        assert "steps/s" in gym_baselines.table(episodes, loop)
