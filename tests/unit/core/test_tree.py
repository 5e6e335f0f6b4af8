"""Tree: tick_exactly_once, tick_once, tick_while_running, halt_tree, pause/resume, listeners."""

from __future__ import annotations

import asyncio

import pytest

from aiobt.core.clock import ManualClock
from aiobt.core.errors import NodeError
from aiobt.core.leaves import StatefulActionNode
from aiobt.core.node import TreeNode
from aiobt.core.status import Status
from aiobt.factory import BehaviorTreeFactory
from aiobt.testing.stubs import Stubs, settle, tree_xml

S, F, R, K, IDLE = Status.SUCCESS, Status.FAILURE, Status.RUNNING, Status.SKIPPED, Status.IDLE


async def test_tick_exactly_once_resets_only_the_root(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("C", "FAILURE")
    tree = bt_factory.create_tree_from_text(
        tree_xml('<IfThenElse><StubAction name="C"/><StubAction name="T"/></IfThenElse>')
    )
    assert await tree.tick_exactly_once() is F
    assert tree.root.status is IDLE
    assert tree.find("C").status is F  # its parent did not reset it


async def test_tick_once_reticks_on_wake_up(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<SequenceWithMemory><StubAction name="A"/><StubAction name="B"/>'
            '<StubAction name="C" results="R"/></SequenceWithMemory>'
        )
    )
    assert await tree.tick_once() is R  # A and B yield with a wake-up; C runs
    assert stubs.log == ["A:start", "B:start", "C:start"]
    assert await tree.tick_once() is R
    assert stubs.log[-1] == "C:running"  # no wake-up: a single tick


async def test_tick_while_running_ticks_at_period(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    stamps: list[float] = []
    results = iter([R, R, R, S])

    def stamped(node: TreeNode) -> Status:
        stamps.append(manual_clock.now())
        return next(results)

    stubs.script("A", stamped)
    tree = bt_factory.create_tree_from_text(tree_xml('<StubAction name="A"/>'), clock=manual_clock)
    ticking = asyncio.ensure_future(tree.tick_while_running(period=0.25))
    try:
        await settle()
        await manual_clock.forward(1.0, step=0.125)  # binary fractions: no rounding
        assert await asyncio.wait_for(ticking, timeout=2.0) is S
    finally:
        ticking.cancel()
    assert stamps == [0.0, 0.25, 0.5, 0.75]


async def test_tick_while_running_sleep_cut_short_by_sleep_node(
    bt_factory: BehaviorTreeFactory, manual_clock: ManualClock
):
    tree = bt_factory.create_tree_from_text(
        tree_xml('<Sequence><Sleep msec="300"/><AlwaysSuccess/></Sequence>'), clock=manual_clock
    )
    ticking = asyncio.ensure_future(tree.tick_while_running(period=60.0))
    try:
        await settle()
        await manual_clock.forward(0.3, step=0.1)
        assert await asyncio.wait_for(ticking, timeout=2.0) is S
    finally:
        ticking.cancel()
    assert manual_clock.now() == pytest.approx(0.3)  # not the 60 s period


async def test_halt_tree_calls_halt_only_on_running_stateful(
    bt_factory: BehaviorTreeFactory, stubs: Stubs
):
    stubs.script("B", "RUNNING")
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Parallel success_count="-1"><StubAction name="A"/><StubAction name="B"/>'
            '<StubAction name="C" results="F"/></Parallel>'
        )
    )
    stubs.script("C", "RUNNING")
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree("test")
    assert (stubs.halts("A"), stubs.halts("B"), stubs.halts("C")) == (0, 1, 1)
    assert all(node.status is IDLE for node in tree.nodes())
    assert [e.kind for e in tree.events] == ["halted"]
    assert tree.events[0].reason == "test"


async def test_pause_resume_and_reasons(
    bt_factory: BehaviorTreeFactory, stubs: Stubs, manual_clock: ManualClock
):
    stubs.script("A", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(tree_xml('<StubAction name="A"/>'), clock=manual_clock)
    tree.pause("battery swap")
    assert tree.paused
    ticking = asyncio.ensure_future(tree.tick_while_running(period=0.1))
    try:
        await asyncio.sleep(0.01)
        assert stubs.ticks("A") == 0  # paused: not ticked
        manual_clock.advance(1.0)
        tree.resume("battery ok")
        await settle()
        await manual_clock.forward(0.2, step=0.1)
        assert await asyncio.wait_for(ticking, timeout=2.0) is S
    finally:
        ticking.cancel()
    assert [(e.kind, e.reason, e.stamp) for e in tree.events] == [
        ("paused", "battery swap", 0.0),
        ("resumed", "battery ok", 1.0),
    ]
    assert not tree.paused


async def test_status_listeners_fire_only_on_change(bt_factory: BehaviorTreeFactory, stubs: Stubs):
    stubs.script("A", "RUNNING", "RUNNING", "RUNNING", "SUCCESS")
    tree = bt_factory.create_tree_from_text(tree_xml('<Sequence><StubAction name="A"/></Sequence>'))
    changes: list[tuple[str, Status, Status]] = []
    remove = tree.add_status_listener(
        lambda stamp, node, prev, status: changes.append((node.name, prev, status))
    )
    for _ in range(3):
        await tree.tick_exactly_once()
    assert changes == [("Sequence", IDLE, R), ("A", IDLE, R)]
    await tree.tick_exactly_once()
    assert changes[2:] == [("A", R, S), ("A", S, IDLE), ("Sequence", R, S), ("Sequence", S, IDLE)]
    remove()
    await tree.tick_exactly_once()
    assert len(changes) == 6


async def test_nodes_order_and_find(bt_factory: BehaviorTreeFactory):
    tree = bt_factory.create_tree_from_text(
        tree_xml(
            '<Sequence><Inverter><StubAction name="A"/></Inverter>'
            '<StubCondition name="B"/></Sequence>'
        )
    )
    assert [n.name for n in tree.nodes()] == ["Sequence", "Inverter", "A", "B"]
    assert [n.uid for n in tree.nodes()] == [1, 2, 3, 4]
    assert tree.find("MainTree/Sequence/Inverter/StubAction[A]").name == "A"
    with pytest.raises(KeyError, match="nothing"):
        tree.find("nothing")


class Counter(StatefulActionNode):
    """on_start RUNNING, on_running SUCCESS on the 3rd call; counts halts."""

    __slots__ = ()
    calls: list[str]

    def on_start(self) -> Status:
        Counter.calls.append("start")
        return R

    def on_running(self) -> Status:
        Counter.calls.append("running")
        return S if Counter.calls.count("running") >= 2 else R

    def on_halted(self) -> None:
        Counter.calls.append("halted")


async def test_stateful_action_lifecycle():
    Counter.calls = []
    factory = BehaviorTreeFactory()
    factory.register_node_type(Counter)
    tree = factory.create_tree_from_text(tree_xml("<Counter/>"))
    assert [await tree.tick_exactly_once() for _ in range(3)] == [R, R, S]
    assert Counter.calls == ["start", "running", "running"]
    Counter.calls = []
    assert await tree.tick_exactly_once() is R
    await tree.halt_tree()
    await tree.halt_tree()  # a second halt finds it IDLE: no callback
    assert Counter.calls == ["start", "halted"]


async def test_stateful_action_returning_idle_is_an_error():
    class Idle(StatefulActionNode):
        __slots__ = ()

        def on_start(self) -> Status:
            return IDLE

    factory = BehaviorTreeFactory()
    factory.register_node_type(Idle)
    tree = factory.create_tree_from_text(tree_xml("<Idle/>"))
    with pytest.raises(NodeError, match="IDLE"):
        await tree.tick_exactly_once()
