"""A small process supervisor: start, watch, restart with back-off, stop everything.

Each :class:`Child` is one process (its own session, so a terminal's Ctrl-C
reaches only the supervisor, which stops the children in order); a child
dies with the supervisor even when that is SIGKILLed (:mod:`.lifeline`). Its output is
read line by line and handed to a :class:`LogSink` with the child's name. A
child that exits while the supervisor runs is restarted after a back-off that
doubles per crash. An exit before the child ever became healthy (it failed to
start: a bad flag, a taken port, a bad world file) or too many crashes in a
window is fatal: :attr:`Supervisor.fatal` gets the reason.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import os
import re
import signal
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Protocol

from aiobt.core.clock import SystemClock
from aiobt.system.config import RestartConfig
from aiobt.system.lifeline import child_env

log = logging.getLogger("aiobt.system.supervisor")
_TAIL = 5  # last output lines kept per child, for the report when it dies
_REAP = 0.5  # s to wait for a SIGKILLed child to be reaped
_LOG_PREFIX = re.compile(r"^\d{4}-\d\d-\d\d [\d:,.]+ [A-Z] [\w.]+: ")


class LogSink(Protocol):
    def line(self, name: str, text: str) -> None: ...

    def event(self, name: str, text: str) -> None: ...


@dataclass(slots=True)
class Child:
    name: str
    argv: Sequence[str]
    env: dict[str, str] | None = None
    process: asyncio.subprocess.Process | None = None
    healthy: bool = False
    ever_healthy: bool = False
    crashes: list[float] = field(default_factory=list)
    tail: list[str] = field(default_factory=list)
    reader: asyncio.Task[None] | None = None

    @property
    def pid(self) -> int | None:
        return self.process.pid if self.process else None

    def last_words(self) -> str:
        """The child's last output line, without a log record's time/level/logger prefix."""
        return _LOG_PREFIX.sub("", self.tail[-1]) if self.tail else "no output"


class Fatal(Exception):
    """A child that cannot be kept running; the message says which and why."""


class Supervisor:
    """Runs :class:`Child` processes until :meth:`stop`; see the module docstring."""

    def __init__(self, restart: RestartConfig, sink: LogSink) -> None:
        self.restart = restart
        self.sink = sink
        self.children: dict[str, Child] = {}
        self.fatal: asyncio.Future[object] = asyncio.get_running_loop().create_future()
        self._watchers: list[asyncio.Task[None]] = []
        self._stopping = False
        self._clock = SystemClock()

    async def start(self, child: Child) -> None:
        """Start ``child`` and keep it running (restarts included) until :meth:`stop`."""
        self.children[child.name] = child
        await self._spawn(child)
        self._watchers.append(asyncio.create_task(self._watch(child)))

    def mark_healthy(self, name: str, healthy: bool) -> None:
        child = self.children.get(name)
        if child is None or child.healthy == healthy:
            return
        child.healthy = healthy
        child.ever_healthy |= healthy
        if not self._stopping:
            self.sink.event(name, "up" if healthy else "no longer answering (token gone)")

    async def _spawn(self, child: Child) -> None:
        env = {**os.environ, "PYTHONUNBUFFERED": "1", **child_env(), **(child.env or {})}
        child.process = await asyncio.create_subprocess_exec(
            *child.argv,
            stdin=asyncio.subprocess.DEVNULL,
            stdout=asyncio.subprocess.PIPE,
            stderr=asyncio.subprocess.STDOUT,
            env=env,
            start_new_session=True,
        )
        child.reader = asyncio.create_task(self._read(child, child.process))
        log.debug("%s started, pid %d", child.name, child.process.pid)

    async def _read(self, child: Child, process: asyncio.subprocess.Process) -> None:
        assert process.stdout is not None
        async for raw in process.stdout:
            text = raw.decode(errors="replace").rstrip()
            child.tail = [*child.tail[-_TAIL + 1 :], text]
            self.sink.line(child.name, text)

    async def _watch(self, child: Child) -> None:
        while not self._stopping:
            assert child.process is not None
            assert child.reader is not None
            code = await child.process.wait()
            await child.reader
            if self._stopping:
                return
            child.healthy = False
            delay = self._after_exit(child, code)
            if delay is None:
                return
            await asyncio.sleep(delay)
            if self._stopping:
                return
            self.sink.event(child.name, f"restarting (crash {len(child.crashes)})")
            await self._spawn(child)

    def _after_exit(self, child: Child, code: int) -> float | None:
        """The back-off before restarting ``child``, or None when its exit is fatal."""
        now = self._clock.now()
        child.crashes = [t for t in child.crashes if now - t < self.restart.window] + [now]
        why = exit_reason(code, child.last_words())
        if not child.ever_healthy:
            self._give_up(f"{child.name} failed to start ({why})")
            return None
        if len(child.crashes) > self.restart.max_restarts:
            count, window = len(child.crashes), self.restart.window
            self._give_up(f"{child.name} {why}; {count} crashes in {window:g} s, giving up")
            return None
        backoff = self.restart.backoff * 2.0 ** (len(child.crashes) - 1)
        delay = min(backoff, self.restart.max_backoff)
        self.sink.event(child.name, f"crashed ({why}); restart in {delay:.1f} s")
        return delay

    def _give_up(self, message: str) -> None:
        if not self.fatal.done():
            self.fatal.set_result(message)

    async def stop(self, keep: Sequence[str] = (), grace: float = 1.0) -> None:
        """Stop every child but ``keep`` (no more restarts of any): SIGTERM together,
        SIGKILL what is left after ``grace`` s. A second call stops the kept ones."""
        self._stopping = True
        for task in self._watchers:
            task.cancel()
        await asyncio.gather(*self._watchers, return_exceptions=True)
        await self._terminate([c for n, c in self.children.items() if n not in keep], grace)

    async def _terminate(self, children: list[Child], grace: float) -> None:
        running = [c for c in children if c.process and c.process.returncode is None]
        for child in running:
            _signal(child, signal.SIGTERM)
        waits = [asyncio.create_task(_wait_exit(c)) for c in running]
        if not waits:
            return
        _done, late = await asyncio.wait(waits, timeout=grace)
        for child in running:
            if child.process and child.process.returncode is None:
                self.sink.event(child.name, f"did not stop within {grace:g} s: killed")
                _signal(child, signal.SIGKILL)
        if late:
            await asyncio.wait(late, timeout=_REAP)

    def pids(self) -> list[int]:
        return [c.pid for c in self.children.values() if c.pid is not None]


def exit_reason(code: int, last_words: str) -> str:
    """``killed by signal 9 (SIGKILL)``: a signal says it all (the last line printed is
    no reason); ``exited with code 1: <its last words>`` otherwise."""
    if code < 0:
        try:
            name = f" ({signal.Signals(-code).name})"
        except ValueError:
            name = ""
        return f"killed by signal {-code}{name}"
    return f"exited with code {code}: {last_words}"


async def _wait_exit(child: Child) -> None:
    assert child.process is not None
    await child.process.wait()
    if child.reader is not None:
        with contextlib.suppress(Exception):
            async with asyncio.timeout(0.5):  # on time-out the reader is cancelled
                await child.reader


def _signal(child: Child, sig: signal.Signals) -> None:
    assert child.process is not None
    with contextlib.suppress(ProcessLookupError):
        os.killpg(child.process.pid, sig)


def on_signals(callback: Callable[[], None]) -> None:
    """Call ``callback`` on SIGINT or SIGTERM (inside the running loop)."""
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, callback)
