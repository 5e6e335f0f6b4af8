"""Nav2's remote leaves against the real robot, planner, controller and behaviors processes."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import pytest

from aiobt.core.status import Status
from aiobt.msgs import PoseStamped
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings
from tests.integration.services import TRUTH
from tests.unit.nav.support import nav_tree, run_to_end

pytestmark = [pytest.mark.integration, pytest.mark.e2e, pytest.mark.timeout(200)]
Spawn = Callable[[Sequence[str]], ServiceProcess]
SERVICES = ("planner", "controller", "behaviors")
SERVER_TIMEOUT = 10.0  # s: a loaded machine's first goal can take over a second to accept


async def start_services(spawn: Spawn, bus: Bus, settings: BusSettings) -> None:
    """The robot (small world, 2x real time) and every service, on sim time where they can."""
    common = ["--connect", settings.connect[0], "--namespace", settings.namespace]
    procs = {"robot": spawn(["-m", "aiobt_services.robot", "--world", "small", "--speed", "2",
                             *TRUTH, *common])}  # fmt: skip
    for name in SERVICES:
        sim_time = [] if name == "planner" else ["--sim-time"]
        procs[name] = spawn(["-m", f"aiobt_services.{name}", *sim_time, *common])
    for name, proc in procs.items():
        if not await bus.presence(bus.keys.topic(f"nodes/{name}")).wait(60.0):
            pytest.fail(f"{name} did not come up:\n{proc.output()}")


PLAN_AND_FOLLOW = """
<Sequence>
  <ClearEntireCostmap service_name="local_costmap/clear_entirely_local_costmap"/>
  <RetryUntilSuccessful num_attempts="40">
    <Fallback>
      <ComputePathToPose goal="{goal}" path="{path}" planner_id="GridBased"
                         error_code_id="{plan_code}"/>
      <ForceFailure><Wait wait_duration="0.25"/></ForceFailure>
    </Fallback>
  </RetryUntilSuccessful>
  <ClearEntireCostmap service_name="global_costmap/clear_entirely_global_costmap"/>
  <CheckPoseOccupancy pose="{wall}"/>
  <Inverter><CheckPoseOccupancy pose="{goal}"/></Inverter>
  <FollowPath path="{path}" controller_id="FollowPath" error_code_id="{follow_code}"
              error_msg="{follow_msg}"/>
</Sequence>
"""


async def test_compute_path_then_follow_path_reaches_the_goal(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    await start_services(spawn, bus, bus_settings)
    goal = PoseStamped.from_xy_yaw(1.5, 1.5, math.pi / 2)
    wall = PoseStamped.from_xy_yaw(2.45, 0.0, 0.0)  # the small world's east wall
    tree = nav_tree(bus, PLAN_AND_FOLLOW, server_timeout=SERVER_TIMEOUT, goal=goal, wall=wall)
    status = await run_to_end(tree, timeout=80.0)
    bb = tree.root_blackboard
    assert status is Status.SUCCESS, (
        bb.get("plan_code"),
        bb.get("follow_code"),
        bb.get("follow_msg"),
    )
    assert bb["path"].poses[-1].x == pytest.approx(1.5)
    assert bb["follow_code"] == 0
    final = await bus.subscribe("pose", PoseStamped).next(timeout=10.0)
    assert math.hypot(final.x - 1.5, final.y - 1.5) <= 0.3
    assert tree.root_blackboard.get("number_recoveries") == 2  # the two clears


RECOVERIES = """
<Sequence>
  <Spin spin_dist="1.57" error_code_id="{spin_code}"/>
  <BackUp backup_dist="0.3" backup_speed="0.15" error_code_id="{backup_code}"/>
  <Wait wait_duration="0.5" error_code_id="{wait_code}"/>
  <ReinitializeGlobalLocalization/>
</Sequence>
"""


async def test_spin_backup_and_wait_succeed_and_move_the_robot(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
) -> None:
    await start_services(spawn, bus, bus_settings)
    tree = nav_tree(bus, RECOVERIES, server_timeout=SERVER_TIMEOUT)
    assert await run_to_end(tree, timeout=80.0) is Status.SUCCESS
    bb = tree.root_blackboard
    assert (bb["spin_code"], bb["backup_code"], bb["wait_code"]) == (0, 0, 0)
    assert bb["number_recoveries"] == 3  # Spin (is_recovery), BackUp, Wait
    final = await bus.subscribe("pose", PoseStamped).next(timeout=10.0)
    # the ports reached the behaviors (their precision on a loaded machine is theirs to test)
    assert abs(math.remainder(final.yaw - math.pi / 2, 2 * math.pi)) < 0.5
    assert math.hypot(final.x, final.y) == pytest.approx(0.3, abs=0.12)
    assert final.y < -0.2  # backwards, while facing about +y
