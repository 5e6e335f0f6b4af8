"""From a detection of the dock's marker to the dock's pose (Nav2's
``SimpleChargingDock::getRefinedPose`` with ``use_external_detection_pose``, and its
``PoseFilter``): the detection, placed in the fixed frame, is low-pass filtered
(``filter_coef``; orientation by slerp); the filtered orientation is turned by the
``external_detection_rotation_*`` (roll, pitch, yaw: Nav2's defaults turn an AprilTag
detector's tag frame into the dock's) and its yaw kept; the dock's position is the
filtered position moved by ``external_detection_translation_x/y`` along that yaw.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import numpy.typing as npt

from aiobt.geometry import Pose2D

Quat = npt.NDArray[np.float64]  # x, y, z, w


def quat_mul(a: Quat, b: Quat) -> Quat:
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return np.array([
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    ])  # fmt: skip


def quat_from_rpy(roll: float, pitch: float, yaw: float) -> Quat:
    """tf2's ``setRPY``: about the fixed x, then y, then z axes."""

    def axis(i: int, angle: float) -> Quat:
        q = np.zeros(4)
        q[i], q[3] = math.sin(0.5 * angle), math.cos(0.5 * angle)
        return q

    return quat_mul(axis(2, yaw), quat_mul(axis(1, pitch), axis(0, roll)))


def quat_yaw(q: Quat) -> float:
    x, y, z, w = q
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def slerp(a: Quat, b: Quat, t: float) -> Quat:
    dot = float(np.dot(a, b))
    if dot < 0.0:
        b, dot = -b, -dot
    if dot > 0.9995:
        q = a + t * (b - a)
        return np.asarray(q / np.linalg.norm(q), dtype=np.float64)
    theta = math.acos(dot)
    q = (math.sin((1.0 - t) * theta) * a + math.sin(t * theta) * b) / math.sin(theta)
    return np.asarray(q, dtype=np.float64)


@dataclass(slots=True, frozen=True)
class Detection:
    """A detected pose (position and full orientation) in ``frame`` at ``stamp``."""

    x: float
    y: float
    z: float
    q: Quat
    stamp: float
    frame: str

    def moved(self, by: Pose2D, frame: str) -> Detection:
        """This detection seen from a frame in which its own frame stands at ``by``."""
        c, s = math.cos(by.yaw), math.sin(by.yaw)
        turn = quat_from_rpy(0.0, 0.0, by.yaw)
        return replace(self, x=by.x + c * self.x - s * self.y, y=by.y + s * self.x + c * self.y,
                       q=quat_mul(turn, self.q), frame=frame)  # fmt: skip


class PoseFilter:
    """Nav2's ``PoseFilter``: an exponential filter of detections, restarted by one
    older than ``timeout`` or in another frame; ``coef`` <= 0: no filtering."""

    def __init__(self, coef: float, timeout: float) -> None:
        self.coef = coef
        self.timeout = timeout
        self.pose: Detection | None = None

    def update(self, m: Detection) -> Detection:
        if self.coef <= 0.0:
            return m
        old, k = self.pose, self.coef
        if old is None or m.stamp - old.stamp > self.timeout or old.frame != m.frame:
            self.pose = m
        else:
            self.pose = Detection((1 - k) * old.x + k * m.x, (1 - k) * old.y + k * m.y,
                                  (1 - k) * old.z + k * m.z, slerp(old.q, m.q, k),
                                  m.stamp, m.frame)  # fmt: skip
        return self.pose


def dock_pose(filtered: Detection, rotation: Quat, translation: tuple[float, float]) -> Pose2D:
    """The dock from a filtered detection: the rotation's yaw, then the offsets."""
    yaw = quat_yaw(quat_mul(filtered.q, rotation))
    tx, ty = translation
    c, s = math.cos(yaw), math.sin(yaw)
    return Pose2D(filtered.x + c * tx - s * ty, filtered.y + s * tx + c * ty, yaw)
