"""A kinematic robot and an object given as a function of time: the following
server's logic on a clock that steps them (no physics, no Zenoh)."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from contextlib import contextmanager

from aiobt.geometry import STOP, Pose2D, Velocity
from aiobt.geometry.pose_filter import StampedPose
from aiobt.msgs import TFMessage
from aiobt.msgs.geometry import Header, Quaternion, Vector3
from aiobt.msgs.localization import Transform, TransformStamped
from aiobt.msgs.remote_actions import FollowObject
from aiobt_services.following.follow import FollowingServer
from aiobt_services.following.frames import RobotFrames
from aiobt_services.following.params import FollowingParams
from aiobt_services.following.tf_frames import FrameDetections, TransformTree

DT = 0.01
ObjectAt = Callable[[float], Pose2D | None]  # the object at a time; None: not detected


def transform(parent: str, child: str, pose: Pose2D, stamp: float) -> TransformStamped:
    """``child``'s planar ``pose`` in ``parent``, as on ``{ns}/tf``."""
    return TransformStamped(
        header=Header(stamp=stamp, frame_id=parent),
        child_frame_id=child,
        transform=Transform(
            translation=Vector3(x=pose.x, y=pose.y), rotation=Quaternion.from_yaw(pose.yaw)
        ),
    )


class Kinematic:
    """``now``/``sleep`` (a Clock), ``open`` (detections), ``command``, feedback."""

    def __init__(self, obj: ObjectAt, params: FollowingParams) -> None:
        self.obj, self.time, self.robot, self.cmd = obj, 0.0, Pose2D(), STOP
        self.frames = RobotFrames(params.base_frame, params.transform_tolerance)
        self.detection: StampedPose | None = None
        self.commands: list[Velocity] = []
        self.states: list[int] = []
        self.opened: list[str] = []
        self.topic = ""
        self.tree = TransformTree(self.frames.knows)  # the object also as tf's odom -> "person"
        self.server = FollowingServer(params, self.frames, self, self.open, self.command,
                                      open_frame=self.open_frame)  # fmt: skip
        self._feed()

    def now(self) -> float:
        return self.time

    async def sleep(self, seconds: float) -> None:
        for _ in range(max(1, round(seconds / DT))):
            r, c = self.robot, self.cmd
            self.robot = Pose2D(r.x + c.v * DT * math.cos(r.yaw), r.y + c.v * DT * math.sin(r.yaw),
                                r.yaw + c.w * DT)  # fmt: skip
            self.time = round(self.time + DT, 9)
            self._feed()

    def _feed(self) -> None:
        steps = round(self.time / DT)
        if steps % 2 == 0:
            self.frames.add("odom", self.time, self.robot)
            self.frames.add_turn_rate(self.cmd.w)
        obj = self.obj(self.time) if steps % 10 == 0 else None
        if obj is not None:
            self.detection = StampedPose(self.robot.inverse().compose(obj), self.time, "base_link")
            if obj.is_finite():
                self.tree.add(TFMessage(transforms=[self._transform("odom", "person", obj)]))

    def _transform(self, parent: str, child: str, pose: Pose2D) -> TransformStamped:
        return transform(parent, child, pose, self.time)

    def latest(self) -> StampedPose | None:
        return self.detection

    @contextmanager
    def open(self, topic: str) -> Iterator[Kinematic]:
        if "*" in topic:
            raise ValueError(f"topic {topic!r} is not a valid key")
        self.opened.append(topic)
        self.topic = f"robot/{topic}"
        yield self

    @contextmanager
    def open_frame(self, frame: str) -> Iterator[FrameDetections]:
        self.opened.append(f"tf:{frame}")
        yield FrameDetections(self.tree, frame, "robot/tf")

    def command(self, cmd: Velocity) -> None:
        self.cmd = cmd
        self.commands.append(cmd)

    def publish_feedback(self, feedback: FollowObject.Feedback) -> None:
        self.states.append(feedback.state)

    async def follow(self, **goal: object) -> FollowObject.Result:
        return await self.server.execute(FollowObject.Goal.model_validate(goal), self)
