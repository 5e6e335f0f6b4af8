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
from collections.abc import Callable
from typing import Any, ClassVar

from aiobt.core import eager
from aiobt.core.errors import LogicError, NodeError
from aiobt.core.node import NodeKind, TreeNode, own_copy, tick_error
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status

log = logging.getLogger("aiobt.core.leaves")


class SyncLeaf(TreeNode):
    """Base of the synchronous leaves below (the tick itself is TreeNode's)."""

    __slots__ = ()

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        # The leaf bases below inline their execute_sync into a fast tick_sync;
        # a subclass with its own execute_sync gets the generic tick back.
        if "execute_sync" in cls.__dict__ and "tick_sync" not in cls.__dict__:
            cls.tick_sync = own_copy(TreeNode.tick_sync)  # type: ignore[method-assign]


class _OneCallLeaf(SyncLeaf):
    """The tick of ConditionNode and SyncActionNode: one call of the author's
    hook (``check`` or ``on_tick``, named by ``HOOK``), its result as a
    Status; never RUNNING."""

    __slots__ = ()
    HOOK: ClassVar[str] = ""
    _hook: ClassVar[Callable[[Any], Status | bool | None]]

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        cls._hook = getattr(cls, cls.HOOK)  # the class's own check/on_tick: one call per tick

    def tick_sync(self) -> Status:
        """TreeNode's tick with ``execute_sync`` inlined (the hot path)."""
        if self._conditions is not None:
            return self._conditions.tick_sync(self)
        try:
            status = self._hook()
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
            value = self._hook()
        except Exception as exc:
            raise tick_error(self, exc) from exc
        return self._result(value)

    def _result(self, value: Status | bool | None) -> Status:
        try:
            status = Status.of(value)
        except Exception as exc:
            raise tick_error(self, exc) from exc
        if status is RUNNING:
            message = f"{type(self).__name__}.{self.HOOK}() must not return RUNNING"
            raise NodeError(self.path, LogicError(message))
        return status


class ConditionNode(_OneCallLeaf):
    """A check of the world; returns SUCCESS or FAILURE, never RUNNING."""

    __slots__ = ()
    KIND = NodeKind.CONDITION
    HOOK = "check"

    def check(self) -> Status | bool:
        raise LogicError(f"{type(self).__name__} does not implement check()")


class SyncActionNode(_OneCallLeaf):
    """An action that finishes within its tick."""

    __slots__ = ()
    HOOK = "on_tick"

    def on_tick(self) -> Status | bool | None:
        raise LogicError(f"{type(self).__name__} does not implement on_tick()")


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


class AsyncActionNode(SyncLeaf):
    """A leaf written as one coroutine: ``async def run(self) -> Status | bool | None``.

    - first tick from IDLE: ``run()`` starts as a task whose first step runs
      within the tick; if it finishes without waiting, its result is returned
      in that same tick (as BT.CPP's ``on_start`` would);
    - while the task is pending: RUNNING, with no new task; when it finishes
      the tree is woken at once;
    - halt: the task is cancelled (CancelledError at its current await) and
      the tree awaits its cleanup (``finally``) after the tick, for at most the
      tree's ``halt_timeout``;
    - an exception in ``run()`` surfaces as :class:`NodeError` with the path.
    """

    __slots__ = ("_step",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._step: eager.Step | None = None

    async def run(self) -> Status | bool | None:
        raise LogicError(f"{type(self).__name__} does not implement run()")

    def execute_sync(self) -> Status:
        previous = self._status
        if previous is not IDLE and previous is not RUNNING:
            return previous
        step = self._step
        if step is None:
            step = eager.start(self.run(), name=self.path)
            if not step.done:
                self._step = step
                assert step.task is not None
                step.task.add_done_callback(self._on_task_done)
                return RUNNING
        elif not step.done:
            return RUNNING
        self._step = None
        return self._outcome(step)

    def _on_task_done(self, task: asyncio.Task[Any]) -> None:
        step = self._step
        if step is not None and step.task is task:
            self._ctx.wake_up()

    def _outcome(self, step: eager.Step) -> Status:
        if step.cancelled:
            return FAILURE
        if step.error is not None:
            raise tick_error(self, step.error) from step.error
        try:
            status = Status.of(step.value)
        except TypeError as type_exc:
            raise tick_error(self, type_exc) from type_exc
        if status is IDLE or status is RUNNING:
            raise NodeError(
                self.path, LogicError(f"run() must finish with a result, not {status.name}")
            )
        return status

    def halt_sync(self) -> None:
        step, self._step = self._step, None
        if step is not None and not step.done:
            step.cancel()
            assert step.task is not None
            self._ctx.cleanups[step.task] = self.path
        super().halt_sync()
