"""Nav2's remote action leaves (BtActionNode), one per module."""

from aiobt.core.node import TreeNode
from aiobt.nav.actions.assisted_teleop import AssistedTeleop
from aiobt.nav.actions.base import BtAction
from aiobt.nav.actions.compute_coverage_path import ComputeCoveragePath
from aiobt.nav.actions.compute_path_through_poses import ComputePathThroughPoses
from aiobt.nav.actions.compute_path_to_pose import ComputePathToPose
from aiobt.nav.actions.docking import DockRobot, UndockRobot
from aiobt.nav.actions.drive import BackUp, DriveOnHeading
from aiobt.nav.actions.follow_object import FollowObject
from aiobt.nav.actions.follow_path import FollowPath
from aiobt.nav.actions.navigate import NavigateThroughPoses, NavigateToPose
from aiobt.nav.actions.route import ComputeAndTrackRoute, ComputeRoute
from aiobt.nav.actions.smooth_path import SmoothPath
from aiobt.nav.actions.spin import Spin
from aiobt.nav.actions.wait import Wait

ACTION_NODES: tuple[type[TreeNode], ...] = (
    AssistedTeleop,
    BackUp,
    ComputeAndTrackRoute,
    ComputeCoveragePath,
    ComputePathThroughPoses,
    ComputePathToPose,
    ComputeRoute,
    DockRobot,
    DriveOnHeading,
    FollowObject,
    FollowPath,
    NavigateThroughPoses,
    NavigateToPose,
    SmoothPath,
    Spin,
    UndockRobot,
    Wait,
)

__all__ = ["ACTION_NODES", "BtAction"]
