"""Wires the following server onto the bus: the robot's odometry and pose in, the
goal's detections subscribed for the goal's time, the command and the filtered
object pose out, the ``follow_object`` action."""

from __future__ import annotations

import logging
from collections.abc import Iterator
from contextlib import contextmanager

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D, Velocity
from aiobt.geometry.pose_filter import StampedPose
from aiobt.msgs import Odometry, PoseStamped, Twist
from aiobt.msgs.remote_actions import FollowObject
from aiobt.transport import Bus
from aiobt.transport.latest import Latest

from .follow import FollowingServer
from .frames import RobotFrames
from .params import FollowingParams

log = logging.getLogger("aiobt_services.following.service")
FILTERED_TOPIC = "filtered_dynamic_pose"  # Nav2's, for viewers
MAP_POSE_TOPIC = "pose"


def planar(msg: PoseStamped) -> StampedPose:
    return StampedPose(Pose2D(msg.x, msg.y, msg.yaw), msg.header.stamp, msg.header.frame_id)


class TopicDetections:
    """The newest detection on one topic (a :class:`~.tracking.Detections`)."""

    def __init__(self, latest: Latest[PoseStamped], key: str) -> None:
        self._latest = latest
        self.topic = key

    def latest(self) -> StampedPose | None:
        msg = self._latest.get()
        return None if msg is None else planar(msg)


class FollowingService:
    def __init__(
        self, bus: Bus, clock: Clock, params: FollowingParams, cmd_vel_topic: str = "cmd_vel"
    ) -> None:
        self.bus = bus
        self.params = params
        self.frames = RobotFrames(params.base_frame, params.transform_tolerance)
        self._cmd = bus.publisher(cmd_vel_topic, Twist, reliable=True)
        self._filtered = bus.publisher(FILTERED_TOPIC, PoseStamped)
        self.server = FollowingServer(params, self.frames, clock, self.detections,
                                      self.command, self.publish_filtered)  # fmt: skip
        self.clock = clock

    def start(self) -> None:
        bus = self.bus
        bus.subscribe(self.params.odom_topic, Odometry, self.on_odom, queue_size=10)
        bus.subscribe(MAP_POSE_TOPIC, PoseStamped, self.on_pose, queue_size=10)
        bus.action_server(FollowObject.name, FollowObject, self.server.execute, clock=self.clock)

    def on_odom(self, msg: Odometry) -> None:
        pose = msg.pose
        stamp = msg.header.stamp
        self.frames.add(msg.header.frame_id or "odom", stamp,
                        Pose2D(pose.position.x, pose.position.y, pose.yaw))  # fmt: skip
        self.frames.add_turn_rate(msg.twist.angular.z)

    def on_pose(self, msg: PoseStamped) -> None:
        self.frames.add(msg.header.frame_id or "map", msg.header.stamp, planar(msg).pose)

    @contextmanager
    def detections(self, topic: str) -> Iterator[TopicDetections]:
        latest = self.bus.latest(topic, PoseStamped)
        try:
            yield TopicDetections(latest, self.bus.keys.topic(topic))
        finally:
            latest.close()

    def command(self, cmd: Velocity) -> None:
        self._cmd.put(Twist.planar(cmd.v, cmd.w))

    def publish_filtered(self, pose: StampedPose) -> None:
        p = pose.pose
        self._filtered.put(PoseStamped.from_xy_yaw(p.x, p.y, p.yaw, pose.frame, pose.stamp))
