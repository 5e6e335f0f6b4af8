"""The action client: send a goal, await its result, cancel; never hangs on a dead server."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Generic, TypeVar

import zenoh

from aiobt.msgs import ActionDef, ActionResult, GoalState, MessageError, Msg, decode, decoder
from aiobt.transport import _z
from aiobt.transport.actions import protocol as p
from aiobt.transport.actions.client_goal import ClientGoal, settle
from aiobt.transport.actions.lost import LostGoals
from aiobt.transport.bridge import JSON, LoopBridge, PayloadTooLarge, callback
from aiobt.transport.keys import ActionKeys
from aiobt.transport.presence import Presence
from aiobt.transport.services import ServiceError, call, first_reply

G = TypeVar("G", bound=Msg)
R = TypeVar("R", bound=ActionResult)
F = TypeVar("F", bound=Msg)
log = logging.getLogger("aiobt.transport.actions")
_GOAL_STREAM_TIMEOUT = 7 * 24 * 3600.0  # the goal's query lives as long as the goal
_RETRY_PAUSE = 0.02
_RESULT_GRACE = 0.25  # s a result may trail its server's vanished liveliness token


class _Stream(Generic[G, R, F]):
    """A goal's reply stream on the Zenoh thread: relays replies, and the end only if needed."""

    __slots__ = ("_client", "_handle", "_result_seen")

    def __init__(self, client: ActionClient[G, R, F], handle: ClientGoal[G, R, F]) -> None:
        self._client = client
        self._handle = handle
        self._result_seen = False

    def on_reply(self, reply: zenoh.Reply) -> None:
        sample = reply.ok
        if sample is not None and sample.attachment is not None:
            self._result_seen |= sample.attachment.to_bytes().startswith(p.RESULT_PREFIX)
        self._client._bridge.call(self._handle.on_reply, reply)

    def on_drop(self) -> None:
        goals = self._client._goals
        if goals.get(self._handle.goal_id) is self._handle:
            goals.pop(self._handle.goal_id, None)  # atomic under the GIL
        if not self._result_seen:
            self._client._bridge.call(self._handle.on_stream_end)


class ActionClient(Generic[G, R, F]):
    """Sends goals to one action server; fails goals within ~1 s if the server dies."""

    def __init__(
        self,
        session: zenoh.Session,
        bridge: LoopBridge,
        keys: ActionKeys,
        action: type[ActionDef[G, R, F]],
        presence: Presence,
    ) -> None:
        self.keys = keys
        self.action = action
        self.result_model = action.result_type()
        self.feedback_model = action.feedback_type()
        self._goal_model = action.goal_type()
        self.decode_result = decoder(self.result_model, key=keys.base)
        self.decode_feedback = decoder(self.feedback_model, key=keys.base)
        self._session = session
        self._bridge = bridge
        self._presence = presence
        self._goals: dict[str, ClientGoal[G, R, F]] = {}
        # goals whose stream ended without a result while the server was still announced:
        # judged when its token ends (a moment later) or after TOKEN_GRACE
        self.ended_unjudged: set[ClientGoal[G, R, F]] = set()
        self.lost_goals = LostGoals(keys.base, self.request_cancel)  # canceled when it is back
        self._querier = session.declare_querier(
            keys.goal, consolidation=zenoh.ConsolidationMode.NONE, timeout=_GOAL_STREAM_TIMEOUT
        )  # declared once: every goal reuses its route
        presence.add_listener(self._on_presence)

    @property
    def server_present(self) -> bool:
        return self._presence.present

    @property
    def server_lost(self) -> bool:
        """The server was seen, and its liveliness token has ended since."""
        return self._presence.lost

    async def wait_for_server(self, timeout: float | None) -> bool:  # noqa: ASYNC109
        return await self._presence.wait(timeout)

    async def send_goal(
        self,
        goal: G,
        *,
        server_timeout: float = 1.0,
        on_feedback: Callable[[F], object] | None = None,
        goal_id: str | None = None,
        absent_timeout: float | None = None,
    ) -> ClientGoal[G, R, F]:
        """Send ``goal``; returns once accepted. ``server_timeout`` bounds the whole wait;
        ``absent_timeout`` (default: the same) bounds each wait for a server with no
        liveliness token (not started, or gone mid-send), so a dead server is given up on
        sooner than a busy one.

        Raises :class:`ServerUnavailable` (no answer in time) or :class:`GoalRejected`.
        """
        if not isinstance(goal, self._goal_model):
            raise TypeError(f"{self.keys.base}: expected {self._goal_model.__name__}")
        payload = goal.to_json()
        self._bridge.check_size(self.keys.goal, payload)
        absent = server_timeout if absent_timeout is None else absent_timeout
        return await self._send(goal, payload, goal_id, server_timeout, absent, on_feedback)

    async def _send(
        self,
        goal: G,
        payload: bytes,
        given_id: str | None,
        server_timeout: float,
        absent_timeout: float,
        on_feedback: Callable[[F], object] | None,
    ) -> ClientGoal[G, R, F]:
        loop = asyncio.get_running_loop()
        deadline = loop.time() + server_timeout
        goal_id = given_id or p.new_goal_id()
        while self._presence.present or await self._presence.wait(
            min(absent_timeout, deadline - loop.time())
        ):
            handle = ClientGoal(self, goal_id, goal)
            # set before the query: a feedback may come in one batch with the acceptance
            handle.on_feedback = on_feedback
            self._goals[goal_id] = handle
            stream = _Stream(self, handle)
            self._querier.get(
                callback(stream.on_reply, stream.on_drop),
                parameters=f"id={goal_id}",
                payload=payload,
                encoding=JSON,
            )
            if await self._accepted(handle, deadline):
                return handle
            self._forget(goal_id)
            if loop.time() >= deadline:
                self._cancel_quietly(goal_id)  # it may still arrive: do not let it run
                break
            if given_id is None:
                # the unanswered get may still reach the server late: that copy is
                # canceled, and the retry is a new goal (the same id would be refused
                # as a duplicate)
                self._cancel_quietly(goal_id)
                goal_id = p.new_goal_id()
            await asyncio.sleep(_RETRY_PAUSE)  # no queryable routed yet: ask again
        raise p.ServerUnavailable(
            f"action server {self.keys.base} did not accept the goal within {server_timeout} s"
            f" ({'present' if self.server_present else 'not present'})"
        )

    async def _accepted(self, handle: ClientGoal[G, R, F], deadline: float) -> bool:
        """True once accepted; False when the stream ended unanswered or at the deadline."""
        timer = asyncio.get_running_loop().call_at(deadline, settle, handle._accepted, None)
        try:
            return bool(await handle._accepted)
        except asyncio.CancelledError:
            self._cancel_quietly(handle.goal_id)  # the caller gave up: do not leave it running
            raise
        finally:
            timer.cancel()

    def _forget(self, goal_id: str) -> None:
        self._goals.pop(goal_id, None)

    def _on_presence(self, present: bool) -> None:
        """The server's token went away: its accepted goals are lost, unless their result
        (sent just before a clean shutdown withdrew the token) arrives within a moment:
        Zenoh does not order the token's end and the goal stream's replies. Goals whose
        stream already ended without a result are judged at once (a killed server's
        goal is failed within milliseconds). The token back: the goals lost meanwhile
        are canceled (a cut-off server ran them on: :mod:`.lost`)."""
        if present:
            self.lost_goals.server_back()
            return
        loop = asyncio.get_running_loop()
        for handle in list(self._goals.values()):
            if handle._accepted.done() and not handle._accepted.exception():
                loop.call_later(_RESULT_GRACE, handle.server_lost, loop.time())
        for handle in list(self.ended_unjudged):  # their streams ended first: judged now
            handle.server_lost()

    def _cancel_quietly(self, goal_id: str) -> None:
        payload = p.CancelRequest(goal_id=goal_id).to_json()
        self._session.get(self.keys.cancel, payload=payload, encoding=JSON, timeout=1.0)

    async def request_cancel(self, goal_id: str, timeout: float = 2.0) -> list[str]:  # noqa: ASYNC109
        """Ask the server to cancel ``goal_id`` ("" = all); returns the ids being canceled."""
        request = p.CancelRequest(goal_id=goal_id)
        response = await call(
            self._session, self._bridge, self.keys.cancel, request, p.CancelResponse, timeout
        )
        return response.goals_canceling

    async def cancel_all(self, timeout: float = 2.0) -> list[str]:  # noqa: ASYNC109
        """Cancel every goal of the server (anyone's); returns the ids being canceled."""
        return await self.request_cancel("", timeout)

    async def fetch_result(self, goal_id: str, timeout: float = 2.0) -> tuple[GoalState, R]:  # noqa: ASYNC109
        """Query a goal's result (waits for it if the goal is still running)."""
        key = self.keys.result(goal_id)
        return await _fetch_result(self._session, self._bridge, key, self.result_model, timeout)

    def close(self) -> None:
        self._presence.remove_listener(self._on_presence)
        self.lost_goals.close()
        for handle in list(self._goals.values()):  # before their streams end with the querier
            handle.lost("the client closed")
        _z.undeclare(self._querier)
        self._goals.clear()


async def _fetch_result(
    session: zenoh.Session,
    bridge: LoopBridge,
    key: str,
    model: type[R],
    timeout: float,  # noqa: ASYNC109
) -> tuple[GoalState, R]:
    reply = await first_reply(session, bridge, key, timeout)
    if reply is None or reply.err is not None:
        why = reply.err.payload.to_string() if reply and reply.err else "no server answered"
        raise ServiceError(f"{key}: {why}")
    sample = reply.ok
    assert sample is not None
    tag = sample.attachment.to_bytes() if sample.attachment is not None else b""
    state = p.parse_result_tag(tag) or GoalState.UNKNOWN
    try:
        return state, decode(model, sample.payload.to_bytes(), key=key)
    except (MessageError, PayloadTooLarge) as exc:
        raise ServiceError(str(exc)) from None
