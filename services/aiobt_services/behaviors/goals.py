"""From wire goals to behavior state machines, and from outcomes to Nav2 error codes."""

from __future__ import annotations

from enum import IntEnum

from aiobt.costmap.checker import CollisionChecker
from aiobt.msgs import AssistedTeleop as AssistedTeleopAction
from aiobt.msgs import BackUp, DriveOnHeading, Spin, Wait

from .assisted_teleop import AssistedTeleop
from .base import BehaviorInputError, Outcome, Safety
from .drive import DriveOnHeading as DriveBehavior
from .drive import back_up
from .spin import SpinBehavior
from .wait import WaitBehavior

DriveGoal = BackUp.Goal


def error_code(table: type[IntEnum], outcome: Outcome) -> int:
    """The action's number for ``outcome``; its UNKNOWN when the table lacks the name."""
    if outcome is Outcome.NONE:
        return 0
    members = table.__members__
    return int(members[outcome.value] if outcome.value in members else members["UNKNOWN"])


def _planar(goal: DriveGoal, what: str) -> None:
    if goal.target.y != 0.0 or goal.target.z != 0.0:
        raise BehaviorInputError(f"{what} drives along x only; target.y and target.z must be 0")


def _checker(disabled: bool, checker: CollisionChecker) -> CollisionChecker | None:
    return None if disabled else checker


def spin_of(goal: Spin.Goal, checker: CollisionChecker, safety: Safety) -> SpinBehavior:
    return SpinBehavior(
        goal.target_yaw,
        goal.time_allowance,
        _checker(goal.disable_collision_checks, checker),
        safety=safety,
    )


def backup_of(goal: BackUp.Goal, checker: CollisionChecker, safety: Safety) -> DriveBehavior:
    _planar(goal, "BackUp")
    return back_up(
        goal.target.x,
        goal.speed,
        goal.time_allowance,
        _checker(goal.disable_collision_checks, checker),
        safety,
    )


def drive_of(goal: DriveOnHeading.Goal, checker: CollisionChecker, safety: Safety) -> DriveBehavior:
    _planar(goal, "DriveOnHeading")
    return DriveBehavior(
        goal.target.x,
        goal.speed,
        goal.time_allowance,
        _checker(goal.disable_collision_checks, checker),
        safety,
    )


def wait_of(goal: Wait.Goal) -> WaitBehavior:
    return WaitBehavior(goal.time)


def teleop_of(
    goal: AssistedTeleopAction.Goal, checker: CollisionChecker, safety: Safety
) -> AssistedTeleop:
    return AssistedTeleop(goal.time_allowance, checker, safety=safety)
