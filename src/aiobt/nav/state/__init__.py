"""Nav2's conditions and leaves on the robot's state (pose, odometry, battery...)."""

from aiobt.core.node import TreeNode
from aiobt.nav.state.is_goal_nearby import IsGoalNearby

STATE_NODES: tuple[type[TreeNode], ...] = (IsGoalNearby,)

__all__ = ["STATE_NODES", "IsGoalNearby"]
