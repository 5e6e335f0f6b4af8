"""Test helpers for real Zenoh on loopback: a router process, service processes.

Processes start with ``subprocess`` (fork+exec: a forked Zenoh process hangs)
and are stopped by PID. Their output goes to a log file, shown on failure.
Each dies with the process that started it (SIGTERM on Linux, even when that is
SIGKILLed: :func:`aiobt.system.lifeline.popen_bound`); a test's or benchmark's
own SIGTERM stops them in order when it calls :func:`exit_on_sigterm`.
:func:`service_main` is the other end: the ``main`` of such a process.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import os
import signal
import socket
import subprocess
import sys
import tempfile
import time
import uuid
from collections.abc import AsyncIterator, Callable, Iterator, Mapping, Sequence
from pathlib import Path

from aiobt.system.lifeline import popen_bound
from aiobt.transport import Bus, BusSettings, add_bus_arguments, open_bus
from aiobt.transport.endpoints import LOOPBACK
from aiobt.transport.endpoints import free_endpoint as free_endpoint  # for the tests
from aiobt.transport.endpoints import free_port as free_port


def port_of(endpoint: str) -> int:
    return int(endpoint.rsplit(":", 1)[1])


def wait_port(port: int, timeout: float = 10.0, host: str = LOOPBACK) -> bool:
    """True once something accepts TCP connections on ``port``."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        with contextlib.suppress(OSError), socket.create_connection((host, port), timeout=0.2):
            return True
        time.sleep(0.02)
    return False


class ServiceProcess:
    """A child Python process (``python ARGS``), stopped by PID; it gets SIGTERM if
    this process dies first."""

    def __init__(self, args: Sequence[str], env: Mapping[str, str] | None = None) -> None:
        self.args = list(args)
        handle, name = tempfile.mkstemp(prefix="aiobt-proc-", suffix=".log")
        os.close(handle)
        self.log_path = Path(name)
        with self.log_path.open("wb") as log_file:
            self.popen: subprocess.Popen[bytes] = popen_bound(
                [sys.executable, *self.args],
                stdout=log_file,
                stderr=subprocess.STDOUT,
                stdin=subprocess.DEVNULL,
                env={**os.environ, **(env or {})},
            )

    @property
    def pid(self) -> int:
        return self.popen.pid

    @property
    def running(self) -> bool:
        return self.popen.poll() is None

    def output(self) -> str:
        return self.log_path.read_text(errors="replace") if self.log_path.exists() else ""

    def wait_for_output(self, text: str, timeout: float = 10.0) -> bool:
        """True once ``text`` appears in the process's output (False on timeout or exit)."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if text in self.output():
                return True
            if not self.running:
                return text in self.output()
            time.sleep(0.02)
        return False

    def kill(self) -> None:
        """SIGKILL by PID (a crash), and reap."""
        if self.running:
            os.kill(self.pid, signal.SIGKILL)
        self.popen.wait(timeout=10)

    def stop(self, timeout: float = 5.0) -> int:
        """SIGTERM, then SIGKILL after ``timeout``; returns the exit code."""
        if self.running:
            os.kill(self.pid, signal.SIGTERM)
            try:
                self.popen.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                os.kill(self.pid, signal.SIGKILL)
                self.popen.wait(timeout=10)
        return int(self.popen.returncode)

    def cleanup(self) -> None:
        self.stop()
        with contextlib.suppress(OSError):
            self.log_path.unlink()


def spawn_service(args: Sequence[str], env: Mapping[str, str] | None = None) -> ServiceProcess:
    """Start ``python ARGS`` (e.g. ``["-m", "aiobt_services.robot", "--connect", ep]``)."""
    return ServiceProcess(args, env)


def start_router(
    endpoint: str | None = None, extra_args: Sequence[str] = (), timeout: float = 10.0
) -> tuple[ServiceProcess, str]:
    """A router process listening on ``endpoint`` (a free loopback port by default)."""
    for _ in range(3):
        where = endpoint or free_endpoint()
        proc = spawn_service(["-m", "aiobt.cli.router", "--listen", where, *extra_args])
        if wait_port(port_of(where), timeout) and proc.running:
            return proc, where
        output = proc.output()
        proc.cleanup()
        if endpoint is not None:
            break
    raise RuntimeError(f"the router did not start on {where}:\n{output}")


@contextlib.contextmanager
def running_router(
    endpoint: str | None = None, extra_args: Sequence[str] = ()
) -> Iterator[tuple[ServiceProcess, str]]:
    proc, where = start_router(endpoint, extra_args)
    try:
        yield proc, where
    finally:
        proc.cleanup()


def exit_on_sigterm() -> None:
    """SIGTERM raises ``SystemExit`` in the main thread, as SIGINT raises
    ``KeyboardInterrupt``: a benchmark's ``finally`` blocks and ``with`` exits still stop
    the processes it started (Python's default SIGTERM ends it without them, leaving
    its stack running)."""

    def stop(signum: int, frame: object) -> None:
        raise SystemExit(128 + signum)

    signal.signal(signal.SIGTERM, stop)


def service_main(declare: Callable[[Bus], object]) -> int:
    """``main`` of a test or benchmark service process (bus options from the command line):
    opens the bus, ``declare(bus)``, prints ``ready``, serves until SIGINT or SIGTERM.
    What ``declare`` returns is kept referenced until then (e.g. raw Zenoh entities)."""
    parser = argparse.ArgumentParser()
    add_bus_arguments(parser)
    asyncio.run(_serve(BusSettings.from_args(parser.parse_args()), declare))
    return 0


async def _serve(settings: BusSettings, declare: Callable[[Bus], object]) -> None:
    stop = asyncio.Event()
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):  # before opening: a stop is never missed
        loop.add_signal_handler(sig, stop.set)
    async with open_bus(settings) as bus:
        declared = declare(bus)
        print("ready", flush=True)
        await stop.wait()
        del declared  # undeclared with the session


@contextlib.asynccontextmanager
async def open_local_bus(namespace: str | None = None) -> AsyncIterator[Bus]:
    """An in-process bus: a Zenoh peer listening on a free loopback port, no router.

    Publishers, subscribers, services and actions declared on it reach each other
    within the process (Zenoh delivers within one session), so nodes and servers
    can be tested together without a router process. ``namespace`` defaults to a
    fresh one, so tests never hear each other.
    """
    settings = BusSettings(
        mode="peer",
        listen=(f"tcp/{LOOPBACK}:0",),
        namespace=namespace or f"t{uuid.uuid4().hex[:10]}",
    )
    async with open_bus(settings) as bus:
        yield bus
