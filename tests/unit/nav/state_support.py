"""Helpers of the Nav2 node tests: trees with the Nav2 node set on an in-process bus,
and publishing a message until the nodes' shared topic has it."""

from __future__ import annotations

import asyncio
from typing import Any, TypeVar

from aiobt.core.clock import Clock
from aiobt.core.tree import Tree
from aiobt.factory import BehaviorTreeFactory
from aiobt.msgs import Msg, Path, PoseStamped
from aiobt.nav import NavContext, register_nav2_nodes
from aiobt.nav.robot_state import KEEP
from aiobt.nav.shared_topics import SharedTopic, shared_topics
from aiobt.testing.stubs import Stubs, tree_xml
from aiobt.transport import Bus

M = TypeVar("M", bound=Msg)
WAIT = 10.0  # s: generous, the machine is shared


def nav_tree(
    bus: Bus | None, body: str, clock: Clock | None = None, stubs: Stubs | None = None
) -> Tree:
    """A tree of ``body`` with Nav2's nodes on ``bus`` (and ``stubs``' leaves, if given)."""
    factory = stubs.factory() if stubs is not None else BehaviorTreeFactory()
    register_nav2_nodes(factory, bus, clock=clock)
    return factory.create_tree_from_text(tree_xml(body), clock=clock)


async def wait_received(topic: SharedTopic[Any], more_than: int, timeout: float = WAIT) -> None:  # noqa: ASYNC109
    """Until ``topic`` has received more than ``more_than`` messages (a shared topic is
    read, not delivered: there is no arrival to await)."""
    async with asyncio.timeout(timeout):
        while topic.received <= more_than:  # noqa: ASYNC110 - nothing to await
            await asyncio.sleep(0.005)


async def deliver(bus: Bus, name: str, message: M, *, latched: bool = False) -> None:
    """Publish ``message`` on ``{ns}/{name}`` and wait until the shared topic has it."""
    hub = shared_topics(NavContext(bus=bus), "test")
    topic = hub.topic(name, type(message), latched=latched, keep=KEEP.get(name, 1))
    publisher = (
        bus.latched_publisher(name, type(message))
        if latched
        else bus.publisher(name, type(message))
    )
    assert await publisher.wait_for_subscribers(WAIT), f"nobody subscribed to {name}"
    before = topic.received
    publisher.put(message)
    await wait_received(topic, before)
    assert topic.latest == message
    publisher.close()


def straight_path(n: int, step: float = 1.0, frame: str = "map") -> Path:
    """Poses (0, 0), (step, 0) ... along x."""
    return Path(poses=[PoseStamped.from_xy_yaw(i * step, 0.0, frame_id=frame) for i in range(n)])


def at(x: float, y: float = 0.0, yaw: float = 0.0, stamp: float = 0.0) -> PoseStamped:
    return PoseStamped.from_xy_yaw(x, y, yaw, stamp=stamp)
