"""Nav2's PoseFilter (aiobt.geometry.pose_filter), the one both the following and the
docking servers filter their detections with."""

from __future__ import annotations

import math

import pytest

from aiobt.geometry import Pose2D, wrap_angle
from aiobt.geometry.pose_filter import PoseFilter, StampedPose, StampedPose3D
from aiobt.geometry.quaternion import quat_from_rpy, quat_yaw


def at(x: float, stamp: float, yaw: float = 0.0, frame: str = "odom") -> StampedPose:
    return StampedPose(Pose2D(x, 0.0, yaw), stamp, frame)


def test_each_update_moves_coef_of_the_way() -> None:
    f = PoseFilter(0.1, 2.0)
    assert f.update(at(0.0, 0.0)).pose.x == 0.0
    assert f.update(at(1.0, 0.1)).pose.x == pytest.approx(0.1)
    assert f.update(at(1.0, 0.2)).pose.x == pytest.approx(0.19)


def test_heading_goes_the_short_way_round() -> None:
    f = PoseFilter(0.5, 2.0)
    f.update(at(0.0, 0.0, yaw=math.pi - 0.1))
    yaw = f.update(at(0.0, 0.1, yaw=-math.pi + 0.1)).pose.yaw
    assert abs(abs(yaw) - math.pi) < 1e-9


def test_a_stale_estimate_or_another_frame_restarts_it() -> None:
    f = PoseFilter(0.1, 2.0)
    f.update(at(0.0, 0.0))
    assert f.update(at(5.0, 2.5)).pose.x == 5.0
    assert f.update(at(7.0, 2.6, frame="map")).pose.x == 7.0


def test_coef_zero_passes_through_and_a_bad_coef_is_named() -> None:
    assert PoseFilter(0.0).update(at(3.0, 0.0)).pose.x == 3.0
    with pytest.raises(ValueError, match="filter_coef"):
        PoseFilter(1.5)


def test_nav2s_filter_tests() -> None:
    """Nav2's ``PoseFilterTests.FilterTests``, in 3D."""
    f = PoseFilter(0.5, 1.0)
    meas1 = StampedPose3D(1.0, 3.0, 5.0, quat_from_rpy(0.0, 0.0, 0.0), 1.0, "test")
    pose = f.update(meas1)
    assert (pose.x, pose.y, pose.z, pose.q[3]) == (1.0, 3.0, 5.0, 1.0)
    meas2 = StampedPose3D(2.0, 4.0, 6.0, quat_from_rpy(0.0, 0.0, 0.5), 1.0 + 500e-9, "test")
    pose = f.update(meas2)
    assert (pose.x, pose.y, pose.z) == pytest.approx((1.5, 3.5, 5.5), abs=1e-4)
    assert quat_yaw(pose.q) == pytest.approx(0.25, abs=1e-4)
    pose = f.update(meas2)
    assert (pose.x, pose.y, pose.z) == pytest.approx((1.75, 3.75, 5.75), abs=1e-4)
    assert quat_yaw(pose.q) == pytest.approx(0.375, abs=1e-4)
    late = StampedPose3D(2.0, 4.0, 6.0, meas2.q, 3.0, "test")  # past the timeout: restarts
    assert (f.update(late).x, f.update(late).y) == (2.0, 4.0)
    assert PoseFilter(0.0, 1.0).update(meas1) is meas1


def test_a_planar_heading_moves_coef_of_the_shorter_arc() -> None:
    """The planar pose as the 3D pose turned about z: slerp is the shorter-arc blend."""
    f, k = PoseFilter(0.3, 2.0), 0.3
    yaw = f.update(at(0.0, 0.0, yaw=0.2)).pose.yaw
    for i, new in enumerate([2.9, -2.9, 1.0, -3.1], start=1):
        expected = wrap_angle(yaw + k * wrap_angle(new - yaw))
        yaw = f.update(at(float(i), 0.1 * i, yaw=new)).pose.yaw
        assert yaw == pytest.approx(expected, abs=1e-12)
