"""The action server: one goal at a time, preemption by a newer goal, cancel, results.

``execute(goal, handle)`` is a coroutine returning the Result. Cancel and
"abort" preemption cancel its task (clean up in ``finally``); with
``preemption="replace"`` the running execute keeps going and takes the newer
goal over through :meth:`GoalHandle.take_new_goal` / :meth:`GoalHandle.wait_new_goal`.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable, Coroutine
from typing import Any, Generic, TypeVar

import zenoh

from aiobt.core.clock import Clock, SystemClock
from aiobt.msgs import ActionDef, ActionResult, GoalState, MessageError, Msg, decode
from aiobt.transport import _z
from aiobt.transport.actions import protocol as p
from aiobt.transport.actions.goals import GoalHandle, GoalRecord, ResultStore, WaitingGoals
from aiobt.transport.actions.intake import GoalIntake
from aiobt.transport.actions.observers import Observers
from aiobt.transport.bridge import JSON, LoopBridge, callback
from aiobt.transport.keys import ActionKeys
from aiobt.transport.services import query_payload

G = TypeVar("G", bound=Msg)
R = TypeVar("R", bound=ActionResult)
F = TypeVar("F", bound=Msg)
log = logging.getLogger("aiobt.transport.actions")
_STOP_TIMEOUT = 5.0  # a cancelled execute still running after this is cancelled again
_SHUTTING_DOWN = "action server shutting down"


Execute = Callable[[G, GoalHandle[G, R, F]], Awaitable[R]]


class ActionServer(Generic[G, R, F]):
    """Serves one action, one goal at a time (Nav2's simple action server).

    - ``execute(goal, handle) -> Result`` runs as a task per goal; ``error_code``
      0 ends the goal SUCCEEDED, anything else ABORTED; an exception ends it
      ABORTED with the action's UNKNOWN code (also one raised by the cleanup of a
      canceled or preempted goal: the error is what the client learns). Cancel
      ends it CANCELED, also when execute catches the cancellation and returns a
      Result (which it carries); a shutdown ends it ABORTED even then.
    - ``preemption="abort"``: a newer goal cancels the running task and the old
      goal ends ABORTED "preempted by goal ..." (whatever execute returns). The
      newer goal starts only once the old task has ended: two executes never run
      at once. A task still running ``_STOP_TIMEOUT`` (5 s) after its cancellation
      is cancelled again, with a warning, every ``_STOP_TIMEOUT``.
      ``"replace"``: the running execute continues with the newer goal
      (``handle.take_new_goal()``); the old goal ends ABORTED the same way.
      A goal being canceled is not preempted (it ends CANCELED): newer goals wait.
    - A canceled goal that waits to run ends CANCELED at once and never runs;
      the goals after it keep their order. Cancel-all: running and waiting ones,
      except a running goal already being preempted (its outcome is decided).
    - :meth:`aclose` rejects new goals ("action server shutting down"), ends the
      waiting and running goals ABORTED with that reason, then withdraws the token.
    - ``clock`` (robot time; default the system's) stamps GoalStatus messages.
    - ``accept(goal) -> reason | None`` (in the loop) may reject a goal with a
      reason; without it goals are checked in the Zenoh thread (faster).
    - A starting goal is acknowledged after execute's first step (up to its
      first real await, which must come soon, as anywhere in an event loop); a
      goal that finished by then is answered by its result alone.
    """

    def __init__(
        self,
        session: zenoh.Session,
        bridge: LoopBridge,
        keys: ActionKeys,
        action: type[ActionDef[G, R, F]],
        execute: Execute[G, R, F],
        *,
        preemption: p.Preemption = "abort",
        accept: Callable[[G], str | None] | None = None,
        clock: Clock | None = None,
    ) -> None:
        if preemption not in ("abort", "replace"):
            raise ValueError(f"preemption must be 'abort' or 'replace', got {preemption!r}")
        self.keys = keys
        self.action = action
        self.preemption = preemption
        self._intake = GoalIntake(keys.goal, action.goal_type(), bridge, accept)
        self._result_model = action.result_type()
        self._execute = execute
        self._session = session
        self._bridge = bridge
        self._active: GoalRecord | None = None
        self._task: asyncio.Task[None] | None = None
        self._handle: GoalHandle[G, R, F] | None = None
        self._lock = asyncio.Lock()
        self._waiting = WaitingGoals()
        self._results = ResultStore()
        self._tasks: set[asyncio.Task[None]] = set()
        self._closing = False
        self._closed = asyncio.Event()
        self._queryables = [
            session.declare_queryable(keys.goal, callback(self._on_goal_query)),
            session.declare_queryable(keys.cancel, callback(self._from_zenoh(self._on_cancel))),
            session.declare_queryable(keys.any_result, callback(self._from_zenoh(self._on_result))),
        ]
        self._observed = Observers(session, keys, clock or SystemClock())  # unobserved: no puts
        self._token = session.liveliness().declare_token(keys.alive)

    def _from_zenoh(self, handle: Callable[[zenoh.Query], None]) -> Callable[[zenoh.Query], None]:
        def on_query(query: zenoh.Query) -> None:
            self._bridge.call(handle, query)

        return on_query

    def _spawn(self, coroutine: Callable[..., Coroutine[Any, Any, None]], *args: Any) -> None:
        task: asyncio.Task[None] = asyncio.get_running_loop().create_task(coroutine(*args))
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    @property
    def active_goal_id(self) -> str | None:
        return self._active.goal_id if self._active else None

    # -- goal intake -------------------------------------------------------------------------

    def _on_goal_query(self, query: zenoh.Query) -> None:
        """Zenoh thread. Without a user ``accept`` callback the goal is checked right
        here (a bad or duplicate goal is answered at once); the rest runs in the loop."""
        if self._intake.accept is not None:
            self._bridge.call(self._check_in_loop, query)  # user code runs in the loop
            return
        checked = self._intake.check(query)
        if checked is not None:
            self._bridge.call(self._begin, GoalRecord(checked[0], query), checked[1])

    def _check_in_loop(self, query: zenoh.Query) -> None:
        checked = self._intake.check(query)
        if checked is not None:
            self._begin(GoalRecord(checked[0], query), checked[1])

    def _begin(self, record: GoalRecord, goal: G) -> None:
        if self._closing:
            record.reject(_SHUTTING_DOWN)
            return
        self._observed.put_status(record.goal_id, GoalState.ACCEPTED)
        if self._lock.locked() or (self._running() and not self._replaceable()):
            record.acknowledge()
            self._waiting.add(record)  # until it takes over it may be canceled
            self._spawn(self._take_over_in_order, record, goal)  # must wait for the old goal
        elif self._replaceable():
            record.acknowledge()
            self._replace(record, goal)
        else:
            self._start(record, goal)

    def _running(self) -> bool:
        return self._task is not None and not self._task.done()

    def _replaceable(self) -> bool:
        """A running execute that can take a newer goal over (not one being canceled)."""
        return (
            self.preemption == "replace"
            and self._running()
            and self._active is not None
            and not self._active.cancel_requested
        )

    async def _take_over_in_order(self, record: GoalRecord, goal: G) -> None:
        try:
            async with self._lock:
                if record.done:
                    return  # canceled while it waited for an earlier waiting goal
                if self._replaceable():
                    self._replace(record, goal)
                    return
                if self._task is not None and self._running():
                    self._stop_running(record.goal_id)
                    await self._stopped(self._task)
                if not record.done:  # else canceled while the old goal stopped
                    self._start(record, goal)
        finally:
            self._waiting.discard(record)

    async def _stopped(self, task: asyncio.Task[None]) -> None:
        """Wait until the cancelled execute ``task`` has ended, cancelling it again (with a
        warning) each ``_STOP_TIMEOUT``: the next goal never starts while it runs."""
        goal_id = self._handle.goal_id if self._handle is not None else "?"
        while not (await asyncio.wait({task}, timeout=_STOP_TIMEOUT))[0]:
            log.warning(
                "%s: goal %s still runs %.1f s after its cancellation; cancelling it again "
                "(the next goal waits for it)",
                self.keys.base,
                goal_id,
                _STOP_TIMEOUT,
            )
            task.cancel()

    def _stop_running(self, by: str) -> None:
        """Preempt the running goal, unless it is being canceled already (it ends CANCELED)."""
        assert self._task is not None
        active = self._active
        if active is not None and active.cancel_requested:
            return  # its task is cancelled already: do not interrupt its cleanup
        if active is not None:
            active.preempted_by = by
            self._settle_when_done(active, self._task)
        self._task.cancel()

    def _replace(self, record: GoalRecord, goal: G) -> None:
        assert self._handle is not None
        assert self._active is not None
        self._finish(self._active, GoalState.ABORTED, self._preempted(record.goal_id))
        self._active = record
        self._handle._switch(record, goal)
        self._observed.put_status(record.goal_id, GoalState.EXECUTING)

    def _start(self, record: GoalRecord, goal: G) -> None:
        self._active = record
        self._handle = GoalHandle(self.publish_feedback, record, goal)
        loop = asyncio.get_running_loop()
        self._task = loop.create_task(self._run(self._handle))
        # acknowledged after execute's first step: a goal done by then (a quick
        # one) is answered by its result alone, one reply and one client hop less
        loop.call_soon(record.acknowledge)

    def _preempted(self, by: str) -> R:
        return self._result_model(error_msg=f"preempted by goal {by}")

    # -- execution ---------------------------------------------------------------------------

    async def _run(self, handle: GoalHandle[G, R, F]) -> None:
        self._observed.put_status(handle.goal_id, GoalState.EXECUTING)
        try:
            result = await self._execute(handle.goal, handle)
            if not isinstance(result, self._result_model):
                raise TypeError(f"execute returned {type(result).__name__}, not a Result")
            state = p.terminal_state(result)
            record = handle.record
            if record.preempted_by or record.cancel_requested or self._closing:
                state, result = self._cancel_outcome(record, result)  # caught, returned
        except asyncio.CancelledError:
            state, result = self._cancel_outcome(handle.record)
            self._finish_handle(handle, state, result)
            if not (handle.record.preempted_by or handle.record.cancel_requested):
                raise  # the server itself is shutting down
            return
        except Exception as exc:
            log.exception("%s: execute failed on goal %s", self.keys.base, handle.goal_id)
            code = p.unknown_error_code(self.action.ErrorCode)
            state = GoalState.ABORTED
            result = self._result_model(error_code=code, error_msg=f"{type(exc).__name__}: {exc}")
        self._finish_handle(handle, state, result)

    def _cancel_outcome(self, record: GoalRecord, returned: R | None = None) -> tuple[GoalState, R]:
        """A stopped goal's end; ``returned``: the Result of an execute that caught it."""
        if record.preempted_by:
            return GoalState.ABORTED, self._preempted(record.preempted_by)
        if record.cancel_requested:
            if returned is None:
                returned = self._result_model(error_msg="canceled")
            return GoalState.CANCELED, returned
        return GoalState.ABORTED, self._result_model(error_msg=_SHUTTING_DOWN)

    def _finish_handle(self, handle: GoalHandle[G, R, F], state: GoalState, result: R) -> None:
        self._finish(handle.record, state, result)
        if self._active is handle.record:
            self._active = None

    def _finish(self, record: GoalRecord, state: GoalState, result: R) -> None:
        if record.done:
            return
        payload = result.to_json()
        tag = p.result_tag(state)
        self._results.store(record.goal_id, tag, payload)
        record.finish(tag, payload)
        self._observed.put_status(record.goal_id, state, result.error_msg)
        if self._observed("result"):
            key = self.keys.result(record.goal_id)
            self._session.put(key, payload, encoding=JSON, attachment=tag)

    # -- cancel, result query, observers -----------------------------------------------------

    def _on_cancel(self, query: zenoh.Query) -> None:
        try:
            request = decode(p.CancelRequest, query_payload(query) or b"{}", key=self.keys.cancel)
        except MessageError as exc:
            query.reply_err(f"bad cancel request: {exc}")
            _z.drop(query)
            return
        canceling = []
        active = self._active
        preempted = active is not None and active.preempted_by  # decided: ends ABORTED
        if active and self._task and not preempted and request.goal_id in ("", active.goal_id):
            canceling.append(active.goal_id)
            self._cancel_active(active, self._task)
        for record in self._waiting.take(request.goal_id):
            canceling.append(record.goal_id)
            self._cancel_waiting(record)
        response = p.CancelResponse(goals_canceling=canceling)
        query.reply(query.key_expr, response.to_json(), encoding=JSON)
        _z.drop(query)

    def _cancel_active(self, active: GoalRecord, task: asyncio.Task[None]) -> None:
        if active.cancel_requested:
            return  # asked again: its task is not cancelled twice (cleanup runs on)
        active.cancel_requested = True
        self._observed.put_status(active.goal_id, GoalState.CANCELING)
        self._settle_when_done(active, task)
        task.cancel()

    def _settle_when_done(self, record: GoalRecord, task: asyncio.Task[None]) -> None:
        """A task cancelled before its first step never runs ``_run``: its goal still ends."""
        task.add_done_callback(lambda _: self._settle(record))

    def _settle(self, record: GoalRecord) -> None:
        self._finish(record, *self._cancel_outcome(record))  # no-op if ``_run`` ended it
        if self._active is record:
            self._active = None

    def _cancel_waiting(self, record: GoalRecord) -> None:
        """End a goal that never started CANCELED; its take-over then skips it."""
        record.cancel_requested = True
        self._observed.put_status(record.goal_id, GoalState.CANCELING)
        self._finish(record, GoalState.CANCELED, self._result_model(error_msg="canceled"))

    def _on_result(self, query: zenoh.Query) -> None:
        goal_id = str(query.key_expr).rsplit("/", 1)[-1]
        stored = self._results.get(goal_id)
        if stored is not None:
            query.reply(query.key_expr, stored[1], encoding=JSON, attachment=stored[0])
            _z.drop(query)
        elif self._active and self._active.goal_id == goal_id:
            self._active.waiters.append(query)  # answered when the goal finishes
        elif (waiting := self._waiting.get(goal_id)) is not None:
            waiting.waiters.append(query)
        else:
            query.reply_err(f"unknown goal id {goal_id}")
            _z.drop(query)

    def publish_feedback(self, goal_id: str, feedback: F) -> None:
        active = self._active
        if active is None or active.goal_id != goal_id:
            return  # a preempted goal's late feedback
        payload = feedback.to_json()
        active.reply(payload, p.FEEDBACK)
        if self._observed("feedback"):
            self._session.put(self.keys.feedback(goal_id), payload, encoding=JSON)

    async def aclose(self) -> None:
        """Refuse new goals, end the waiting and running goals ABORTED ("action server
        shutting down"; clients get these results), then withdraw the token and undeclare.
        Idempotent: a second call waits for the first to finish."""
        if self._closing:
            await self._closed.wait()
            return
        self._closing = True
        try:
            await self._abort_all()
        finally:
            self._closed.set()  # waiters resume after this, at the next await: none below
            for task in list(self._tasks):
                task.cancel()
            _z.undeclare(self._token)
            for entity in self._queryables:
                _z.undeclare(entity)
            self._observed.close()

    async def _abort_all(self) -> None:
        shutting_down = self._result_model(error_msg=_SHUTTING_DOWN)
        for record in self._waiting.take(""):  # first: they must not start once it stops
            self._finish(record, GoalState.ABORTED, shutting_down)
        task, active = self._task, self._active
        if task is None or task.done():
            return
        if active is not None:
            active.preempted_by = ""  # its preemptor never runs: it ends by the shutdown
        for attempt in range(2):  # a task stopping already (cleanup) is not cut at once
            if attempt or not task.cancelling():
                task.cancel()
            if (await asyncio.wait({task}, timeout=_STOP_TIMEOUT))[0]:
                if active is not None:
                    self._settle(active)  # in case it was cancelled before its first step
                return
        log.warning("%s: goal %s did not stop on shutdown", self.keys.base, self.active_goal_id)
        if self._active is not None:
            self._finish(self._active, GoalState.ABORTED, shutting_down)
