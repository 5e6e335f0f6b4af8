"""Detections put in the fixed frame with the robot's poses at their stamps."""

from __future__ import annotations

import math

import pytest

from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import StampedPose
from aiobt_services.following.errors import TransformError
from aiobt_services.following.frames import RobotFrames


def frames() -> RobotFrames:
    f = RobotFrames("base_link", tolerance=0.1)
    for i in range(11):  # the robot drives +x at 1 m/s in odom; map is odom shifted by (10, 0)
        t = i * 0.02
        f.add("odom", t, Pose2D(t, 0.0, math.pi / 2))
        f.add("map", t, Pose2D(10.0 + t, 0.0, math.pi / 2))
    return f


def test_a_detection_in_the_robot_frame_uses_the_pose_at_its_stamp() -> None:
    seen = StampedPose(Pose2D(2.0, 0.0, 0.0), 0.1, "base_link")  # 2 m ahead, facing +y
    fixed = frames().to_frame(seen, "odom")
    assert (fixed.pose.x, fixed.pose.y) == pytest.approx((0.1, 2.0))
    assert fixed.frame == "odom"
    assert fixed.stamp == 0.1


def test_a_detection_in_map_goes_through_the_robot_pose_in_both() -> None:
    seen = StampedPose(Pose2D(12.0, 3.0, 0.0), 0.2, "map")
    fixed = frames().to_frame(seen, "odom")
    assert (fixed.pose.x, fixed.pose.y) == pytest.approx((2.0, 3.0))


def test_no_pose_near_the_stamp_is_a_transform_error_naming_the_tolerance() -> None:
    seen = StampedPose(Pose2D(1.0, 0.0, 0.0), 0.5, "base_link")
    with pytest.raises(TransformError, match=r"within 0.1 s \(transform_tolerance\) of 0.500"):
        frames().to_frame(seen, "odom")


def test_an_unknown_frame_is_named() -> None:
    seen = StampedPose(Pose2D(1.0, 0.0, 0.0), 0.1, "camera_7")
    with pytest.raises(TransformError, match="'camera_7'"):
        frames().to_frame(seen, "odom")
    with pytest.raises(TransformError, match="no robot pose in frame 'odom'"):
        RobotFrames("base_link", 0.1).robot_in("odom")


def test_a_restarted_clock_starts_the_history_anew() -> None:
    f = frames()
    f.add("odom", 0.0, Pose2D(5.0, 5.0, 0.0))
    assert f.robot_in("odom") == Pose2D(5.0, 5.0, 0.0)
    assert f.robot_in("odom", 0.05) == Pose2D(5.0, 5.0, 0.0)
