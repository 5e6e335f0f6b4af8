"""aiobt.core.eager: a coroutine's first step runs now, as its own task."""

from __future__ import annotations

import asyncio
import contextvars

import pytest

from aiobt.core.eager import start

VAR: contextvars.ContextVar[str] = contextvars.ContextVar("VAR", default="outer")


async def test_a_coroutine_that_never_waits_is_done_at_once_in_its_own_task() -> None:
    async def quick() -> str:
        task = asyncio.current_task()
        assert task is not None
        return task.get_name()

    step = start(quick(), name="quick")
    assert (step.done, step.value, step.error) == (True, "quick", None)
    await asyncio.sleep(0)  # the task itself then ends without running anything again


async def test_the_rest_runs_on_the_loop_with_its_own_context() -> None:
    log: list[str] = []

    async def slow() -> int:
        VAR.set("inner")
        log.append("first")
        await asyncio.sleep(0.01)
        log.append(f"after, VAR={VAR.get()}")
        return 42

    step = start(slow())
    assert not step.done
    assert log == ["first"]
    assert VAR.get() == "outer"  # the first step ran in a copy of the context
    assert step.task is not None
    assert await asyncio.wait_for(step.task, timeout=2.0) == 42
    assert (step.done, step.value) == (True, 42)
    assert log == ["first", "after, VAR=inner"]


@pytest.mark.parametrize("loop_turn_first", [False, True])
async def test_cancel_reaches_the_coroutine_before_and_after_the_task_started(
    loop_turn_first: bool,
) -> None:
    log: list[str] = []
    waited: list[asyncio.Future[None]] = []

    async def waits() -> None:
        future: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        waited.append(future)
        try:
            await future
        except asyncio.CancelledError:
            log.append("cancelled")
            raise
        finally:
            await asyncio.sleep(0)  # cleanup may itself await
            log.append("cleanup")

    step = start(waits())
    if loop_turn_first:
        await asyncio.sleep(0)
    step.cancel()
    assert step.task is not None
    await asyncio.wait({step.task}, timeout=2.0)
    assert step.task.cancelled()
    assert (step.done, step.cancelled) == (True, True)
    assert log == ["cancelled", "cleanup"]
    assert waited[0].cancelled()


async def test_asyncio_timeout_in_the_first_step_binds_to_the_new_task() -> None:
    async def bounded() -> str:
        try:
            async with asyncio.timeout(0.01):
                await asyncio.Event().wait()
        except TimeoutError:
            return "timed out"
        return "not reached"

    step = start(bounded())
    assert step.task is not None
    assert await asyncio.wait_for(step.task, timeout=2.0) == "timed out"
    me = asyncio.current_task()
    assert me is not None
    assert me.cancelling() == 0  # the caller's task was never the one cancelled


async def test_an_error_in_the_first_step_is_kept_for_the_caller() -> None:
    async def boom() -> None:
        raise ValueError("sensor unplugged")

    step = start(boom())
    assert step.done
    assert isinstance(step.error, ValueError)
    await asyncio.sleep(0)
