"""The Gymnasium environment's reference figures: the two shipped policies
(random over the valid actions, and the paper's eq. 14) over test
buildings, their mean episode return and final uncertain share (the figures
a learned policy has to beat), and the environment's steps per second
beside :func:`covmap.explore`'s on the same buildings, in the same run.

Run: ``python -m covmap.experiments.gym_baselines [--action lattice|goal]
[--count 8] [--area 120] [--max-steps 1000] [--resolution 0.1]`` (the
``gym`` extra). With goal actions the paper's policy is eq. 14's choice
itself; on the lattice, the valid lattice goal nearest to it. Episode ``i``
explores test building ``generated:(1000 + i):AREA`` from the start drawn
from seed ``i``; the loop's run starts from the same pose.
"""

from __future__ import annotations

import argparse
import math
import statistics
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import covmap
import covmap.buildings

if TYPE_CHECKING:
    from collections.abc import Sequence

POLICIES = ("random", "paper")
"""The shipped policies: :class:`covmap.gym.RandomPolicy` and
:class:`covmap.gym.PaperPolicy`."""


@dataclass(frozen=True)
class Episode:
    """One episode of a policy in a building."""

    policy: str
    building: str
    episode_return: float
    steps: int
    path_m: float
    termination: str
    uncertain_share: float
    seconds: float


@dataclass(frozen=True)
class LoopRun:
    """The loop's own run (the coverage strategy) in a building, from the
    episodes' start."""

    building: str
    steps: int
    seconds: float
    uncertain_share: float
    path_m: float


def run(
    *,
    count: int = 8,
    area_m2: float = 120.0,
    policies: Sequence[str] = POLICIES,
    max_steps: int = 1000,
    resolution: float = 0.1,
    action: str = "lattice",
    progress: bool = True,
) -> tuple[list[Episode], list[LoopRun]]:
    """The episodes of every policy in ``count`` test buildings of
    ``area_m2``, and per building the coverage strategy's own run
    (``covmap.explore`` from the episode's start: building, steps,
    seconds, uncertain share)."""
    from covmap import gym as cgym

    env = cgym.ExploreEnv(buildings="test", area_m2=area_m2, max_steps=max_steps, resolution=resolution, action=action)
    names = [f"generated:{covmap.buildings.TEST_SEEDS[i]}:{area_m2:g}" for i in range(count)]
    episodes: list[Episode] = []
    loop: list[LoopRun] = []
    for i, name in enumerate(names):
        world = covmap.buildings.building(name).world
        for policy_name in policies:
            policy: Any = cgym.RandomPolicy(seed=i) if policy_name == "random" else cgym.PaperPolicy()
            started = time.perf_counter()
            done = cgym.episode(env, policy, seed=i, options={"world": world})
            seconds = time.perf_counter() - started
            start = done["start"]
            episodes.append(
                Episode(
                    policy_name,
                    name,
                    done["return"],
                    done["steps"],
                    done["path_m"],
                    done["termination"],
                    done["uncertain_share"],
                    seconds,
                )
            )
            if progress:
                e = episodes[-1]
                print(
                    f"{name} {policy_name}: return {e.episode_return:.0f}, {e.steps} steps, {e.path_m:.0f} m, "
                    f"{e.termination}, {100 * e.uncertain_share:.1f} % uncertain, {e.seconds:.1f} s",
                    flush=True,
                )
        started = time.perf_counter()
        result = covmap.explore(
            world, covmap.Strategy.coverage(0.5), start=start, seed=0, resolution=resolution, max_steps=max_steps
        )
        loop.append(LoopRun(name, result.steps, time.perf_counter() - started, result.high_entropy_fraction, result.path_length_m))
    return episodes, loop


def table(episodes: Sequence[Episode], loop: Sequence[LoopRun]) -> str:
    """Per policy: episodes, mean return, mean final uncertain share, mean
    steps and path, steps per second; then the loop's steps per second."""
    lines = [
        "| policy | episodes | mean return (nats) | mean uncertain share | mean steps | mean path (m) | steps/s |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for name in dict.fromkeys(e.policy for e in episodes):
        mine = [e for e in episodes if e.policy == name]
        rate = sum(e.steps for e in mine) / sum(e.seconds for e in mine)
        lines.append(
            f"| {name} | {len(mine)} | {statistics.fmean(e.episode_return for e in mine):.0f} | "
            f"{100 * statistics.fmean(e.uncertain_share for e in mine):.1f} % | "
            f"{statistics.fmean(e.steps for e in mine):.0f} | {statistics.fmean(e.path_m for e in mine):.0f} | {rate:.2f} |"
        )
    steps, seconds = sum(r.steps for r in loop), sum(r.seconds for r in loop)
    uncertain = statistics.fmean(r.uncertain_share for r in loop) if loop else math.nan
    path = statistics.fmean(r.path_m for r in loop) if loop else math.nan
    lines.append(
        f"| `covmap.explore`, coverage strategy | {len(loop)} | | {100 * uncertain:.1f} % | "
        f"{steps / max(len(loop), 1):.0f} | {path:.0f} | {steps / seconds:.2f} |"
    )
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="python -m covmap.experiments.gym_baselines", description=__doc__)
    parser.add_argument("--count", type=int, default=8, help="test buildings (default 8)")
    parser.add_argument("--area", type=float, default=120.0, help="their area, square metres (default 120)")
    parser.add_argument("--action", choices=("lattice", "goal"), default="lattice", help="the kind of action (default lattice)")
    parser.add_argument("--max-steps", type=int, default=1000, help="steps an episode (default 1000)")
    parser.add_argument("--resolution", type=float, default=0.1, help="the maps' cell size, metres (default 0.1)")
    args = parser.parse_args(argv)
    episodes, loop = run(
        count=args.count, area_m2=args.area, max_steps=args.max_steps, resolution=args.resolution, action=args.action
    )
    print(table(episodes, loop))


if __name__ == "__main__":
    main()
