"""The docking server's logic against the real simulation, in one process, no Zenoh:
the server's clock steps the pybullet world (its sleeps are sim time), its commands go
to the base, and it reads what the robot service would publish: the odometry, the pose
(the localization stand-in), the battery and the camera's detections of the dock."""

from __future__ import annotations

import asyncio
import math
from collections import deque
from collections.abc import Iterator
from dataclasses import dataclass, field

from aiobt.costmap import footprint_from_radius
from aiobt.costmap.local import LocalCostmap
from aiobt.geometry import FloatArray, Pose2D, Velocity
from aiobt.geometry.pose_filter import StampedPose3D
from aiobt.geometry.smooth import SmoothControlParams
from aiobt.geometry.static_frames import StaticFrames
from aiobt.msgs import BatteryState, JointState, LaserScan, Odometry, PoseStamped, Trigger
from aiobt.msgs.remote_actions import DockRobot
from aiobt.system.plugin_params import params_from
from aiobt_services.docking.collisions import ScanCollisions
from aiobt_services.docking.controller import ControllerParams, DockController
from aiobt_services.docking.database import DockInstance
from aiobt_services.docking.frames import RobotFrames
from aiobt_services.docking.motion import Motion
from aiobt_services.docking.options import PLUGIN_TYPES, SHIPPED
from aiobt_services.docking.params import DockingParams
from aiobt_services.docking.plugins import DockWiring
from aiobt_services.docking.server import DockingServer
from aiobt_services.docking.service import detection_of
from aiobt_services.robot import convert
from aiobt_services.robot.dock_detector import DockDetectorSwitch
from aiobt_services.robot.mapfile import load_map
from aiobt_services.robot.sensors import BatteryConfig, NoiseConfig
from aiobt_services.robot.sim import SimConfig, Simulation
from aiobt_services.robot.worlds import WORLDS_DIR

STAGED = Pose2D(1.45, 9.8, math.pi - 0.1)  # about the office dock's staging pose
HOME = DockRobot.Goal(dock_id="home_dock", navigate_to_staging_pose=False)
CAMERA_EVERY = 7  # steps: about 15 Hz, as the robot service
BATTERY_EVERY = 100  # 1 Hz
SCAN_EVERY = 10  # 10 Hz


class SimClock:
    """Robot time is the simulation's; a sleep steps it (publishing as the robot does)."""

    def __init__(self, base: SimBase) -> None:
        self.base = base

    def now(self) -> float:
        return self.base.sim.time

    async def sleep(self, seconds: float) -> None:
        self.base.step(max(1, round(seconds / self.base.sim.config.dt)))
        await asyncio.sleep(0)


@dataclass
class SimBase:
    sim: Simulation
    odometry: deque[Odometry] = field(default_factory=lambda: deque(maxlen=25))
    detected: PoseStamped | None = None
    joints: JointState | None = None  # the wheels, as joint_states
    battery: BatteryState | None = None
    scan: LaserScan | None = None
    last: tuple[float, float] = (0.0, 0.0)  # the last command
    detector: DockDetectorSwitch = field(default_factory=DockDetectorSwitch)  # the robot's
    calls: list[str] = field(default_factory=list)  # Trigger services called, by name

    def step(self, count: int) -> None:
        for _ in range(count):
            self.sim.step()
            steps = self.sim.steps
            if steps % 2 == 0:
                self.odometry.appendleft(convert.odometry(self.sim))
                self.joints = self.sim.wheels.state(self.sim.time)
            seen = self.sim.detect_dock() if steps % CAMERA_EVERY == 0 else None
            if seen is not None and self.detector.on:
                self.detected = convert.dock_detection(seen, self.sim.time)
            if steps % SCAN_EVERY == 0:
                self.scan = convert.laser_scan(self.sim.scan())
            if steps % BATTERY_EVERY == 0:
                self.battery = convert.battery_state(self.sim.battery, self.sim.time)

    def place(self, pose: Pose2D) -> None:
        """Teleport the robot, then let a few odometry and camera messages out."""
        self.sim.teleport(pose)
        self.step(10)

    def drive(self, cmd: Velocity) -> None:
        self.last = (cmd.v, cmd.w)
        self.sim.command(cmd.v, cmd.w)

    def pose(self) -> PoseStamped:
        return convert.map_pose(self.sim)

    def odoms(self) -> Iterator[Odometry]:
        return iter(self.odometry)

    def detection(self) -> StampedPose3D | None:
        return None if self.detected is None else detection_of(self.detected)

    async def trigger(self, name: str, timeout: float) -> str | None:  # noqa: ASYNC109
        """The robot's ``dock_detector/toggle``, the one Trigger service it has."""
        self.calls.append(name)
        if name != "dock_detector/toggle":
            return f"no service '{name}'"
        self.detector.toggle(Trigger.Request())
        return None


async def no_navigation(pose: Pose2D, frame: str, max_time: float) -> None:
    raise AssertionError("the robot was near the staging pose: no navigation expected")


def office_sim(battery: float = 0.5, seed: int = 3) -> Simulation:
    noise = NoiseConfig(odom_linear=0.05, odom_angular=0.05, slip=0.02, odom_angular_scale=0.02,
                        seed=seed)  # fmt: skip
    config = SimConfig(noise=noise, battery=BatteryConfig(initial_percentage=battery))
    return Simulation(load_map(WORLDS_DIR / "office.yaml"), config)


def docking_server(base: SimBase, navigate: object, params: DockingParams | None = None,
                   dock_params: dict[str, str] | None = None,
                   kind: str = "opennav_docking::SimpleChargingDock",
                   footprint: FloatArray | None = None,
                   statics: StaticFrames | None = None) -> DockingServer:  # fmt: skip
    """The server with one dock plugin of Nav2's type ``kind`` (set up as shipped, with
    ``dock_params`` over it), for the office's dock; the approach checks ``footprint``
    (default: the robot's circle, as ``aiobt docking`` without ``--footprint``); ``statics``
    the transforms of ``tf_static``."""
    clock = SimClock(base)
    frames = RobotFrames(base.pose, base.odoms, statics)
    wiring = DockWiring(frames, clock, base.detection, lambda: base.battery, lambda *_: None,
                        trigger=base.trigger, joint_states=lambda: base.joints)  # fmt: skip
    given = SHIPPED["simple_charging_dock"] | (dock_params or {})
    params_type, make = PLUGIN_TYPES[kind]
    plugin = make("simple_charging_dock", params_from(params_type, "simple_charging_dock", given),
                  wiring)  # fmt: skip
    law = SmoothControlParams(k_phi=5.0, k_delta=3.0, v_linear_min=0.15, v_linear_max=0.15)
    outline = footprint_from_radius(0.22) if footprint is None else footprint
    costmap = ScanCollisions(LocalCostmap(), outline, lambda: base.scan, frames, clock)
    controller = DockController(ControllerParams(law), costmap.collides)
    motion = Motion(params or DockingParams(), controller, frames, clock, base.drive,
                    lambda: base.sim.odometry.angular, costmap.refresh)  # fmt: skip
    dock = base.sim.world.dock
    assert dock is not None
    home = DockInstance("home_dock", "simple_charging_dock", Pose2D(dock.x, dock.y, dock.yaw))
    return DockingServer(motion, navigate, {"simple_charging_dock": plugin},  # type: ignore[arg-type]
                         {"home_dock": home})  # fmt: skip


class Feedback:
    """A goal handle's feedback: the states in order; ``controlling`` once approaching."""

    def __init__(self) -> None:
        self.states: list[int] = []
        self.controlling = asyncio.Event()

    def publish_feedback(self, feedback: DockRobot.Feedback) -> None:
        if not self.states or self.states[-1] != feedback.state:
            self.states.append(feedback.state)
        if feedback.state == 3:
            self.controlling.set()


def docked_error(sim: Simulation) -> tuple[float, float]:
    """The robot's distance (m) and heading error (rad) from the dock pose, from the truth."""
    station = sim.dock_station
    assert station is not None
    off = station.offset(sim.true_pose)
    return math.hypot(off.x, off.y), abs(off.yaw)
