"""Coverage-map exploration as a Gymnasium environment (the ``gym`` extra:
``pip install 'covmap[gym]'``).

Importing this module registers ``"covmap/Explore-v0"``;
``gymnasium.make("covmap.gym:covmap/Explore-v0", ...)`` imports it on the
way. An episode is a run of covmap's exploration loop whose goals the agent
chooses: each step the robot plans a path to the goal on its coverage map,
drives it through the true world scanning on the way, and scans at the goal,
as a step of :class:`covmap.Exploration` does.

**Building and start.** ``reset(seed=...)`` draws from the seed a building
of the ``buildings`` split (:mod:`covmap.buildings`: ``"development"``, seeds
0 to 999, to train on; ``"test"``, seeds 1000 to 1999, only to report on) of
``area_m2`` square metres, unless a ``world`` is given, and a free start in
it. The same seed gives the same episode on every machine.

**Observation** (a dict; float32 arrays of ``size`` x ``size``): the map is
padded to a square from its origin (its lower left corner) and averaged over
blocks of cells down to ``size`` x ``size`` pixels (rows along y, row 0 at
the origin; a map smaller than ``size`` cells is padded only):

- ``"entropy"``: the cells' entropy, nats, mean over the block;
- ``"coverage"``: the maximum-likelihood coverage of the observed cells of
  the block, mean (0 where none is observed: read it with ``"observed"``);
- ``"observed"``: the share of the block's cells that evidence reached;
- ``"robot"``: 1 in the robot's pixel, else 0;
- ``"pose"``: ``(x, y, theta)``, x and y as fractions of the square's side
  from its origin, theta in radians.

**Action.** ``action="lattice"`` (the default): the index of a goal on a
fixed lattice around the robot, ``len(lattice_radii_m)`` rings of
``lattice_headings`` goals each, in the world's frame (ring ``i``, heading
``j``: ``radius[i]`` metres at ``2 pi j / headings``, facing outward).
``info["action_mask"]`` marks the goals the robot can reach on its map
(:meth:`covmap.Exploration.reachable`); a masked or
out-of-range action raises :class:`covmap.InvalidActionError` and leaves
the episode as it was. ``action="goal"``: a goal ``(u, v)`` anywhere in the
observation's square, as fractions of its side; one the robot cannot reach
raises :class:`covmap.InvalidGoalError`, the episode as it was. With ``masked="stay"`` such an action is a step
where the robot stays where it is (reward 0, ``info["stayed"]``; it counts
towards ``max_steps``): for agents and tools that sample the whole action
space, Gymnasium's ``check_env`` among them. ``info["candidate_goals"]`` holds the goals of the
candidate viewpoints worth one, as such fractions.

**Reward**: the entropy the step removed from the map (nats, all cells)
minus ``lam`` times the metres driven, where ``lam = (1 - alpha) / alpha *
G_max / C_max`` from the candidate viewpoints of the state the action was
chosen in (``G_max``, ``C_max``: the largest expected gain and path cost
among the candidates worth a goal). Eq. 14's utility of a candidate is
``alpha / G_max * (G - lam * C)``: the paper's choice is the greedy policy of
this reward's expectation (``info["lam"]``, ``info["paper_action"]``).

**End.** ``terminated`` when the paper's rule holds on the reachable region
(every cell certain or stagnated) or no candidate is worth a goal (no
action left: also when every lattice goal is masked); ``truncated`` at
``max_steps`` steps or ``max_path_m`` metres. ``info["termination"]`` says
which, ``info["uncertain_share"]`` the share of the evaluation cells left
above ``epsilon`` (Table I's figure) at the end.

In a vectorised environment, start the copies by spawning
(``gymnasium.vector.AsyncVectorEnv(fns, context="spawn")``): covmap's
worker threads do not survive a fork, and a forked copy waits for them
forever.

Two reference policies: :class:`RandomPolicy` (uniform over the valid
actions) and :class:`PaperPolicy` (eq. 14, the built-in coverage strategy's
choice).
"""

from __future__ import annotations

import math
import numbers
from typing import TYPE_CHECKING, Any

import numpy as np

from covmap._errors import (
    InvalidActionError,
    InvalidParameterError,
    InvalidTypeError,
    MissingDependencyError,
    quoted,
)

try:
    import gymnasium
    from gymnasium import spaces
except ImportError as e:  # pragma: no cover - the extra is installed in CI
    raise MissingDependencyError(
        "covmap.gym needs gymnasium: pip install 'covmap[gym]'"
    ) from e

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

    from covmap._native import Building, Exploration, Plan, World

__all__ = ["ENV_ID", "ExploreEnv", "PaperPolicy", "RandomPolicy", "episode"]

ENV_ID = "covmap/Explore-v0"
"""The environment's id for :func:`gymnasium.make`."""

SPLITS = ("development", "test")
"""The building splits an environment draws from (:mod:`covmap.buildings`)."""

ACTIONS = ("lattice", "goal")
"""The kinds of action: a lattice goal's index, or a goal in the square."""

MASKED = ("raise", "stay")
"""What a masked action (or a goal out of reach) does: raise, or stay."""

Observation = dict[str, "npt.NDArray[np.float32]"]


def _positive(name: str, value: Any, *, integer: bool = False, upper: float = math.inf) -> Any:
    """``value`` checked: a finite positive number (an int with
    ``integer``) of at most ``upper``, else a typed error naming ``name``."""
    kind = numbers.Integral if integer else numbers.Real
    if isinstance(value, bool) or not isinstance(value, kind):
        raise InvalidTypeError(f"{name} must be {'an integer' if integer else 'a number'}, got {type(value).__name__}")
    number = float(value)  # type: ignore[arg-type]
    if not (0 < number <= upper) or not math.isfinite(number):
        raise InvalidParameterError(f"invalid parameter `{name}` = {quoted(value)}: expected a finite number in (0, {upper}]")
    return int(value) if integer else number  # type: ignore[call-overload]


class ExploreEnv(gymnasium.Env[Observation, Any]):
    """Coverage-map exploration as a Gymnasium environment (see the module
    documentation). Every option is checked when the environment is made:
    a bad one raises a :class:`covmap.CovmapError` naming it.

    ``world``: a ``World``, a ``Building`` or a building's name
    (:func:`covmap.buildings.building`), or ``None`` to draw a generated
    building of the ``buildings`` split and ``area_m2`` each reset.
    ``sensor``, ``model``, ``bins``, ``epsilon``, ``robot_radius_m``,
    ``candidate_stride_m``, ``scan_spacing_m``: as :func:`covmap.explore`
    takes them; ``resolution``: the maps' cell size, metres (0.1: the
    observation's detail at a tenth of the cost of 0.05)."""

    metadata = {"render_modes": ["rgb_array"], "render_fps": 4}

    def __init__(
        self,
        world: World | Building | str | None = None,
        *,
        buildings: str = "development",
        area_m2: float = 120.0,
        action: str = "lattice",
        size: int = 64,
        lattice_radii_m: Sequence[float] = (1.0, 2.0, 4.0),
        lattice_headings: int = 8,
        alpha: float = 0.5,
        max_steps: int = 200,
        max_path_m: float = 1000.0,
        resolution: float = 0.1,
        masked: str = "raise",
        render_mode: str | None = None,
        **explore_options: Any,
    ) -> None:
        import covmap
        import covmap.buildings

        if buildings not in SPLITS:
            raise InvalidParameterError(f"invalid parameter `buildings` = {quoted(buildings)}: expected one of {', '.join(SPLITS)}")
        if action not in ACTIONS:
            raise InvalidParameterError(f"invalid parameter `action` = {quoted(action)}: expected one of {', '.join(ACTIONS)}")
        if masked not in MASKED:
            raise InvalidParameterError(f"invalid parameter `masked` = {quoted(masked)}: expected one of {', '.join(MASKED)}")
        self._masked: str = masked
        if render_mode is not None and render_mode not in self.metadata["render_modes"]:
            raise InvalidParameterError(f"invalid parameter `render_mode` = {quoted(render_mode)}: expected rgb_array or None")
        self._area_m2: float = _positive("area_m2", area_m2, upper=1e5)
        self._size: int = _positive("size", size, integer=True, upper=4096)
        radii = np.asarray(lattice_radii_m, dtype=np.float64) if not isinstance(lattice_radii_m, str) else None
        if radii is None or radii.ndim != 1 or len(radii) == 0 or not np.all(np.isfinite(radii)) or np.any(radii <= 0):
            raise InvalidParameterError(
                f"invalid parameter `lattice_radii_m` = {quoted(lattice_radii_m)}: expected positive finite radii, metres"
            )
        headings = _positive("lattice_headings", lattice_headings, integer=True, upper=360)
        if isinstance(alpha, bool) or not isinstance(alpha, numbers.Real) or not 0.0 < alpha <= 1.0:
            raise InvalidParameterError(f"invalid parameter `alpha` = {quoted(alpha)}: expected a weight in (0, 1]")
        self._alpha: float = float(alpha)
        self._split: str = buildings
        self._action_kind: str = action
        self.render_mode = render_mode
        self._world: World | None = None if world is None else covmap.buildings.building(world).world
        self._max_steps: int = _positive("max_steps", max_steps, integer=True, upper=10**6)
        self._steps: int = 0
        self._options: dict[str, Any] = {
            "max_steps": self._max_steps,
            "max_path_m": _positive("max_path_m", max_path_m, upper=1e7),
            "resolution": _positive("resolution", resolution, upper=10.0),
            **explore_options,
        }
        # Every option of the run checked now, on a world at hand.
        probe = self._world if self._world is not None else self._building(0)
        covmap.Exploration(probe, covmap.Strategy.coverage(self._alpha), **self._options)

        angles = 2 * np.pi * np.arange(headings) / headings
        self._lattice: npt.NDArray[np.float64] = np.array([(r * math.cos(a), r * math.sin(a), a) for r in radii for a in angles])
        s = self._size
        bins = int(self._options.get("bins", 16))
        # Rounded down to a float32, so that every pooled entropy lies in the box.
        self._max_entropy: float = float(np.nextafter(np.float32(math.log(bins)), np.float32(0)))
        layer = spaces.Box(0.0, 1.0, (s, s), np.float32)
        self.observation_space = spaces.Dict(
            {
                "entropy": spaces.Box(0.0, self._max_entropy, (s, s), np.float32),
                "coverage": layer,
                "observed": layer,
                "robot": layer,
                "pose": spaces.Box(
                    np.array([0.0, 0.0, -math.pi], np.float32), np.array([1.0, 1.0, math.pi], np.float32), dtype=np.float32
                ),
            }
        )
        self.action_space: spaces.Space[Any] = (
            spaces.Discrete(len(self._lattice)) if action == "lattice" else spaces.Box(0.0, 1.0, (2,), np.float32)
        )
        self._run: Exploration | None = None
        self._plan: Plan | None = None
        self._info: dict[str, Any] = {}
        self._entropy: float = 0.0
        self._observation: Observation | None = None
        self._frame: tuple[float, float, float] | None = None

    # The episode.

    def _building(self, seed: int) -> World:
        import covmap.buildings

        first = covmap.buildings.DEVELOPMENT_SEEDS if self._split == "development" else covmap.buildings.TEST_SEEDS
        return covmap.buildings.building(f"generated:{first[seed % len(first)]}:{self._area_m2:g}").world

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None) -> tuple[Observation, dict[str, Any]]:
        """A new episode: a building (``options["world"]``, the
        environment's world, or one drawn from the seed) and a start drawn
        from the seed."""
        import covmap
        import covmap.buildings

        super().reset(seed=seed)
        draws = self.np_random.integers(0, 2**62, size=2)
        if options is not None and options.get("world") is not None:
            world = covmap.buildings.building(options["world"]).world
        elif self._world is not None:
            world = self._world
        else:
            world = self._building(int(draws[0]))
        self._run = covmap.Exploration(world, covmap.Strategy.coverage(self._alpha), seed=int(draws[1]), **self._options)
        grid = self._run.map.grid
        cells = -(-max(grid.rows, grid.cols) // self._size) * self._size
        self._frame = (*grid.origin, cells * grid.resolution)
        self._steps = 0
        self._run.begin()
        self._observe()
        self._end_check()
        return self._observation_now(), self._info_now()

    def step(self, action: Any) -> tuple[Observation, float, bool, bool, dict[str, Any]]:
        """Drive to the action's goal (see the module documentation)."""
        from covmap._errors import InvalidGoalError

        run = self._run
        if run is None:
            raise InvalidActionError("step before reset: call reset() first")
        if run.done:
            raise InvalidActionError("step after the episode ended: call reset()")
        goal = self._goal_of(action)
        before_m, before_h, lam = run.path_length_m, self._entropy, self._info["lam"]
        stayed = goal is None
        if goal is not None:
            try:
                run.step(goal=goal)
            except InvalidGoalError:
                if self._masked == "raise":
                    raise
                stayed = True
        self._steps += 1
        if not stayed:
            self._observe()
        terminated, truncated = self._end_check()
        driven = run.path_length_m - before_m
        reward = (before_h - self._entropy) - lam * driven
        info = dict(self._info_now(), driven_m=driven, entropy_removed=before_h - self._entropy, stayed=stayed)
        return self._observation_now(), float(reward), terminated, truncated, info

    def _goal_of(self, action: Any) -> tuple[float, float, float] | None:
        """The goal an action names, checked (``None``: a masked action,
        with ``masked="stay"``)."""
        assert self._run is not None
        if self._action_kind == "lattice":
            if isinstance(action, (bool, np.bool_)) or not isinstance(action, (numbers.Integral, np.integer)):
                raise InvalidActionError(f"a lattice action is an integer index, got {type(action).__name__}")
            k = int(action)
            mask = self._info["action_mask"]
            if not 0 <= k < len(mask):
                raise InvalidActionError(f"action {quoted(k)}: expected 0 to {len(mask) - 1}")
            if not mask[k]:
                if self._masked == "stay":
                    return None
                raise InvalidActionError(
                    f"action {k} is masked: the robot cannot reach its goal on its map (see info['action_mask'])"
                )
            return self._lattice_goals()[k]
        a = np.asarray(action, dtype=np.float64) if not isinstance(action, str) else None
        if a is None or a.shape != (2,) or not np.all(np.isfinite(a)) or np.any(a < 0) or np.any(a > 1):
            raise InvalidActionError(f"a goal action is (u, v) in [0, 1]^2, got {quoted(action)}")
        x0, y0, side = self._square()
        return (x0 + a[0] * side, y0 + a[1] * side, 0.0)

    def _end_check(self) -> tuple[bool, bool]:
        """Whether the episode ended now, and how: the run's limit
        (truncated), the paper's rule or no goal left (terminated)."""
        run = self._run
        assert run is not None
        terminated = truncated = False
        if not run.done and self._steps >= self._max_steps:
            run.finish()
            truncated = True
        elif not run.done and not run.begin():
            truncated = True  # a limit: begin() ends the run there
        elif run.done:
            truncated = run.termination == "limit"
            terminated = not truncated
        elif run.rule() is not None or self._plan is None or self._plan.pose is None or self._no_action():
            run.finish()
            terminated = True
        if terminated or truncated:
            self._info["termination"] = "limit" if truncated else run.termination
            self._info["uncertain_share"] = run.result().high_entropy_fraction
        return terminated, truncated

    def _no_action(self) -> bool:
        """Whether no action is left: every lattice goal masked (goal
        actions always have one while a candidate is worth a goal)."""
        return self._action_kind == "lattice" and not self._info["action_mask"].any()

    # What the agent sees.

    def _square(self) -> tuple[float, float, float]:
        """The observation's square: its origin and side, metres (the map's
        grid, which an episode keeps)."""
        assert self._frame is not None
        return self._frame

    def _lattice_goals(self) -> list[tuple[float, float, float]]:
        assert self._run is not None
        x, y, _ = self._run.pose
        return [(x + dx, y + dy, a) for dx, dy, a in self._lattice]

    def _observe(self) -> None:
        """Read the run's state once: the layers, the plan, the mask, lam."""
        run = self._run
        assert run is not None
        m = run.map
        grid = m.grid
        entropy = m.entropy().astype(np.float64)
        observed = m.observed()
        self._entropy = float(entropy.sum())
        s = self._size
        block = -(-max(grid.rows, grid.cols) // s)

        def pool(a: npt.NDArray[Any]) -> npt.NDArray[np.float64]:
            padded = np.zeros((s * block, s * block))
            padded[: a.shape[0], : a.shape[1]] = a
            return padded.reshape(s, block, s, block).sum(axis=(1, 3))

        n = block * block
        seen = pool(observed)
        covered = pool(np.where(observed, m.ml(), 0.0))
        x0, y0, side = self._square()
        x, y, theta = (float(v) for v in run.pose)
        robot = np.zeros((s, s), np.float32)
        robot[min(int((y - y0) / side * s), s - 1), min(int((x - x0) / side * s), s - 1)] = 1.0
        self._observation = {
            "entropy": np.clip(pool(entropy) / n, 0.0, self._max_entropy).astype(np.float32),
            "coverage": np.divide(covered, seen, out=np.zeros_like(covered), where=seen > 0).astype(np.float32),
            "observed": (seen / n).astype(np.float32),
            "robot": robot,
            "pose": np.array([(x - x0) / side, (y - y0) / side, math.atan2(math.sin(theta), math.cos(theta))], np.float32),
        }
        # The candidates of this state: eq. 14's choice and lam.
        plan = self._plan = run.viewpoints(self._alpha)
        c = plan.candidates
        worth = np.isfinite(c.utilities)
        g_max = float(c.gains[worth].max()) if worth.any() else 0.0
        c_max = float(c.costs[worth].max()) if worth.any() else 0.0
        lam = (1 - self._alpha) / self._alpha * g_max / c_max if c_max > 0 else 0.0
        reachable = run.reachable()
        goals = self._lattice_goals()
        mask = np.zeros(len(goals), np.int8)
        for k, (gx, gy, _) in enumerate(goals):
            if grid.contains(gx, gy):
                col, row = int((gx - x0) / grid.resolution), int((gy - y0) / grid.resolution)
                mask[k] = 0 <= row < grid.rows and 0 <= col < grid.cols and bool(reachable[row, col])
        self._info = {"action_mask": mask, "lam": lam, "paper_action": self._paper_action(plan, goals, mask)}
        if self._action_kind == "goal":
            self._info["candidate_goals"] = np.column_stack(
                [(c.poses[:, 0] - x0) / side, (c.poses[:, 1] - y0) / side]
            ).astype(np.float32)[worth]

    def _paper_action(self, plan: Plan, goals: list[tuple[float, float, float]], mask: npt.NDArray[np.int8]) -> Any:
        """Eq. 14's choice as an action: the goal itself, or on the lattice
        the valid goal nearest to it (``None``: no candidate worth a goal)."""
        if plan.pose is None:
            return None
        px, py = float(plan.pose[0]), float(plan.pose[1])
        if self._action_kind == "goal":
            x0, y0, side = self._square()
            return np.array([(px - x0) / side, (py - y0) / side], np.float32)
        if not mask.any():
            return None
        d = [math.hypot(gx - px, gy - py) if mask[k] else math.inf for k, (gx, gy, _) in enumerate(goals)]
        return int(np.argmin(d))

    def _info_now(self) -> dict[str, Any]:
        """The info of now, its arrays copied (the caller keeps them)."""
        return {k: v.copy() if isinstance(v, np.ndarray) else v for k, v in self._info.items()}

    def _observation_now(self) -> Observation:
        assert self._observation is not None
        return {k: v.copy() for k, v in self._observation.items()}

    def render(self) -> npt.NDArray[np.uint8] | None:
        """``render_mode="rgb_array"``: the observation as a picture, entropy
        in grey (white certain), unobserved in blue, the robot in red."""
        if self.render_mode is None or self._observation is None:
            return None
        o = self._observation
        grey = 1.0 - o["entropy"] / max(self._max_entropy, 1e-9)
        rgb = np.stack([grey, grey, grey], axis=-1)
        rgb[o["observed"] == 0] = (0.55, 0.65, 0.8)
        rgb[o["robot"] > 0] = (0.9, 0.1, 0.1)
        return (np.flipud(rgb) * 255).astype(np.uint8)


class RandomPolicy:
    """Uniform over the valid actions: the lattice goals
    ``info["action_mask"]`` allows, or (goal actions) the goals of the
    candidate viewpoints worth one, ``info["candidate_goals"]``. Seeded; a
    function of the observation and info only, as a vectorised
    environment's policy must be."""

    def __init__(self, seed: int = 0) -> None:
        self._rng = np.random.default_rng(seed)

    def __call__(self, observation: Observation, info: dict[str, Any]) -> Any:
        if "candidate_goals" in info:
            goals = info["candidate_goals"]
            return goals[int(self._rng.integers(len(goals)))]
        return int(self._rng.choice(np.flatnonzero(info["action_mask"])))


class PaperPolicy:
    """The paper's choice (eq. 14): ``info["paper_action"]``, the coverage
    strategy's goal (on the lattice, the valid goal nearest to it)."""

    def __call__(self, observation: Observation, info: dict[str, Any]) -> Any:
        return info["paper_action"]


def episode(env: ExploreEnv, policy: Any, seed: int, options: dict[str, Any] | None = None) -> dict[str, Any]:
    """One episode of ``policy`` (a function of the observation and info)
    from ``reset(seed=seed, options=options)``: its return, steps, path,
    how it ended, the uncertain share at the end and the start pose."""
    observation, info = env.reset(seed=seed, options=options)
    total, steps, done = 0.0, 0, info.get("termination") is not None
    while not done:
        observation, reward, terminated, truncated, info = env.step(policy(observation, info))
        total, steps, done = total + reward, steps + 1, terminated or truncated
    assert env._run is not None
    return {
        "return": total,
        "steps": steps,
        "path_m": env._run.path_length_m,
        "termination": info["termination"],
        "uncertain_share": info["uncertain_share"],
        "start": env._run.trajectory[0],
    }


gymnasium.register(id=ENV_ID, entry_point="covmap.gym:ExploreEnv")
