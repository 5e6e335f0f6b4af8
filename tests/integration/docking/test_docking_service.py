"""The docking server process with the robot process over a real router: DockRobot from
near the staging pose docks on the contacts (measured on the simulation's truth) and
the battery reports CHARGING, UndockRobot leaves; a dock id not in the database and a
database that does not parse are clear errors, and the server keeps serving."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import pytest

from aiobt.msgs import BatteryState, PoseStamped, PowerSupplyStatus, TFMessage, Trigger
from aiobt.msgs.docking import DockingState, DockList, ReloadDockDatabase
from aiobt.msgs.geometry import Header, Vector3
from aiobt.msgs.localization import Transform, TransformStamped
from aiobt.msgs.remote_actions import DockRobot, DockRobotError, UndockRobot
from aiobt.msgs.sim import Ack
from aiobt.testing.bus import ServiceProcess
from aiobt.transport import Bus, BusSettings
from aiobt.transport.keys import SIM_POSE, sim_namespace

from ..services import TRUTH, common, up

pytestmark = pytest.mark.integration
Spawn = Callable[[Sequence[str]], ServiceProcess]
DOCK = (0.49, 9.75, math.pi)  # the office's dock (worlds/office.yaml)
HOME = DockRobot.Goal(dock_id="home_dock", navigate_to_staging_pose=False)


async def start(spawn: Spawn, bus: Bus, settings: BusSettings, *docking: str) -> None:
    robot = spawn(["-m", "aiobt_services.robot", "--world", "office", "--speed", "4",
                   "--battery", "0.5", "--seed", "5", *TRUTH, *common(settings)])  # fmt: skip
    await up(bus, "robot", robot)
    server = spawn(["-m", "aiobt_services.docking", "--sim-time", *docking, *common(settings)])
    await up(bus, "docking", server)


async def send(bus: Bus, action: Any, goal: Any) -> Any:
    client = bus.action_client(action.name, action)
    return await (await client.send_goal(goal, server_timeout=10.0)).result(timeout=120.0)


async def place(bus: Bus, x: float, y: float, yaw: float) -> None:
    sim = sim_namespace(bus.namespace)  # the simulation's services
    ack = await bus.call("reset_pose", PoseStamped.from_xy_yaw(x, y, yaw), Ack, namespace=sim)
    assert ack.ok, ack.message


def off_the_dock(truth: PoseStamped) -> tuple[float, float]:
    """Distance and heading error of the robot from the dock pose (the truth)."""
    heading = math.atan2(math.sin(truth.yaw - DOCK[2]), math.cos(truth.yaw - DOCK[2]))
    return math.hypot(truth.x - DOCK[0], truth.y - DOCK[1]), abs(heading)


@pytest.mark.timeout(240)
async def test_docks_charging_and_undocks(spawn: Spawn, bus: Bus, bus_settings: BusSettings):
    truth = bus.latest(SIM_POSE, PoseStamped)
    battery = bus.latest("battery", BatteryState)
    await start(spawn, bus, bus_settings, "--dock-database", "office")
    docks = await bus.latest("docks", DockList, latched=True).wait_latest(10.0)
    assert [d.name for d in docks.docks] == ["home_dock"]
    for x, y, yaw in ((1.6, 9.6, 3.0), (1.4, 9.9, -2.95)):
        await place(bus, x, y, yaw)
        done = await send(bus, DockRobot, HOME)
        assert done.error_code == 0, done.error_msg
        assert done.success
        distance, heading = off_the_dock(await truth.wait_latest(5.0))
        assert distance <= 0.02, distance
        assert heading <= 0.05, heading
        state = await bus.latest("docking_state", DockingState, latched=True).wait_latest(5.0)
        assert (state.docked, state.dock) == (True, "home_dock")
        charging = await battery.wait_latest(5.0)
        assert charging.power_supply_status is PowerSupplyStatus.CHARGING
        left = await send(bus, UndockRobot, UndockRobot.Goal())
        assert left.error_code == 0, left.error_msg
        assert off_the_dock(await truth.wait_latest(5.0))[0] > 0.9

    unknown = await send(bus, DockRobot, DockRobot.Goal(dock_id="kitchen"))
    assert unknown.error_code == DockRobotError.DOCK_NOT_IN_DB
    assert "'kitchen'; known: home_dock" in unknown.error_msg


@pytest.mark.timeout(120)
async def test_a_database_that_does_not_parse(spawn: Spawn, bus: Bus, bus_settings: BusSettings,
                                              tmp_path: Path):  # fmt: skip
    broken = tmp_path / "docks.yaml"
    broken.write_text("docks:\n  home_dock:\n    type: simple_charging_dock\n    pose: [1, 2]\n")
    robot = spawn(["-m", "aiobt_services.robot", "--world", "office", "--speed", "4",
                   *TRUTH, *common(bus_settings)])  # fmt: skip
    await up(bus, "robot", robot)
    server = spawn(["-m", "aiobt_services.docking", "--sim-time", "--dock-database", str(broken),
                    *common(bus_settings)])  # fmt: skip
    await up(bus, "docking", server)
    problem = f"dock database {broken}:4: dock 'home_dock' 'pose' must be [x, y, theta]"
    assert server.wait_for_output(problem), server.output()
    refused = await send(bus, DockRobot, HOME)
    assert refused.error_code == DockRobotError.DOCK_NOT_IN_DB
    assert problem in refused.error_msg
    assert server.running

    # reload_database: a good one is taken and shown; a bad one is refused, the good kept
    reload, reply = ReloadDockDatabase, ReloadDockDatabase.Response
    good = await bus.call(reload.service_name, reload.Request(filepath="office"), reply)
    assert good.success, good.message
    docks = await bus.latest("docks", DockList, latched=True).wait_latest(5.0)
    assert [d.name for d in docks.docks] == ["home_dock"]
    bad = await bus.call(reload.service_name, reload.Request(filepath=str(broken)), reply)
    assert not bad.success
    assert problem in bad.message
    unknown = await send(bus, DockRobot, DockRobot.Goal(dock_id="kitchen"))
    assert "known: home_dock)" in unknown.error_msg


@pytest.mark.timeout(180)
async def test_docks_given_as_parameters_with_the_detector_only_while_docking(
    spawn: Spawn, bus: Bus, bus_settings: BusSettings
):
    """Nav2's ``docks`` parameter instead of a file, the robot's detector started and
    stopped by the docking server through ``srv/dock_detector/toggle``, docked by
    stall detection alone (the robot's wheels on ``joint_states``; no battery status),
    the approach checked with a footprint polygon (Nav2's ``footprint`` string), the dock
    given in a frame of its own, ``bay``, that ``tf_static`` places in ``map``."""
    truth = bus.latest(SIM_POSE, PoseStamped)
    bay = TransformStamped(
        header=Header(frame_id="map"),
        child_frame_id="bay",
        transform=Transform(translation=Vector3(x=DOCK[0] - 1.0, y=DOCK[1])),
    )
    bus.latched_publisher("tf_static", TFMessage).put(TFMessage(transforms=[bay]))
    pose = f"home.pose=[1.0,0.0,{DOCK[2]}]"  # 1 m along the bay's x: the dock
    plugin = "simple_charging_dock."
    await start(spawn, bus, bus_settings, "--docks", "home", "--param",
                "home.type=simple_charging_dock", "--param", pose, "--param", "home.frame=bay",
                "--param", f"{plugin}detector_service_name=dock_detector/toggle",
                "--param", f"{plugin}subscribe_toggle=true",
                "--param", f"{plugin}use_stall_detection=true",
                "--param", f"{plugin}stall_joint_names=[wheel_left_joint,wheel_right_joint]",
                "--param", f"{plugin}use_battery_status=false",
                "--footprint", "[[0.2, 0.2], [0.2, -0.2], [-0.2, -0.2], [-0.2, 0.2]]")  # fmt: skip
    docks = await bus.latest("docks", DockList, latched=True).wait_latest(10.0)
    assert [d.name for d in docks.docks] == ["home"]
    await place(bus, 1.6, 9.6, 3.0)
    detections = bus.subscribe("detected_dock_pose", PoseStamped, queue_size=1)
    await detections.next(timeout=10.0)  # the robot's detector is on from the start
    done = await send(bus, DockRobot, DockRobot.Goal(dock_id="home",
                                                     navigate_to_staging_pose=False))  # fmt: skip
    assert done.success, done.error_msg
    assert off_the_dock(await truth.wait_latest(5.0))[0] <= 0.02
    after = bus.subscribe("battery", BatteryState, queue_size=1)  # reported after the docking
    assert (await after.next(timeout=5.0)).power_supply_status is PowerSupplyStatus.CHARGING
    stopped = bus.subscribe("detected_dock_pose", PoseStamped, queue_size=1)  # after the stop
    with pytest.raises(TimeoutError):
        await stopped.next(timeout=2.0)  # 8 s of sim time: 120 detections were it on
    turned = await bus.call("dock_detector/toggle", Trigger.Request(), Trigger.Response)
    assert turned.message == "dock detector on"
    await stopped.next(timeout=10.0)
