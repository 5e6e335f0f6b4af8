"""Groot2 attaches live to a running tree, as to BehaviorTree.CPP's ``Groot2Publisher``.

::

    async with Groot2Publisher(tree, port=1667):
        await tree.tick_while_running()

A REP socket on ``port`` answers Groot2's requests (:mod:`.groot2_monitor`)
and a PUB socket on ``port + 1`` announces breakpoints. Both are served by a
task of the running event loop (``zmq.asyncio``): nothing blocks the loop,
and a breakpoint suspends only the coroutine ticking the tree
(:mod:`.groot2_hooks`). As in BT.CPP, when Groot2 sends no request for
``max_heartbeat_delay`` seconds every hook is disabled (a held breakpoint
lets the tree go on), and enabled again when Groot2 comes back.

A process that runs one tree after another (the navigator: a tree per
navigation) keeps one publisher, bound once, and calls :meth:`attach` with each
new tree; before the first, Groot2's requests get an error reply.

The sockets bind to 127.0.0.1 unless another ``host`` is given (a warning is
logged for a non-loopback address: anyone who reaches it can stop the tree).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import logging
from types import TracebackType
from typing import Self

import zmq
import zmq.asyncio

from aiobt.core.tree import Tree
from aiobt.hosts import is_loopback as _is_loopback
from aiobt.loggers.groot2_monitor import Groot2Monitor
from aiobt.loggers.groot2_protocol import error_reply, notification

log = logging.getLogger("aiobt.loggers.groot2")

DEFAULT_PORT = 1667
_HEARTBEAT_CHECK = 0.1  # seconds of wall time between two checks of the heartbeat


def port_argument(text: str) -> int:
    """A command line's ``--groot2 PORT`` (argparse type): 1..65534, PORT+1 is used too."""
    try:
        port = int(text)
    except ValueError:
        port = 0
    if not 0 < port < 0xFFFF:
        raise argparse.ArgumentTypeError(f"{text!r} is not a port in 1..65534 (PORT+1 is used too)")
    return port


def _report_end(task: asyncio.Task[None]) -> None:
    if not task.cancelled() and task.exception() is not None:
        log.error("Groot2 publisher: %s stopped: %r", task.get_name(), task.exception())


class Groot2Publisher:
    """Serves Groot2 for ``tree`` on ``tcp://host:port`` (and ``port + 1``).

    Call :meth:`start` and :meth:`stop` (or use ``async with``) from the event
    loop that ticks the tree; one publisher per tree, each on its own port.
    """

    def __init__(
        self,
        tree: Tree | None,
        port: int = DEFAULT_PORT,
        host: str = "127.0.0.1",
        *,
        max_heartbeat_delay: float = 5.0,
    ) -> None:
        if not 0 < port < 0xFFFF:
            raise ValueError(f"Groot2Publisher: port {port} is not in 1..65534 (port + 1 is used)")
        if max_heartbeat_delay <= 0:
            raise ValueError(
                f"Groot2Publisher: max_heartbeat_delay must be > 0, got {max_heartbeat_delay}"
            )
        self.tree = tree
        self.port = port
        self.host = host
        self.max_heartbeat_delay = max_heartbeat_delay
        self._monitor: Groot2Monitor | None = None
        self._context: zmq.asyncio.Context | None = None
        self._server: zmq.asyncio.Socket | None = None
        self._publisher: zmq.Socket[bytes] | None = None
        self._tasks: list[asyncio.Task[None]] = []
        self._started = False
        self._last_request = 0.0
        self._hooks_on = True  # Groot2 heard from within max_heartbeat_delay

    @property
    def monitor(self) -> Groot2Monitor:
        if self._monitor is None:
            raise RuntimeError("Groot2Publisher is not started")
        return self._monitor

    @property
    def endpoint(self) -> str:
        return f"tcp://{self.host}:{self.port}"

    async def start(self) -> None:
        """Bind both sockets and start serving; raises OSError if a port is taken."""
        if self._started:
            raise RuntimeError(f"Groot2Publisher on {self.endpoint} is already started")
        if not _is_loopback(self.host):
            log.warning(
                "Groot2 publisher bound to %s: anyone who reaches it can inspect and stop the tree",
                self.host,
            )
        self._bind()
        self._started = True
        if self.tree is not None:
            self.attach(self.tree)
        self._last_request = asyncio.get_running_loop().time()
        self._tasks = [
            asyncio.create_task(self._serve(), name=f"groot2-serve-{self.port}"),
            asyncio.create_task(self._heartbeat(), name=f"groot2-heartbeat-{self.port}"),
        ]
        for task in self._tasks:
            task.add_done_callback(_report_end)
        shown = self.tree.tree_id if self.tree is not None else "(none yet)"
        log.info("Groot2 publisher for tree %s on %s", shown, self.endpoint)

    def attach(self, tree: Tree) -> None:
        """Show ``tree`` from now on (on the same ports): the previous tree's hooks are
        removed (a held breakpoint lets it go on), Groot2 reloads on the new tree's UUID."""
        if not self._started:
            raise RuntimeError("Groot2Publisher is not started")
        if self._monitor is not None:
            self._monitor.close()
        self.tree = tree
        self._monitor = Groot2Monitor(tree, self._notify)
        self._monitor.hooks.enable_all(self._hooks_on)

    def _bind(self) -> None:
        context = zmq.asyncio.Context()
        server = context.socket(zmq.REP)
        publisher: zmq.Socket[bytes] = zmq.Socket(context, zmq.PUB)  # sends never wait
        for socket in (server, publisher):
            socket.setsockopt(zmq.LINGER, 0)
        try:
            server.bind(f"tcp://{self.host}:{self.port}")
            publisher.bind(f"tcp://{self.host}:{self.port + 1}")
        except zmq.ZMQError as exc:
            server.close()
            publisher.close()
            context.term()
            raise OSError(
                f"Groot2Publisher: cannot bind tcp://{self.host}:{self.port} and "
                f"port {self.port + 1}: {exc}"
            ) from exc
        self._context, self._server, self._publisher = context, server, publisher

    async def stop(self) -> None:
        """Stop serving, remove every hook (a held breakpoint lets the tree go on), close."""
        for task in self._tasks:
            task.cancel()
        await asyncio.gather(*self._tasks, return_exceptions=True)
        self._tasks = []
        if self._monitor is not None:
            self._monitor.close()
            self._monitor = None
        self._started = False
        for socket in (self._server, self._publisher):
            if socket is not None:
                socket.close()
        if self._context is not None:
            self._context.term()
        self._context = self._server = self._publisher = None

    async def __aenter__(self) -> Self:
        await self.start()
        return self

    async def __aexit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        await self.stop()

    # -- serving ------------------------------------------------------------------------
    async def _serve(self) -> None:
        assert self._server is not None
        server = self._server
        while True:
            frames = await server.recv_multipart()
            self._last_request = asyncio.get_running_loop().time()
            try:
                if self._monitor is None:
                    reply = error_reply("no tree is running yet")
                else:
                    reply = self._monitor.handle(frames)
            except Exception as exc:  # never leave Groot2's REQ socket without a reply
                log.exception("Groot2 request failed")
                reply = error_reply(f"{type(exc).__name__}: {exc}")
            await server.send_multipart(reply)

    async def _heartbeat(self) -> None:
        loop = asyncio.get_running_loop()
        while True:
            await asyncio.sleep(_HEARTBEAT_CHECK)  # wall time: Groot2's polling, not robot time
            alive = loop.time() - self._last_request < self.max_heartbeat_delay
            if alive != self._hooks_on:
                self._hooks_on = alive
                log.info(
                    "Groot2 %s: hooks %s", "back" if alive else "silent", "on" if alive else "off"
                )
                if self._monitor is not None:
                    self._monitor.hooks.enable_all(alive)

    def _notify(self, uid: int) -> None:
        if self._publisher is None:
            return
        with contextlib.suppress(zmq.Again):  # PUB drops when nobody keeps up, as in BT.CPP
            self._publisher.send_multipart(notification(uid), flags=zmq.NOBLOCK)
