"""Wire goals to behaviors, and outcomes to each action's Nav2 error code."""

from __future__ import annotations

import math

import pytest

from aiobt.costmap.checker import CollisionChecker, GridCostmap
from aiobt.msgs import (
    AssistedTeleopError,
    BackUp,
    BackUpError,
    DriveOnHeading,
    DriveOnHeadingError,
    Point,
    Spin,
    SpinError,
    Wait,
    WaitError,
)
from aiobt_services.behaviors import BehaviorInputError, Outcome, Safety, goals

CHECKER = CollisionChecker(GridCostmap.empty(2.0, 2.0, 0.05, (-1.0, -1.0)))


@pytest.mark.parametrize(
    ("table", "outcome", "code"),
    [
        (SpinError, Outcome.NONE, 0),
        (SpinError, Outcome.COLLISION_AHEAD, 703),
        (SpinError, Outcome.INVALID_INPUT, 700),  # Spin has no INVALID_INPUT: UNKNOWN
        (BackUpError, Outcome.COLLISION_AHEAD, 714),
        (BackUpError, Outcome.INVALID_INPUT, 713),
        (DriveOnHeadingError, Outcome.TIMEOUT, 721),
        (DriveOnHeadingError, Outcome.INVALID_INPUT, 724),
        (AssistedTeleopError, Outcome.TIMEOUT, 731),
        (AssistedTeleopError, Outcome.COLLISION_AHEAD, 730),
        (WaitError, Outcome.TF_ERROR, 740),
    ],
)
def test_outcomes_map_to_the_action_table(table, outcome, code):
    assert goals.error_code(table, outcome) == code


def test_backup_goal_drives_backwards_and_keeps_collision_checks():
    goal = BackUp.Goal(target=Point(x=0.3), speed=0.1, time_allowance=5.0)
    behavior = goals.backup_of(goal, CHECKER, Safety())
    assert behavior.distance == -0.3
    assert behavior.speed == -0.1
    assert behavior.time_allowance == 5.0
    assert behavior.collision() is CHECKER
    unchecked = BackUp.Goal(target=Point(x=0.3), speed=0.1, disable_collision_checks=True)
    assert goals.backup_of(unchecked, CHECKER, Safety()).collision() is None


@pytest.mark.parametrize("target", [Point(x=0.5, y=0.1), Point(x=0.5, z=1.0)])
def test_drive_goal_off_the_x_axis_is_invalid_input(target):
    with pytest.raises(BehaviorInputError, match=r"target.y and target.z must be 0"):
        goals.drive_of(DriveOnHeading.Goal(target=target, speed=0.1), CHECKER, Safety())


def test_spin_and_wait_goals():
    spin = goals.spin_of(Spin.Goal(target_yaw=-math.pi), CHECKER, Safety())
    assert spin.target_yaw == -math.pi
    assert spin.time_allowance == 10.0
    assert goals.wait_of(Wait.Goal(time=2.5)).duration == 2.5
