"""A file descriptor whose writes never block, read back line by line: Zenoh's log.

Zenoh writes its log from the threads that route messages; with access control, a
line per message routed (``aiobt.transport.access_refusals``). Into a pipe, a write
blocks once the pipe is full, that is once the process's reader has been kept off
the CPU long enough (a loaded machine): routing then waits for the log, and messages
arrive late (bench/history/deploy.md: a reader held for 5 s delayed poses by up to
3.9 s). Here the descriptor is a file in memory (``memfd``) opened for appending,
which never makes a writer wait. A thread reads what was appended every ``POLL``
seconds; once a file holds ``ROTATE`` bytes, all read, a fresh file takes the
descriptor's place (``dup2``: atomic, nothing is lost) and the old one is read to
its end, then closed. A starved reader costs memory, never the writers' time.
"""

from __future__ import annotations

import fcntl
import os
import tempfile
import threading
from collections.abc import Callable
from dataclasses import dataclass

POLL = 0.05  # s between reads
ROTATE = 1 << 20  # bytes a file holds before a fresh one replaces it


def _memory_file() -> int:
    """A new file in memory, for appending (a temporary file where memfd is missing)."""
    if hasattr(os, "memfd_create"):
        fd = os.memfd_create("aiobt-log", os.MFD_CLOEXEC)
    else:  # pragma: no cover - not Linux
        with tempfile.TemporaryFile() as file:
            fd = os.dup(file.fileno())
    fcntl.fcntl(fd, fcntl.F_SETFL, fcntl.fcntl(fd, fcntl.F_GETFL) | os.O_APPEND)
    return fd


@dataclass(slots=True)
class _File:
    fd: int
    offset: int = 0
    partial: bytes = b""

    def drain(self, on_line: Callable[[str], None]) -> None:
        while chunk := os.pread(self.fd, 65536, self.offset):
            self.offset += len(chunk)
            *lines, self.partial = (self.partial + chunk).split(b"\n")
            for line in lines:
                on_line(line.decode("utf-8", errors="replace"))


class LogTail:
    """Takes over descriptor ``target`` (what is written to it lands in a file in memory)
    and calls ``on_line`` with each complete line written, in order, from a thread."""

    def __init__(
        self,
        target: int,
        on_line: Callable[[str], None],
        rotate: int = ROTATE,
        *,
        start: bool = True,  # False: no thread, the caller calls read_once()
    ) -> None:
        self._target = target
        self._on_line = on_line
        self._rotate = rotate
        self._current = _File(_memory_file())
        self._old: _File | None = None  # replaced last round: a write may still land in it
        self._stop = threading.Event()
        os.dup2(self._current.fd, target)
        self._thread = threading.Thread(target=self._run, name="log-tail", daemon=True)
        if start:
            self._thread.start()

    def _run(self) -> None:
        while not self._stop.wait(POLL):
            self.read_once()
        self.read_once()

    def read_once(self) -> None:
        """Pass on what was appended since the last read; replace a full file."""
        if self._old is not None:  # a round after the swap: its last writes have landed
            self._old.drain(self._on_line)
            os.close(self._old.fd)
            self._old = None
        self._current.drain(self._on_line)
        if self._current.offset >= self._rotate:
            self._old, self._current = self._current, _File(_memory_file())
            os.dup2(self._current.fd, self._target)  # atomic: new writes go to the new file

    def close(self, timeout: float = 1.0) -> None:
        """Stop after a last read (the descriptor keeps writing to the file)."""
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout)
        else:
            self.read_once()
