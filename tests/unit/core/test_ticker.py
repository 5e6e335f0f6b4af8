"""Many trees driven by tick_while_running in one loop share one ticker per (clock, period)."""

from __future__ import annotations

import asyncio
from collections import Counter

import pytest

from aiobt.core.clock import ManualClock, SystemClock
from aiobt.core.leaves import AsyncActionNode, StatefulActionNode
from aiobt.core.status import Status
from aiobt.core.ticker import ticker_for
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import settle, tree_xml

S, R = Status.SUCCESS, Status.RUNNING
TICKS: Counter[str] = Counter()


class Ticking(StatefulActionNode):
    """RUNNING; counts its ticks by tree name (its ``name`` attribute)."""

    def on_start(self) -> Status:
        TICKS[self.name] += 1
        return R

    def on_running(self) -> Status:
        TICKS[self.name] += 1
        return R


class Awaiting(AsyncActionNode):
    """SUCCESS once the test resolves ``Awaiting.done``."""

    done: asyncio.Future[None]

    async def run(self) -> Status:
        await Awaiting.done
        return S


@pytest.fixture
def factory() -> BehaviorTreeFactory:
    TICKS.clear()
    factory = BehaviorTreeFactory()
    factory.register_node_type(Ticking, "Ticking")
    factory.register_node_type(Awaiting, "Awaiting")
    return factory


def _trees(factory: BehaviorTreeFactory, clock: ManualClock, n: int) -> list[Tree]:
    xml = '<ReactiveSequence><AlwaysSuccess/><Ticking name="t{}"/></ReactiveSequence>'
    return [factory.create_tree_from_text(tree_xml(xml.format(i)), clock=clock) for i in range(n)]


async def _stop(tasks: list[asyncio.Task[Status]], trees: list[Tree]) -> None:
    for task in tasks:
        task.cancel()
    await asyncio.gather(*tasks, return_exceptions=True)
    for tree in trees:
        await tree.halt_tree("test done")


@pytest.mark.timeout(30)
async def test_many_trees_wait_on_one_clock_sleeper_and_each_ticks_once_per_period(
    factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    trees = _trees(factory, manual_clock, 50)
    tasks = [asyncio.create_task(tree.tick_while_running(period=0.5)) for tree in trees]
    try:
        await settle()
        assert manual_clock.pending_sleepers == 1  # one ticker, not one sleeper per tree
        assert set(TICKS.values()) == {1}
        await manual_clock.forward(0.5, step=0.5)
        await settle()
        assert set(TICKS.values()) == {2}
        manual_clock.advance(0.25)  # half a period: nobody is due
        await settle()
        assert set(TICKS.values()) == {2}
    finally:
        await _stop(tasks, trees)


@pytest.mark.timeout(30)
async def test_cancelling_one_tree_leaves_the_others_ticking(
    factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    trees = _trees(factory, manual_clock, 3)
    tasks = [asyncio.create_task(tree.tick_while_running(period=1.0)) for tree in trees]
    try:
        await settle()
        tasks[1].cancel()
        await trees[1].halt_tree("cancelled by the test")
        await manual_clock.forward(2.0, step=1.0)
        await settle()
        assert TICKS == {"t0": 3, "t1": 1, "t2": 3}
        assert trees[1].root.status is Status.IDLE
    finally:
        await _stop(tasks, trees)


@pytest.mark.timeout(30)
async def test_a_finished_tree_leaves_the_ticker_and_an_idle_ticker_stops(
    factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    Awaiting.done = asyncio.get_running_loop().create_future()
    finishing = factory.create_tree_from_text(tree_xml("<Awaiting/>"), clock=manual_clock)
    trees = _trees(factory, manual_clock, 2)
    tasks = [asyncio.create_task(tree.tick_while_running(period=1.0)) for tree in trees]
    done = asyncio.create_task(finishing.tick_while_running(period=1.0))
    try:
        await settle()
        Awaiting.done.set_result(None)
        assert await asyncio.wait_for(done, 5.0) is S
        await manual_clock.forward(1.0, step=1.0)
        await settle()
        assert ticker_for(manual_clock, 1.0).waiting == 2  # the finished tree is gone
        await _stop(tasks, trees)
        await manual_clock.forward(1.0, step=1.0)
        await settle()
        assert manual_clock.pending_sleepers == 0  # nothing left to wait for
        assert ticker_for(manual_clock, 1.0).waiting == 0
    finally:
        await _stop(tasks, trees)


@pytest.mark.timeout(30)
async def test_a_leaf_finishing_wakes_its_tree_without_the_clock_moving(
    factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    Awaiting.done = asyncio.get_running_loop().create_future()
    tree = factory.create_tree_from_text(tree_xml("<Awaiting/>"), clock=manual_clock)
    others = _trees(factory, manual_clock, 5)  # sharing the same ticker
    tasks = [asyncio.create_task(other.tick_while_running(period=10.0)) for other in others]
    ticking = asyncio.create_task(tree.tick_while_running(period=10.0))
    try:
        await settle()
        assert not ticking.done()
        Awaiting.done.set_result(None)
        assert await asyncio.wait_for(ticking, 5.0) is S
        assert manual_clock.now() == 0.0
        assert set(TICKS.values()) == {1}  # the others were not woken
    finally:
        await _stop(tasks, others)


@pytest.mark.timeout(30)
async def test_trees_of_different_periods_keep_their_own_period(
    factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    trees = _trees(factory, manual_clock, 2)
    tasks = [
        asyncio.create_task(trees[0].tick_while_running(period=0.3)),
        asyncio.create_task(trees[1].tick_while_running(period=1.0)),
    ]
    try:
        await settle()
        await manual_clock.forward(0.9, step=0.3)
        await settle()
        assert TICKS == {"t0": 4, "t1": 1}
    finally:
        await _stop(tasks, trees)


class _BrokenClock(ManualClock):
    async def sleep(self, seconds: float) -> None:
        raise RuntimeError("simulation clock lost")


@pytest.mark.timeout(30)
async def test_a_failing_clock_fails_the_waiting_trees_instead_of_hanging(
    factory: BehaviorTreeFactory,
):
    clock = _BrokenClock()
    trees = _trees(factory, clock, 2)
    tasks = [asyncio.create_task(tree.tick_while_running(period=1.0)) for tree in trees]
    try:
        for task in tasks:
            with pytest.raises(RuntimeError, match="simulation clock lost"):
                await asyncio.wait_for(task, 5.0)
    finally:
        await _stop(tasks, trees)


@pytest.mark.parametrize("period", [-0.1, float("nan")])
async def test_a_bad_period_is_refused_before_any_tick(
    factory: BehaviorTreeFactory, manual_clock: ManualClock, period: float
):
    (tree,) = _trees(factory, manual_clock, 1)
    with pytest.raises(ValueError, match="tick period must be a number of seconds >= 0"):
        await tree.tick_while_running(period=period)
    assert TICKS == {}


@pytest.mark.timeout(30)
async def test_trees_built_without_a_clock_share_one_ticker(factory: BehaviorTreeFactory):
    """The default wall clock is one clock: trees given none (or each its own
    SystemClock) share one ticker task, not one task per tree and wait."""
    xml = '<ReactiveSequence><AlwaysSuccess/><Ticking name="w{}"/></ReactiveSequence>'
    trees = [factory.create_tree_from_text(tree_xml(xml.format(i))) for i in range(20)]
    trees.append(factory.create_tree_from_text(tree_xml(xml.format(20)), clock=SystemClock()))
    tasks = [asyncio.create_task(tree.tick_while_running(period=30.0)) for tree in trees]
    try:
        await settle()
        assert set(TICKS.values()) == {1}
        tickers = [t for t in asyncio.all_tasks() if t.get_name() == "aiobt ticker 30.0"]
        assert len(tickers) == 1
        assert ticker_for(SystemClock(), 30.0) is ticker_for(SystemClock(), 30.0)
        assert ticker_for(SystemClock(), 30.0).waiting == len(trees)
    finally:
        await _stop(tasks, trees)
