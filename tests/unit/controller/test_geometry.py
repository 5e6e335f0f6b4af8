"""Properties of the planar geometry every controller and behavior relies on."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from aiobt.geometry import (
    PlanarPath,
    Pose2D,
    Velocity,
    integrate_arc,
    turn_rate,
    wrap_angle,
)
from aiobt.robot.freshness import FRESH
from aiobt_services.behaviors import Inputs, SpinBehavior
from aiobt_services.controller.unicycle import Unicycle

finite = st.floats(-50.0, 50.0, allow_nan=False)
speeds = st.floats(-1.0, 1.0, allow_nan=False)


@given(finite)
def test_wrap_angle_is_in_range_and_equivalent(angle):
    wrapped = wrap_angle(angle)
    assert -math.pi <= wrapped < math.pi
    assert math.isclose(math.cos(wrapped), math.cos(angle), abs_tol=1e-9)
    assert math.isclose(math.sin(wrapped), math.sin(angle), abs_tol=1e-9)


@given(finite, finite, finite, speeds, speeds)
def test_arc_projection_matches_the_unicycle(x, y, yaw, v, w):
    start = Pose2D(x, y, yaw)
    robot = Unicycle(start)
    for _ in range(10):
        robot.step(Velocity(v, w), 0.1)
    end = integrate_arc(start, Velocity(v, w), np.array([1.0]))[0]
    assert math.isclose(end[0], robot.pose.x, abs_tol=1e-6)
    assert math.isclose(end[1], robot.pose.y, abs_tol=1e-6)
    assert abs(wrap_angle(end[2] - robot.pose.yaw)) < 1e-6


@given(st.floats(-math.pi, math.pi), st.floats(-12.0, 12.0).filter(lambda a: abs(a) > 0.05))
def test_spin_accounts_any_angle_from_any_start(start_yaw, target):
    robot = Unicycle(Pose2D(0.0, 0.0, start_yaw), max_angular_accel=3.2)
    spin = SpinBehavior(target, time_allowance=0.0)
    now = 0.0
    for _ in range(1000):  # 50 s: far more than any of these spins needs
        step = spin.step(Inputs(now, robot.pose, FRESH))
        if step.done:
            break
        assert step.cmd is not None
        robot.step(step.cmd, 0.05)
        now += 0.05
    assert step.succeeded
    assert abs(step.feedback - abs(target)) < 0.05
    assert abs(wrap_angle(robot.pose.yaw - (start_yaw + target))) < 0.07


def test_path_through_points_is_dense_and_keeps_the_corners():
    path = PlanarPath.through([(0.0, 0.0), (1.0, 0.0), (1.0, 0.52)], spacing=0.1)
    assert path.frame_id == "map"
    assert path.xy[0].tolist() == [0.0, 0.0]
    assert path.xy[-1].tolist() == [1.0, 0.52]
    assert [1.0, 0.0] in path.xy.tolist()
    assert float(path.segment_lengths().max()) <= 0.1 + 1e-12
    assert len(path) == 10 + 6 + 1
    assert path.yaw[0] == 0.0
    assert math.isclose(path.yaw[-1], math.pi / 2)


def test_turn_rate_decelerates_onto_the_heading_and_limits_acceleration():
    # far from the heading: capped by max_rate, reached only as fast as accel allows
    assert turn_rate(3.0, 1.0, 2.0, previous=1.0, dt=0.1) == 1.0
    assert math.isclose(turn_rate(3.0, 1.0, 2.0, previous=0.0, dt=0.1), 0.2)
    # close to it: sqrt(2 a |e|), with the error's sign
    assert math.isclose(turn_rate(-0.01, 1.0, 2.0, previous=-0.2, dt=0.1), -0.2)
    assert math.isclose(turn_rate(-0.04, 1.0, 2.0, previous=-0.4, dt=0.1), -0.4)
