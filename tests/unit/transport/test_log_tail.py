"""LogTail: writes to the descriptor never wait for the reader; every line comes back,
in order, across the files it swaps in."""

from __future__ import annotations

import os
import threading
from collections.abc import Iterator

import pytest

from aiobt.transport import log_tail
from aiobt.transport.log_tail import LogTail

pytestmark = pytest.mark.timeout(30)


@pytest.fixture
def target() -> Iterator[int]:
    fd = os.open(os.devnull, os.O_WRONLY)  # a descriptor to take over
    yield fd
    os.close(fd)


def _line(i: int) -> bytes:
    return f"line {i:06d} {'x' * 200}\n".encode()


@pytest.mark.parametrize("thread", [True, False])
def test_every_line_comes_back_in_order_across_swaps(target: int, thread: bool) -> None:
    got: list[str] = []
    tail = LogTail(target, got.append, rotate=10_000, start=thread)  # swapped every ~45 lines
    for i in range(2000):
        os.write(target, _line(i))
        if not thread and i % 7 == 0:
            tail.read_once()
    tail.close()
    assert [line.split()[1] for line in got] == [f"{i:06d}" for i in range(2000)]


def test_a_reader_held_off_never_makes_a_writer_wait(
    target: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The reader does not run at all while 20 MB are written (a pipe would have
    blocked the writer after its 64 KiB to 1 MiB)."""
    held = threading.Event()
    monkeypatch.setattr(log_tail, "POLL", 0.01)
    got: list[str] = []

    def slow(line: str) -> None:
        held.wait()
        got.append(line)

    tail = LogTail(target, slow)
    written = threading.Event()

    def write() -> None:
        for i in range(80_000):  # 20 MB
            os.write(target, _line(i))
        written.set()

    writer = threading.Thread(target=write)
    writer.start()
    assert written.wait(20.0), "the writer was held"
    held.set()
    writer.join()
    tail.close(timeout=20.0)
    assert len(got) == 80_000  # and the reader catches up


def test_a_line_without_its_end_yet_waits_for_it(target: int) -> None:
    got: list[str] = []
    tail = LogTail(target, got.append, start=False)
    os.write(target, b"half a ")
    tail.read_once()
    assert got == []
    os.write(target, b"line\n")
    tail.close()
    assert got == ["half a line"]
