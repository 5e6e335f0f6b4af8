"""Leaf bases: what node authors subclass.

- :class:`ConditionNode` — ``def check(self) -> bool | Status``; never RUNNING.
- :class:`SyncActionNode` — ``def on_tick(self) -> Status | bool | None``; never RUNNING.
- :class:`StatefulActionNode` — BT.CPP's ``on_start`` / ``on_running`` /
  ``on_halted``, synchronous.
- :class:`AsyncActionNode` — one straight-line ``async def run(self)``; the
  runtime starts it once per activation, reports RUNNING while it is pending,
  and cancels it on halt (cleanup goes in ``finally``, bounded in time).
"""

from __future__ import annotations

import asyncio
import logging
import sys
from collections.abc import Coroutine
from typing import Any, ClassVar

from aiobt.core.errors import LogicError, NodeError
from aiobt.core.node import NodeKind, TreeNode, tick_error
from aiobt.core.status import Status

IDLE = Status.IDLE
RUNNING = Status.RUNNING
SUCCESS = Status.SUCCESS
FAILURE = Status.FAILURE
SKIPPED = Status.SKIPPED

log = logging.getLogger("aiobt.core.leaves")
_EAGER_TASKS = sys.version_info >= (3, 12)


class SyncLeaf(TreeNode):
    """A leaf whose tick is a plain function call (the parent's fast path)."""

    __slots__ = ()
    is_sync: ClassVar[bool] = True

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        # The leaf bases below inline their execute_sync into a fast tick_sync;
        # a subclass with its own execute_sync gets the generic tick back.
        if "execute_sync" in cls.__dict__ and "tick_sync" not in cls.__dict__:
            cls.tick_sync = SyncLeaf.tick_sync  # type: ignore[method-assign]

    def tick_sync(self) -> Status:
        conditions = self._conditions
        if conditions is not None:
            return conditions.tick_sync(self)
        status = self.execute_sync()
        if status is not SKIPPED:
            self._set_status(status)
        return status

    async def execute(self) -> Status:
        return self.execute_sync()

    def execute_sync(self) -> Status:
        raise LogicError(f"{type(self).__name__} does not implement execute_sync()")

    def halt_sync(self) -> None:
        self._set_status(IDLE)
        if self._conditions is not None:
            self._conditions.on_halted(self)

    async def halt(self) -> None:
        self.halt_sync()


class ConditionNode(SyncLeaf):
    """A check of the world; returns SUCCESS or FAILURE, never RUNNING."""

    __slots__ = ()
    KIND = NodeKind.CONDITION

    def check(self) -> Status | bool:
        raise LogicError(f"{type(self).__name__} does not implement check()")

    def tick_sync(self) -> Status:
        """``SyncLeaf.tick_sync`` with ``execute_sync`` inlined (the hot path)."""
        if self._conditions is not None:
            return self._conditions.tick_sync(self)
        try:
            status = self.check()
        except Exception as exc:
            raise tick_error(self, exc) from exc
        if status is not SUCCESS and status is not FAILURE:
            status = self._result(status)
            if status is SKIPPED:
                return status
        if status is not self._status:
            if self._ctx.listeners:
                self._set_status(status)
            else:
                self._status = status
        return status

    def execute_sync(self) -> Status:
        try:
            value = self.check()
        except Exception as exc:
            raise tick_error(self, exc) from exc
        return self._result(value)

    def _result(self, value: Status | bool | None) -> Status:
        try:
            status = Status.of(value)
        except Exception as exc:
            raise tick_error(self, exc) from exc
        if status is RUNNING:
            raise NodeError(self.path, LogicError("a condition must not return RUNNING"))
        return status


class SyncActionNode(SyncLeaf):
    """An action that finishes within its tick."""

    __slots__ = ()

    def on_tick(self) -> Status | bool | None:
        raise LogicError(f"{type(self).__name__} does not implement on_tick()")

    def tick_sync(self) -> Status:
        """``SyncLeaf.tick_sync`` with ``execute_sync`` inlined (the hot path)."""
        if self._conditions is not None:
            return self._conditions.tick_sync(self)
        try:
            status = self.on_tick()
        except Exception as exc:
            raise tick_error(self, exc) from exc
        if status is not SUCCESS and status is not FAILURE:
            status = self._result(status)
            if status is SKIPPED:
                return status
        if status is not self._status:
            if self._ctx.listeners:
                self._set_status(status)
            else:
                self._status = status
        return status

    def execute_sync(self) -> Status:
        try:
            value = self.on_tick()
        except Exception as exc:
            raise tick_error(self, exc) from exc
        return self._result(value)

    def _result(self, value: Status | bool | None) -> Status:
        try:
            status = Status.of(value)
        except Exception as exc:
            raise tick_error(self, exc) from exc
        if status is RUNNING:
            raise NodeError(self.path, LogicError("a SyncActionNode must not return RUNNING"))
        return status


class StatefulActionNode(SyncLeaf):
    """BT.CPP's StatefulActionNode: on_start, then on_running until done.

    A node still SUCCESS or FAILURE (its parent has not reset it) returns that
    status again without calling any hook, as BT.CPP does.
    """

    __slots__ = ()

    def on_start(self) -> Status:
        raise LogicError(f"{type(self).__name__} does not implement on_start()")

    def on_running(self) -> Status:
        raise LogicError(f"{type(self).__name__} does not implement on_running()")

    def on_halted(self) -> None:
        return None

    def tick_sync(self) -> Status:
        """``SyncLeaf.tick_sync`` with ``execute_sync`` inlined (the hot path)."""
        if self._conditions is not None:
            return self._conditions.tick_sync(self)
        previous = self._status
        if previous is not IDLE and previous is not RUNNING:
            return previous
        try:
            status = self.on_start() if previous is IDLE else self.on_running()
        except Exception as exc:
            raise tick_error(self, exc) from exc
        if status is IDLE:
            raise NodeError(self.path, LogicError("on_start/on_running must not return IDLE"))
        if status is previous or status is SKIPPED:
            return status
        if self._ctx.listeners:
            self._set_status(status)
        else:
            self._status = status
        return status

    def execute_sync(self) -> Status:
        previous = self._status
        if previous is not IDLE and previous is not RUNNING:
            return previous
        try:
            status = self.on_start() if previous is IDLE else self.on_running()
        except Exception as exc:
            raise tick_error(self, exc) from exc
        if status is IDLE:
            raise NodeError(self.path, LogicError("on_start/on_running must not return IDLE"))
        return status

    def halt_sync(self) -> None:
        if self._status is RUNNING:
            try:
                self.on_halted()
            except Exception as exc:
                raise tick_error(self, exc) from exc
        super().halt_sync()


class AsyncActionNode(TreeNode):
    """A leaf written as one coroutine: ``async def run(self) -> Status | bool | None``.

    - first tick from IDLE: ``run()`` starts as a task; if it finishes without
      waiting, its result is returned in the same tick;
    - while the task is pending: RUNNING; when it finishes the tree is woken;
    - halt: the task is cancelled and awaited for at most the tree's
      ``halt_timeout`` (cleanup in ``finally``);
    - an exception in ``run()`` surfaces as :class:`NodeError` with the path.
    """

    __slots__ = ("_task",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._task: asyncio.Task[Any] | None = None

    async def run(self) -> Status | bool | None:
        raise LogicError(f"{type(self).__name__} does not implement run()")

    async def execute(self) -> Status:
        previous = self._status
        if previous is not IDLE and previous is not RUNNING:
            return previous
        task = self._task
        if task is None:
            task = await self._start(self.run())
        if not task.done():
            return RUNNING
        self._task = None
        return self._outcome(task)

    async def _start(self, coro: Coroutine[Any, Any, Any]) -> asyncio.Task[Any]:
        loop = asyncio.get_running_loop()
        if _EAGER_TASKS:
            task: asyncio.Task[Any] = asyncio.Task(coro, loop=loop, eager_start=True)  # type: ignore[call-arg]
        else:
            task = loop.create_task(coro)
            await asyncio.sleep(0)  # let the task take its first step, as eager_start would
        self._task = task
        task.add_done_callback(self._on_task_done)
        return task

    def _on_task_done(self, task: asyncio.Task[Any]) -> None:
        if self._task is task:
            self._ctx.wake_up()

    def _outcome(self, task: asyncio.Task[Any]) -> Status:
        if task.cancelled():
            return FAILURE
        exc = task.exception()
        if exc is not None:
            raise tick_error(self, exc) from exc
        try:
            status = Status.of(task.result())
        except TypeError as type_exc:
            raise tick_error(self, type_exc) from type_exc
        if status is IDLE or status is RUNNING:
            raise NodeError(
                self.path, LogicError(f"run() must finish with a result, not {status.name}")
            )
        return status

    async def on_halt(self) -> None:
        task, self._task = self._task, None
        if task is None or task.done():
            return
        task.cancel()
        done, _ = await asyncio.wait({task}, timeout=self._ctx.halt_timeout)
        if not done:
            log.warning(
                "%s: run() did not finish its cleanup within %.1f s of halt",
                self.path,
                self._ctx.halt_timeout,
            )
            return
        if not task.cancelled() and task.exception() is not None:
            log.warning("%s: run() raised while halting: %r", self.path, task.exception())
