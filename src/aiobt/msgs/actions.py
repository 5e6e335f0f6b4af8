"""Nav2's actions: ``ComputePathToPose.Goal``, ``.Result``, ``.Feedback``, ``.ErrorCode``.

Fields follow ``nav2_msgs/action``; durations are float seconds. Every result
carries ``error_code`` and ``error_msg`` (see :class:`ActionResult`).
"""

from __future__ import annotations

from typing import TypeAlias

from pydantic import Field

from aiobt.msgs import errors
from aiobt.msgs._base import Msg
from aiobt.msgs.action import ActionDef, ActionResult, Empty
from aiobt.msgs.geometry import Point, PoseStamped
from aiobt.msgs.nav import Goals, Path

Seconds = float


class _ComputePathToPoseGoal(Msg):
    goal: PoseStamped
    start: PoseStamped = Field(default_factory=PoseStamped)
    viapoints: list[PoseStamped] = Field(default_factory=list)  # passed in order, before goal
    use_start: bool = False
    planner_id: str = ""


class _ComputePathResult(ActionResult):
    path: Path = Field(default_factory=Path)
    planning_time: Seconds = Field(default=0.0, ge=0.0)


class ComputePathToPose(ActionDef[_ComputePathToPoseGoal, _ComputePathResult, Empty]):
    name = "compute_path_to_pose"
    ErrorCode = errors.ComputePathToPoseError
    Goal: TypeAlias = _ComputePathToPoseGoal
    Result: TypeAlias = _ComputePathResult
    Feedback: TypeAlias = Empty


class _ComputePathThroughPosesGoal(Msg):
    goals: Goals
    start: PoseStamped = Field(default_factory=PoseStamped)
    use_start: bool = False
    planner_id: str = ""


class ComputePathThroughPoses(ActionDef[_ComputePathThroughPosesGoal, _ComputePathResult, Empty]):
    name = "compute_path_through_poses"
    ErrorCode = errors.ComputePathThroughPosesError
    Goal: TypeAlias = _ComputePathThroughPosesGoal
    Result: TypeAlias = _ComputePathResult
    Feedback: TypeAlias = Empty


class _SmoothPathGoal(Msg):
    path: Path
    smoother_id: str = ""
    max_smoothing_duration: Seconds = Field(default=3.0, ge=0.0)
    check_for_collisions: bool = False


class _SmoothPathResult(ActionResult):
    path: Path = Field(default_factory=Path)
    smoothing_duration: Seconds = Field(default=0.0, ge=0.0)
    was_completed: bool = False


class SmoothPath(ActionDef[_SmoothPathGoal, _SmoothPathResult, Empty]):
    name = "smooth_path"
    ErrorCode = errors.SmoothPathError
    Goal: TypeAlias = _SmoothPathGoal
    Result: TypeAlias = _SmoothPathResult
    Feedback: TypeAlias = Empty


class _FollowPathGoal(Msg):
    path: Path
    controller_id: str = ""
    goal_checker_id: str = ""
    progress_checker_id: str = ""
    path_handler_id: str = ""


class _FollowPathFeedback(Msg):
    distance_to_goal: float = 0.0
    speed: float = 0.0


class FollowPath(ActionDef[_FollowPathGoal, ActionResult, _FollowPathFeedback]):
    name = "follow_path"
    ErrorCode = errors.FollowPathError
    Goal: TypeAlias = _FollowPathGoal
    Result: TypeAlias = ActionResult
    Feedback: TypeAlias = _FollowPathFeedback


class _ElapsedResult(ActionResult):
    total_elapsed_time: Seconds = Field(default=0.0, ge=0.0)


class _SpinGoal(Msg):
    target_yaw: float
    time_allowance: Seconds = Field(default=10.0, ge=0.0)
    disable_collision_checks: bool = False


class _SpinFeedback(Msg):
    angular_distance_traveled: float = 0.0


class Spin(ActionDef[_SpinGoal, _ElapsedResult, _SpinFeedback]):
    name = "spin"
    ErrorCode = errors.SpinError
    Goal: TypeAlias = _SpinGoal
    Result: TypeAlias = _ElapsedResult
    Feedback: TypeAlias = _SpinFeedback


class _DriveGoal(Msg):
    """``target.x`` is the signed distance to travel (m); ``speed`` is its magnitude."""

    target: Point
    speed: float = Field(default=0.025, gt=0.0)
    time_allowance: Seconds = Field(default=10.0, ge=0.0)
    disable_collision_checks: bool = False


class _DriveOnHeadingGoal(_DriveGoal):
    """``target.x`` and ``speed`` signed alike: both negative drive backwards (Nav2's rule)."""

    speed: float = 0.025


class _DriveFeedback(Msg):
    distance_traveled: float = 0.0


class BackUp(ActionDef[_DriveGoal, _ElapsedResult, _DriveFeedback]):
    name = "backup"
    ErrorCode = errors.BackUpError
    Goal: TypeAlias = _DriveGoal
    Result: TypeAlias = _ElapsedResult
    Feedback: TypeAlias = _DriveFeedback


class DriveOnHeading(ActionDef[_DriveOnHeadingGoal, _ElapsedResult, _DriveFeedback]):
    name = "drive_on_heading"
    ErrorCode = errors.DriveOnHeadingError
    Goal: TypeAlias = _DriveOnHeadingGoal
    Result: TypeAlias = _ElapsedResult
    Feedback: TypeAlias = _DriveFeedback


class _WaitGoal(Msg):
    time: Seconds = Field(ge=0.0)


class _WaitFeedback(Msg):
    time_left: Seconds = 0.0


class Wait(ActionDef[_WaitGoal, _ElapsedResult, _WaitFeedback]):
    name = "wait"
    ErrorCode = errors.WaitError
    Goal: TypeAlias = _WaitGoal
    Result: TypeAlias = _ElapsedResult
    Feedback: TypeAlias = _WaitFeedback


class _AssistedTeleopGoal(Msg):
    time_allowance: Seconds = Field(default=10.0, ge=0.0)


class _AssistedTeleopFeedback(Msg):
    current_teleop_duration: Seconds = 0.0


class AssistedTeleop(ActionDef[_AssistedTeleopGoal, _ElapsedResult, _AssistedTeleopFeedback]):
    name = "assisted_teleop"
    ErrorCode = errors.AssistedTeleopError
    Goal: TypeAlias = _AssistedTeleopGoal
    Result: TypeAlias = _ElapsedResult
    Feedback: TypeAlias = _AssistedTeleopFeedback


class _NavigateToPoseGoal(Msg):
    pose: PoseStamped
    behavior_tree: str = ""


class _NavigateFeedback(Msg):
    current_pose: PoseStamped = Field(default_factory=PoseStamped)
    navigation_time: Seconds = 0.0
    estimated_time_remaining: Seconds = 0.0
    number_of_recoveries: int = 0
    distance_remaining: float = 0.0


class NavigateToPose(ActionDef[_NavigateToPoseGoal, ActionResult, _NavigateFeedback]):
    name = "navigate_to_pose"
    ErrorCode = errors.NavigateToPoseError
    Goal: TypeAlias = _NavigateToPoseGoal
    Result: TypeAlias = ActionResult
    Feedback: TypeAlias = _NavigateFeedback


class _NavigateThroughPosesGoal(Msg):
    poses: Goals
    behavior_tree: str = ""


class _NavigateThroughPosesFeedback(_NavigateFeedback):
    number_of_poses_remaining: int = 0


class NavigateThroughPoses(
    ActionDef[_NavigateThroughPosesGoal, ActionResult, _NavigateThroughPosesFeedback]
):
    name = "navigate_through_poses"
    ErrorCode = errors.NavigateThroughPosesError
    Goal: TypeAlias = _NavigateThroughPosesGoal
    Result: TypeAlias = ActionResult
    Feedback: TypeAlias = _NavigateThroughPosesFeedback


class _ComputeCoveragePathGoal(Msg):
    """A field as polygons in ``frame_id``: the outer boundary first, then cut-outs."""

    generate_headland: bool = True
    generate_route: bool = True
    generate_path: bool = True
    use_gml_file: bool = False
    gml_field: str = ""
    gml_field_id: int = Field(default=0, ge=0)
    polygons: list[list[Point]] = Field(default_factory=list)
    frame_id: str = "map"


class _ComputeCoveragePathResult(ActionResult):
    nav_path: Path = Field(default_factory=Path)
    coverage_path: Path = Field(default_factory=Path, description="swaths and turns, in order")
    planning_time: Seconds = Field(default=0.0, ge=0.0)


class ComputeCoveragePath(ActionDef[_ComputeCoveragePathGoal, _ComputeCoveragePathResult, Empty]):
    name = "compute_coverage_path"
    ErrorCode = errors.ComputeCoveragePathError
    Goal: TypeAlias = _ComputeCoveragePathGoal
    Result: TypeAlias = _ComputeCoveragePathResult
    Feedback: TypeAlias = Empty
