"""The controllers drive a kinematic unicycle along straight, curved and U-turn paths."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aiobt.geometry import Pose2D, wrap_angle
from aiobt_services.controller.session import ControllerConfig

from .courses import curve, drive, straight, u_turn


@pytest.mark.parametrize("controller_id", ["FollowPath", "DWB"])
@pytest.mark.parametrize(
    ("course", "bound"),
    [(straight, 0.02), (curve, 0.10), (u_turn, 0.15)],
    ids=["straight", "curve", "u_turn"],
)
def test_tracks_course_to_goal_within_cross_track_bound(controller_id, course, bound):
    path = course()
    run, robot = drive(path, controller_id=controller_id)
    assert run.result is not None
    assert run.result.succeeded, run.result
    goal = path.goal
    assert robot.pose.distance_to(goal) <= 0.25
    assert abs(wrap_angle(robot.pose.yaw - goal.yaw)) <= 0.25
    assert max(abs(e) for e in run.cross_track) <= bound


def test_rpp_rotates_in_place_first_when_path_starts_behind():
    path = straight()
    run, _robot = drive(path, start=Pose2D(0.0, 0.0, math.pi))
    assert run.result is not None
    assert run.result.succeeded
    first = run.commands[:5]
    assert all(v == 0.0 and w != 0.0 for v, w in first)


def test_rpp_speed_scales_down_on_tight_curvature_and_near_goal():
    run, _ = drive(curve(radius=0.5))
    speeds = [v for v, _ in run.commands if v > 0]
    assert max(speeds) == pytest.approx(0.5, abs=1e-6)
    assert min(speeds) < 0.3  # regulated on the 0.5 m radius and on approach


def test_precise_goal_checker_ends_closer_and_stopped():
    path = straight()
    run, robot = drive(path, goal_checker_id="precise_goal_checker")
    assert run.result is not None
    assert run.result.succeeded
    assert robot.pose.distance_to(path.goal) <= 0.1
    assert abs(robot.velocity.v) <= 0.05
    assert abs(robot.velocity.w) <= 0.1


def test_offset_start_converges_onto_path():
    run, _ = drive(straight(6.0), start=Pose2D(0.0, 0.4, 0.0))
    assert run.result is not None
    assert run.result.succeeded
    errors = np.abs(np.asarray(run.cross_track))
    assert errors[0] == pytest.approx(0.4, abs=1e-6)
    assert errors[-1] < 0.05


def test_odom_frame_path_uses_odom_state():
    path = straight()
    odom_path = type(path)("odom", path.xy, path.yaw)
    run, _ = drive(odom_path, config=ControllerConfig())
    assert run.result is not None
    assert run.result.succeeded
