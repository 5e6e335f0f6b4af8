"""Start a coroutine as a task whose first step runs now, inside the caller.

A behavior-tree tick is a plain function call (as in BehaviorTree.CPP), yet an
async leaf must report its result in the tick that started it when its
coroutine finishes without waiting. :func:`start` runs the coroutine's first
step synchronously, as the task it belongs to (``asyncio.current_task()``,
``asyncio.timeout()`` and context variables see that task), and hands the rest
to the event loop. This is Python 3.12's ``eager_start``, done by hand so that
one code path serves 3.11 and later.
"""

from __future__ import annotations

import asyncio
import contextvars
from asyncio import tasks as _tasks
from collections.abc import Callable, Coroutine, Generator
from typing import Any

_enter_task: Callable[[asyncio.AbstractEventLoop, asyncio.Task[Any]], None] = _tasks._enter_task
_leave_task: Callable[[asyncio.AbstractEventLoop, asyncio.Task[Any]], None] = _tasks._leave_task


class Step:
    """A started coroutine: done at once, or still running in :attr:`task`."""

    __slots__ = ("_cancel", "_coro", "_pending", "_started", "done", "error", "task", "value")

    def __init__(self, coro: Coroutine[Any, Any, Any]) -> None:
        self._coro = coro
        self._pending: Any = None
        self._started = False
        self._cancel = False
        self.done = False
        self.value: Any = None
        self.error: BaseException | None = None
        self.task: asyncio.Task[Any] | None = None

    @property
    def cancelled(self) -> bool:
        return isinstance(self.error, asyncio.CancelledError)

    def cancel(self) -> None:
        """Cancel the coroutine: CancelledError is raised at its current await."""
        if self.done or self.task is None:
            return
        if self._started:
            self.task.cancel()
        else:  # the task has not taken its first step: tell it to throw at once,
            self._cancel = True  # and cancel what the coroutine waits on, as Task.cancel does
            waited_on = self._pending
            if isinstance(waited_on, asyncio.Future):
                waited_on.cancel()

    def _first(self) -> None:
        try:
            self._pending = self._coro.send(None)
        except StopIteration as stop:
            self._finish(stop.value, None)
        except BaseException as exc:
            self._finish(None, exc)

    def _finish(self, value: Any, error: BaseException | None) -> None:
        self.done = True
        self.value = value
        self.error = error

    async def _rest(self) -> Any:
        self._started = True
        if self.done:
            return self.value
        return await _Resume(self)


class _Resume:
    """Awaitable that continues a coroutine already past its first step."""

    __slots__ = ("_step",)

    def __init__(self, step: Step) -> None:
        self._step = step

    def __await__(self) -> Generator[Any, Any, Any]:
        step = self._step
        coro = step._coro
        value = step._pending
        step._pending = None
        try:
            if step._cancel:
                value = coro.throw(asyncio.CancelledError())
            while True:
                try:
                    sent = yield value
                except GeneratorExit:
                    coro.close()
                    raise
                except BaseException as exc:
                    value = coro.throw(exc)
                else:
                    value = coro.send(sent)
        except StopIteration as stop:
            step._finish(stop.value, None)
            return stop.value
        except BaseException as exc:
            step._finish(None, exc)
            raise


def start(coro: Coroutine[Any, Any, Any], *, name: str | None = None) -> Step:
    """Run ``coro``'s first step now; the rest runs as a task on the running loop."""
    loop = asyncio.get_running_loop()
    step = Step(coro)
    context = contextvars.copy_context()
    task = loop.create_task(step._rest(), name=name, context=context)
    step.task = task
    current = _tasks.current_task(loop)
    if current is not None:
        _leave_task(loop, current)
    _enter_task(loop, task)
    try:
        context.run(step._first)
    finally:
        _leave_task(loop, task)
        if current is not None:
            _enter_task(loop, current)
    return step
