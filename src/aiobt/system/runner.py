"""The whole system on one machine: a router, then every service, watched and kept up.

    async with run_system(config, ConsoleSink()) as system:
        await system.wait_healthy(timeout=30.0)
        ...                               # navigate, monitor; system.bus is a client
        await system.stopped()            # SIGINT/SIGTERM, or a fatal service failure

Health comes from the liveliness tokens ``{ns}/nodes/<service>``; the router is
healthy once this process's own bus reaches it.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import socket
from collections.abc import AsyncIterator, Callable
from typing import Any
from urllib.parse import urlsplit

from aiobt.system.catalog import COMPOSITIONS
from aiobt.system.commands import (
    available,
    identity_config,
    process_argv,
    processes,
    router_command,
    service_command,
)
from aiobt.system.config import SystemConfig
from aiobt.system.supervisor import Child, Fatal, LogSink, Supervisor
from aiobt.transport import Bus, BusConfigError, BusSettings, BusUnavailable, open_bus

log = logging.getLogger("aiobt.system.runner")
ROUTER_TIMEOUT = 30.0  # s for the router to accept this process's session (a loaded machine)
_PORT_POLL = 0.05  # s between probes of the router's port while it starts


class System:
    """The running services (see :func:`run_system`)."""

    def __init__(self, config: SystemConfig, supervisor: Supervisor, services: list[str]) -> None:
        self.config = config
        self.supervisor = supervisor
        self.services = services
        self.bus: Bus | None = None
        self._up: dict[str, asyncio.Event] = {name: asyncio.Event() for name in services}

    def _watch(self, bus: Bus) -> None:
        """Each process is up while every token it declares is: ``nodes/<service>``, one
        per service of a composition."""
        self.bus = bus
        for name in self.services:
            tokens = COMPOSITIONS.get(name, (name,))
            alive: dict[str, bool] = dict.fromkeys(tokens, False)
            for token in tokens:
                presence = bus.presence(f"{bus.namespace}/nodes/{token}")
                presence.add_listener(self._listener(name, token, alive))
                if presence.present:
                    alive[token] = True
            if all(alive.values()):
                self._set(name, True)

    def _listener(self, name: str, token: str, alive: dict[str, bool]) -> Callable[[bool], None]:
        def on_change(present: bool) -> None:
            alive[token] = present
            self._set(name, all(alive.values()))

        return on_change

    def _set(self, name: str, alive: bool) -> None:
        self.supervisor.mark_healthy(name, alive)
        if alive:
            self._up[name].set()
        else:
            self._up[name].clear()

    def healthy(self) -> dict[str, bool]:
        return {name: event.is_set() for name, event in self._up.items()}

    async def wait_healthy(self, timeout: float) -> list[str]:  # noqa: ASYNC109
        """Wait until every service is up: the ones still down after ``timeout`` s.

        Raises :class:`Fatal` if a service fails for good meanwhile.
        """
        fatal = self.supervisor.fatal
        loop = asyncio.get_running_loop()
        deadline = loop.time() + timeout
        pending: set[asyncio.Future[object]] = {
            asyncio.ensure_future(event.wait()) for event in self._up.values()
        }
        try:
            while pending and not fatal.done():
                left = deadline - loop.time()
                done, pending = await asyncio.wait(
                    {*pending, fatal}, timeout=left, return_when=asyncio.FIRST_COMPLETED
                )
                pending.discard(fatal)
                if not done:
                    break
        finally:
            for waiting in pending:
                waiting.cancel()
        if self.supervisor.fatal.done():
            raise Fatal(str(self.supervisor.fatal.result()))
        return [name for name, up in self.healthy().items() if not up]

    async def stopped(self, stop: asyncio.Event) -> str | None:
        """Wait for ``stop`` or a fatal failure: None, or the failure's reason."""
        stopper: asyncio.Future[object] = asyncio.ensure_future(stop.wait())
        try:
            await asyncio.wait({stopper, self.supervisor.fatal},
                               return_when=asyncio.FIRST_COMPLETED)  # fmt: skip
        finally:
            stopper.cancel()
        return str(self.supervisor.fatal.result()) if self.supervisor.fatal.done() else None


@contextlib.asynccontextmanager
async def run_system(config: SystemConfig, sink: LogSink) -> AsyncIterator[System]:
    """Start the router (unless ``router.start`` is false) and every enabled service;
    stop them all on exit (under 3 s). :class:`Fatal` names what could not start."""
    services = [name for name in processes(config) if _present(name, sink)]
    supervisor = Supervisor(config.restart, sink)
    system = System(config, supervisor, services)
    try:
        if config.router.start:
            _check_port_free(config.router.listen)
            await supervisor.start(Child("router", process_argv(router_command(config))))
            await _wait_listening(config.router.listen, supervisor)
        async with _open_client(config, supervisor) as bus:
            try:  # the services stop before this process's session closes
                supervisor.mark_healthy("router", True)
                system._watch(bus)
                for name in services:
                    argv = process_argv(service_command(name, config))
                    await supervisor.start(Child(name, argv))
                yield system
            finally:  # everything at once, so a loaded machine still stops within 3 s
                await supervisor.stop()
    finally:
        await supervisor.stop()


def _present(name: str, sink: LogSink) -> bool:
    if available(name):
        return True
    sink.event(name, "not installed in this version of aiobt: not started")
    return False


@contextlib.asynccontextmanager
async def _open_client(config: SystemConfig, supervisor: Supervisor) -> AsyncIterator[Bus]:
    """This process's bus on the router; :class:`Fatal` if the router fails or is absent."""
    settings = BusSettings(
        connect=(config.router.listen,),
        namespace=config.namespace,
        connect_timeout=ROUTER_TIMEOUT,
        config_file=identity_config(config, "supervisor") if config.router.certs else None,
    )
    async with contextlib.AsyncExitStack() as stack:
        opening: asyncio.Future[Any] = asyncio.ensure_future(
            stack.enter_async_context(open_bus(settings))
        )
        await asyncio.wait({opening, supervisor.fatal}, return_when=asyncio.FIRST_COMPLETED)
        if supervisor.fatal.done():
            opening.cancel()
            await asyncio.gather(opening, return_exceptions=True)
            raise Fatal(str(supervisor.fatal.result()))
        try:
            bus = opening.result()
        except (BusUnavailable, BusConfigError) as exc:
            raise Fatal(f"no Zenoh router at {config.router.listen}: {exc}") from None
        yield bus


def _tcp_address(endpoint: str) -> tuple[str, int] | None:
    protocol, _, address = endpoint.partition("/")
    parts = urlsplit(f"//{address}")
    if protocol not in ("tcp", "tls") or parts.port is None:
        return None
    host = parts.hostname or "127.0.0.1"
    return ("127.0.0.1" if host in ("0.0.0.0", "::") else host), parts.port


def _listening(address: tuple[str, int]) -> bool:
    with socket.socket() as probe:
        probe.settimeout(0.5)
        return probe.connect_ex(address) == 0


async def _wait_listening(endpoint: str, supervisor: Supervisor) -> None:
    """Until the router's TCP port accepts (bounded), so the first session open succeeds."""
    address = _tcp_address(endpoint)
    if address is None:
        return
    for _ in range(int(ROUTER_TIMEOUT / _PORT_POLL)):  # a port has no event to wait on
        if supervisor.fatal.done() or _listening(address):
            return
        await asyncio.sleep(_PORT_POLL)


def _check_port_free(endpoint: str) -> None:
    """:class:`Fatal` if something already listens on the router's TCP endpoint."""
    address = _tcp_address(endpoint)
    if address is not None and _listening(address):
        raise Fatal(
            f"router.listen {endpoint}: the port is already in use (another router? "
            "set router.start: false to use it, or choose another port)"
        )
