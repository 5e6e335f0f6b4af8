"""Nav2's SimpleNonChargingDock (its ObjectLifecycle, StagingPose and
StagingPoseWithYawOffset tests), and DockRobot / UndockRobot to the office's dock taken
as a non-charging one on the simulation: docked, no wait for a charge."""

from __future__ import annotations

import pytest

from aiobt.geometry import Pose2D
from aiobt.msgs.remote_actions import UndockRobot
from aiobt_services.docking.docking import State
from aiobt_services.docking.frames import RobotFrames
from aiobt_services.docking.plugins import DockWiring
from aiobt_services.docking.simple_dock import SimpleDockParams
from aiobt_services.docking.simple_non_charging_dock import SimpleNonChargingDock

from . import simbase as sb

NON_CHARGING = "opennav_docking::SimpleNonChargingDock"


def dock(**given: object) -> SimpleNonChargingDock:
    wiring = DockWiring(RobotFrames(lambda: None, lambda: iter(())), None,  # type: ignore[arg-type]
                        lambda: None, lambda: None, lambda *_: None)  # fmt: skip
    return SimpleNonChargingDock("my_dock", SimpleDockParams(**given), wiring)  # type: ignore[arg-type]


async def test_object_lifecycle() -> None:
    plugin = dock(use_external_detection_pose=True)
    assert await plugin.start_detection()
    assert await plugin.stop_detection()
    for question in (plugin.is_charging, plugin.disable_charging, plugin.has_stopped_charging):
        with pytest.raises(RuntimeError, match="This dock is not a charging dock!"):
            question()
    assert not plugin.is_charger


@pytest.mark.parametrize(("yaw_offset", "yaw"), [(0.0, 0.0), (3.14, 3.14)])
def test_staging_pose(yaw_offset: float, yaw: float) -> None:
    staging = dock(staging_yaw_offset=yaw_offset).staging_pose(Pose2D(), "my_frame")
    assert (staging.x, staging.y, staging.yaw) == pytest.approx((-0.7, 0.0, yaw), abs=0.01)


@pytest.mark.timeout(60)
async def test_docks_and_undocks_without_charging() -> None:
    with sb.office_sim() as sim:
        base = sb.SimBase(sim)
        server = sb.docking_server(base, sb.no_navigation, kind=NON_CHARGING)
        assert not server.plugins["simple_charging_dock"].is_charger
        base.place(sb.STAGED)
        feedback = sb.Feedback()
        result = await server.dock_robot(sb.HOME, feedback)
        assert result.success, result.error_msg
        assert sb.docked_error(sim)[0] <= 0.02
        assert State.WAIT_FOR_CHARGE not in feedback.states
        undone = await server.undock_robot(UndockRobot.Goal(), sb.Feedback())
        assert undone.success, undone.error_msg
        assert sb.docked_error(sim)[0] > 0.9
