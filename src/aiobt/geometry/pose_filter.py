"""Nav2's ``opennav_docking::PoseFilter``: a first-order low-pass on a stream of
detected poses (Nav2's docking and following servers smooth their detections with it).

Each update moves the estimate ``coef`` of the way to the measurement (the heading
along the shorter arc, as Nav2's quaternion slerp does in the plane); a measurement
more than ``timeout`` seconds after the estimate, or in another frame, restarts it.
``coef`` 0 passes measurements through unfiltered.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .pose import Pose2D, wrap_angle


@dataclass(slots=True, frozen=True)
class StampedPose:
    """A planar pose in ``frame`` at ``stamp`` (s of robot time)."""

    pose: Pose2D
    stamp: float
    frame: str


class PoseFilter:
    """``update(measurement)`` returns the filtered pose (Nav2's ``filter_coef``,
    ``detection_timeout``)."""

    __slots__ = ("_estimate", "coef", "timeout")

    def __init__(self, coef: float = 0.1, timeout: float = 2.0) -> None:
        if not (math.isfinite(coef) and 0.0 <= coef <= 1.0):
            raise ValueError(f"filter_coef must be within [0, 1], got {coef}")
        self.coef = coef
        self.timeout = timeout
        self._estimate: StampedPose | None = None

    def reset(self) -> None:
        self._estimate = None

    def update(self, measurement: StampedPose) -> StampedPose:
        if self.coef <= 0.0:
            return measurement
        old = self._estimate
        if (
            old is None
            or measurement.stamp - old.stamp > self.timeout
            or (old.frame != measurement.frame)
        ):
            self._estimate = measurement
            return measurement
        k, was, new = self.coef, old.pose, measurement.pose
        pose = Pose2D(
            (1.0 - k) * was.x + k * new.x,
            (1.0 - k) * was.y + k * new.y,
            wrap_angle(was.yaw + k * wrap_angle(new.yaw - was.yaw)),
        )
        self._estimate = StampedPose(pose, measurement.stamp, measurement.frame)
        return self._estimate
