"""Request/reply services: every query is answered, with a result or an error naming why."""

from __future__ import annotations

import asyncio
import inspect
import logging
from collections.abc import Awaitable, Callable
from typing import Generic, TypeVar

import zenoh

from aiobt.msgs import MessageError, Msg, decode
from aiobt.transport import _z
from aiobt.transport.bridge import JSON, LoopBridge, PayloadTooLarge, callback
from aiobt.transport.repeats import RepeatedErrors

Req = TypeVar("Req", bound=Msg)
Resp = TypeVar("Resp", bound=Msg)
Handler = Callable[[Req], Awaitable[Resp] | Resp]
log = logging.getLogger("aiobt.transport.services")
_CLOSE_TIMEOUT = 2.0  # s for cancelled handlers to send their "shutting down" replies


class ServiceError(RuntimeError):
    """The server answered with an error (bad request, handler failure)."""


class ServiceUnavailable(ServiceError):
    """Nobody answered: no server, or it did not reply in time."""


class NoAnswer(ServiceUnavailable):
    """The get's reply stream ended empty: no server routed yet, or it went away."""


class NoReply(ServiceUnavailable):
    """A server had the request but did not reply in time."""


def query_payload(query: zenoh.Query) -> bytes:
    payload = query.payload
    return payload.to_bytes() if payload is not None else b""


class ServiceServer(Generic[Req, Resp]):
    """Answers queries on ``key`` with ``handler(request)``; holds a liveliness token."""

    def __init__(
        self,
        session: zenoh.Session,
        bridge: LoopBridge,
        key: str,
        models: tuple[type[Req], type[Resp]],
        handler: Handler[Req, Resp],
    ) -> None:
        self.key = key
        self._request, self._response = models
        self._handler = handler
        self._bridge = bridge
        self._tasks: set[asyncio.Task[None]] = set()
        self._closed = False
        self._errors = RepeatedErrors(log, f"{key}: service handler")
        self._queryable = session.declare_queryable(key, callback(self._on_query))
        self._token = session.liveliness().declare_token(key)

    def _on_query(self, query: zenoh.Query) -> None:
        self._bridge.call(self._answer, query)

    def _answer(self, query: zenoh.Query) -> None:
        """In the loop: a sync handler is answered at once, an awaitable one in a task."""
        try:
            payload = query_payload(query) or b"{}"
            self._bridge.check_size(self.key, payload)
            response = self._handler(decode(self._request, payload, key=self.key))
        except Exception as exc:
            self._fail(query, exc)
            return
        if inspect.isawaitable(response):
            task = asyncio.get_running_loop().create_task(self._answer_later(query, response))
            self._tasks.add(task)
            task.add_done_callback(self._tasks.discard)
        else:
            self._respond(query, response)

    async def _answer_later(self, query: zenoh.Query, pending: Awaitable[Resp]) -> None:
        try:
            response = await pending
        except Exception as exc:
            self._fail(query, exc)
        except BaseException:  # cancelled: the server is closing; never leave a query open
            query.reply_err("the service is shutting down")
            _z.drop(query)
            raise
        else:
            self._respond(query, response)

    def _respond(self, query: zenoh.Query, response: object) -> None:
        try:
            if not isinstance(response, self._response):
                raise TypeError(f"handler returned {type(response).__name__}")
            payload = response.to_json()
        except Exception as exc:
            self._fail(query, exc)
            return
        try:
            query.reply(self.key, payload, encoding=JSON)  # the service's key, not a wildcard
        finally:
            _z.drop(query)

    def _fail(self, query: zenoh.Query, exc: Exception) -> None:
        """Answer with an error naming why (the bad field of a bad request), end the query."""
        try:
            if isinstance(exc, MessageError | PayloadTooLarge):
                query.reply_err(f"bad request: {exc}")
            else:
                self._errors.report(exc)
                query.reply_err(f"handler failed: {type(exc).__name__}: {exc}")
        finally:
            _z.drop(query)

    def close(self) -> None:
        """Withdraw the service; calls still in a handler are cancelled (idempotent)."""
        if self._closed:
            return
        self._closed = True
        self._errors.flush()
        _z.undeclare(self._token)
        _z.undeclare(self._queryable)
        for task in self._tasks:
            task.cancel()

    async def aclose(self) -> None:
        """Like :meth:`close`, but the calls still in a handler are answered with the
        error "the service is shutting down" before the service is withdrawn."""
        if self._closed:
            return
        tasks = list(self._tasks)
        for task in tasks:
            task.cancel()
        if tasks:
            await asyncio.wait(tasks, timeout=_CLOSE_TIMEOUT)
        self.close()


class _Call:
    """One get: the first reply (or the end of the stream) resolves the future."""

    __slots__ = ("_bridge", "_replied", "future")

    def __init__(self, bridge: LoopBridge) -> None:
        self.future: asyncio.Future[zenoh.Reply | None] = bridge.loop.create_future()
        self._bridge = bridge
        self._replied = False

    def on_reply(self, reply: zenoh.Reply) -> None:
        if not self._replied:
            self._replied = True  # Zenoh thread: the end of stream then needs no loop hop
            self._bridge.call(self._resolve, reply)

    def on_drop(self) -> None:
        if not self._replied:
            self._bridge.call(self._resolve, None)

    def _resolve(self, reply: zenoh.Reply | None) -> None:
        if not self.future.done():
            self.future.set_result(reply)


async def first_reply(
    session: zenoh.Session,
    bridge: LoopBridge,
    key: str,
    timeout: float,  # noqa: ASYNC109
    payload: bytes | None = None,
) -> zenoh.Reply | None:
    """Get ``key`` (with a JSON ``payload``, if any): the first reply, None if none came."""
    pending = _Call(bridge)
    session.get(
        key,
        callback(pending.on_reply, pending.on_drop),
        payload=payload,
        encoding=JSON if payload is not None else None,
        timeout=timeout,
    )
    async with asyncio.timeout(timeout + 0.5):
        return await pending.future


async def call(
    session: zenoh.Session,
    bridge: LoopBridge,
    key: str,
    request: Msg,
    response_model: type[Resp],
    timeout: float,  # noqa: ASYNC109
) -> Resp:
    """Send ``request``, return the decoded response; raise ServiceError/Unavailable."""
    payload = request.to_json()
    bridge.check_size(key, payload)
    reply = await first_reply(session, bridge, key, timeout, payload)
    if reply is None:
        raise NoAnswer(f"{key}: no service answered")
    if reply.err is not None:
        message = reply.err.payload.to_string()
        if message.lower().startswith("timeout"):
            raise NoReply(f"{key}: no reply within {timeout:.3g} s")
        raise ServiceError(f"{key}: {message}")
    assert reply.ok is not None
    data = reply.ok.payload.to_bytes()
    bridge.check_size(key, data)
    return decode(response_model, data, key=key)
