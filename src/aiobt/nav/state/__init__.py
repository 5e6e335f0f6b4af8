"""Nav2's conditions and leaves on the robot's state (pose, odometry, battery...)."""

from aiobt.core.node import TreeNode
from aiobt.nav.state.are_poses_near import ArePosesNear
from aiobt.nav.state.battery import IsBatteryCharging, IsBatteryLow
from aiobt.nav.state.check_stop_status import CheckStopStatus
from aiobt.nav.state.distance_traveled import DistanceTraveled
from aiobt.nav.state.get_current_pose import GetCurrentPose
from aiobt.nav.state.goal_reached import GoalReached
from aiobt.nav.state.initial_pose_received import InitialPoseReceived
from aiobt.nav.state.is_goal_nearby import IsGoalNearby
from aiobt.nav.state.is_stuck import IsStuck
from aiobt.nav.state.is_within_path_tracking_bounds import IsWithinPathTrackingBounds
from aiobt.nav.state.transform_available import TransformAvailable

STATE_NODES: tuple[type[TreeNode], ...] = (
    GoalReached,
    TransformAvailable,
    DistanceTraveled,
    InitialPoseReceived,
    IsStuck,
    IsBatteryLow,
    IsBatteryCharging,
    IsGoalNearby,
    ArePosesNear,
    IsWithinPathTrackingBounds,
    GetCurrentPose,
    CheckStopStatus,
)

__all__ = [
    "STATE_NODES",
    "ArePosesNear",
    "CheckStopStatus",
    "DistanceTraveled",
    "GetCurrentPose",
    "GoalReached",
    "InitialPoseReceived",
    "IsBatteryCharging",
    "IsBatteryLow",
    "IsGoalNearby",
    "IsStuck",
    "IsWithinPathTrackingBounds",
    "TransformAvailable",
]
