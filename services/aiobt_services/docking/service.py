"""Wires the docking server onto the bus: the robot's odometry, its pose in ``map``
(:class:`~aiobt.geometry.map_pose.MapPose`: the odometry composed with localization's
correction on ``tf``, ``pose`` read only until one is composed), static transforms
(``tf_static``), battery and the dock's detections in; ``cmd_vel``, the poses it works
with (``dock_pose``, ``filtered_dock_pose``, ``staging_pose``), the docks and the docked
state (latched, for viewers) out; the two actions and ``docking_server/reload_database``."""

from __future__ import annotations

import asyncio
import logging
from typing import Any

import numpy as np

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D, Velocity
from aiobt.geometry.map_pose import TF_KEPT, MapPose
from aiobt.geometry.pose_filter import StampedPose3D
from aiobt.geometry.static_frames import StaticFrames
from aiobt.msgs import (
    BatteryState,
    JointState,
    LaserScan,
    Odometry,
    PoseStamped,
    TFMessage,
    Trigger,
    Twist,
)
from aiobt.msgs.docking import DockEntry, DockingState, DockList, ReloadDockDatabase
from aiobt.msgs.remote_actions import DockRobot, UndockRobot
from aiobt.transport import Bus, Latest

from .database import DockInstance, database_path, load_database
from .errors import DockDatabaseError
from .frames import RobotFrames
from .server import DockingServer

log = logging.getLogger("aiobt_services.docking.service")
ODOMETRY_KEPT = 60  # 1.2 s of odometry at 50 Hz: to place a detection (up to 1 s old) by its stamp
SHOWN = ("dock_pose", "filtered_dock_pose", "staging_pose")


def detection_of(msg: PoseStamped) -> StampedPose3D:
    q = msg.pose.orientation
    p = msg.pose.position
    return StampedPose3D(p.x, p.y, p.z, np.array([q.x, q.y, q.z, q.w]), msg.header.stamp,
                     msg.header.frame_id)  # fmt: skip


class DockingBus:
    """The server's inputs and outputs on ``bus``; :meth:`serve` starts the actions."""

    def __init__(self, bus: Bus, clock: Clock, cmd_vel_topic: str = "cmd_vel") -> None:
        self.bus = bus
        self.clock = clock
        self._odom = bus.latest("odom", Odometry, keep=ODOMETRY_KEPT)
        tf = bus.latest("tf", TFMessage, keep=TF_KEPT)
        self._pose = MapPose(self._odom, tf, bus.latest("pose", PoseStamped))
        # between goals nothing reads the pose: let ``pose`` go once localization corrects
        self._settle = asyncio.create_task(self._pose.settle(), name="docking.map_pose")
        self._detected: Latest[PoseStamped] | None = None  # while a plugin subscribes
        self._subscribers = 0
        self._joints: Latest[JointState] | None = None  # once a plugin detects stalls
        self._battery = bus.latest("battery", BatteryState)
        self._scan = bus.latest("scan", LaserScan)
        statics = StaticFrames()  # every latched publisher's, kept for good (tf2's)
        bus.subscribe("tf_static", TFMessage, callback=statics.add, latched=True)
        self.frames = RobotFrames(self._pose.get, self._odom.newest_first, statics)
        self._cmd = bus.publisher(cmd_vel_topic, Twist)
        self._shown = {name: bus.publisher(name, PoseStamped) for name in SHOWN}
        self._docks = bus.latched_publisher("docks", DockList)
        self._state = bus.latched_publisher("docking_state", DockingState)

    def detection(self) -> StampedPose3D | None:
        msg = None if self._detected is None else self._detected.get()
        return None if msg is None else detection_of(msg)

    def joint_states(self) -> JointState | None:
        """The wheels' newest ``joint_states`` (subscribed at the first call)."""
        if self._joints is None:
            self._joints = self.bus.latest("joint_states", JointState)
        return self._joints.get()

    def subscribe(self, on: bool) -> None:
        """Open (``True``) or close the detections' subscription; it lasts while any
        plugin holds it."""
        self._subscribers = max(0, self._subscribers + (1 if on else -1))
        if self._subscribers and self._detected is None:
            self._detected = self.bus.latest("detected_dock_pose", PoseStamped)
        elif not self._subscribers and self._detected is not None:
            self._detected.close()
            self._detected = None

    async def trigger(self, name: str, timeout: float) -> str | None:  # noqa: ASYNC109
        """Call the ``std_srvs/Trigger`` service ``{ns}/srv/{name}``: None, or why not."""
        try:
            reply = await self.bus.call(name.strip("/"), Trigger.Request(), Trigger.Response,
                                        timeout)  # fmt: skip
        except Exception as exc:  # any failure of the call fails the start, as in Nav2
            return str(exc) or type(exc).__name__
        return None if reply.success else f"success false ({reply.message or 'no message'})"

    def battery(self) -> BatteryState | None:
        return self._battery.get()

    def scan(self) -> LaserScan | None:
        return self._scan.get()

    def drive(self, cmd: Velocity) -> None:
        self._cmd.put(Twist.planar(cmd.v, cmd.w))

    def turn_rate(self) -> float:
        odom = self._odom.get()
        return 0.0 if odom is None else odom.twist.angular.z

    def show(self, name: str, pose: Pose2D, frame: str) -> None:
        msg = PoseStamped.from_xy_yaw(pose.x, pose.y, pose.yaw, frame, self.clock.now())
        self._shown[name].put(msg)

    def serve(self, server: DockingServer) -> None:
        bus = self.bus

        async def dock(goal: DockRobot.Goal, handle: Any) -> DockRobot.Result:
            result = await server.dock_robot(goal, handle)
            self.publish_state(server)
            return result

        async def undock(goal: UndockRobot.Goal, handle: Any) -> UndockRobot.Result:
            result = await server.undock_robot(goal, handle)
            self.publish_state(server)
            return result

        bus.action_server(DockRobot.name, DockRobot, dock, clock=self.clock)
        bus.action_server(UndockRobot.name, UndockRobot, undock, clock=self.clock)
        bus.serve(ReloadDockDatabase.service_name, ReloadDockDatabase.Request,
                  ReloadDockDatabase.Response, lambda req: self.reload(server, req))  # fmt: skip
        self.publish_docks(server)
        self.publish_state(server)

    def reload(self, server: DockingServer, req: Any) -> Any:
        if server.lock.locked():
            log.error("Cannot reload database while docking!")
            return ReloadDockDatabase.Response(message="Cannot reload database while docking!")
        try:
            server.docks = load_database(database_path(req.filepath))
            server.database_error = ""
        except DockDatabaseError as exc:
            log.error("%s", exc)
            return ReloadDockDatabase.Response(message=str(exc))
        log.info("Dock database reloaded from file %s.", req.filepath)
        self.publish_docks(server)
        return ReloadDockDatabase.Response(success=True)

    def publish_docks(self, server: DockingServer) -> None:
        self._docks.put(
            DockList(docks=[self._entry(server, dock) for dock in server.docks.values()])
        )

    def publish_state(self, server: DockingServer) -> None:
        docked = bool(server.current_type or server.docked_at)
        self._state.put(DockingState(docked=docked, dock=server.docked_at,
                                     dock_type=server.current_type))  # fmt: skip

    def _entry(self, server: DockingServer, dock: DockInstance) -> DockEntry:
        pose = PoseStamped.from_xy_yaw(dock.pose.x, dock.pose.y, dock.pose.yaw, dock.frame)
        plugin = server.find_plugin(dock.type)
        staging = None
        if plugin is not None:
            s = plugin.staging_pose(dock.pose, dock.frame)
            staging = PoseStamped.from_xy_yaw(s.x, s.y, s.yaw, dock.frame)
        return DockEntry(name=dock.name, type=dock.type, id=dock.id, pose=pose, staging=staging)
