"""Nav2's conditions on the blackboard: goal updates, error codes, timers."""

from aiobt.core.node import TreeNode
from aiobt.nav.conditions.error_codes import (
    AreErrorCodesPresent,
    WouldAControllerRecoveryHelp,
    WouldAPlannerRecoveryHelp,
    WouldARouteRecoveryHelp,
    WouldASmootherRecoveryHelp,
)
from aiobt.nav.conditions.goal_updated import GlobalUpdatedGoal, GoalUpdated
from aiobt.nav.conditions.time_expired import PathExpiringTimer, TimeExpired

CONDITION_NODES: tuple[type[TreeNode], ...] = (
    GoalUpdated,
    GlobalUpdatedGoal,
    AreErrorCodesPresent,
    WouldAControllerRecoveryHelp,
    WouldAPlannerRecoveryHelp,
    WouldASmootherRecoveryHelp,
    WouldARouteRecoveryHelp,
    TimeExpired,
    PathExpiringTimer,
)

__all__ = [
    "CONDITION_NODES",
    "AreErrorCodesPresent",
    "GlobalUpdatedGoal",
    "GoalUpdated",
    "PathExpiringTimer",
    "TimeExpired",
    "WouldAControllerRecoveryHelp",
    "WouldAPlannerRecoveryHelp",
    "WouldARouteRecoveryHelp",
    "WouldASmootherRecoveryHelp",
]
