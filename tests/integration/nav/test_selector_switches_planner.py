"""A `zenoh put` on {ns}/planner_selector changes the planner the real planner service uses."""

from __future__ import annotations

import asyncio

import pytest

from aiobt.core.status import Status
from aiobt.core.tree import Tree
from aiobt.msgs import ComputePathToPoseError, PoseStamped, String
from aiobt.nav import NavContext
from aiobt.nav.shared_topics import shared_topics
from aiobt.transport import Bus, BusSettings
from tests.integration.nav.test_selector_cli import put_and_wait
from tests.integration.robot.test_robot_service import Spawn
from tests.integration.services import TRUTH
from tests.unit.nav.support import nav_tree, run_to_end

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(200)]
PLAN = """
<Sequence>
  <PlannerSelector default_planner="GridBased" selected_planner="{planner}"/>
  <ComputePathToPose goal="{goal}" planner_id="{planner}" path="{path}"
                     error_code_id="{code}" error_msg="{msg}"/>
</Sequence>
"""


async def start_robot_and_planner(spawn: Spawn, bus: Bus, settings: BusSettings) -> None:
    common = ["--connect", settings.connect[0], "--namespace", settings.namespace]
    procs = {
        "robot": spawn(["-m", "aiobt_services.robot", "--world", "small", *TRUTH, *common]),
        "planner": spawn(["-m", "aiobt_services.planner", *common]),
    }
    for name, proc in procs.items():
        if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(60.0):
            pytest.fail(f"{name} did not come up:\n{proc.output()}")


async def plan(tree: Tree) -> Status:
    """Run the tree; a planner still waiting for its map or pose is retried, bounded."""
    async with asyncio.timeout(60):
        while True:
            status = await run_to_end(tree, timeout=30.0)
            code = tree.root_blackboard.get("code")
            if status is Status.SUCCESS or code == ComputePathToPoseError.INVALID_PLANNER:
                return status
            await asyncio.sleep(0.25)  # the planner's map/pose: the next attempt's pause


async def test_zenoh_put_on_the_selector_changes_the_planner(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings, router_endpoint: str
) -> None:
    tree = nav_tree(bus, PLAN, server_timeout=10.0, goal=PoseStamped.from_xy_yaw(1.5, 1.5))
    await start_robot_and_planner(spawn, bus, bus_settings)
    assert await plan(tree) is Status.SUCCESS
    assert tree.root_blackboard["planner"] == "GridBased"
    topic = shared_topics(NavContext(bus=bus), "test").topic(
        "planner_selector", String, latched=True
    )
    await put_and_wait(bus, router_endpoint, topic, "NoSuchPlanner")
    assert await plan(tree) is Status.FAILURE
    assert tree.root_blackboard["code"] == ComputePathToPoseError.INVALID_PLANNER
    assert "NoSuchPlanner" in tree.root_blackboard["msg"]
    await put_and_wait(bus, router_endpoint, topic, "ThetaStar")
    assert await plan(tree) is Status.SUCCESS
    assert tree.root_blackboard["planner"] == "ThetaStar"
    assert tree.root_blackboard["path"].poses[-1].x == pytest.approx(1.5)
