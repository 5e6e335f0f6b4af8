"""Nav2's selectors: the plugin ids a tree uses, switched at run time over a topic."""

from aiobt.core.node import TreeNode
from aiobt.nav.selectors.selector import (
    ControllerSelector,
    GoalCheckerSelector,
    PathHandlerSelector,
    PlannerSelector,
    ProgressCheckerSelector,
    Selector,
    SmootherSelector,
)

SELECTOR_NODES: tuple[type[TreeNode], ...] = (
    PlannerSelector,
    ControllerSelector,
    SmootherSelector,
    GoalCheckerSelector,
    ProgressCheckerSelector,
    PathHandlerSelector,
)

__all__ = [
    "SELECTOR_NODES",
    "ControllerSelector",
    "GoalCheckerSelector",
    "PathHandlerSelector",
    "PlannerSelector",
    "ProgressCheckerSelector",
    "Selector",
    "SmootherSelector",
]
