"""Nav2's path and goal utilities: truncate, pick, join and prune paths and goals."""

from aiobt.core.node import TreeNode
from aiobt.nav.path.concatenate_paths import ConcatenatePaths
from aiobt.nav.path.get_pose_from_path import GetPoseFromPath
from aiobt.nav.path.goals import AppendGoalPoseToGoals, ExtractRouteNodesAsGoals, GetNextFewGoals
from aiobt.nav.path.remove_passed_goals import RemovePassedGoals
from aiobt.nav.path.truncate_path import TruncatePath
from aiobt.nav.path.truncate_path_local import TruncatePathLocal

PATH_NODES: tuple[type[TreeNode], ...] = (
    TruncatePath,
    TruncatePathLocal,
    RemovePassedGoals,
    GetPoseFromPath,
    ConcatenatePaths,
    GetNextFewGoals,
    AppendGoalPoseToGoals,
    ExtractRouteNodesAsGoals,
)

__all__ = [
    "PATH_NODES",
    "AppendGoalPoseToGoals",
    "ConcatenatePaths",
    "ExtractRouteNodesAsGoals",
    "GetNextFewGoals",
    "GetPoseFromPath",
    "RemovePassedGoals",
    "TruncatePath",
    "TruncatePathLocal",
]
