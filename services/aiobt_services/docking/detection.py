"""From a detection of the dock's marker to the dock's pose (Nav2's
``SimpleChargingDock::getRefinedPose`` with ``use_external_detection_pose``): the
detection, placed in the fixed frame, is low-pass filtered (the library's
:class:`~aiobt.geometry.pose_filter.PoseFilter`, Nav2's, with ``filter_coef``); the
filtered orientation is turned by the ``external_detection_rotation_*`` (roll, pitch,
yaw: Nav2's defaults turn an AprilTag detector's tag frame into the dock's) and its yaw
kept; the dock's position is the filtered position moved by
``external_detection_translation_x/y`` along that yaw.
"""

from __future__ import annotations

import math

from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import StampedPose3D
from aiobt.geometry.quaternion import Quat, quat_mul, quat_yaw


def dock_pose(filtered: StampedPose3D, rotation: Quat, translation: tuple[float, float]) -> Pose2D:
    """The dock from a filtered detection: the rotation's yaw, then the offsets."""
    yaw = quat_yaw(quat_mul(filtered.q, rotation))
    tx, ty = translation
    c, s = math.cos(yaw), math.sin(yaw)
    return Pose2D(filtered.x + c * tx - s * ty, filtered.y + s * tx + c * ty, yaw)
