"""Running the README's shell lines as written, on this test's router and ports.

:func:`command_lines` reads the commands of every ``bash`` block (comments dropped,
``\\`` continuations joined, a ``for ... done`` loop as one command).
:class:`Shell` runs one through bash in a scratch directory, with the README's
fixed router endpoints (``tcp/127.0.0.1:7447``, and the two-machine example's)
replaced by the test's, and the test's router added to the client commands
that connect to the default one. A long-running command is a :class:`Terminal`:
its output read line by line, stopped with Ctrl-C (SIGINT to its process group,
by its id) and killed if still there when the test leaves it.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import time
from dataclasses import dataclass
from pathlib import Path

from aiobt.system.lifeline import popen_bound
from tests.integration.system.helpers import OutputLines
from tests.unit.cli.test_readme import _blocks

WAIT = 120.0  # s for a command or a line of output (a loaded 2-core machine)
README_ROUTERS = ("tcp/127.0.0.1:7447", "tcp/0.0.0.0:7447", "tcp/192.168.1.10:7447")
CLIENTS = ("status", "navigate", "goal", "monitor", "foxglove", "web")  # default router


def command_lines() -> list[str]:
    """Every command of the README's bash blocks, as one line each."""
    commands: list[str] = []
    for block in _blocks("bash"):
        loop: list[str] = []
        for raw in block.replace("\\\n", " ").splitlines():
            line = re.sub(r"\s+#\s.*$", "", raw).strip()
            if not line or line.startswith("#"):
                continue
            if loop or line.startswith("for "):
                loop.append(line)
                if line == "done":
                    commands.append(" ".join(loop))
                    loop = []
                continue
            commands.append(re.sub(r"\s+", " ", line))
    return commands


@dataclass(frozen=True, slots=True)
class Shell:
    cwd: Path
    endpoint: str

    def localise(self, line: str, extra: tuple[str, ...], port: str | None) -> str:
        for readme_router in README_ROUTERS:
            line = line.replace(readme_router, self.endpoint)
        words = line.split()
        if words[0] == ".venv/bin/aiobt" and words[1] in CLIENTS and "--connect" not in words:
            extra = ("--connect", self.endpoint, *extra)
        if port is not None:
            line = re.sub(r"--port \d+", f"--port {port}", line)
        return " ".join([line, *extra])

    def run(self, line: str, *extra: str, timeout: float = WAIT) -> str:
        """Run ``line`` to its end; its stdout (AssertionError, with its output, unless 0)."""
        command = self.localise(line, extra, None)
        done = subprocess.run(
            ["bash", "-c", command], cwd=self.cwd, capture_output=True, text=True,
            timeout=timeout, check=False, env=self.env(),
        )  # fmt: skip
        assert done.returncode == 0, (
            f"{command}: exit {done.returncode}\n{done.stdout}{done.stderr}"
        )
        return done.stdout

    def start(self, line: str, *extra: str, port: str | None = None) -> Terminal:
        return Terminal(self.localise(line, extra, port), self.cwd, self.env())

    def env(self) -> dict[str, str]:
        return {**os.environ, "NO_COLOR": "1", "PYTHONPATH": str(self.cwd)}


class Terminal:
    """A long-running command: stdout and stderr read line by line on a thread."""

    def __init__(self, command: str, cwd: Path, env: dict[str, str]) -> None:
        self.command = command
        self.proc: subprocess.Popen[str] = popen_bound(
            ["bash", "-c", command], cwd=cwd, env=env, text=True, start_new_session=True,
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
        )  # fmt: skip
        assert self.proc.stdout is not None
        self.output = OutputLines(self.proc.stdout)

    def wait_for(self, text: str, timeout: float = WAIT) -> str:
        """The first line holding ``text``; AssertionError (with the output) after ``timeout``."""
        line = self.output.first(text, timeout)
        if line is None:
            raise AssertionError(f"{self.command}: no line with {text!r} in:\n{self.text()}")
        return line

    def interrupt(self, within: float = 10.0) -> int:
        """Ctrl-C: SIGINT to its process group; its exit code (AssertionError if it takes
        longer than ``within`` s)."""
        began = time.monotonic()
        os.killpg(self.proc.pid, signal.SIGINT)
        code = self.proc.wait(WAIT)
        took = time.monotonic() - began
        assert took < within, f"{self.command}: stopped after {took:.1f} s\n{self.text()}"
        return code

    def text(self) -> str:
        return "\n".join(self.output.drain()[-80:])

    def __enter__(self) -> Terminal:
        return self

    def __exit__(self, *_: object) -> None:
        """Kill its process group (by its id) if it still runs; close the pipe."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGKILL)
            self.proc.wait(10)
        if self.proc.stdout is not None:
            self.proc.stdout.close()
