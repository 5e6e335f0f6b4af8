"""The robot-state nodes read the real robot service (pybullet) through a router."""

from __future__ import annotations

import asyncio

import pytest

from aiobt.core.status import Status
from aiobt.nav import NavContext
from aiobt.nav.robot_state import robot_state
from aiobt.transport import Bus, BusSettings
from tests.integration.robot.test_robot_service import Spawn, start_robot
from tests.unit.nav.state_support import nav_tree

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(120)]
READ_ALL = (
    '<Sequence><TransformAvailable parent="map" child="odom"/>'
    '<GetCurrentPose current_pose="{map_pose}"/>'
    '<GetCurrentPose global_frame="odom" current_pose="{odom_pose}"/>'
    '<IsBatteryLow min_battery="1.0"/>'  # any battery message: SUCCESS once one came
    "<Inverter><IsStuck/></Inverter></Sequence>"
)


async def test_state_nodes_read_the_robot(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    tree = nav_tree(bus, READ_ALL)  # subscribes before the robot starts
    robot = robot_state(NavContext(bus=bus), "test")
    await start_robot(spawn, bus, bus_settings)
    async with asyncio.timeout(60):
        while (status := await tree.tick_exactly_once()) is not Status.SUCCESS:
            assert status is Status.FAILURE
            await asyncio.sleep(0.05)  # the tick period of a tree runner, between ticks
    map_pose, odom_pose = tree.root_blackboard["map_pose"], tree.root_blackboard["odom_pose"]
    assert (map_pose.header.frame_id, odom_pose.header.frame_id) == ("map", "odom")
    assert robot.battery() is not None
    assert robot.pose is not None
