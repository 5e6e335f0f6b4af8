"""The followed object in the web view: the following server's filtered pose of it
(``{ns}/filtered_dynamic_pose``, Nav2's topic, in the server's fixed frame) put in
``map`` with the robot's newest poses, as the page draws everything in ``map``."""

from __future__ import annotations

from aiobt.geometry import Pose2D
from aiobt.msgs import Odometry, PoseStamped

TOPIC = "filtered_dynamic_pose"
ROBOT_FRAMES = ("base_link", "base_footprint", "base_scan")


def _planar(msg: PoseStamped) -> Pose2D:
    return Pose2D(msg.x, msg.y, msg.yaw)


def followed_in_map(
    followed: PoseStamped, robot: PoseStamped | None, odom: Odometry | None
) -> Pose2D | None:
    """``followed`` in ``map`` (None when the robot's poses needed are not there yet)."""
    frame = followed.header.frame_id
    if frame in ("", "map"):
        return _planar(followed)
    if robot is None:
        return None
    if frame in ROBOT_FRAMES:
        return _planar(robot).compose(_planar(followed))
    if frame == "odom" and odom is not None:
        p = odom.pose
        in_odom = Pose2D(p.position.x, p.position.y, p.yaw)
        return _planar(robot).compose(in_odom.inverse()).compose(_planar(followed))
    return None


def followed_payload(pose: Pose2D, stamp: float) -> dict[str, float]:
    return {"x": round(pose.x, 3), "y": round(pose.y, 3), "stamp": stamp}
