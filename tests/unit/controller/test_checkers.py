"""Goal checker and progress checker state machines."""

from __future__ import annotations

import math

import pytest

from aiobt.geometry import Pose2D, Velocity
from aiobt_services.controller.checkers import (
    SimpleGoalChecker,
    SimpleProgressChecker,
    default_checkers,
)

GOAL = Pose2D(1.0, 1.0, 0.0)
STILL = Velocity(0.0, 0.0)


def test_goal_needs_both_xy_and_yaw():
    checker = SimpleGoalChecker(0.25, 0.25, stateful=False)
    assert not checker.is_goal_reached(Pose2D(0.5, 1.0, 0.0), GOAL, STILL)
    assert not checker.is_goal_reached(Pose2D(1.1, 1.0, 1.0), GOAL, STILL)
    assert checker.is_goal_reached(Pose2D(1.1, 1.0, 0.2), GOAL, STILL)


def test_yaw_tolerance_wraps_around_pi():
    checker = SimpleGoalChecker(0.25, 0.25)
    goal = Pose2D(0.0, 0.0, math.pi - 0.05)
    assert checker.is_goal_reached(Pose2D(0.0, 0.0, -math.pi + 0.05), goal, STILL)


def test_stateful_checker_latches_xy_while_rotating():
    stateful = SimpleGoalChecker(0.25, 0.25, stateful=True)
    stateless = SimpleGoalChecker(0.25, 0.25, stateful=False)
    for checker in (stateful, stateless):
        assert not checker.is_goal_reached(Pose2D(1.2, 1.0, 1.0), GOAL, STILL)  # xy ok, yaw not
    drifted = Pose2D(1.3, 1.0, 0.1)  # rotating drifted it out of xy tolerance
    assert stateful.is_goal_reached(drifted, GOAL, STILL)
    assert not stateless.is_goal_reached(drifted, GOAL, STILL)
    stateful.reset()
    assert not stateful.is_goal_reached(drifted, GOAL, STILL)


def test_precise_checker_is_tighter_and_needs_the_robot_stopped():
    registry = default_checkers()
    general = registry.goal_checkers["general_goal_checker"]()
    precise = registry.goal_checkers["precise_goal_checker"]()
    assert precise.xy_goal_tolerance < general.xy_goal_tolerance
    near = Pose2D(1.2, 1.0, 0.0)
    assert general.is_goal_reached(near, GOAL, STILL)
    assert not precise.is_goal_reached(near, GOAL, STILL)
    on_goal = Pose2D(1.02, 1.0, 0.0)
    assert not precise.is_goal_reached(on_goal, GOAL, Velocity(0.2, 0.0))
    assert precise.is_goal_reached(on_goal, GOAL, STILL)


@pytest.mark.parametrize("bad", [0.0, -0.1, math.nan, math.inf])
def test_goal_checker_rejects_bad_tolerance(bad):
    with pytest.raises(ValueError, match="xy_goal_tolerance"):
        SimpleGoalChecker(bad, 0.25)


def test_progress_checker_fails_after_window_without_movement():
    checker = SimpleProgressChecker(required_movement_radius=0.5, movement_time_allowance=10.0)
    start = Pose2D(0.0, 0.0, 0.0)
    assert checker.check(start, 0.0)
    assert checker.check(Pose2D(0.4, 0.0, 0.0), 9.9)  # moved, but not past the radius
    assert not checker.check(Pose2D(0.4, 0.0, 0.0), 10.1)


def test_progress_checker_resets_its_window_on_movement():
    checker = SimpleProgressChecker(0.5, 10.0)
    assert checker.check(Pose2D(0.0, 0.0, 0.0), 0.0)
    assert checker.check(Pose2D(0.6, 0.0, 0.0), 8.0)  # new baseline at t=8
    assert checker.check(Pose2D(0.7, 0.0, 0.0), 17.9)
    assert not checker.check(Pose2D(0.7, 0.0, 0.0), 18.1)
    checker.reset()
    assert checker.check(Pose2D(0.7, 0.0, 0.0), 100.0)


def test_progress_checker_rejects_bad_parameters():
    with pytest.raises(ValueError, match="movement_time_allowance"):
        SimpleProgressChecker(0.5, -1.0)
    with pytest.raises(ValueError, match="required_movement_radius"):
        SimpleProgressChecker(math.nan, 10.0)
