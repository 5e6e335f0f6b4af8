"""The :class:`Bus`: one Zenoh session per process, typed topics, services, actions."""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import AsyncIterator, Callable
from typing import Any, Literal, TypeVar

import zenoh

from aiobt.core.clock import Clock
from aiobt.msgs import ActionDef, ActionResult, Msg
from aiobt.transport import _z, publishers, services, topics
from aiobt.transport.actions.client import ActionClient
from aiobt.transport.actions.runner import Execute
from aiobt.transport.actions.server import ActionServer
from aiobt.transport.bridge import LoopBridge
from aiobt.transport.keys import Keys
from aiobt.transport.latest import Latest
from aiobt.transport.presence import Presence
from aiobt.transport.session import open_session
from aiobt.transport.settings import BusSettings

M = TypeVar("M", bound=Msg)
T = TypeVar("T")
Req = TypeVar("Req", bound=Msg)
Resp = TypeVar("Resp", bound=Msg)
G = TypeVar("G", bound=Msg)
R = TypeVar("R", bound=ActionResult)
F = TypeVar("F", bound=Msg)
log = logging.getLogger("aiobt.transport")
_RETRY_PAUSE = 0.02  # s between gets that no server answered (routing, a restart)


class Bus:
    """Everything a process says on Zenoh. Create with :func:`open_bus`.

    Names are relative to the namespace: ``bus.publisher("odom", Odometry)``
    publishes on ``{ns}/odom``; services live on ``{ns}/srv/{name}`` and actions
    on ``{ns}/action/{name}/...``.
    """

    def __init__(self, session: zenoh.Session, settings: BusSettings) -> None:
        self.session = session
        self.settings = settings
        self.keys = Keys(settings.namespace)
        self.bridge = LoopBridge(asyncio.get_running_loop(), settings.max_payload)
        self._closables: list[Any] = []
        self._presence: dict[str, Presence] = {}
        self._closed = False

    @property
    def namespace(self) -> str:
        return self.keys.namespace

    def _track(self, entity: T) -> T:
        """Close ``entity`` with the bus (newest first)."""
        self._closables.append(entity)
        return entity

    def _untrack(self, entity: Any) -> None:
        """``entity`` was closed by its owner: the bus need not keep it."""
        if not self._closed:
            with contextlib.suppress(ValueError):
                self._closables.remove(entity)

    def publisher(
        self, name: str, model: type[M], *, reliable: bool = False
    ) -> publishers.Publisher[M]:
        """A publisher on ``{ns}/{name}``; ``reliable``: block, not drop, when congested."""
        key = self.keys.topic(name)
        pub = publishers.declare_publisher(self.session, self.bridge, key, model, reliable=reliable)
        return self._track(pub)

    def latched_publisher(self, name: str, model: type[M]) -> publishers.Publisher[M]:
        """A publisher whose last value late subscribers (``latched=True``) still get."""
        pub = publishers.declare_latched_publisher(
            self.session, self.bridge, self.keys.topic(name), model
        )
        return self._track(pub)

    def subscribe(
        self,
        name: str,
        model: type[M],
        callback: Callable[[M], object] | None = None,
        *,
        latched: bool = False,
        queue_size: int = 100,
        namespace: str | None = None,
    ) -> topics.Subscription[M]:
        """Messages on ``{ns}/{name}``; ``latched`` also gets a latched publisher's last value.

        At most ``queue_size`` messages wait (the oldest dropped): 1 for a reader of
        the latest value (see :class:`~aiobt.transport.topics.Subscription`).
        ``namespace`` (default: the bus's) reads another robot's topic."""
        keys = self.keys if namespace is None else Keys(namespace)
        sub = topics.declare_subscription(
            self.session,
            self.bridge,
            keys.topic(name),
            model,
            callback_fn=callback,
            latched=latched,
            queue_size=queue_size,
        )
        sub.on_close = lambda: self._untrack(sub)  # one subscribed while needed, then closed
        return self._track(sub)

    def latest(
        self, name: str, model: type[M], *, latched: bool = False, namespace: str | None = None,
        keep: int = 1,
    ) -> Latest[M]:  # fmt: skip
        """The newest message on ``{ns}/{name}``, decoded when read (``get()``): arrivals
        run no Python (a Zenoh ring, see :mod:`aiobt.transport.latest`). For a reader of
        the value now; :meth:`subscribe` to react to each message. ``keep``: the last
        messages kept for :meth:`Latest.newest_first`."""
        keys = self.keys if namespace is None else Keys(namespace)
        key = keys.topic(name)
        newest = Latest(key, model, self.bridge.max_payload, keep=keep)
        topics.bind_ring(self.session, key, newest, latched=latched)
        newest.on_close = lambda: self._untrack(newest)
        return self._track(newest)

    def serve(
        self,
        name: str,
        request: type[Req],
        response: type[Resp],
        handler: services.Handler[Req, Resp],
        *,
        namespace: str | None = None,
    ) -> services.ServiceServer[Req, Resp]:
        """Answer ``{ns}/srv/{name}`` with ``handler(request)`` (sync or async);
        ``namespace`` (default: the bus's), e.g. the simulation's
        (:func:`~aiobt.transport.keys.sim_namespace`)."""
        key = (Keys(namespace) if namespace else self.keys).service(name)
        server = services.ServiceServer(
            self.session, self.bridge, key, (request, response), handler
        )
        return self._track(server)

    async def call(
        self,
        name: str,
        request: Msg,
        response: type[Resp],
        timeout: float = 2.0,  # noqa: ASYNC109
        *,
        namespace: str | None = None,
    ) -> Resp:
        """Call ``{ns}/srv/{name}`` (``namespace``, default the bus's): waits up to
        ``timeout`` for the server to be there.

        A request that no server answered (not routed yet, or its server went away,
        e.g. restarting) is sent again until ``timeout``: a request whose server died
        while handling it may be handled twice."""
        key = (Keys(namespace) if namespace else self.keys).service(name)
        loop = asyncio.get_running_loop()
        deadline = loop.time() + timeout
        while True:
            if not await self.presence(key).wait(max(0.0, deadline - loop.time())):
                raise services.ServiceUnavailable(f"{key}: no server within {timeout} s")
            remaining = max(0.05, deadline - loop.time())
            try:
                return await services.call(
                    self.session, self.bridge, key, request, response, remaining
                )
            except services.NoAnswer:
                if deadline - loop.time() <= _RETRY_PAUSE:
                    raise services.ServiceUnavailable(
                        f"{key}: no service answered within {timeout} s"
                    ) from None
            except services.NoReply:
                raise services.ServiceUnavailable(f"{key}: no reply within {timeout} s") from None
            await asyncio.sleep(_RETRY_PAUSE)

    def presence(self, key: str) -> Presence:
        """Liveliness watcher on an absolute key (shared; closed with the bus)."""
        if key not in self._presence:
            self._presence[key] = Presence(self.session, self.bridge, key)
        return self._presence[key]

    async def tokens(self, key: str, timeout: float = 1.0) -> list[str]:  # noqa: ASYNC109
        """The keys of the liveliness tokens alive now on the absolute ``key`` (wildcards
        allowed, e.g. ``**/nodes/*``), sorted."""

        def collect() -> list[str]:
            replies = self.session.liveliness().get(key, timeout=timeout)
            return sorted(str(r.ok.key_expr) for r in replies if r.ok is not None)

        return await asyncio.to_thread(collect)

    def routers(self) -> list[str]:
        """The Zenoh ids of the routers this session is connected to."""
        return [str(zid) for zid in self.session.info.routers_zid()]

    def declare_token(self, name: str) -> zenoh.LivelinessToken:
        """A liveliness token on ``{ns}/{name}`` (e.g. ``nodes/planner``), until the bus closes."""
        token = self.session.liveliness().declare_token(self.keys.topic(name))
        return self._track(token)

    def action_server(
        self,
        name: str,
        action: type[ActionDef[G, R, F]],
        execute: Execute[G, R, F],
        *,
        preemption: Literal["abort", "replace"] = "abort",
        accept: Callable[[G], str | None] | None = None,
        clock: Clock | None = None,
    ) -> ActionServer[G, R, F]:
        """Serve action ``name`` (see :class:`ActionServer`; ``clock`` stamps its statuses)."""
        server = ActionServer(
            self.session,
            self.bridge,
            self.keys.action(name),
            action,
            execute,
            preemption=preemption,
            accept=accept,
            clock=clock,
        )
        return self._track(server)

    def action_client(self, name: str, action: type[ActionDef[G, R, F]]) -> ActionClient[G, R, F]:
        """A client of action server ``name`` (see :class:`ActionClient`)."""
        keys = self.keys.action(name)
        client = ActionClient(self.session, self.bridge, keys, action, self.presence(keys.alive))
        return self._track(client)

    async def close(self) -> None:
        """Undeclare everything (newest first), then close the session. Idempotent."""
        if self._closed:
            return
        self._closed = True
        for entity in reversed(self._closables):
            await _close_one(entity)
        for presence in self._presence.values():
            presence.close()
        self.bridge.closed = True
        _z.close(self.session)


async def _close_one(entity: Any) -> None:
    try:
        if hasattr(entity, "aclose"):
            await entity.aclose()
        elif hasattr(entity, "close"):
            entity.close()
        else:
            _z.undeclare(entity)
    except Exception:
        log.exception("closing %r failed", entity)


@contextlib.asynccontextmanager
async def open_bus(settings: BusSettings | None = None) -> AsyncIterator[Bus]:
    """Open the process's bus; always closed on exit (no exit hangs)."""
    settings = settings or BusSettings()
    session = await open_session(settings)
    try:
        bus = Bus(session, settings)
    except BaseException:
        _z.close(session)
        raise
    try:
        yield bus
    finally:
        await bus.close()
