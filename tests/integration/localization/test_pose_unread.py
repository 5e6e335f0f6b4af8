"""In a driving stack nobody reads ``{ns}/pose``: localization composes it for nothing.

Robot (no pose in map), localization, controller, planner and navigator on a real
router, a NavigateToPose goal across the office running. Each service that needs the
robot in ``map`` composes it from the odometry and localization's ``map`` -> ``odom``
on ``{ns}/tf`` (the controller: :class:`aiobt.robot.correction.MapSource`; the
navigator and the planner: :class:`aiobt.geometry.map_pose.MapPose`), as Nav2's
nodes read TF. A publisher the test declares on ``{ns}/pose`` and never puts on is
matched by any subscription there, as localization's is (it composes ``pose`` only
while matched): it must match none while the robot drives. The control: a viewer's
subscription is matched and is sent poses.

The docking and following servers read the pose only in a goal, through a
:class:`~aiobt.geometry.map_pose.MapPose` too: idle beside localization, they let
``pose`` go once its first correction has come.
"""

from __future__ import annotations

import asyncio
import contextlib
import time
from collections.abc import Callable

import pytest

from aiobt.msgs import NavigateToPose, PoseStamped, TFMessage
from aiobt.testing.navwatch import start_navigation
from aiobt.testing.stack import NavStack, StackConfig
from aiobt.transport import open_bus

pytestmark = [pytest.mark.integration, pytest.mark.timeout(240)]

CONFIG = StackConfig(
    world="office",
    speed=1.0,
    services=("robot", "localization", "controller", "planner", "navigator"),
)
FAR_ROOM = (18.5, 18.0, 1.5708)  # about 25 m of path from the start: still driving after 10 s
DRIVING = 3.0  # m the robot drives before the look (the planner and navigator attached)
WATCHED = 3.0  # wall s the pose key is watched for a reader while driving


async def _within(seconds: float, what: str, holds: Callable[[], bool]) -> None:
    try:
        async with asyncio.timeout(seconds):
            while not holds():  # noqa: ASYNC110 - polled state
                await asyncio.sleep(0.05)
    except TimeoutError:
        pytest.fail(f"{what} within {seconds} s")


async def _readers_seen(watch_matched: Callable[[], bool], seconds: float) -> list[float]:
    """Wall s (into the window) at which the pose key had a reader, looked at every 20 ms."""
    seen: list[float] = []
    start = time.monotonic()
    while (now := time.monotonic() - start) < seconds:
        if watch_matched():
            seen.append(round(now, 2))
        await asyncio.sleep(0.02)
    return seen


async def test_a_driving_stack_leaves_localizations_pose_unread(router_endpoint: str) -> None:
    with contextlib.closing(NavStack(router_endpoint, CONFIG)) as stack:
        async with open_bus(stack.settings()) as bus:
            for service in CONFIG.services:
                stack.start(service)
            await stack.wait_ready(bus, timeout=120.0)
            watch = bus.publisher("pose", PoseStamped)  # never put on: a matching probe
            tf = bus.latest("tf", TFMessage)
            await tf.wait_latest(60.0)  # localization sends its correction
            client = bus.action_client(NavigateToPose.name, NavigateToPose)
            running = await start_navigation(client, PoseStamped.from_xy_yaw(*FAR_ROOM))

            def driven() -> bool:
                feedback = running.feedback
                far = max((f.distance_remaining for f in feedback), default=0.0)
                return bool(feedback) and far - feedback[-1].distance_remaining > DRIVING

            await _within(90.0, f"the robot driving {DRIVING} m toward the goal\n{stack.logs()}",
                          driven)  # fmt: skip
            assert not running.goal.done, running.goal.status
            seen = await _readers_seen(lambda: watch.matched, WATCHED)
            assert not running.goal.done, "the goal ended within the watch"
            assert seen == [], f"{{ns}}/pose had a reader at {seen} s of {WATCHED}:\n{stack.logs()}"
            viewer = bus.subscribe("pose", PoseStamped, queue_size=1)  # the control
            assert await watch.wait_for_subscribers(10.0)
            await viewer.wait_latest(10.0)  # localization composes it for a viewer
            viewer.close()
            await running.goal.cancel(10.0)
            tf.close()


async def test_idle_docking_and_following_servers_leave_the_pose_unread(
    router_endpoint: str,
) -> None:
    config = StackConfig(world="office", speed=1.0,
                         services=("robot", "localization", "docking", "following"),
                         extra={"docking": ["--dock-database", "office"]})  # fmt: skip
    with contextlib.closing(NavStack(router_endpoint, config)) as stack:
        async with open_bus(stack.settings()) as bus:
            watch = bus.publisher("pose", PoseStamped)  # never put on: a matching probe
            for service in config.services:
                stack.start(service)
            await stack.wait_ready(bus, timeout=120.0)
            tf = bus.latest("tf", TFMessage)
            await tf.wait_latest(60.0)  # localization sends its correction
            # each server looks for it once a second (MapPose.settle) and lets pose go
            await _within(20.0, f"{{ns}}/pose let go by the servers\n{stack.logs()}",
                          lambda: not watch.matched)  # fmt: skip
            seen = await _readers_seen(lambda: watch.matched, WATCHED)
            assert seen == [], f"{{ns}}/pose had a reader at {seen} s of {WATCHED}:\n{stack.logs()}"
            tf.close()
