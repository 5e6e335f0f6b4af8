"""The action server's goals in the event loop: one execute at a time, preemption,
cancel, shutdown. No Zenoh here: :class:`~aiobt.transport.actions.server.ActionServer`
receives the queries and sends what :meth:`GoalRunner.finish` hands it.
"""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Awaitable, Callable, Coroutine
from typing import Any, Generic, TypeVar

from aiobt.msgs import ActionDef, ActionResult, GoalState, Msg
from aiobt.transport.actions import protocol as p
from aiobt.transport.actions.goals import GoalHandle, GoalRecord, WaitingGoals
from aiobt.transport.actions.observers import Observers

G = TypeVar("G", bound=Msg)
R = TypeVar("R", bound=ActionResult)
F = TypeVar("F", bound=Msg)
log = logging.getLogger("aiobt.transport.actions")
_STOP_TIMEOUT = 5.0  # a cancelled execute still running after this is cancelled again
SHUTTING_DOWN = "action server shutting down"

Execute = Callable[[G, GoalHandle[G, R, F]], Awaitable[R]]


class GoalRunner(Generic[G, R, F]):
    """Runs accepted goals as execute tasks, one at a time (see ActionServer's rules)."""

    def __init__(
        self,
        name: str,
        action: type[ActionDef[G, R, F]],
        execute: Execute[G, R, F],
        preemption: p.Preemption,
        observed: Observers,
        finish: Callable[[GoalRecord, GoalState, R], None],
        publish_feedback: Callable[[str, F], None],
    ) -> None:
        self.name = name  # for logs: the action's key
        self.action = action
        self.preemption = preemption
        self.active: GoalRecord | None = None
        self.waiting = WaitingGoals()
        self.closing = False
        self._result_model = action.result_type()
        self._execute = execute
        self._observed = observed
        self._finish = finish
        self._publish_feedback = publish_feedback
        self._task: asyncio.Task[None] | None = None
        self._handle: GoalHandle[G, R, F] | None = None
        self._lock = asyncio.Lock()
        self._tasks: set[asyncio.Task[None]] = set()

    def result(self, error_msg: str) -> R:
        return self._result_model(error_msg=error_msg)

    # -- starting goals ----------------------------------------------------------------------

    def begin(self, record: GoalRecord, goal: G) -> None:
        if self.closing:
            record.reject(SHUTTING_DOWN)
            return
        self._observed.put_status(record.goal_id, GoalState.ACCEPTED)
        if self._lock.locked() or (self._running() and not self._replaceable()):
            record.acknowledge()
            for older in self.waiting.take(""):  # Nav2: one pending slot, the newest goal
                self._finish(older, GoalState.ABORTED, self._preempted(record.goal_id))
            self.waiting.add(record)  # until it takes over it may be canceled
            self._spawn(self._take_over_in_order, record, goal)  # must wait for the old goal
        elif self._replaceable():
            record.acknowledge()
            self._replace(record, goal)
        else:
            self._start(record, goal)

    def _spawn(self, coroutine: Callable[..., Coroutine[Any, Any, None]], *args: Any) -> None:
        task: asyncio.Task[None] = asyncio.get_running_loop().create_task(coroutine(*args))
        self._tasks.add(task)
        task.add_done_callback(self._tasks.discard)

    def _running(self) -> bool:
        return self._task is not None and not self._task.done()

    def _replaceable(self) -> bool:
        """A running execute that can take a newer goal over (not one being canceled)."""
        return (
            self.preemption == "replace"
            and self._running()
            and self.active is not None
            and not self.active.cancel_requested
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
            self.waiting.discard(record)

    async def _stopped(self, task: asyncio.Task[None]) -> None:
        """Wait until the cancelled execute ``task`` has ended, cancelling it again (with a
        warning) each ``_STOP_TIMEOUT``: the next goal never starts while it runs."""
        goal_id = self._handle.goal_id if self._handle is not None else "?"
        while not (await asyncio.wait({task}, timeout=_STOP_TIMEOUT))[0]:
            log.warning(
                "%s: goal %s still runs %.1f s after its cancellation; cancelling it again "
                "(the next goal waits for it)",
                self.name,
                goal_id,
                _STOP_TIMEOUT,
            )
            task.cancel()

    def _stop_running(self, by: str) -> None:
        """Preempt the running goal, unless it is being canceled already (it ends CANCELED)."""
        assert self._task is not None
        active = self.active
        if active is not None and active.cancel_requested:
            return  # its task is cancelled already: do not interrupt its cleanup
        if active is not None:
            active.preempted_by = by
            self._settle_when_done(active, self._task)
        self._task.cancel()

    def _replace(self, record: GoalRecord, goal: G) -> None:
        assert self._handle is not None
        assert self.active is not None
        self._finish(self.active, GoalState.ABORTED, self._preempted(record.goal_id))
        self.active = record
        self._handle._switch(record, goal)
        self._observed.put_status(record.goal_id, GoalState.EXECUTING)

    def _start(self, record: GoalRecord, goal: G) -> None:
        self.active = record
        self._handle = GoalHandle(self._publish_feedback, record, goal)
        loop = asyncio.get_running_loop()
        self._task = loop.create_task(self._run(self._handle))
        # acknowledged after execute's first step: a goal done by then (a quick
        # one) is answered by its result alone, one reply and one client hop less
        loop.call_soon(record.acknowledge)

    def _preempted(self, by: str) -> R:
        return self.result(f"preempted by goal {by}")

    # -- execution ---------------------------------------------------------------------------

    async def _run(self, handle: GoalHandle[G, R, F]) -> None:
        self._observed.put_status(handle.goal_id, GoalState.EXECUTING)
        try:
            result = await self._execute(handle.goal, handle)
            if not isinstance(result, self._result_model):
                raise TypeError(f"execute returned {type(result).__name__}, not a Result")
            state = p.terminal_state(result)
            record = handle.record
            if record.preempted_by or record.cancel_requested or self.closing:
                state, result = self._cancel_outcome(record, result)  # caught, returned
        except asyncio.CancelledError:
            state, result = self._cancel_outcome(handle.record)
            self._finish_handle(handle, state, result)
            if not (handle.record.preempted_by or handle.record.cancel_requested):
                raise  # the server itself is shutting down
            return
        except Exception as exc:
            log.exception("%s: execute failed on goal %s", self.name, handle.goal_id)
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
                returned = self.result("canceled")
            return GoalState.CANCELED, returned
        return GoalState.ABORTED, self.result(SHUTTING_DOWN)

    def _finish_handle(self, handle: GoalHandle[G, R, F], state: GoalState, result: R) -> None:
        self._finish(handle.record, state, result)
        if self.active is handle.record:
            self.active = None

    # -- cancel ------------------------------------------------------------------------------

    def cancel(self, goal_id: str) -> list[str]:
        """Cancel ``goal_id`` ("" = all): the ids being canceled."""
        canceling = []
        active, task = self.active, self._task
        preempted = active is not None and active.preempted_by  # decided: ends ABORTED
        if active and task and not preempted and goal_id in ("", active.goal_id):
            canceling.append(active.goal_id)
            self._cancel_active(active, task)
        for record in self.waiting.take(goal_id):
            canceling.append(record.goal_id)
            self._cancel_waiting(record)
        return canceling

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
        if self.active is record:
            self.active = None

    def _cancel_waiting(self, record: GoalRecord) -> None:
        """End a goal that never started CANCELED; its take-over then skips it."""
        record.cancel_requested = True
        self._observed.put_status(record.goal_id, GoalState.CANCELING)
        self._finish(record, GoalState.CANCELED, self.result("canceled"))

    # -- shutdown ----------------------------------------------------------------------------

    async def close(self) -> None:
        """Refuse new goals; end the waiting and running ones ABORTED (shutting down)."""
        self.closing = True
        try:
            await self._abort_all()
        finally:
            for task in list(self._tasks):
                task.cancel()

    async def _abort_all(self) -> None:
        shutting_down = self.result(SHUTTING_DOWN)
        for record in self.waiting.take(""):  # first: they must not start once it stops
            self._finish(record, GoalState.ABORTED, shutting_down)
        task, active = self._task, self.active
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
        goal_id = self.active.goal_id if self.active else "?"
        log.warning("%s: goal %s did not stop on shutdown", self.name, goal_id)
        if self.active is not None:
            self._finish(self.active, GoalState.ABORTED, shutting_down)
