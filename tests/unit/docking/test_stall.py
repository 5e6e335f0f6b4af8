"""Stall detection (Nav2's SimpleChargingDock ``StallDetection`` test): docked when the
wheels named have stopped while their motors push; and DockRobot on the simulation
docking by it, the robot's wheels reported on ``joint_states``."""

from __future__ import annotations

import pytest

from aiobt.msgs import JointState, PowerSupplyStatus
from aiobt.system.plugin_params import params_from
from aiobt_services.docking.frames import RobotFrames
from aiobt_services.docking.plugins import DockWiring
from aiobt_services.docking.simple_charging_dock import SimpleChargingDock, SimpleChargingDockParams

from . import simbase as sb

NAMES = ["left_motor", "right_motor", "another_motor"]


def joints(velocity: list[float], effort: list[float]) -> JointState:
    return JointState(name=NAMES, velocity=velocity, effort=effort)


def test_nav2s_stall_detection_case() -> None:
    newest: list[JointState] = []
    wiring = DockWiring(RobotFrames(lambda: None, lambda: iter(())), None,  # type: ignore[arg-type]
                        lambda: None, lambda: None, lambda *_: None,
                        joint_states=lambda: newest[-1] if newest else None)  # fmt: skip
    given = {"use_stall_detection": "true", "stall_joint_names": "[left_motor, right_motor]",
             "stall_velocity_threshold": "0.1", "stall_effort_threshold": "5.0"}  # fmt: skip
    params = params_from(SimpleChargingDockParams, "my_dock", given)
    assert params.stall_joint_names == ("left_motor", "right_motor")
    dock = SimpleChargingDock("my_dock", params, wiring)
    assert not dock.is_docked()  # nothing yet
    newest.append(joints([0.0, 0.0, 0.0], [0.0, 0.0, 0.0]))  # stopped, below the effort
    assert not dock.is_docked()
    newest.append(joints([1.0, 1.0, 0.0], [5.1, -5.1, 0.0]))  # moving, with effort
    assert not dock.is_docked()
    newest.append(joints([0.0, 0.0, 0.0], [5.1, -5.1, 0.0]))  # stopped, with effort
    assert dock.is_docked()
    newest.append(JointState(name=["left_motor"], velocity=[0.0], effort=[5.1]))
    assert not dock.is_docked()  # the mean is over both names: 2.55 N m


def test_stall_detection_without_joint_names_is_refused() -> None:
    with pytest.raises(ValueError, match="stall_joint_names cannot be empty"):
        SimpleChargingDockParams(use_stall_detection=True)


STALL = {"use_stall_detection": "true", "use_battery_status": "false",  # docked: stalled only
         "stall_joint_names": "wheel_left_joint,wheel_right_joint"}  # fmt: skip


@pytest.mark.timeout(60)
async def test_docks_by_stall_on_the_simulation() -> None:
    with sb.office_sim() as sim:
        base = sb.SimBase(sim)
        server = sb.docking_server(base, sb.no_navigation, dock_params=STALL)
        base.place(sb.STAGED)
        plugin = server.plugins["simple_charging_dock"]
        assert not plugin.is_docked()  # standing: no effort
        result = await server.dock_robot(sb.HOME, sb.Feedback())
        assert result.success, result.error_msg
        distance, heading = sb.docked_error(sim)
        assert distance <= 0.02, distance
        assert heading <= 0.05, heading
        base.step(100)  # the battery's next report
        assert base.battery is not None
        assert base.battery.power_supply_status is PowerSupplyStatus.CHARGING
        assert base.joints is not None
        assert max(abs(v) for v in base.joints.velocity) < 1.0  # stopped on the dock
