"""Pure logic: box merging, poses, drive limits, battery, odometry, obstacle checks."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from aiobt.geometry import Pose2D, wrap_angle
from aiobt_services.robot.boxes import merge_boxes
from aiobt_services.robot.drive import DriveController, DriveLimits
from aiobt_services.robot.mapfile import MapInfo
from aiobt_services.robot.obstacles import Motion, ObstacleError, ObstacleSpec, validate
from aiobt_services.robot.sensors import Battery, NoiseConfig, WheelOdometry


@settings(max_examples=60, deadline=None)
@given(arrays(np.bool_, st.tuples(st.integers(1, 12), st.integers(1, 12))))
def test_merged_boxes_cover_mask_exactly_once(mask: np.ndarray) -> None:
    cover = np.zeros(mask.shape, dtype=np.int32)
    for r, c, nr, nc in merge_boxes(mask):
        assert nr > 0
        assert nc > 0
        cover[r : r + nr, c : c + nc] += 1
    assert (cover == mask.astype(np.int32)).all()


def test_merge_boxes_joins_a_thick_wall_into_one_box() -> None:
    mask = np.zeros((50, 40), dtype=bool)
    mask[10:13, 2:38] = True  # a 3-cell thick horizontal wall
    mask[20:45, 5:8] = True  # a vertical one
    assert len(merge_boxes(mask)) == 2
    assert merge_boxes(np.zeros((3, 3), dtype=bool)).shape == (0, 4)


def test_pose_compose_and_inverse() -> None:
    a = Pose2D(1.0, 2.0, math.pi / 2)
    b = Pose2D(1.0, 0.0, 0.0)
    assert a.compose(b) == pytest.approx(Pose2D(1.0, 3.0, math.pi / 2))
    ident = a.compose(a.inverse())
    assert (ident.x, ident.y, ident.yaw) == pytest.approx((0.0, 0.0, 0.0))
    assert wrap_angle(3 * math.pi) == pytest.approx(-math.pi)  # the range is [-pi, pi)
    assert wrap_angle(math.pi) == pytest.approx(-math.pi)


def test_drive_clamps_rejects_nonfinite_and_limits_acceleration() -> None:
    drive = DriveController(DriveLimits(max_linear=1.0, max_angular=2.0, max_linear_accel=2.0))
    assert not drive.command(math.nan, 0.0, now=0.0).accepted
    assert not drive.command(0.0, math.inf, now=0.0).accepted
    verdict = drive.command(5.0, -9.0, now=0.0)
    assert verdict.accepted
    assert verdict.clamped
    assert (verdict.linear, verdict.angular) == (1.0, -2.0)
    linear, _ = drive.update(0.0, 0.1)
    assert linear == pytest.approx(0.2)  # 2 m/s^2 for 0.1 s
    for i in range(10):
        linear, angular = drive.update(0.1 * (i + 1) * 0.4, 0.1)
    assert (linear, angular) == pytest.approx((1.0, -2.0))


def test_drive_times_out_and_stops() -> None:
    drive = DriveController(DriveLimits(cmd_timeout=0.5, max_linear_accel=100.0))
    drive.command(0.5, 0.0, now=0.0)
    assert drive.update(0.4, 0.01)[0] == pytest.approx(0.5)
    assert drive.update(0.6, 0.01)[0] == pytest.approx(0.0)


def test_drive_limits_refuse_nonsense() -> None:
    with pytest.raises(ValueError, match="max_linear"):
        DriveLimits(max_linear=-1.0)


def test_battery_drains_with_motion_and_charges_on_dock() -> None:
    idle, moving = Battery(), Battery()
    for _ in range(600):
        idle.update(0.0, 0.0, on_dock=False, dt=1.0)
        moving.update(1.0, 1.0, on_dock=False, dt=1.0)
    assert 1.0 > idle.percentage > moving.percentage
    level = moving.percentage
    moving.update(0.0, 0.0, on_dock=True, dt=60.0)
    assert moving.charging
    assert moving.percentage > level
    assert idle.voltage > moving.voltage - 1.0


def test_odometry_integrates_arc_and_noise_is_seeded() -> None:
    odom = WheelOdometry()
    noise = NoiseConfig()
    rng = np.random.default_rng(0)
    for _ in range(100):
        odom.update(1.0, math.pi / 2, 0.01, noise, rng)  # a quarter circle of radius 2/pi
    r = 2 / math.pi
    assert (odom.pose.x, odom.pose.y) == pytest.approx((r, r), abs=1e-3)
    assert odom.pose.yaw == pytest.approx(math.pi / 2)
    runs = []
    for _ in range(2):
        noisy, rng = WheelOdometry(), np.random.default_rng(7)
        for _ in range(100):
            noisy.update(1.0, 0.0, 0.01, NoiseConfig(odom_linear=0.1), rng)
        runs.append(noisy.pose.x)
    assert runs[0] == runs[1] != pytest.approx(1.0, abs=1e-9)


def test_obstacle_validation_reasons() -> None:
    world = MapInfo(
        grid=np.zeros((40, 40), dtype=np.int8), resolution=0.1, origin=(-2.0, -2.0, 0.0)
    )
    validate(ObstacleSpec("ok", "box", Pose2D(1.0, 1.0), size_x=0.4, size_y=0.4), world)
    with pytest.raises(ObstacleError, match="outside the world"):
        validate(ObstacleSpec("far", "cylinder", Pose2D(5.0, 0.0)), world)
    with pytest.raises(ObstacleError, match="outside the world"):
        validate(ObstacleSpec("edge", "cylinder", Pose2D(1.9, 0.0), radius=0.3), world)
    with pytest.raises(ObstacleError, match="shape"):
        validate(ObstacleSpec("tri", "triangle", Pose2D()), world)
    with pytest.raises(ObstacleError, match="radius"):
        validate(ObstacleSpec("neg", "cylinder", Pose2D(), radius=-1.0), world)
    with pytest.raises(ObstacleError, match="motion end"):
        validate(ObstacleSpec("m", "cylinder", Pose2D(), motion=Motion(9.0, 0.0, 0.5)), world)


def test_dynamic_obstacle_ping_pongs_along_segment() -> None:
    spec = ObstacleSpec("d", "cylinder", Pose2D(0.0, 0.0), motion=Motion(2.0, 0.0, 1.0))
    assert spec.pose_at(1.0).x == pytest.approx(1.0)
    assert spec.pose_at(2.0).x == pytest.approx(2.0)
    assert spec.pose_at(3.0).x == pytest.approx(1.0)
    assert spec.pose_at(4.0).x == pytest.approx(0.0)


def test_obstacle_distance_is_to_its_footprint_not_its_bounding_circle() -> None:
    door = ObstacleSpec("door", "box", Pose2D(0.0, 0.0), size_x=0.8, size_y=0.3)
    assert door.distance_to(0.0, 0.0) == 0.0  # inside
    assert door.distance_to(0.0, 0.5) == pytest.approx(0.35)  # off a long side
    assert door.distance_to(0.9, 0.0) == pytest.approx(0.5)  # off a short side
    assert door.distance_to(0.7, 0.35) == pytest.approx(math.hypot(0.3, 0.2))  # off a corner
    turned = door.distance_to(0.0, 0.5, Pose2D(0.0, 0.0, math.pi / 2))  # the long side faces y
    assert turned == pytest.approx(0.1)
    pillar = ObstacleSpec("p", "cylinder", Pose2D(1.0, 1.0), radius=0.25)
    assert pillar.distance_to(1.0, 2.0) == pytest.approx(0.75)
    assert pillar.distance_to(1.1, 1.0) == 0.0
