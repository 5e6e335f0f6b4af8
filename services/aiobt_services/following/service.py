"""Wires the following server onto the bus: the robot's odometry and its pose in ``map``
(:class:`~aiobt.geometry.map_pose.MapPose`: the odometry composed with localization's
correction on ``tf``, ``pose`` read only until one is composed) in; the goal's detections
subscribed for the goal's time; the command and the filtered object pose out; the
``follow_object`` action."""

from __future__ import annotations

import asyncio
import logging
import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from typing import Any, Protocol

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D, Velocity
from aiobt.geometry.map_pose import TF_KEPT, MapPose
from aiobt.geometry.pose_filter import StampedPose
from aiobt.msgs import Odometry, PoseStamped, TFMessage, Twist
from aiobt.msgs.remote_actions import FollowObject
from aiobt.transport import Bus
from aiobt.transport.latest import Latest

from .follow import FollowingServer
from .frames import HISTORY, RobotFrames
from .params import FollowingParams
from .tf_frames import FrameDetections, TransformTree

log = logging.getLogger("aiobt_services.following.service")
FILTERED_TOPIC = "filtered_dynamic_pose"  # Nav2's, for viewers
MAP_POSE_TOPIC = "pose"
TF_TOPIC = "tf"  # transforms, as localization's map -> odom: a tracked_frame's come here
KEEP = round(HISTORY * 50)  # the poses of HISTORY s at the robot's 50 Hz
Stamped = tuple[str, float, Pose2D, float | None]  # frame, stamp, pose, turn rate


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


class Kept(Protocol):
    """The last messages of a topic, newest first (:class:`Latest` with ``keep``)."""

    def newest_first(self) -> Iterator[Any]: ...


class PoseFeed:
    """A pose topic's kept messages into :class:`RobotFrames` when the server looks
    (``refresh``), not as each arrives: read from Zenoh's own buffer, the robot's poses
    are as fresh as the detection read beside them, however late this process's event
    loop runs (a pose behind its detection by more than ``transform_tolerance`` would
    lose the object)."""

    def __init__(self, latest: Kept, frames: RobotFrames, read: Callable[[Any], Stamped]) -> None:
        self._latest, self._frames, self._read = latest, frames, read
        self._last = -math.inf

    def refresh(self) -> None:
        fresh: list[Stamped] = []
        for msg in self._latest.newest_first():
            stamped = self._read(msg)
            if not fresh and stamped[1] < self._last:  # the robot restarted: time anew
                self._last = -math.inf
            if stamped[1] <= self._last:
                break
            fresh.append(stamped)
        for frame, stamp, pose, rate in reversed(fresh):
            self._frames.add(frame, stamp, pose)
            if rate is not None:
                self._frames.add_turn_rate(rate)
        if fresh:
            self._last = fresh[0][1]


def odom_reading(msg: Odometry) -> Stamped:
    p = msg.pose
    pose = Pose2D(p.position.x, p.position.y, p.yaw)
    return msg.header.frame_id or "odom", msg.header.stamp, pose, msg.twist.angular.z


def map_reading(msg: PoseStamped) -> Stamped:
    return msg.header.frame_id or "map", msg.header.stamp, planar(msg).pose, None


class FollowingService:
    def __init__(
        self, bus: Bus, clock: Clock, params: FollowingParams, cmd_vel_topic: str = "cmd_vel"
    ) -> None:
        self.bus = bus
        self.params = params
        self.frames = RobotFrames(params.base_frame, params.transform_tolerance, self.refresh)
        self._feeds: list[PoseFeed] = []
        self._settle: asyncio.Task[None] | None = None
        self._cmd = bus.publisher(cmd_vel_topic, Twist, reliable=True)
        self._filtered = bus.publisher(FILTERED_TOPIC, PoseStamped)
        self.server = FollowingServer(params, self.frames, clock, self.detections,
                                      self.command, self.publish_filtered,
                                      self.frame_detections)  # fmt: skip
        self.clock = clock

    def start(self) -> None:
        bus = self.bus
        odom = bus.latest(self.params.odom_topic, Odometry, keep=KEEP)
        in_map = MapPose(odom, bus.latest(TF_TOPIC, TFMessage, keep=TF_KEPT),
                         bus.latest(MAP_POSE_TOPIC, PoseStamped, keep=KEEP))  # fmt: skip
        self._feeds += [PoseFeed(odom, self.frames, odom_reading),
                        PoseFeed(in_map, self.frames, map_reading)]  # fmt: skip
        # between goals nothing reads the pose: let ``pose`` go once localization corrects
        self._settle = asyncio.create_task(in_map.settle(), name="following.map_pose")
        bus.action_server(FollowObject.name, FollowObject, self.server.execute, clock=self.clock)

    def refresh(self) -> None:
        for feed in self._feeds:
            feed.refresh()

    @contextmanager
    def detections(self, topic: str) -> Iterator[TopicDetections]:
        latest = self.bus.latest(topic, PoseStamped)
        try:
            yield TopicDetections(latest, self.bus.keys.topic(topic))
        finally:
            latest.close()

    @contextmanager
    def frame_detections(self, frame: str) -> Iterator[FrameDetections]:
        """``{ns}/tf`` read into a tree for the goal's time: the tracked frame's poses."""
        tree = TransformTree(self.frames.knows)
        tf = self.bus.subscribe(TF_TOPIC, TFMessage, callback=tree.add)
        try:
            yield FrameDetections(tree, frame, self.bus.keys.topic(TF_TOPIC))
        finally:
            tf.close()

    def command(self, cmd: Velocity) -> None:
        self._cmd.put(Twist.planar(cmd.v, cmd.w))

    def publish_filtered(self, pose: StampedPose) -> None:
        p = pose.pose
        self._filtered.put(PoseStamped.from_xy_yaw(p.x, p.y, p.yaw, pose.frame, pose.stamp))
