"""Progress shown by the commands: plain lines where the stream is not a
terminal, counts that count what they say."""

from __future__ import annotations

import io

import pytest

from covmap._progress import Progress


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def _run(total: int | None, items: int, stream: io.StringIO) -> str:
    with Progress(total, "scans", stream=stream) as progress:
        for i in range(items):
            progress.update(f"item {i}")
    return stream.getvalue()


@pytest.mark.parametrize("total", [1, 7, 10, 910, 100_000])
def test_a_known_total_off_a_terminal_gives_plain_lines_at_each_tenth(total: int) -> None:
    text = _run(total, total, io.StringIO())
    assert "\r" not in text and "\x1b" not in text
    lines = text.splitlines()
    assert 1 <= len(lines) <= 11
    assert lines[0].startswith("scans 1/")
    assert lines[-1] == f"scans {total}/{total}: item {total - 1}"
    counts = [int(line.split()[1].split("/")[0]) for line in lines]
    assert counts == sorted(set(counts))


def test_an_unknown_total_off_a_terminal_gives_lines_at_1_2_5_10_and_the_end() -> None:
    lines = _run(None, 73, io.StringIO()).splitlines()
    assert [line.split(":")[0] for line in lines] == [f"scans {n}" for n in (1, 2, 5, 10, 20, 50, 73)]


def test_a_task_cut_short_ends_with_its_last_count() -> None:
    assert _run(910, 455, io.StringIO()).splitlines()[-1] == "scans 455/910: item 454"


def test_nothing_done_writes_nothing() -> None:
    assert _run(10, 0, io.StringIO()) == ""


def test_on_a_terminal_the_line_rewrites_itself() -> None:
    stream = _Terminal()
    progress = Progress(3, "runs", stream=stream)
    if progress.bar is not None:  # tqdm draws its own bar on a terminal
        progress.bar.close()
        pytest.skip("tqdm is installed: the bar is tqdm's")
    with progress:
        for _ in range(3):
            progress.update()
    assert stream.getvalue().count("\r") == 3 and stream.getvalue().endswith("runs 3/3\x1b[K\n")
