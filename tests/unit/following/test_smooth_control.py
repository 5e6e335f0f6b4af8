"""Nav2's smooth control law (aiobt.geometry.smooth): figures from Nav2's own
formulas, and the robot it steers reaching its target."""

from __future__ import annotations

import math

import pytest

from aiobt.geometry import Pose2D
from aiobt.geometry.smooth import EgoPolar, SmoothControlLaw, SmoothControlParams


def test_ego_polar_coordinates_are_nav2s() -> None:
    # target 1 m ahead and 1 m left, facing +y: line of sight atan2(-1, 1) = -pi/4
    ego = EgoPolar.of(Pose2D(1.0, 1.0, math.pi / 2))
    assert ego.r == pytest.approx(math.sqrt(2.0))
    assert ego.phi == pytest.approx(math.pi / 2 - math.pi / 4)
    assert ego.delta == pytest.approx(-math.pi / 4)


def test_straight_ahead_drives_at_full_speed_without_turning() -> None:
    cmd = SmoothControlLaw().velocity(Pose2D(2.0, 0.0, 0.0))
    assert cmd.v == pytest.approx(0.25)
    assert cmd.w == pytest.approx(0.0)


def test_near_the_target_it_slows_within_the_slowdown_radius() -> None:
    law = SmoothControlLaw(SmoothControlParams(v_linear_min=0.0))
    assert law.velocity(Pose2D(0.1, 0.0, 0.0)).v == pytest.approx(0.25 * 0.1 / 0.25)


def test_a_target_to_the_left_turns_left_within_the_angular_limit() -> None:
    cmd = SmoothControlLaw().velocity(Pose2D(0.5, 1.5, math.pi / 2))
    assert 0.0 < cmd.w <= 0.75
    assert cmd.v > 0.0


def test_the_curvature_is_nav2s_formula() -> None:
    law = SmoothControlLaw()
    r, phi, delta = 2.0, 0.3, -0.4
    expected = -1.0 / r * (2.0 * (delta - math.atan(-3.0 * phi))
                           + (1.0 + 3.0 / (1.0 + (3.0 * phi) ** 2)) * math.sin(delta))  # fmt: skip
    assert law.curvature(r, phi, delta) == pytest.approx(expected)


@pytest.mark.parametrize("target", [Pose2D(3.0, 1.0, 0.5), Pose2D(2.0, -2.0, -1.0)])
def test_simulated_next_poses_reach_the_target(target: Pose2D) -> None:
    law, pose = SmoothControlLaw(SmoothControlParams(v_linear_max=0.5)), Pose2D()
    for _ in range(2000):
        pose = law.next_pose(0.02, target, pose)
        if pose.distance_to(target) < 0.02:
            break
    assert pose.distance_to(target) < 0.02
    assert abs(math.remainder(pose.yaw - target.yaw, 2 * math.pi)) < 0.2


def test_bad_gains_are_named() -> None:
    with pytest.raises(ValueError, match=r"controller\.v_linear_min"):
        SmoothControlParams(v_linear_min=1.0, v_linear_max=0.5)
    with pytest.raises(ValueError, match=r"controller\.k_phi"):
        SmoothControlParams(k_phi=-1.0)
