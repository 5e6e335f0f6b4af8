"""Goal checkers and the progress checker, selectable by Nav2's plugin ids."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Protocol

from aiobt.geometry import Pose2D, Velocity, wrap_angle


class GoalChecker(Protocol):
    @property
    def xy_goal_tolerance(self) -> float: ...

    def reset(self) -> None: ...

    def is_goal_reached(self, pose: Pose2D, goal: Pose2D, velocity: Velocity) -> bool: ...


class ProgressChecker(Protocol):
    def reset(self) -> None: ...

    def check(self, pose: Pose2D, now: float) -> bool:
        """False once the robot has not moved far enough within the time window."""
        ...


class SimpleGoalChecker:
    """Nav2's SimpleGoalChecker: within xy and yaw tolerance.

    Stateful: once the position is within tolerance it stays "reached" while
    the robot rotates to the goal heading (rotation may drift the position).
    With ``stopped`` (Nav2's StoppedGoalChecker) the robot must also be still.
    """

    __slots__ = (
        "_xy",
        "_xy_latched",
        "rot_stopped",
        "stateful",
        "stopped",
        "trans_stopped",
        "yaw_goal_tolerance",
    )

    def __init__(
        self,
        xy_goal_tolerance: float = 0.25,
        yaw_goal_tolerance: float = 0.25,
        stateful: bool = True,
        stopped: bool = False,
        trans_stopped_velocity: float = 0.05,
        rot_stopped_velocity: float = 0.1,
    ) -> None:
        for name, value in (
            ("xy_goal_tolerance", xy_goal_tolerance),
            ("yaw_goal_tolerance", yaw_goal_tolerance),
        ):
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"goal checker {name} must be a positive number, got {value!r}")
        self._xy = xy_goal_tolerance
        self.yaw_goal_tolerance = yaw_goal_tolerance
        self.stateful = stateful
        self.stopped = stopped
        self.trans_stopped = trans_stopped_velocity
        self.rot_stopped = rot_stopped_velocity
        self._xy_latched = False

    @property
    def xy_goal_tolerance(self) -> float:
        return self._xy

    def reset(self) -> None:
        self._xy_latched = False

    def is_goal_reached(self, pose: Pose2D, goal: Pose2D, velocity: Velocity) -> bool:
        if not self._xy_latched:
            if pose.distance_to(goal) > self._xy:
                return False
            self._xy_latched = self.stateful
        if abs(wrap_angle(goal.yaw - pose.yaw)) > self.yaw_goal_tolerance:
            return False
        if self.stopped:
            return abs(velocity.v) <= self.trans_stopped and abs(velocity.w) <= self.rot_stopped
        return True


class SimpleProgressChecker:
    """Nav2's SimpleProgressChecker: move a radius within a time window, or fail."""

    __slots__ = (
        "_baseline",
        "_baseline_time",
        "movement_time_allowance",
        "required_movement_radius",
    )

    def __init__(
        self, required_movement_radius: float = 0.5, movement_time_allowance: float = 10.0
    ) -> None:
        if not (math.isfinite(required_movement_radius) and required_movement_radius >= 0.0):
            raise ValueError(
                f"required_movement_radius must be >= 0, got {required_movement_radius!r}"
            )
        if not (math.isfinite(movement_time_allowance) and movement_time_allowance > 0.0):
            raise ValueError(
                f"movement_time_allowance must be > 0, got {movement_time_allowance!r}"
            )
        self.required_movement_radius = required_movement_radius
        self.movement_time_allowance = movement_time_allowance
        self._baseline: Pose2D | None = None
        self._baseline_time = 0.0

    def reset(self) -> None:
        self._baseline = None

    def check(self, pose: Pose2D, now: float) -> bool:
        if (
            self._baseline is None
            or pose.distance_to(self._baseline) > self.required_movement_radius
        ):
            self._baseline = pose
            self._baseline_time = now
            return True
        return now - self._baseline_time <= self.movement_time_allowance


@dataclass(slots=True, frozen=True)
class CheckerRegistry:
    """Plugin ids -> factories, as in Nav2's controller_server parameters."""

    goal_checkers: dict[str, Callable[[], GoalChecker]]
    progress_checkers: dict[str, Callable[[], ProgressChecker]]


def default_checkers() -> CheckerRegistry:
    return CheckerRegistry(
        goal_checkers={
            "general_goal_checker": lambda: SimpleGoalChecker(0.25, 0.25, stateful=True),
            "precise_goal_checker": lambda: SimpleGoalChecker(
                0.1, 0.1, stateful=True, stopped=True
            ),
        },
        progress_checkers={"progress_checker": lambda: SimpleProgressChecker(0.5, 10.0)},
    )
