"""Nav2's navigation decorators: tick a child by distance, speed, goal updates, path length."""

from aiobt.core.node import TreeNode
from aiobt.nav.decorators.distance_controller import DistanceController
from aiobt.nav.decorators.goal_updater import GoalUpdater
from aiobt.nav.decorators.path_longer_on_approach import PathLongerOnApproach
from aiobt.nav.decorators.speed_controller import SpeedController

DECORATOR_NODES: tuple[type[TreeNode], ...] = (
    DistanceController,
    SpeedController,
    GoalUpdater,
    PathLongerOnApproach,
)

__all__ = [
    "DECORATOR_NODES",
    "DistanceController",
    "GoalUpdater",
    "PathLongerOnApproach",
    "SpeedController",
]
