"""The docking server's pure parts: the graceful control law, the robot's frames, the
detection's filter and turn into a dock pose, the plugin's parameters."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.geometry import Pose2D, wrap_angle
from aiobt.geometry.pose_filter import PoseFilter, StampedPose3D
from aiobt.geometry.quaternion import quat_from_rpy, quat_mul, quat_yaw
from aiobt.geometry.smooth import (
    RotateParams,
    SmoothControlLaw,
    SmoothControlParams,
    rotate_to_heading,
)
from aiobt.msgs import Odometry, PoseStamped
from aiobt.msgs.geometry import Header, Pose
from aiobt.system.plugin_params import params_from
from aiobt_services.docking.detection import dock_pose
from aiobt_services.docking.frames import RobotFrames
from aiobt_services.docking.simple_charging_dock import SimpleChargingDockParams


def drive_to_line(law: SmoothControlLaw, start: Pose2D, target: Pose2D, x_stop: float) -> Pose2D:
    """Unicycle steps of the law toward ``target`` until the robot crosses ``x_stop``."""
    pose, dt = start, 0.02
    while pose.x < x_stop:
        cmd = law.velocity(target, pose)
        yaw = wrap_angle(pose.yaw + cmd.w * dt)
        pose = Pose2D(pose.x + cmd.v * dt * math.cos(pose.yaw),
                      pose.y + cmd.v * dt * math.sin(pose.yaw), yaw)  # fmt: skip
    return pose


def test_the_law_spirals_onto_the_line_of_the_target() -> None:
    law = SmoothControlLaw(SmoothControlParams())
    end = drive_to_line(law, Pose2D(0.0, 0.3, 0.4), Pose2D(2.25, 0.0, 0.0), 2.0)
    assert abs(end.y) < 0.02
    assert abs(end.yaw) < 0.05


def test_the_law_keeps_nav2s_limits() -> None:
    law = SmoothControlLaw(SmoothControlParams())
    far = law.velocity(Pose2D(3.0, 0.0, 0.0))
    assert far.v == pytest.approx(0.25)  # v_linear_max
    sharp = law.velocity(Pose2D(0.3, 0.3, math.pi / 2))
    assert abs(sharp.w) <= 0.75 + 1e-9  # v_angular_max
    backward = law.velocity(Pose2D(-1.0, 0.0, 0.0), backward=True)
    assert backward.v < 0.0


def test_rotate_to_heading_stops_on_it() -> None:
    rotate = RotateParams()
    assert rotate_to_heading(rotate, 1.0, 0.0, 0.02) == pytest.approx(3.2 * 0.02)  # accel limited
    slowing = rotate_to_heading(rotate, -0.001, -1.0, 0.02)
    assert slowing == pytest.approx(-math.sqrt(2 * 3.2 * 0.001))


def odom(x: float, y: float, yaw: float, stamp: float) -> Odometry:
    return Odometry(header=Header(stamp=stamp, frame_id="odom"), pose=Pose.from_xy_yaw(x, y, yaw))


def test_frames_from_the_map_pose_and_odometry_by_stamp() -> None:
    odoms = [odom(1.0, 0.0, 0.0, 2.0), odom(0.5, 0.0, 0.0, 1.0)]  # newest first
    pose = PoseStamped.from_xy_yaw(11.0, 5.0, 0.0, "map")  # map = odom + (10, 5)
    frames = RobotFrames(lambda: pose, lambda: odoms)
    assert frames.robot("map") == Pose2D(11.0, 5.0, 0.0)
    dock = frames.transform(Pose2D(12.0, 5.0, math.pi), "map", "odom")
    assert (dock.x, dock.y) == pytest.approx((2.0, 0.0))
    seen = frames.transform(Pose2D(0.5, 0.0, 0.0), "base_link", "odom", stamp=1.0)
    assert seen.x == pytest.approx(1.0)  # placed by the odometry at its stamp
    ahead = frames.transform(Pose2D(12.0, 5.0, 0.0), "map", "base_link")
    assert (ahead.x, ahead.y) == pytest.approx((1.0, 0.0))
    with pytest.raises(LookupError, match="no robot pose"):
        RobotFrames(lambda: None, lambda: odoms).robot("map")
    with pytest.raises(LookupError, match="frame 'world' on tf_static, and it is none of map"):
        frames.transform(Pose2D(), "world", "odom")


def test_nav2s_default_rotation_turns_a_tag_frame_into_the_docks() -> None:
    rotation = quat_from_rpy(-1.57, 1.57, 0.0)
    tag = quat_mul(quat_from_rpy(0.0, 0.0, 0.7), np.array([*-rotation[:3], rotation[3]]))
    seen = StampedPose3D(1.0, 2.0, 0.0, tag, 0.0, "odom")
    dock = dock_pose(seen, rotation, (-0.2, 0.0))
    assert dock.yaw == pytest.approx(0.7)
    assert (dock.x, dock.y) == pytest.approx((1.0 - 0.2 * math.cos(0.7), 2.0 - 0.2 * math.sin(0.7)))
    assert quat_yaw(quat_from_rpy(0.0, 0.0, -2.0)) == pytest.approx(-2.0)


def test_the_filter_smooths_and_restarts_after_its_timeout() -> None:
    f = PoseFilter(0.1, 1.0)
    flat = quat_from_rpy(0.0, 0.0, 0.0)
    f.update(StampedPose3D(0.0, 0.0, 0.0, flat, 0.0, "odom"))
    smoothed = f.update(StampedPose3D(1.0, 0.0, 0.0, quat_from_rpy(0.0, 0.0, 1.0), 0.1, "odom"))
    assert smoothed.x == pytest.approx(0.1)
    assert quat_yaw(smoothed.q) == pytest.approx(0.1)
    assert f.update(StampedPose3D(5.0, 0.0, 0.0, flat, 2.0, "odom")).x == 5.0


def test_plugin_parameters_by_nav2s_names() -> None:
    p = params_from(SimpleChargingDockParams, "dock", {"docking_threshold": "0.01",
                                                       "use_battery_status": "false"})  # fmt: skip
    assert (p.docking_threshold, p.use_battery_status, p.staging_x_offset) == (0.01, False, -0.7)
    with pytest.raises(ValueError, match=r"dock\.docking_treshold: no such parameter"):
        params_from(SimpleChargingDockParams, "dock", {"docking_treshold": "0.01"})
    with pytest.raises(ValueError, match="bad value 'high'"):
        params_from(SimpleChargingDockParams, "dock", {"filter_coef": "high"})
    with pytest.raises(ValueError, match="Dock direction is not valid"):
        SimpleChargingDockParams(dock_direction="sideways")
