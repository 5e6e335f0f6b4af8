"""The async leaf: one task per activation, same-tick results, wake-up, halt, errors."""

from __future__ import annotations

import asyncio
import logging

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.errors import LogicError, NodeError
from aiobt.core.leaves import AsyncActionNode, ConditionNode, SyncActionNode
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import tree_xml

S, F, R, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.IDLE


class Gate(AsyncActionNode):
    """Waits for ``Gate.open`` (an Event); records tasks, starts, cleanups."""

    __slots__ = ()
    open: asyncio.Event
    tasks: list[asyncio.Task[object] | None]
    cleanups: list[str]
    result: Status = S

    async def run(self) -> Status:
        Gate.tasks.append(asyncio.current_task())
        try:
            await Gate.open.wait()
        finally:
            await asyncio.sleep(0)  # an awaited cleanup step
            Gate.cleanups.append(self.name)
        return Gate.result


class Instant(AsyncActionNode):
    """Finishes without ever awaiting."""

    __slots__ = ()

    async def run(self) -> Status:
        return F


class Boom(AsyncActionNode):
    __slots__ = ()
    after_wait: bool = False

    async def run(self) -> Status:
        if Boom.after_wait:
            await asyncio.sleep(0.001)
        raise ValueError("sensor unplugged")


class BadResult(AsyncActionNode):
    __slots__ = ()

    async def run(self) -> object:  # type: ignore[override]
        return 42


class SyncBoom(SyncActionNode):
    __slots__ = ()

    def on_tick(self) -> Status:
        raise KeyError("missing")


class CondBoom(ConditionNode):
    __slots__ = ()

    def check(self) -> bool:
        raise ZeroDivisionError("division")


@pytest.fixture
def factory() -> BehaviorTreeFactory:
    Gate.open = asyncio.Event()
    Gate.tasks, Gate.cleanups, Gate.result = [], [], S
    Boom.after_wait = False
    factory = BehaviorTreeFactory()
    for cls in (Gate, Instant, Boom, BadResult, SyncBoom, CondBoom):
        factory.register_node_type(cls)
    return factory


async def test_one_task_per_activation_and_running_while_pending(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(tree_xml("<Gate/>"), clock=ManualClock())
    for _ in range(5):
        assert await tree.tick_exactly_once() is R
    assert len(Gate.tasks) == 1
    Gate.open.set()
    await asyncio.sleep(0.01)
    assert await tree.tick_exactly_once() is S
    assert len(Gate.tasks) == 1
    Gate.open.clear()
    assert await tree.tick_exactly_once() is R  # a new activation: a new task
    assert len(Gate.tasks) == 2
    assert Gate.tasks[0] is not Gate.tasks[1]
    await tree.halt_tree("end")


async def test_result_in_same_tick_when_run_never_awaits(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(tree_xml("<Sequence><Instant/><Gate/></Sequence>"))
    assert await tree.tick_exactly_once() is F
    assert Gate.tasks == []


async def test_finished_task_wakes_tick_while_running(factory: BehaviorTreeFactory):
    clock = ManualClock()  # never advanced: only the wake-up can end the period sleep
    tree = factory.create_tree_from_text(tree_xml("<Gate/>"), clock=clock)
    ticking = asyncio.ensure_future(tree.tick_while_running(period=1000.0))
    try:
        await asyncio.sleep(0.01)
        assert not ticking.done()
        Gate.open.set()
        assert await asyncio.wait_for(ticking, timeout=2.0) is S
    finally:
        ticking.cancel()
    assert clock.now() == 0.0


async def test_halt_cancels_task_and_runs_cleanup(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(tree_xml("<Gate/>"))
    assert await tree.tick_exactly_once() is R
    task = Gate.tasks[0]
    assert task is not None
    await tree.halt_tree("operator stop")
    assert task.cancelled()
    assert Gate.cleanups == ["Gate"]
    assert tree.root.status is IDLE


async def test_cleanup_overrunning_halt_timeout_is_warned(
    factory: BehaviorTreeFactory, caplog: pytest.LogCaptureFixture
):
    release = asyncio.Event()
    started: list[asyncio.Task[object] | None] = []

    class Stubborn(AsyncActionNode):
        __slots__ = ()

        async def run(self) -> Status:
            started.append(asyncio.current_task())
            try:
                await asyncio.Event().wait()
            finally:
                await release.wait()  # cleanup that takes too long
            return S

    factory.register_node_type(Stubborn)
    tree = factory.create_tree_from_text(tree_xml("<Stubborn/>"))
    tree.context.halt_timeout = 0.05
    assert await tree.tick_exactly_once() is R
    with caplog.at_level(logging.WARNING, logger="aiobt.core.leaves"):
        await asyncio.wait_for(tree.halt_tree("stop"), timeout=2.0)
    assert any("within 0.1 s of halt" in r.getMessage() for r in caplog.records)
    assert tree.root.status is IDLE
    release.set()
    task = started[0]
    assert task is not None
    await asyncio.wait_for(asyncio.gather(task, return_exceptions=True), timeout=2.0)


@pytest.mark.parametrize("after_wait", [False, True])
async def test_exception_surfaces_as_node_error_with_path(
    factory: BehaviorTreeFactory, after_wait: bool
):
    Boom.after_wait = after_wait
    tree = factory.create_tree_from_text(tree_xml("<Sequence><Boom name='probe'/></Sequence>"))
    if after_wait:
        assert await tree.tick_exactly_once() is R
        await asyncio.sleep(0.02)
    with pytest.raises(NodeError) as info:
        await tree.tick_exactly_once()
    assert info.value.node_path == "MainTree/Sequence/Boom[probe]"
    assert isinstance(info.value.cause, ValueError)
    assert "sensor unplugged" in str(info.value)


async def test_bad_result_is_node_error(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(tree_xml("<BadResult/>"))
    with pytest.raises(NodeError, match="BadResult"):
        await tree.tick_exactly_once()


@pytest.mark.parametrize(
    ("node", "cause"), [("SyncBoom", KeyError), ("CondBoom", ZeroDivisionError)]
)
async def test_sync_leaf_exception_is_node_error(
    factory: BehaviorTreeFactory, node: str, cause: type[Exception]
):
    tree = factory.create_tree_from_text(tree_xml(f"<Fallback><{node}/></Fallback>"))
    with pytest.raises(NodeError) as info:
        await tree.tick_exactly_once()
    assert info.value.node_path == f"MainTree/Fallback/{node}"
    assert isinstance(info.value.cause, cause)


async def test_simple_coroutine_action_is_async_leaf():
    factory = BehaviorTreeFactory()
    calls: list[str] = []

    async def go(node: object) -> bool:
        calls.append("go")
        await asyncio.sleep(0)
        return True

    factory.register_simple_action("Go", go)
    tree = factory.create_tree_from_text(tree_xml("<Go/>"))
    assert await tree.tick_exactly_once() is R
    await asyncio.sleep(0.01)
    assert await tree.tick_exactly_once() is S
    assert calls == ["go"]


async def test_condition_returning_running_is_logic_error():
    factory = BehaviorTreeFactory()
    factory.register_simple_condition("Odd", lambda node: Status.RUNNING)
    tree = factory.create_tree_from_text(tree_xml("<Odd/>"))
    with pytest.raises(NodeError) as info:
        await tree.tick_exactly_once()
    assert isinstance(info.value.cause, LogicError)
