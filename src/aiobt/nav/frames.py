"""Poses between the frames the robot reports (``map`` from localization, ``odom``).

aiobt has no TF tree: the robot publishes its pose in ``map`` on ``{ns}/pose``
and in ``odom`` on ``{ns}/odom``; together they give the planar map<-odom
transform, which is enough for Nav2's nodes that compare poses across frames.
"""

from __future__ import annotations

import math

from aiobt.msgs import PoseStamped, Quaternion
from aiobt.msgs.geometry import Header, Point, Pose
from aiobt.nav.robot_state import RobotState


def frames_of(robot: RobotState) -> set[str]:
    """The frames connected by the data received so far (base frame included)."""
    pose, odom = robot.pose, robot.odometry
    frames: set[str] = set()
    if odom is not None:
        frames |= {odom.header.frame_id, odom.child_frame_id}
    if pose is not None:
        base = odom.child_frame_id if odom is not None else "base_link"
        frames |= {pose.header.frame_id, base}
    return frames


def transform_pose(pose: PoseStamped, target: str, robot: RobotState) -> PoseStamped | None:
    """``pose`` expressed in frame ``target``; None when the robot's data cannot tell."""
    source = pose.header.frame_id
    if source == target:
        return pose
    in_target, in_source = robot.pose_in(target), robot.pose_in(source)
    if in_target is None or in_source is None:
        return None
    # target<-source: the robot's pose in both frames fixes it
    theta = in_target.yaw - in_source.yaw
    c, s = math.cos(theta), math.sin(theta)
    sx, sy = in_source.x, in_source.y
    tx = in_target.x - (c * sx - s * sy)
    ty = in_target.y - (s * sx + c * sy)
    x, y = pose.x, pose.y
    moved = Pose(
        position=Point(x=tx + c * x - s * y, y=ty + s * x + c * y, z=pose.pose.position.z),
        orientation=Quaternion.from_yaw(pose.yaw + theta),
    )
    return PoseStamped(header=Header(stamp=pose.header.stamp, frame_id=target), pose=moved)
