"""The supervisor with real (tiny) child processes: output, restarts, fatal exits, stop."""

from __future__ import annotations

import asyncio
import os
import sys
import time
from collections.abc import Callable

import pytest

from aiobt.system.config import RestartConfig
from aiobt.system.supervisor import Child, Supervisor

WAIT = 20.0  # s: generous bound for anything a child does on a loaded machine
SLEEP = "__import__('time').sleep(60)"  # a child that stays until it is stopped


class Recorder:
    """A sink that keeps lines and events, and can react to a line."""

    def __init__(self) -> None:
        self.lines: list[tuple[str, str]] = []
        self.events: list[tuple[str, str]] = []
        self.on_line: Callable[[str, str], None] = lambda name, text: None
        self.changed = asyncio.Event()

    def line(self, name: str, text: str) -> None:
        self.lines.append((name, text))
        self.on_line(name, text)
        self.changed.set()

    def event(self, name: str, text: str) -> None:
        self.events.append((name, text))
        self.changed.set()

    async def until(self, check: Callable[[], bool]) -> None:
        async with asyncio.timeout(WAIT):
            while not check():
                self.changed.clear()
                await self.changed.wait()


def _python(code: str) -> list[str]:
    return [sys.executable, "-c", code]


def _gone(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    return False


async def test_output_is_forwarded_line_by_line_under_the_child_name() -> None:
    sink = Recorder()
    supervisor = Supervisor(RestartConfig(), sink)
    await supervisor.start(Child("talker", _python(f"print('one'); print('two'); {SLEEP}")))
    try:
        await sink.until(lambda: len(sink.lines) == 2)
        assert sink.lines == [("talker", "one"), ("talker", "two")]
    finally:
        await supervisor.stop()


async def test_a_child_that_fails_before_it_was_ever_healthy_is_fatal_and_named() -> None:
    sink = Recorder()
    supervisor = Supervisor(RestartConfig(), sink)
    code = "import sys; print('robot: world nowhere.yaml: no such file'); sys.exit(2)"
    await supervisor.start(Child("robot", _python(code)))
    try:
        async with asyncio.timeout(WAIT):
            reason = await supervisor.fatal
        assert reason == (
            "robot failed to start (exited with code 2: robot: world nowhere.yaml: no such file)"
        )
    finally:
        await supervisor.stop()


async def test_a_crash_after_being_up_restarts_with_doubling_back_off_then_gives_up() -> None:
    sink = Recorder()
    restart = RestartConfig(backoff=0.1, max_backoff=0.3, max_restarts=3, window=60.0)
    supervisor = Supervisor(restart, sink)
    sink.on_line = lambda name, text: supervisor.mark_healthy(name, text == "ready")
    code = f"print('ready', flush=True); {SLEEP}"
    child = Child("planner", _python(code))
    await supervisor.start(child)
    try:
        pids = set()
        for _ in range(4):  # the first run and three restarts, each ended by a SIGTERM
            await sink.until(lambda: child.healthy and child.pid not in pids)
            assert child.process is not None
            pids.add(child.pid)
            child.process.terminate()
        async with asyncio.timeout(WAIT):
            reason = await supervisor.fatal
        assert "planner killed by signal 15 (SIGTERM);" in str(reason)
        assert "4 crashes in 60 s, giving up" in str(reason)
        crashes = [text for name, text in sink.events if text.startswith("crashed")]
        assert [c.rsplit("restart in ", 1)[1] for c in crashes] == ["0.1 s", "0.2 s", "0.3 s"]
        assert [text for _, text in sink.events].count("up") == 4
    finally:
        await supervisor.stop()


async def test_stop_terminates_and_kills_a_child_that_ignores_sigterm_within_the_grace() -> None:
    sink = Recorder()
    supervisor = Supervisor(RestartConfig(), sink)
    stubborn = f"import signal; signal.signal(signal.SIGTERM, signal.SIG_IGN); print('x'); {SLEEP}"
    await supervisor.start(Child("stubborn", _python(stubborn)))
    await supervisor.start(Child("polite", _python(f"print('x'); {SLEEP}")))
    await sink.until(lambda: len(sink.lines) == 2)
    pids = supervisor.pids()
    began = time.monotonic()
    await supervisor.stop(keep=("polite",), grace=0.5)
    assert supervisor.children["polite"].process.returncode is None  # type: ignore[union-attr]
    await supervisor.stop(grace=0.5)
    assert time.monotonic() - began < 2.0
    codes = {name: c.process.returncode for name, c in supervisor.children.items() if c.process}
    assert codes == {"polite": -15, "stubborn": -9}
    assert all(_gone(pid) for pid in pids)
    assert not any(text.startswith("restarting") for _, text in sink.events)


@pytest.mark.parametrize("healthy", [True, False])
async def test_health_changes_are_reported_once(healthy: bool) -> None:
    sink = Recorder()
    supervisor = Supervisor(RestartConfig(), sink)
    await supervisor.start(Child("robot", _python(SLEEP)))
    try:
        supervisor.mark_healthy("robot", True)
        supervisor.mark_healthy("robot", True)
        if not healthy:
            supervisor.mark_healthy("robot", False)
        expected = ["up"] if healthy else ["up", "no longer answering (token gone)"]
        assert [text for _, text in sink.events] == expected
    finally:
        await supervisor.stop()
