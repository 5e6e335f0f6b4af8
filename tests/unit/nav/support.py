"""Shared by the Nav2 remote-leaf tests: build a tree on a bus, tick it to the end."""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import Callable

from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import Path, PoseStamped
from aiobt.nav import register_nav2_nodes
from aiobt.testing.stubs import tree_xml
from aiobt.transport import Bus


def nav_tree(
    bus: Bus | None, body: str, server_timeout: float | None = None, **blackboard: object
) -> Tree:
    """A tree of ``body`` with Nav2's nodes bound to ``bus``; ``blackboard`` preset."""
    factory = BehaviorTreeFactory()
    register_nav2_nodes(factory, bus, server_timeout=server_timeout)
    tree = factory.create_tree_from_text(tree_xml(body))
    for key, value in blackboard.items():
        tree.root_blackboard[key] = value
    return tree


async def run_to_end(tree: Tree, timeout: float = 10.0) -> Status:  # noqa: ASYNC109
    async with asyncio.timeout(timeout):
        return await tree.tick_while_running(period=0.01)


async def tick_until(tree: Tree, done: asyncio.Event, timeout: float = 10.0) -> Status:  # noqa: ASYNC109
    """Tick every 10 ms until a tick after ``done`` was set; that tick's status."""
    async with asyncio.timeout(timeout):
        while True:
            seen = done.is_set()
            status = await tree.tick_once()
            if seen:
                return status
            with contextlib.suppress(TimeoutError):
                await asyncio.wait_for(done.wait(), 0.01)


def straight_path(length: float = 1.0, step: float = 0.1, y: float = 0.0) -> Path:
    count = int(length / step) + 1
    return Path(poses=[PoseStamped.from_xy_yaw(i * step, y, 0.0) for i in range(count)])


async def tick_until_true(
    tree: Tree,
    condition: Callable[[], bool],
    timeout: float = 10.0,  # noqa: ASYNC109
) -> Status:
    """Tick every 10 ms, as a tree runner does, until ``condition()`` holds after a tick."""
    async with asyncio.timeout(timeout):
        while True:
            status = await tree.tick_once()
            if condition():
                return status
            await tree.clock.sleep(0.01)  # the tick period, not a wait for an event
