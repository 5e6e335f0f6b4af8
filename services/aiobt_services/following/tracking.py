"""The followed object's pose for the control loop (Nav2's ``getRefinedPose``): the
newest detection on the goal's topic, fresh within ``detection_timeout``, put in the
fixed frame, aimed at from the robot (``skip_orientation``), low-pass filtered."""

from __future__ import annotations

import math
from typing import Protocol

from aiobt.core.clock import Clock
from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import PoseFilter, StampedPose

from .errors import FailedToDetect, FollowingError
from .frames import RobotFrames
from .params import FollowingParams


class Detections(Protocol):
    """The newest detection received on the goal's pose topic (None before one)."""

    @property
    def topic(self) -> str: ...

    def latest(self) -> StampedPose | None: ...


class Tracking:
    """:meth:`pose` is the object's filtered pose in the fixed frame, or FailedToDetect."""

    def __init__(
        self, detections: Detections, frames: RobotFrames, params: FollowingParams, clock: Clock
    ) -> None:
        self.detections = detections
        self.frames = frames
        self.params = params
        self.clock = clock
        self.filter = PoseFilter(params.filter_coef, params.detection_timeout)
        self.seen = False  # a detection came during this goal

    async def first_detection(self) -> StampedPose:
        """The newest detection, waiting up to ``detection_timeout`` for a first one."""
        found = self.detections.latest()
        deadline = self.clock.now() + self.params.detection_timeout
        while found is None and self.clock.now() < deadline:
            await self.clock.sleep(self.params.period)
            found = self.detections.latest()
        if found is None:
            raise FailedToDetect(
                f"no detection of the object on '{self.detections.topic}' within "
                f"{self.params.detection_timeout:g} s (detection_timeout): nothing publishes "
                f"a pose of it there"
            )
        return found

    def pose(self, detected: StampedPose | None = None) -> StampedPose:
        """The filtered pose from ``detected`` (default: the newest detection)."""
        detected = detected or self.detections.latest()
        if detected is None:
            raise FailedToDetect(f"no detection of the object on '{self.detections.topic}'")
        self.seen = True
        if not (detected.pose.is_finite() and math.isfinite(detected.stamp)):
            raise FailedToDetect(f"detection on '{self.detections.topic}' is not finite: "
                                 f"{detected.pose} at {detected.stamp}")  # fmt: skip
        age = self.clock.now() - detected.stamp
        if age > self.params.detection_timeout:
            raise FailedToDetect(
                f"lost the object on '{self.detections.topic}': its newest detection is "
                f"{age:.2f} s old (detection_timeout {self.params.detection_timeout:g} s)"
            )
        try:
            fixed = self.frames.to_frame(detected, self.params.fixed_frame)
        except FollowingError as exc:  # Nav2: a failed transform is a failed detection
            raise FailedToDetect(f"detection on '{self.detections.topic}': {exc}") from None
        if self.params.skip_orientation:
            fixed = self._aimed_at(fixed)
        return self.filter.update(fixed)

    def _aimed_at(self, fixed: StampedPose) -> StampedPose:
        robot = self.frames.robot_in(self.params.fixed_frame)  # now, as Nav2
        bearing = math.atan2(fixed.pose.y - robot.y, fixed.pose.x - robot.x)
        return StampedPose(Pose2D(fixed.pose.x, fixed.pose.y, bearing), fixed.stamp, fixed.frame)
