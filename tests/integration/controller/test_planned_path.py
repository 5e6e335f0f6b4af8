"""Robot, planner and controller processes: plan through the office world, then follow the plan."""

from __future__ import annotations

import math

import pytest

from aiobt.msgs import ComputePathToPose, FollowPath, GoalState, PoseStamped
from aiobt.transport import Bus, BusSettings

from .helpers import Spawn, start, yaw_error

pytestmark = [pytest.mark.integration, pytest.mark.e2e]


async def test_follows_a_planned_path_through_a_door_to_the_goal(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    pose = bus.subscribe("pose", PoseStamped)
    common = ["--connect", bus_settings.connect[0], "--namespace", bus_settings.namespace]
    planner = spawn(["-m", "aiobt_services.planner", *common])
    await start(spawn, bus, bus_settings, "controller", world="office")
    if not await bus.presence(bus.keys.topic("nodes/planner")).wait(30.0):
        pytest.fail(f"planner did not come up:\n{planner.output()}")
    # from the corridor (2.0, 9.75) through the door at x 3.5 into the room south of it
    target = PoseStamped.from_xy_yaw(3.5, 7.0, -math.pi / 2)
    plan_client = bus.action_client("compute_path_to_pose", ComputePathToPose)
    here = await pose.wait_latest(5.0)
    request = ComputePathToPose.Goal(goal=target, start=here, use_start=True)
    planning = await plan_client.send_goal(request, server_timeout=10.0)
    plan = await planning.result(timeout=20.0)
    assert plan.error_code == 0, plan
    assert len(plan.path.poses) > 10
    follow = bus.action_client("follow_path", FollowPath)
    goal = await follow.send_goal(FollowPath.Goal(path=plan.path), server_timeout=10.0)
    result = await goal.result(timeout=60.0)
    assert goal.status is GoalState.SUCCEEDED, result
    final = await pose.wait_latest(2.0)
    assert math.hypot(final.x - 3.5, final.y - 7.0) <= 0.25
    assert yaw_error(final.yaw, plan.path.poses[-1].yaw) <= 0.3
