"""One sent goal, as the client sees it: result, cancel, feedback, status."""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections.abc import AsyncIterator, Callable
from typing import TYPE_CHECKING, Any, Generic, TypeVar

import zenoh

from aiobt.msgs import ActionResult, GoalState, MessageError, Msg
from aiobt.transport.actions import protocol as p
from aiobt.transport.services import ServiceError

if TYPE_CHECKING:
    from aiobt.transport.actions.client import ActionClient

G = TypeVar("G", bound=Msg)
R = TypeVar("R", bound=ActionResult)
F = TypeVar("F", bound=Msg)
T = TypeVar("T")
log = logging.getLogger("aiobt.transport.actions")
TOKEN_GRACE = 0.25  # s a goal stream's end and its server's token's end may be apart
# a server silent this long (s) when its session was dropped was hung, not ended: a
# killed process's session closes at once; a hung one's after its lease (1 s default)
HUNG_SILENCE = 0.5


class ClientGoal(Generic[G, R, F]):
    """One sent goal: ``await result()``, ``await cancel()``, feedback, status."""

    def __init__(self, client: ActionClient[G, R, F], goal_id: str, goal: G) -> None:
        self.goal_id = goal_id
        self.goal = goal
        self.status = GoalState.UNKNOWN
        self.latest_feedback: F | None = None
        self.on_feedback: Callable[[F], object] | None = None
        self._client = client
        loop = asyncio.get_running_loop()
        self._accepted: asyncio.Future[bool | None] = loop.create_future()
        self._result: asyncio.Future[R] = loop.create_future()
        self._feedback_queue: asyncio.Queue[F] | None = None  # made at the first feedback
        self._waiters: list[asyncio.Future[None]] = []  # woken directly: no extra loop pass
        self.last_heard = loop.time()  # loop time of the server's last reply on this goal
        self.stream_ended_at: float | None = None  # ended without a result

    @property
    def _feedback(self) -> asyncio.Queue[F]:
        if self._feedback_queue is None:
            self._feedback_queue = asyncio.Queue(maxsize=100)
        return self._feedback_queue

    @property
    def done(self) -> bool:
        return self._result.done()

    async def result(self, timeout: float | None = None) -> R:  # noqa: ASYNC109
        """The Result (check ``status``: SUCCEEDED, ABORTED or CANCELED).

        Raises :class:`GoalLost` if the server went away, ``TimeoutError`` after ``timeout``.
        """
        if not self._result.done():
            waiter: asyncio.Future[None] = asyncio.get_running_loop().create_future()
            self._waiters.append(waiter)  # cancelling this call leaves the goal's future alone
            try:
                async with asyncio.timeout(timeout):
                    await waiter
            finally:
                self._waiters.remove(waiter)
        return self._result.result()

    async def cancel(self, timeout: float = 2.0) -> R | None:  # noqa: ASYNC109
        """Ask the server to cancel, then wait (bounded) for the final result."""
        if self.done:
            return self._result.result() if not self._result.exception() else None
        with contextlib.suppress(ServiceError, TimeoutError):
            await self._client.request_cancel(self.goal_id, timeout)
        with contextlib.suppress(p.GoalLost, TimeoutError):
            return await self.result(timeout)
        return None

    async def feedback(self) -> AsyncIterator[F]:
        """Feedback messages until the goal ends."""
        while not self.done or not self._feedback.empty():
            if not self._feedback.empty():
                yield self._feedback.get_nowait()
                continue
            getter: asyncio.Future[Any] = asyncio.ensure_future(self._feedback.get())
            ending: asyncio.Future[Any] = self._result
            try:
                await asyncio.wait({getter, ending}, return_when=asyncio.FIRST_COMPLETED)
            finally:
                if not getter.done():
                    getter.cancel()
            if getter.done() and not getter.cancelled():
                yield getter.result()

    # -- the goal's reply stream (called in the loop) ----------------------------------------

    def on_reply(self, reply: zenoh.Reply) -> None:
        self.last_heard = asyncio.get_running_loop().time()
        if reply.err is not None:
            self._fail_or_reject(reply.err.payload.to_string())
            return
        sample = reply.ok
        assert sample is not None
        tag = sample.attachment.to_bytes() if sample.attachment is not None else b""
        payload = sample.payload.to_bytes()
        if tag == p.REJECTED:
            reason = payload.decode(errors="replace")
            _fail(self._accepted, p.GoalRejected(self._client.keys.base, self.goal_id, reason))
            return
        if tag == p.ACCEPTED:
            self._on_accepted()
        elif tag == p.FEEDBACK:
            self._on_accepted()  # implied by feedback (or a result) coming first
            self._on_feedback(payload)
        elif (state := p.parse_result_tag(tag)) is not None:
            self._on_accepted()
            self._on_result(state, payload)

    def _on_accepted(self) -> None:
        if self.status == GoalState.UNKNOWN:
            self.status = GoalState.ACCEPTED
        settle(self._accepted, True)

    def _fail_or_reject(self, message: str) -> None:
        if not self._accepted.done():
            error = p.GoalRejected(self._client.keys.base, self.goal_id, message)
            _fail(self._accepted, error)
        else:
            self.lost(f"error on the goal stream: {message}")

    def _on_feedback(self, payload: bytes) -> None:
        try:
            feedback = self._client.decode_feedback(payload)
        except MessageError as exc:
            log.warning("dropped bad feedback: %s", exc)
            return
        self.status = GoalState.EXECUTING
        self.latest_feedback = feedback
        if self._feedback.full():
            self._feedback.get_nowait()
        self._feedback.put_nowait(feedback)
        if self.on_feedback is not None:
            self.on_feedback(feedback)

    def _on_result(self, state: GoalState, payload: bytes) -> None:
        try:
            result = self._client.decode_result(payload)
        except MessageError as exc:
            self.lost(f"malformed result: {exc}")
            return
        self.status = state
        settle(self._result, result)
        self._wake()

    def on_stream_end(self) -> None:
        if not self._accepted.done():
            settle(self._accepted, None)  # nobody answered: maybe not routed yet
        elif not self.done:
            loop = asyncio.get_running_loop()
            self.stream_ended_at = loop.time()
            if self._client.server_present:  # its token ends a moment later, if it does
                self._client.ended_unjudged.add(self)
                loop.call_later(TOKEN_GRACE, self.server_lost)
            else:
                self.server_lost()

    def server_lost(self, token_ended_at: float | None = None) -> None:
        """The goal's stream ended without a result, or its server's token ended (at loop
        time ``token_ended_at``; the other follows within ``TOKEN_GRACE``): fail the
        goal, saying what was seen."""
        self._client.ended_unjudged.discard(self)
        if self.done:
            return
        ended = self.stream_ended_at or token_ended_at or asyncio.get_running_loop().time()
        silence = ended - self.last_heard
        if self._client.server_present:
            why = "the goal stream ended without a result, though the server is still announced"
        elif silence >= HUNG_SILENCE:
            why = (
                f"the server is not answering: nothing from it for {silence:.1f} s, then its "
                "session was dropped (hung or cut off?)"
            )
        else:
            why = "the server is gone: its session closed and its liveliness token ended"
        self.lost(why)
        self._client.lost_goals.add(self.goal_id)  # canceled when the server is back ...
        if self._client.server_present:  # ... as it is
            self._client.lost_goals.server_back()

    def lost(self, why: str) -> None:
        if not self.done:
            self.status = GoalState.ABORTED
            base = self._client.keys.base
            _fail(self._result, p.GoalLost(f"action {base}: goal {self.goal_id} lost: {why}"))
            self._wake()

    def _wake(self) -> None:
        for waiter in self._waiters:
            settle(waiter, None)


def settle(future: asyncio.Future[T], value: T) -> None:
    if not future.done():
        future.set_result(value)


def _fail(future: asyncio.Future[Any], error: BaseException) -> None:
    if not future.done():
        future.set_exception(error)
        future.exception()  # retrieved: nobody need await it (no "never retrieved" log)
