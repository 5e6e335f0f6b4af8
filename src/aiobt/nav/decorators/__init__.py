"""Nav2's decorators: tick a child by rate, once, on goal updates, by distance, speed,
path length."""

from aiobt.core.node import TreeNode
from aiobt.nav.decorators.distance_controller import DistanceController
from aiobt.nav.decorators.goal_updated_controller import GoalUpdatedController
from aiobt.nav.decorators.goal_updater import GoalUpdater
from aiobt.nav.decorators.path_longer_on_approach import PathLongerOnApproach
from aiobt.nav.decorators.rate_controller import RateController
from aiobt.nav.decorators.single_trigger import SingleTrigger
from aiobt.nav.decorators.speed_controller import SpeedController

DECORATOR_NODES: tuple[type[TreeNode], ...] = (
    RateController,
    SingleTrigger,
    GoalUpdatedController,
    DistanceController,
    SpeedController,
    GoalUpdater,
    PathLongerOnApproach,
)

__all__ = [
    "DECORATOR_NODES",
    "DistanceController",
    "GoalUpdatedController",
    "GoalUpdater",
    "PathLongerOnApproach",
    "RateController",
    "SingleTrigger",
    "SpeedController",
]
