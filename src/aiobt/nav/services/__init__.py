"""Nav2's remote service leaves (BtServiceNode)."""

from aiobt.core.node import TreeNode
from aiobt.nav.services.base import BtService
from aiobt.nav.services.clear_costmap import (
    ClearCostmapAroundPose,
    ClearCostmapAroundRobot,
    ClearCostmapExceptRegion,
    ClearEntireCostmap,
)
from aiobt.nav.services.costs import CheckPoseOccupancy, RemoveInCollisionGoals
from aiobt.nav.services.reinitialize_global_localization import ReinitializeGlobalLocalization
from aiobt.nav.services.toggle_collision_monitor import ToggleCollisionMonitor
from aiobt.nav.services.validate_path import IsPathValid, ValidatePath

SERVICE_NODES: tuple[type[TreeNode], ...] = (
    CheckPoseOccupancy,
    ClearCostmapAroundPose,
    ClearCostmapAroundRobot,
    ClearCostmapExceptRegion,
    ClearEntireCostmap,
    IsPathValid,
    ReinitializeGlobalLocalization,
    RemoveInCollisionGoals,
    ToggleCollisionMonitor,
    ValidatePath,
)

__all__ = ["SERVICE_NODES", "BtService"]
