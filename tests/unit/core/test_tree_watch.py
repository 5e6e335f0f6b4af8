"""Tree.watch: a write to a watched key cuts tick_while_running's sleep short."""

from __future__ import annotations

import asyncio

from aiobt import BehaviorTreeFactory, ManualClock, Status, TreeNode

XML = """
<root BTCPP_format="4"><BehaviorTree ID="T">
  <ReactiveFallback><IsGo/><WaitForever/></ReactiveFallback>
</BehaviorTree></root>"""


def _factory(halts: list[str]) -> BehaviorTreeFactory:
    factory = BehaviorTreeFactory()
    factory.register_simple_condition("IsGo", lambda node: node.blackboard.get("go") == "yes")

    async def wait_forever(node: TreeNode) -> Status:
        try:
            await node.clock.sleep(1e9)
        finally:
            halts.append(node.name)
        return Status.SUCCESS

    factory.register_simple_action("WaitForever", wait_forever)
    return factory


async def test_watched_write_wakes_the_tree_although_the_clock_never_moves() -> None:
    halts: list[str] = []
    tree = _factory(halts).create_tree_from_text(XML, clock=ManualClock())
    unwatch = tree.watch("go")
    ticks = 0

    def count(_stamp: float, node: TreeNode, _prev: Status, status: Status) -> None:
        nonlocal ticks
        if node is tree.root and status is Status.RUNNING:
            ticks += 1

    tree.add_status_listener(count)
    runner = asyncio.ensure_future(tree.tick_while_running(period=3600.0))
    await asyncio.sleep(0.05)
    assert not runner.done()
    assert ticks == 1  # asleep for an hour of manual time that never passes
    tree.root_blackboard.set("go", "yes")
    assert await asyncio.wait_for(runner, timeout=2.0) is Status.SUCCESS
    assert halts == ["WaitForever"]  # the running action was halted by the reactive parent
    unwatch()


async def test_unwatched_key_does_not_wake_the_tree() -> None:
    halts: list[str] = []
    tree = _factory(halts).create_tree_from_text(XML, clock=ManualClock())
    tree.watch("go")()  # watch, then stop watching at once
    runner = asyncio.ensure_future(tree.tick_while_running(period=3600.0))
    try:
        await asyncio.sleep(0.02)
        tree.root_blackboard.set("go", "yes")
        await asyncio.sleep(0.05)
        assert not runner.done()
    finally:
        runner.cancel()
        await asyncio.gather(runner, return_exceptions=True)
        await tree.halt_tree("test over")
    assert halts == ["WaitForever"]
