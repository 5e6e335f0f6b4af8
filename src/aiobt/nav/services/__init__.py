"""Nav2's remote service leaves (BtServiceNode)."""

from aiobt.core.node import TreeNode
from aiobt.nav.services.base import BtService
from aiobt.nav.services.clear_costmap import (
    ClearCostmapAroundPose,
    ClearCostmapAroundRobot,
    ClearCostmapExceptRegion,
    ClearEntireCostmap,
)
from aiobt.nav.services.reinitialize_global_localization import ReinitializeGlobalLocalization
from aiobt.nav.services.validate_path import IsPathValid, ValidatePath

SERVICE_NODES: tuple[type[TreeNode], ...] = (
    ClearCostmapAroundPose,
    ClearCostmapAroundRobot,
    ClearCostmapExceptRegion,
    ClearEntireCostmap,
    IsPathValid,
    ReinitializeGlobalLocalization,
    ValidatePath,
)

__all__ = ["SERVICE_NODES", "BtService"]
