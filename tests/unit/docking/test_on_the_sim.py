"""DockRobot and UndockRobot on the real simulation (no Zenoh, no navigator): from
about the staging pose, as the navigator leaves the robot there, and their failures."""

from __future__ import annotations

import asyncio
import math
import random

import numpy as np
import pytest

from aiobt.geometry import Pose2D
from aiobt.msgs import PowerSupplyStatus
from aiobt.msgs.remote_actions import DockRobot, DockRobotError, UndockRobot, UndockRobotError
from aiobt_services.docking.docking import State
from aiobt_services.docking.errors import FailedToStage
from aiobt_services.docking.params import DockingParams
from aiobt_services.robot.obstacles import ObstacleSpec

from .simbase import Feedback, SimBase, docked_error, docking_server, office_sim

STAGING = Pose2D(1.49, 9.75, math.pi)  # 1 m in front of the office's dock
HOME = DockRobot.Goal(dock_id="home_dock", navigate_to_staging_pose=False)


def near_staging(rng: random.Random) -> Pose2D:
    """Where the navigator leaves the robot: within 0.25 m and 0.25 rad of the goal."""
    return Pose2D(STAGING.x + rng.uniform(-0.17, 0.17), STAGING.y + rng.uniform(-0.17, 0.17),
                  STAGING.yaw + rng.uniform(-0.25, 0.25))  # fmt: skip


async def no_navigation(pose: Pose2D, frame: str, max_time: float) -> None:
    raise AssertionError("the robot was near the staging pose: no navigation expected")


@pytest.mark.timeout(120)
async def test_docks_from_near_staging_charging_and_undocks() -> None:
    rng = random.Random(36)
    with office_sim() as sim:
        base = SimBase(sim)
        server = docking_server(base, no_navigation)
        for _ in range(3):
            base.place(near_staging(rng))
            feedback = Feedback()
            result = await server.dock_robot(HOME, feedback)
            assert result.success, result.error_msg
            distance, heading = docked_error(sim)
            assert distance <= 0.02, distance
            assert heading <= 0.05, heading
            assert base.battery is not None
            assert base.battery.power_supply_status is PowerSupplyStatus.CHARGING
            assert feedback.states[:3] == [State.NAV_TO_STAGING_POSE, State.INITIAL_PERCEPTION,
                                           State.CONTROLLING]  # fmt: skip
            undone = await server.undock_robot(UndockRobot.Goal(), Feedback())
            assert undone.success, undone.error_msg
            assert not sim.battery.charging
            assert docked_error(sim)[0] > 0.9


@pytest.mark.timeout(60)
async def test_far_from_staging_it_navigates_there_first() -> None:
    went: list[Pose2D] = []
    with office_sim() as sim:
        base = SimBase(sim)

        async def navigate(pose: Pose2D, frame: str, max_time: float) -> None:
            went.append(pose)
            base.place(Pose2D(pose.x + 0.2, pose.y - 0.1, pose.yaw + 0.2))  # the nav's tolerance

        server = docking_server(base, navigate)
        base.place(Pose2D(3.0, 10.2, 0.0))
        result = await server.dock_robot(DockRobot.Goal(dock_id="home_dock"), Feedback())
        assert result.success, result.error_msg
        assert len(went) == 1
        assert went[0].x == pytest.approx(STAGING.x)
        assert docked_error(sim)[0] <= 0.02


@pytest.mark.timeout(60)
async def test_failures_carry_nav2s_codes_and_leave_the_robot_still() -> None:
    with office_sim() as sim:
        base = SimBase(sim)

        async def cannot_stage(pose: Pose2D, frame: str, max_time: float) -> None:
            raise FailedToStage("Navigation request to staging pose failed.")

        server = docking_server(base, cannot_stage, DockingParams(initial_perception_timeout=1.0))
        unknown = await server.dock_robot(DockRobot.Goal(dock_id="kitchen"), Feedback())
        assert unknown.error_code == DockRobotError.DOCK_NOT_IN_DB
        assert "kitchen" in unknown.error_msg
        assert "home_dock" in unknown.error_msg
        base.place(Pose2D(5.0, 9.75, 0.0))
        staged = await server.dock_robot(DockRobot.Goal(dock_id="home_dock"), Feedback())
        assert staged.error_code == DockRobotError.FAILED_TO_STAGE
        base.place(Pose2D(STAGING.x, STAGING.y, 0.0))  # at staging, facing away from the dock
        blind = await server.dock_robot(HOME, Feedback())
        assert blind.error_code == DockRobotError.FAILED_TO_DETECT_DOCK
        assert "Timeout exceeded" in blind.error_msg
        assert base.last == (0.0, 0.0)
        bad_type = await server.undock_robot(UndockRobot.Goal(dock_type="pallet"), Feedback())
        assert bad_type.error_code == UndockRobotError.DOCK_NOT_VALID


@pytest.mark.timeout(60)
async def test_a_cancelled_goal_stops_the_base() -> None:
    with office_sim() as sim:
        base = SimBase(sim)
        server = docking_server(base, no_navigation)
        base.place(STAGING)
        feedback = Feedback()
        task = asyncio.ensure_future(server.dock_robot(HOME, feedback))
        await asyncio.wait_for(feedback.controlling.wait(), 10.0)
        base.step(50)
        assert base.sim.drive.linear > 0.0
        task.cancel()
        with pytest.raises(asyncio.CancelledError):
            await task
        assert base.last == (0.0, 0.0)
        assert not server.lock.locked()


@pytest.mark.timeout(60)
async def test_an_obstacle_on_the_approach_fails_to_control() -> None:
    with office_sim() as sim:
        base = SimBase(sim)
        server = docking_server(base, no_navigation, DockingParams(max_retries=0))
        # beside the line of sight to the marker (it is still seen), on the robot's way in
        sim.spawn(ObstacleSpec("box", "box", Pose2D(0.95, 9.95), size_x=0.15, size_y=0.15))
        base.place(STAGING)
        base.step(50)  # a scan or two into the docking costmap
        result = await server.dock_robot(HOME, Feedback())
        assert result.error_code == DockRobotError.FAILED_TO_CONTROL, result.error_msg
        assert result.error_msg == "Failed to get control"
        assert docked_error(sim)[0] > 0.9  # it never drove in
        assert base.last == (0.0, 0.0)


@pytest.mark.timeout(90)
async def test_a_wide_footprint_meets_a_box_the_round_robot_passes() -> None:
    """``--footprint``: the outline, not the centre, is checked (Nav2's footprint check)."""
    wide = np.array([[0.2, 0.42], [0.2, -0.42], [-0.2, -0.42], [-0.2, 0.42]])
    with office_sim() as sim:
        base = SimBase(sim)
        for footprint, box, docks in ((wide, False, True), (wide, True, False),
                                      (None, True, True)):  # fmt: skip
            if box and "box" not in sim.obstacles:  # 0.33 m beside the approach's line:
                # 0.1 m clear of the round robot
                sim.spawn(ObstacleSpec("box", "box", Pose2D(1.0, 10.15), size_x=0.15,
                                       size_y=0.15))  # fmt: skip
            server = docking_server(base, no_navigation, DockingParams(max_retries=0),
                                    footprint=footprint)  # fmt: skip
            base.place(STAGING)
            base.step(50)  # a scan or two into the docking costmap
            result = await server.dock_robot(HOME, Feedback())
            assert result.success is docks, (footprint, box, result.error_msg)
            if not docks:
                assert result.error_code == DockRobotError.FAILED_TO_CONTROL
                assert docked_error(sim)[0] > 0.9  # it never drove in
                continue
            assert docked_error(sim)[0] <= 0.02
            assert (await server.undock_robot(UndockRobot.Goal(), Feedback())).success
