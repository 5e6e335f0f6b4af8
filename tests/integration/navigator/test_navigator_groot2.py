"""``aiobt navigator --groot2 PORT``: Groot2 sees the tree of the current navigation.

The navigator process alone (wall time), the robot's pose published by the test,
goals naming trees that hold RUNNING (a Sleep), and a Groot2 stand-in (pyzmq)
asking for FULLTREE and STATUS during each navigation, on the one port bound for
the process life.
"""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator, Callable, Sequence
from pathlib import Path

import pytest

from aiobt.msgs import GoalState, NavigateToPose, PoseStamped
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings
from tests.groot2_client import Groot2Client, free_port_pair, status_pairs

pytestmark = [pytest.mark.integration, pytest.mark.timeout(120)]
Spawn = Callable[[Sequence[str]], ServiceProcess]
RUNNING = 1
SLEEP_UID = 3  # uid 1 the Sequence, 2 AlwaysSuccess, 3 Sleep
TREE = """<root BTCPP_format="4" main_tree_to_execute="{id}">
  <BehaviorTree ID="{id}">
    <Sequence name="{id}Steps"><AlwaysSuccess/><Sleep msec="600000"/></Sequence>
  </BehaviorTree>
</root>
"""


@contextlib.asynccontextmanager
async def robot_pose(bus: Bus) -> AsyncIterator[None]:
    """The robot standing at the origin, as the robot service would publish it."""
    publisher = bus.publisher("pose", PoseStamped)

    async def publish() -> None:
        while True:
            publisher.put(PoseStamped.from_xy_yaw(0.0, 0.0, 0.0))
            await asyncio.sleep(0.05)  # a pose stream's period, not a wait for an event

    task = asyncio.create_task(publish())
    try:
        yield
    finally:
        task.cancel()
        await asyncio.gather(task, return_exceptions=True)


async def running_tree(client: Groot2Client, tree_id: str) -> tuple[bytes, dict[int, int]]:
    """FULLTREE and STATUS once they show ``tree_id`` with its Sleep RUNNING (the goal's
    tree is attached as it starts, before its first tick); AssertionError after 30 s."""
    try:
        async with asyncio.timeout(30.0):
            while True:
                reply = await client.request("T")
                if reply[0] != b"error" and f'ID="{tree_id}"'.encode() in reply[1]:
                    statuses = dict(status_pairs((await client.request("S"))[1]))
                    if statuses.get(SLEEP_UID) == RUNNING:
                        return reply[0], statuses
                await asyncio.sleep(0.05)  # Groot2 polls too: the tree has no event to wait on
    except TimeoutError:
        raise AssertionError(f"Groot2 never saw {tree_id} running") from None


async def test_groot2_follows_each_navigation_on_one_port(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, tmp_path: Path
) -> None:
    trees = {}
    for tree_id in ("HoldA", "HoldB"):
        trees[tree_id] = tmp_path / f"{tree_id}.xml"
        trees[tree_id].write_text(TREE.format(id=tree_id))
    port = free_port_pair()
    common = ["--connect", bus_settings.connect[0], "--namespace", bus_settings.namespace]
    navigator = spawn(["-m", "aiobt_services.navigator", "--groot2", str(port), *common])
    assert await bus.presence(bus.keys.topic("nodes/navigator")).wait(60.0), navigator.output()
    client = Groot2Client(port)
    actions = bus.action_client("navigate_to_pose", NavigateToPose)
    try:
        assert await client.request("T") == [b"error", b"no tree is running yet"]
        async with robot_pose(bus):
            pose = PoseStamped.from_xy_yaw(1.0, 0.0, 0.0)
            first = await actions.send_goal(
                NavigateToPose.Goal(pose=pose, behavior_tree=str(trees["HoldA"])),
                server_timeout=10.0,
            )
            header_a, statuses_a = await running_tree(client, "HoldA")
            second = await actions.send_goal(  # another tree: the first is halted
                NavigateToPose.Goal(pose=pose, behavior_tree=str(trees["HoldB"])),
                server_timeout=10.0,
            )
            header_b, statuses_b = await running_tree(client, "HoldB")
            preempted = await first.result(timeout=10.0)
            await second.cancel(timeout=10.0)
            ended = await second.result(timeout=10.0)
    finally:
        client.close()
    assert first.status is GoalState.ABORTED, preempted  # preempted by the second
    assert second.status is GoalState.CANCELED, ended
    assert statuses_a[1] == RUNNING  # the Sequence, with its Sleep
    assert statuses_b[1] == RUNNING
    assert header_a[6:] != header_b[6:]  # a new tree UUID: Groot2 reloads the new tree
    assert f"127.0.0.1:{port}" in navigator.output()
