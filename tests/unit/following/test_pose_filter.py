"""Nav2's PoseFilter (aiobt.geometry.pose_filter)."""

from __future__ import annotations

import math

import pytest

from aiobt.geometry import Pose2D
from aiobt.geometry.pose_filter import PoseFilter, StampedPose


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
