"""Localization's ``map`` -> ``odom`` correction, and the robot's pose in ``map`` from it.

Nav2's nodes get the robot's pose in ``map`` from TF: AMCL's ``map`` -> ``odom``
(sent with every scan it takes, the last one again while the filter does not
update) chained with the odometry's ``odom`` -> ``base_link``. aiobt's localization
sends the same correction on ``{ns}/tf`` (:func:`correction_message`), and on
``{ns}/pose``, while a viewer reads it, the correction composed with each odometry
message (:func:`compose`). The stack's readers take the odometry anyway and compose
the pose themselves, with the same :func:`compose` and the correction read back
(:func:`correction_of`): the controller (:class:`aiobt.robot.correction.MapSource`),
the navigator and the planner (:class:`aiobt.geometry.map_pose.MapPose`). The two
agree to float rounding (the yaw's way through a quaternion). Here, below ``nav``,
``robot`` and ``costmap`` in the library's layers, so that all of them read it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from aiobt.msgs import TFMessage, yaw_to_quaternion

from .pose import XYYaw

TF_TOPIC = "tf"  # localization's map -> odom, as Nav2's AMCL broadcasts it on /tf
POSE_TOPIC = "pose"  # the pose in map, composed by localization (or a robot's own)
MAP_FRAME = "map"
ODOM_FRAME = "odom"


def compose(correction: XYYaw, x: float, y: float, yaw: float) -> XYYaw:
    """``correction * (x, y, yaw)``: a pose in ``odom`` expressed in ``map``, in plain
    floats (the per-message work of a 50 Hz stream, where numpy's per-call cost would be
    most of it); the yaw wrapped to ``[-pi, pi)``."""
    cx, cy, cyaw = correction
    c, s = math.cos(cyaw), math.sin(cyaw)
    turned = (cyaw + yaw + math.pi) % (2.0 * math.pi) - math.pi
    return cx + c * x - s * y, cy + s * x + c * y, turned


@dataclass(slots=True, frozen=True)
class Correction:
    """``map`` -> ``odom`` as of ``stamp`` (robot time: the scan it was sent with)."""

    transform: XYYaw
    stamp: float


def correction_message(
    transform: XYYaw, stamp: float, parent: str = MAP_FRAME, child: str = ODOM_FRAME
) -> TFMessage:
    """The correction as localization sends it on ``{ns}/tf``."""
    x, y, yaw = transform
    qx, qy, qz, qw = yaw_to_quaternion(yaw)
    return TFMessage.model_validate(
        {
            "transforms": [
                {
                    "header": {"stamp": stamp, "frame_id": parent},
                    "child_frame_id": child,
                    "transform": {
                        "translation": {"x": x, "y": y},
                        "rotation": {"x": qx, "y": qy, "z": qz, "w": qw},
                    },
                }
            ]
        }
    )


def correction_of(
    msg: TFMessage, parent: str = MAP_FRAME, child: str = ODOM_FRAME
) -> Correction | None:
    """The ``parent`` -> ``child`` transform in ``msg`` (the last if several), or None if
    it has none (other frames share ``{ns}/tf``). Finite: the wire model refuses others."""
    for tf in reversed(msg.transforms):
        if tf.header.frame_id == parent and tf.child_frame_id == child:
            t = tf.transform.translation
            return Correction((t.x, t.y, tf.yaw), tf.header.stamp)
    return None
