"""Nav2's route, docking and following actions (served by ``aiobt route``,
``aiobt docking`` and ``aiobt following``).

Their BT leaves exist with Nav2's ports so that Nav2's trees load; against no
server they fail after ``server_timeout`` with a clear "no server" message, and
a user's own server speaking these models works. Fields follow ``nav2_msgs``;
durations are float seconds.
"""

from __future__ import annotations

from enum import IntEnum
from typing import TypeAlias

from pydantic import Field

from aiobt.msgs import errors
from aiobt.msgs._base import Msg
from aiobt.msgs.action import ActionDef, ActionResult, Empty
from aiobt.msgs.geometry import PoseStamped
from aiobt.msgs.nav import Path
from aiobt.msgs.route import Route

Seconds = float


class _RouteGoal(Msg):
    start_id: int = Field(default=0, ge=0)
    start: PoseStamped = Field(default_factory=PoseStamped)
    goal_id: int = Field(default=0, ge=0)
    goal: PoseStamped = Field(default_factory=PoseStamped)
    use_start: bool = False
    use_poses: bool = False


class _ComputeRouteResult(ActionResult):
    planning_time: Seconds = Field(default=0.0, ge=0.0)
    path: Path = Field(default_factory=Path)
    route: Route = Field(default_factory=Route)


class ComputeRoute(ActionDef[_RouteGoal, _ComputeRouteResult, Empty]):
    name = "compute_route"
    ErrorCode = errors.ComputeRouteError
    Goal: TypeAlias = _RouteGoal
    Result: TypeAlias = _ComputeRouteResult
    Feedback: TypeAlias = Empty


class _TrackRouteResult(ActionResult):
    execution_duration: Seconds = Field(default=0.0, ge=0.0)


class _TrackRouteFeedback(Msg):
    last_node_id: int = Field(default=0, ge=0)
    next_node_id: int = Field(default=0, ge=0)
    current_edge_id: int = Field(default=0, ge=0)
    route: Route = Field(default_factory=Route)
    path: Path = Field(default_factory=Path)
    operations_triggered: list[str] = Field(default_factory=list)
    rerouted: bool = False


class ComputeAndTrackRoute(ActionDef[_RouteGoal, _TrackRouteResult, _TrackRouteFeedback]):
    name = "compute_and_track_route"
    ErrorCode = errors.ComputeRouteError
    Goal: TypeAlias = _RouteGoal
    Result: TypeAlias = _TrackRouteResult
    Feedback: TypeAlias = _TrackRouteFeedback


class DockRobotError(IntEnum):
    NONE = 0
    DOCK_NOT_IN_DB = 901
    DOCK_NOT_VALID = 902
    FAILED_TO_STAGE = 903
    FAILED_TO_DETECT_DOCK = 904
    FAILED_TO_CONTROL = 905
    FAILED_TO_CHARGE = 906
    TIMEOUT = 907
    UNKNOWN = 999


class UndockRobotError(IntEnum):
    NONE = 0
    DOCK_NOT_VALID = 902
    FAILED_TO_CONTROL = 905
    TIMEOUT = 907
    UNKNOWN = 999


class FollowObjectError(IntEnum):
    NONE = 0
    TF_ERROR = 901
    FAILED_TO_DETECT_OBJECT = 902
    FAILED_TO_CONTROL = 903
    TIMEOUT = 904
    UNKNOWN = 999


class _DockGoal(Msg):
    use_dock_id: bool = True
    dock_id: str = ""
    dock_pose: PoseStamped = Field(default_factory=PoseStamped)
    dock_type: str = ""
    max_staging_time: Seconds = Field(default=1000.0, ge=0.0)
    navigate_to_staging_pose: bool = True


class _DockResult(ActionResult):
    success: bool = True
    num_retries: int = Field(default=0, ge=0)


class _DockFeedback(Msg):
    state: int = Field(default=0, ge=0)
    docking_time: Seconds = Field(default=0.0, ge=0.0)
    num_retries: int = Field(default=0, ge=0)


class DockRobot(ActionDef[_DockGoal, _DockResult, _DockFeedback]):
    name = "dock_robot"
    ErrorCode = DockRobotError
    Goal: TypeAlias = _DockGoal
    Result: TypeAlias = _DockResult
    Feedback: TypeAlias = _DockFeedback


class _UndockGoal(Msg):
    dock_type: str = ""
    max_undocking_time: Seconds = Field(default=30.0, ge=0.0)


class _UndockResult(ActionResult):
    success: bool = True


class UndockRobot(ActionDef[_UndockGoal, _UndockResult, Empty]):
    name = "undock_robot"
    ErrorCode = UndockRobotError
    Goal: TypeAlias = _UndockGoal
    Result: TypeAlias = _UndockResult
    Feedback: TypeAlias = Empty


class _FollowObjectGoal(Msg):
    pose_topic: str = ""
    tracked_frame: str = ""
    max_duration: Seconds = Field(default=0.0, ge=0.0)


class _FollowObjectResult(ActionResult):
    total_elapsed_time: Seconds = Field(default=0.0, ge=0.0)
    num_retries: int = Field(default=0, ge=0)


class _FollowObjectFeedback(Msg):
    state: int = Field(default=0, ge=0)
    following_time: Seconds = Field(default=0.0, ge=0.0)
    num_retries: int = Field(default=0, ge=0)


class FollowObject(ActionDef[_FollowObjectGoal, _FollowObjectResult, _FollowObjectFeedback]):
    name = "follow_object"
    ErrorCode = FollowObjectError
    Goal: TypeAlias = _FollowObjectGoal
    Result: TypeAlias = _FollowObjectResult
    Feedback: TypeAlias = _FollowObjectFeedback
