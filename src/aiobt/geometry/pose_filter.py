"""Nav2's ``opennav_docking::PoseFilter``: a first-order low-pass on a stream of
detected poses. Nav2's docking and following servers both smooth their detections
with it; so do aiobt's.

Each update moves the estimate ``coef`` of the way to the measurement: the position
linearly, the orientation by quaternion slerp (the shorter arc), as Nav2 does. A
measurement more than ``timeout`` seconds after the estimate, or in another frame,
restarts it. ``coef`` 0 passes measurements through unfiltered.

A measurement is a :class:`StampedPose3D` (a detector's full pose: the docking
server's fiducial) or a planar :class:`StampedPose` (the following server's object),
which the filter treats as the 3D pose at ``z`` 0 turned about ``z`` only.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import overload

from .pose import Pose2D, wrap_angle
from .quaternion import Quat, quat_from_yaw, quat_mul, quat_yaw, slerp


@dataclass(slots=True, frozen=True)
class StampedPose:
    """A planar pose in ``frame`` at ``stamp`` (s of robot time)."""

    pose: Pose2D
    stamp: float
    frame: str


@dataclass(slots=True, frozen=True)
class StampedPose3D:
    """A detected pose (position and full orientation ``q``) in ``frame`` at ``stamp``."""

    x: float
    y: float
    z: float
    q: Quat
    stamp: float
    frame: str

    @classmethod
    def planar(cls, p: StampedPose) -> StampedPose3D:
        return cls(p.pose.x, p.pose.y, 0.0, quat_from_yaw(p.pose.yaw), p.stamp, p.frame)

    def flat(self) -> StampedPose:
        """The planar pose: the position's x and y, the orientation's yaw."""
        return StampedPose(Pose2D(self.x, self.y, wrap_angle(quat_yaw(self.q))), self.stamp,
                           self.frame)  # fmt: skip

    def moved(self, by: Pose2D, frame: str) -> StampedPose3D:
        """This pose seen from ``frame``, in which its own frame stands at ``by``."""
        c, s = math.cos(by.yaw), math.sin(by.yaw)
        return replace(self, x=by.x + c * self.x - s * self.y, y=by.y + s * self.x + c * self.y,
                       q=quat_mul(quat_from_yaw(by.yaw), self.q), frame=frame)  # fmt: skip


class PoseFilter:
    """``update(measurement)`` returns the filtered pose, of the measurement's kind
    (Nav2's ``filter_coef``; the timeout is docking's ``external_detection_timeout``,
    following's ``detection_timeout``)."""

    __slots__ = ("_estimate", "coef", "timeout")

    def __init__(self, coef: float = 0.1, timeout: float = 2.0) -> None:
        if not (math.isfinite(coef) and 0.0 <= coef <= 1.0):
            raise ValueError(f"filter_coef must be within [0, 1], got {coef}")
        self.coef = coef
        self.timeout = timeout
        self._estimate: StampedPose3D | None = None

    def reset(self) -> None:
        self._estimate = None

    @overload
    def update(self, measurement: StampedPose) -> StampedPose: ...

    @overload
    def update(self, measurement: StampedPose3D) -> StampedPose3D: ...

    def update(self, measurement: StampedPose | StampedPose3D) -> StampedPose | StampedPose3D:
        if self.coef <= 0.0:
            return measurement
        if isinstance(measurement, StampedPose):
            return self._filter(StampedPose3D.planar(measurement)).flat()
        return self._filter(measurement)

    def _filter(self, m: StampedPose3D) -> StampedPose3D:
        old, k = self._estimate, self.coef
        if old is None or m.stamp - old.stamp > self.timeout or old.frame != m.frame:
            self._estimate = m
        else:
            self._estimate = StampedPose3D(
                (1.0 - k) * old.x + k * m.x, (1.0 - k) * old.y + k * m.y,
                (1.0 - k) * old.z + k * m.z, slerp(old.q, m.q, k), m.stamp, m.frame,
            )  # fmt: skip
        return self._estimate
