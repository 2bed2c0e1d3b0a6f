"""``covmap learn``: the sensor model fitted by maximum likelihood in simulation."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from covmap._native import LaserModel, SonarModel, World, run_learn, write_atomic
from covmap.cli import _options

if TYPE_CHECKING:
    import argparse
    from pathlib import Path

NAME = "learn"
"""The command's name: ``covmap learn``."""

HELP = "fit the sensor model by maximum likelihood on a simulated drive"
"""The command's line in ``covmap --help``."""

DESCRIPTION = (
    "Simulate a training drive through --world and a test drive through --test-world "
    "(shortest paths to seeded waypoints), fit the sensor model to the training drive by "
    "maximum likelihood of the exact ground truth (Nelder-Mead with restarts), print the "
    "log-likelihood of the truth before and after on both drives and the mean-map errors "
    "with the occupancy grid's beside them, and save the learned model as model.json "
    "(for covmap fig2 --model) and the fit's trace as trace.csv. Maps are built as the "
    "exploration loop builds them, read against the cells the map holds covered and is certain of "
    "(a no-echo reading clears only up to the nearest of them, an echo off one of them marks only the "
    "cells at its bearing), unless --clear-no-echo."
)
"""What ``covmap learn --help`` says the command does."""


def add_arguments(command: argparse.ArgumentParser) -> None:
    """The command's arguments."""
    _options.add_out(command, NAME)
    command.add_argument("--world", default="corridor", help="built-in world of the training drive")
    command.add_argument("--test-world", default="office", help="built-in world of the test drive")
    command.add_argument("--sensor", choices=("sonar", "laser"), default="sonar", help="sensor (default sonar)")
    command.add_argument(
        "--evaluations", type=_options.positive_int, default=300, help="maps built at most (default 300)"
    )
    command.add_argument("--scans", type=_options.positive_int, default=300, help="scans a drive (default 300)")
    command.add_argument(
        "--parameters", help="comma-separated parameters to fit (default: all but max_range_m)"
    )
    command.add_argument(
        "--clear-no-echo",
        action="store_true",
        help="integrate as the paper does: every no-echo reading clears its whole footprint, through "
        "walls the map holds, every echo marks its whole arc (default: read against the map, as the "
        "exploration loop builds its maps)",
    )
    _options.add_seed(command)


def table(result: dict[str, Any], sensor: str) -> str:
    """The figures of a ``run_learn`` result as text."""
    fit = result["fit"]
    lines = [
        f"fit of the {sensor} model: {fit.evaluations} evaluations, "
        f"training log-likelihood {fit.initial_log_likelihood:.0f} -> {fit.log_likelihood:.0f}",
        f"{'parameter':20} {'start':>9} {'learned':>9}",
    ]
    start, learned = fit.trace[0], fit.model.to_dict()
    for name in fit.parameters:
        lines.append(f"{name:20} {start[name]:9.4f} {learned[name]:9.4f}")
    for k, label in enumerate(("training", "test")):
        drive, d, l = result["drives"][k], result["default"][k], result["learned"][k]
        lines.append(
            f"{label} drive ({drive['world']}, {d['cells_reached']} cells reached): "
            f"log-likelihood {d['log_likelihood']:.0f} -> {l['log_likelihood']:.0f}; "
            f"mean-map error {d['mean_error']:.4f} -> {l['mean_error']:.4f} "
            f"(free {d['free_error']:.4f} -> {l['free_error']:.4f}, "
            f"obstacle {d['obstacle_error']:.4f} -> {l['obstacle_error']:.4f}); "
            f"occupancy grid {d['occupancy_error']:.4f}; "
            f"faced walls' mean coverage {d['wall_coverage']:.3f} -> {l['wall_coverage']:.3f} "
            f"(occupancy grid {d['occupancy_wall']:.3f})"
        )
    return "\n".join(lines)


def outputs(args: argparse.Namespace) -> list[Path]:
    """The files the command writes: the model and the fit's trace."""
    return [args.out / "model.json", args.out / "trace.csv"]


def run(args: argparse.Namespace) -> int:
    """Fit, print the figures, save the model and the trace."""
    for name in (args.world, args.test_world):
        World.builtin(name)  # an unknown name fails before any work
    model = SonarModel() if args.sensor == "sonar" else LaserModel()
    parameters = None if args.parameters is None else [p.strip() for p in args.parameters.split(",")]
    result = run_learn(
        model,
        train_world=args.world,
        test_world=args.test_world,
        scans=args.scans,
        max_evaluations=args.evaluations,
        seed=args.seed,
        parameters=parameters,
        occlude_no_echo=not args.clear_no_echo,
        progress=True,
    )
    print(table(result, args.sensor))
    fit = result["fit"]
    args.out.mkdir(parents=True, exist_ok=True)
    saved = {
        "sensor": args.sensor,
        "model": fit.model.to_dict(),
        "log_likelihood": fit.log_likelihood,
        "occlude_no_echo": not args.clear_no_echo,
    }
    model_path, trace_path = outputs(args)
    write_atomic(model_path, (json.dumps(saved, indent=2) + "\n").encode())
    names = fit.parameters
    rows = [",".join(["evaluation", *names, "log_likelihood"])]
    for i, e in enumerate(fit.trace):
        rows.append(",".join([str(i), *(repr(e[n]) for n in names), repr(e["log_likelihood"])]))
    write_atomic(trace_path, ("\n".join(rows) + "\n").encode())
    print(f"wrote {model_path}\nwrote {trace_path}")
    return 0
