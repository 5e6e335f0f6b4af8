"""Ticks and halts are synchronous; async leaves run as tasks started within the tick."""

from __future__ import annotations

import asyncio

import pytest

from aiobt import AsyncActionNode, BehaviorTreeFactory, Status, TreeNode
from aiobt.testing.stubs import tree_xml

S, F, R, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.IDLE


class Probe(AsyncActionNode):
    """Records the task its first step runs in, waits on a future, logs its cleanup."""

    __slots__ = ()
    log: list[str]
    tasks: list[asyncio.Task[object] | None]
    waited: list[asyncio.Future[None]]

    async def run(self) -> Status:
        Probe.tasks.append(asyncio.current_task())
        future: asyncio.Future[None] = asyncio.get_running_loop().create_future()
        Probe.waited.append(future)
        try:
            await future
        except asyncio.CancelledError:
            Probe.log.append(f"{self.name}:cancelled")
            raise
        finally:
            await asyncio.sleep(0)  # a cleanup step that itself awaits
            Probe.log.append(f"{self.name}:cleanup")
        return S


class TimesOut(AsyncActionNode):
    __slots__ = ()

    async def run(self) -> Status:
        try:
            async with asyncio.timeout(0.01):
                await asyncio.Event().wait()
        except TimeoutError:
            return F
        return S


@pytest.fixture
def factory() -> BehaviorTreeFactory:
    Probe.log, Probe.tasks, Probe.waited = [], [], []
    factory = BehaviorTreeFactory()
    for cls in (Probe, TimesOut):
        factory.register_node_type(cls)
    factory.register_simple_condition("No", lambda node: False)
    return factory


async def test_first_step_runs_in_the_leaf_task_not_the_ticking_task(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(tree_xml("<Probe/>"))
    assert await tree.tick_exactly_once() is R
    [task] = Probe.tasks
    assert task is not None
    assert task is not asyncio.current_task()
    assert not task.done()
    Probe.waited[0].set_result(None)
    assert await asyncio.wait_for(tree.tick_while_running(period=10.0), timeout=2.0) is S


async def test_asyncio_timeout_in_run_cancels_the_leaf_not_the_tree(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(tree_xml("<TimesOut/>"))
    assert await asyncio.wait_for(tree.tick_while_running(period=10.0), timeout=2.0) is F
    assert not asyncio.current_task().cancelling()  # type: ignore[union-attr]


async def test_a_leaf_halted_in_the_tick_that_started_it_still_cleans_up(
    factory: BehaviorTreeFactory,
):
    # Parallel fails at its second child, in the very tick the first one started:
    # the leaf's task has not taken a step on the loop yet when it is halted
    tree = factory.create_tree_from_text(
        tree_xml('<Parallel failure_count="1"><Probe name="P"/><No/></Parallel>')
    )
    assert await tree.tick_exactly_once() is F
    # the tree awaited the cleanup before returning from the tick
    assert Probe.log == ["P:cancelled", "P:cleanup"]
    assert Probe.waited[0].cancelled()
    assert tree.find("P").status is IDLE


async def test_reactive_halt_cleanup_is_over_when_the_tick_returns(factory: BehaviorTreeFactory):
    tree = factory.create_tree_from_text(
        tree_xml(
            '<ReactiveSequence><ScriptCondition code="go"/><Probe name="P"/></ReactiveSequence>'
        )
    )
    tree.root_blackboard.set("go", True)
    assert await tree.tick_exactly_once() is R
    await asyncio.sleep(0)  # the task takes its first step on the loop
    assert Probe.log == []
    tree.root_blackboard.set("go", False)
    assert await tree.tick_exactly_once() is F  # the condition fails: P is halted in the tick
    assert Probe.log == ["P:cancelled", "P:cleanup"]
    assert [task.cancelled() for task in Probe.tasks if task is not None] == [True]


def test_a_node_whose_tick_would_wait_is_refused_when_its_class_is_made() -> None:
    with pytest.raises(TypeError, match=r"Waits\.execute is a coroutine function.*execute_sync"):

        class Waits(TreeNode):
            __slots__ = ()

            async def execute(self) -> Status:  # a tick that waits
                await asyncio.sleep(0.01)
                return S

    with pytest.raises(TypeError, match=r"on_halt_sync"):

        class HaltWaits(TreeNode):
            __slots__ = ()

            async def on_halt(self) -> None:
                await asyncio.sleep(0.01)
