"""Timeout, Delay and Sleep on a ManualClock: time is robot time, never wall time."""

from __future__ import annotations

import asyncio

from aiobt.core.clock import ManualClock
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, settle, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE


async def test_timeout_halts_child_and_fails_after_clock_jump(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Timeout msec="1000"><StubAsyncAction name="W" msec="5000"/></Timeout>'),
        clock=manual_clock,
    )
    assert await tree.tick_exactly_once() is R
    manual_clock.advance(0.999)
    await settle()
    assert await tree.tick_exactly_once() is R
    manual_clock.advance(0.001)  # robot time jumps: the deadline is 1 s after the first tick
    await settle()
    assert await tree.tick_once() is F
    assert stubs.events("W") == ["run", "cancelled"]
    assert all(node.status is IDLE for node in tree.nodes())


async def test_timeout_passes_result_of_fast_child_and_stops_timer(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Timeout msec="1000"><StubAsyncAction name="W" msec="500" result="FAILURE"/></Timeout>'
        ),
        clock=manual_clock,
    )
    assert await tree.tick_exactly_once() is R
    await manual_clock.forward(0.5)
    assert await tree.tick_once() is F
    await settle()
    assert manual_clock.pending_sleepers == 0
    await manual_clock.forward(1.0)
    assert stubs.halts("W") == 0


async def test_timeout_zero_never_expires(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    stubs.script("A", "RUNNING", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Timeout msec="0"><StubAction name="A"/></Timeout>'), clock=manual_clock
    )
    assert await tree.tick_exactly_once() is R
    await manual_clock.forward(100.0, step=10.0)
    assert await tree.tick_exactly_once() is R
    assert await tree.tick_exactly_once() is S


async def test_timeout_restarts_timer_on_each_activation(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    stubs.script("A", "RUNNING", "SUCCESS", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Timeout msec="1000"><StubAction name="A"/></Timeout>'), clock=manual_clock
    )
    assert await tree.tick_exactly_once() is R
    await manual_clock.forward(0.8)
    assert await tree.tick_exactly_once() is S
    assert await tree.tick_exactly_once() is R  # new activation at t=0.8
    await manual_clock.forward(0.5)  # t=1.3: old deadline passed, new one not
    assert await tree.tick_exactly_once() is R
    await manual_clock.forward(0.5)
    assert await tree.tick_once() is F
    assert stubs.halts("A") == 1


async def test_delay_waits_before_ticking_child(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Delay delay_msec="1000"><StubAction name="A"/></Delay>'), clock=manual_clock
    )
    assert await tree.tick_exactly_once() is R
    manual_clock.advance(0.5)
    await settle()
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("A") == 0
    manual_clock.advance(0.5)
    await settle()
    assert await tree.tick_once() is S
    assert stubs.ticks("A") == 1
    # a new activation waits again
    assert await tree.tick_exactly_once() is R
    assert stubs.ticks("A") == 1


async def test_delay_halt_cancels_timer(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Delay delay_msec="1000"><StubAction name="A"/></Delay>'), clock=manual_clock
    )
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("stop")
    await manual_clock.forward(2.0, step=0.5)
    assert stubs.ticks("A") == 0
    assert await tree.tick_exactly_once() is R  # the delay starts over


async def test_delay_zero_ticks_child_at_once(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Delay delay_msec="0"><StubAction name="A"/></Delay>'), clock=manual_clock
    )
    assert await tree.tick_exactly_once() is S


async def test_sleep_runs_on_the_tree_clock_and_wakes_the_tree(
    bt_factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Sequence><Sleep msec="2000"/><AlwaysSuccess/></Sequence>'), clock=manual_clock
    )

    ticking = asyncio.ensure_future(tree.tick_while_running(period=0.5))
    try:
        await settle()
        assert manual_clock.pending_sleepers == 2  # Sleep, and the tree's period
        await manual_clock.forward(2.0, step=0.5)
        status = await asyncio.wait_for(ticking, timeout=2.0)
    finally:
        ticking.cancel()
    assert status is S
    assert manual_clock.now() == 2.0


async def test_sleep_zero_succeeds_in_the_same_tick(
    bt_factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(tree_xml('<Sleep msec="0"/>'), clock=manual_clock)
    assert await tree.tick_exactly_once() is S


async def test_sleep_halt_cancels_the_wait(
    bt_factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(tree_xml('<Sleep msec="1000"/>'), clock=manual_clock)
    assert await tree.tick_exactly_once() is R
    assert manual_clock.pending_sleepers == 1
    await tree.halt_tree("stop")
    assert manual_clock.pending_sleepers == 0
    assert tree.root.status is IDLE
