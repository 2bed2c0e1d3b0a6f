"""Every command checks every file it writes before it runs: a directory, a
FIFO, a socket or a symlink where one of them would go is refused with a
one-line message (exit status 1) and nothing is written, the thing in the
way left as it was. And the files a command says it writes
(``outputs(args)``) are the files it writes."""

from __future__ import annotations

import os
import socket
import stat
from pathlib import Path
from typing import Callable

import pytest

import covmap
import covmap.cli
from test_cli_map import square_room_log


def _inputs(tmp: Path) -> dict[str, Path]:
    """The input files the commands below read, made in ``tmp``."""
    log = tmp / "room.log"
    square_room_log(log)
    specs = tmp / "study.json"
    specs.write_text('[{"world": "partial", "strategy": "frontier", "resolution": 0.1, "max_steps": 1}]')
    saved = tmp / "saved.npz"
    covmap.CoverageMap(covmap.Grid(origin=(0.0, 0.0), resolution=0.1, shape=(10, 12))).save(saved)
    return {"log": log, "specs": specs, "map": saved}


#: Each command with settings that keep it short: its arguments, given the
#: input files and the output directory (or file, for ``sweep``).
COMMANDS: dict[str, Callable[[dict[str, Path], Path], list[str]]] = {
    "fig1": lambda i, out: ["fig1", "--readings", "20", "--out", str(out)],
    "fig2": lambda i, out: ["fig2", "--out", str(out)],
    "world": lambda i, out: ["world", "partial", "--resolution", "0.1", "--out", str(out)],
    "fig3": lambda i, out: ["fig3", "--out", str(out)],
    "learn": lambda i, out: ["learn", "--world", "partial", "--test-world", "partial", "--scans", "5", "--evaluations", "1", "--parameters", "xi_min", "--out", str(out)],
    "gain": lambda i, out: ["gain", "--world", "partial", "--scans", "2", "--out", str(out)],
    "explore": lambda i, out: ["explore", "--world", "partial", "--max-steps", "2", "--frames", "2", "--out", str(out)],
    "table1": lambda i, out: ["table1", "--world", "partial", "--seeds", "1", "--max-steps", "2", "--out", str(out)],
    "fig7": lambda i, out: ["fig7", "--world", "partial", "--ns", "1", "--seeds", "1", "--resolution", "0.1", "--max-steps", "2", "--out", str(out)],
    "benchmark": lambda i, out: ["benchmark", "--buildings", "partial", "--strategies", "frontier", "--resolution", "0.1", "--max-steps", "1", "--out", str(out)],
    "sweep": lambda i, out: ["sweep", str(i["specs"]), "--out", str(out / "results.csv")],
    "map": lambda i, out: ["map", str(i["log"]), "--resolution", "0.1", "--max-range", "20", "--out", str(out)],
    "view": lambda i, out: ["view", str(i["map"]), "--out", str(out)],
}


def _outputs(argv: list[str]) -> list[Path]:
    args = covmap.cli.parser().parse_args(argv)
    outputs: list[Path] = args.outputs(args)
    return outputs


def test_every_command_is_listed() -> None:
    assert sorted(COMMANDS) == sorted(m.NAME for m in covmap.cli.COMMANDS)


def _in_the_way(path: Path, kind: str) -> Callable[[], bool]:
    """Put ``kind`` at ``path``; returns whether it is still there, as it was."""
    if kind == "fifo":
        os.mkfifo(path)
        return lambda: stat.S_ISFIFO(os.lstat(path).st_mode)
    if kind == "symlink":
        target = path.parent / "target-of-the-link"
        target.write_bytes(b"kept")
        path.symlink_to(target)
        return lambda: path.is_symlink() and target.read_bytes() == b"kept"
    if kind == "socket":
        with socket.socket(socket.AF_UNIX) as s:  # its file stays
            s.bind(str(path))
        return lambda: stat.S_ISSOCK(os.lstat(path).st_mode)
    path.mkdir()
    return lambda: path.is_dir() and not any(path.iterdir())


@pytest.mark.parametrize("kind", ["fifo", "symlink", "socket", "directory"])
@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_command_refuses_a_target_that_is_no_regular_file_before_it_writes(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str, kind: str
) -> None:
    inputs = _inputs(tmp_path)
    base = COMMANDS[command](inputs, tmp_path / "probe")
    for n, target in enumerate(_outputs(base)):
        out = tmp_path / f"out-{n}"
        argv = COMMANDS[command](inputs, out)
        path = _outputs(argv)[n]
        path.parent.mkdir(parents=True)
        kept = _in_the_way(path, kind)
        assert covmap.cli.main(argv) == 1, f"{command}: {target.name} as a {kind} was not refused"
        err = capsys.readouterr().err
        assert err.startswith(f"covmap {command}: error: ") and str(path) in err and "not a regular file" in err, err
        assert "Traceback" not in err
        assert kept(), f"{command} changed the {kind} at {path}"
        others = [p for p in path.parent.iterdir() if p != path and p.name != "target-of-the-link"]
        assert not others, f"{command} wrote {others} although {path.name} was refused"


@pytest.mark.parametrize("command", ["fig2", "world", "sweep", "map", "gain", "explore", "benchmark", "view"])
def test_the_outputs_are_the_files_a_command_writes(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str
) -> None:
    inputs = _inputs(tmp_path)
    out = tmp_path / "out"
    argv = COMMANDS[command](inputs, out)
    assert covmap.cli.main(argv) in (0, 1), capsys.readouterr().err  # explore: 1 at its step limit
    written = sorted(p for p in out.rglob("*") if p.is_file())
    assert written == sorted(_outputs(argv))
