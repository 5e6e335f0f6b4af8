"""Running ``aiobt up`` (or another system command) as a process and reading its output."""

from __future__ import annotations

import os
import queue
import select
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import IO

from aiobt.system.lifeline import popen_bound

WAIT = 90.0  # s for the whole system to come up on a loaded 2-core machine


class OutputLines:
    """A process's output read line by line on a thread: :attr:`lines` so far."""

    def __init__(self, stream: IO[str]) -> None:
        self.lines: list[str] = []
        self._queue: queue.Queue[str | None] = queue.Queue()
        threading.Thread(target=self._pump, args=(stream,), daemon=True).start()

    def _pump(self, stream: IO[str]) -> None:
        for line in stream:
            self._queue.put(line.rstrip("\n"))
        self._queue.put(None)

    def first(self, text: str, timeout: float) -> str | None:
        """The first line holding ``text``, waiting up to ``timeout`` s for it; None if the
        output ends or the time passes first."""
        deadline = time.monotonic() + timeout
        for line in self.lines:
            if text in line:
                return line
        while (left := deadline - time.monotonic()) > 0:
            try:
                got = self._queue.get(timeout=left)
            except queue.Empty:
                break
            if got is None:
                break
            self.lines.append(got)
            if text in got:
                return got
        return None

    def drain(self) -> list[str]:
        """:attr:`lines` with every line read so far."""
        while True:
            try:
                got = self._queue.get_nowait()
            except queue.Empty:
                return self.lines
            if got is not None:
                self.lines.append(got)


class SystemProcess:
    """``python -m aiobt.cli.main ARGS`` with stdout read line by line on a thread."""

    def __init__(self, args: list[str], cwd: Path | None = None) -> None:
        self.proc: subprocess.Popen[str] = popen_bound(
            [sys.executable, "-m", "aiobt.cli.main", *args],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            cwd=cwd,
            env={**os.environ, "NO_COLOR": "1"},
        )
        assert self.proc.stdout is not None
        self.output = OutputLines(self.proc.stdout)

    @property
    def lines(self) -> list[str]:
        return self.output.lines

    def wait_line(self, text: str, timeout: float = WAIT) -> str:
        """The first output line containing ``text``; AssertionError after ``timeout``."""
        line = self.output.first(text, timeout)
        if line is None:
            raise AssertionError(f"no line with {text!r} in:\n" + "\n".join(self.lines[-60:]))
        return line

    def stop(self, sig: int = signal.SIGTERM, timeout: float = 10.0) -> tuple[int, float]:
        """Send ``sig``; (exit code, seconds until exit)."""
        began = time.monotonic()
        self.proc.send_signal(sig)
        code = self.proc.wait(timeout)
        return code, time.monotonic() - began

    def finish(self, timeout: float = WAIT) -> tuple[int, str]:
        """Wait for the exit: (code, stderr)."""
        assert self.proc.stderr is not None
        err = self.proc.stderr.read()
        return self.proc.wait(timeout), err

    def __enter__(self) -> SystemProcess:
        return self

    def __exit__(self, *_: object) -> None:
        """Kill the process if it still runs (by PID), and close its pipes."""
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(10)
        for pipe in (self.proc.stdout, self.proc.stderr):
            if pipe is not None:
                pipe.close()


def processes_mentioning(text: str) -> list[str]:
    """Command lines of live processes (not zombies) whose arguments contain ``text``."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            cmdline = (entry / "cmdline").read_bytes().replace(b"\0", b" ").decode()
            state = (entry / "stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if text in cmdline and state != "Z":
            found.append(f"{entry.name}: {cmdline}")
    return found


def kill_mentioning(text: str) -> None:
    """Kill, by PID, any process left with ``text`` in its arguments (a failed test's)."""
    for line in processes_mentioning(text):
        pid = int(line.split(":", 1)[0])
        if pid != os.getpid():
            os.kill(pid, signal.SIGKILL)


def wait_gone(pids: list[int], timeout: float) -> list[int]:
    """Wait (on pidfds, no polling) until every process in ``pids`` has exited, at most
    ``timeout`` s: the pids still running (not zombies) then."""
    fds = {}
    for pid in pids:
        try:
            fds[os.pidfd_open(pid)] = pid
        except ProcessLookupError:
            continue
    try:
        waiting = select.poll()
        for fd in fds:
            waiting.register(fd, select.POLLIN)
        deadline = time.monotonic() + timeout
        left = set(fds)
        while left and (remaining := deadline - time.monotonic()) > 0:
            for fd, _ in waiting.poll(remaining * 1000):
                waiting.unregister(fd)
                left.discard(fd)
        return sorted(fds[fd] for fd in left)
    finally:
        for fd in fds:
            os.close(fd)
