"""NavigateToPose and NavigateThroughPoses (Nav2): a whole navigation, by a navigator."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port
from aiobt.msgs import Goals, PoseStamped
from aiobt.msgs import NavigateThroughPoses as NavigateThroughPosesAction
from aiobt.msgs import NavigateToPose as NavigateToPoseAction
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports

_TREE = input_port(
    "behavior_tree", str, description="Behavior tree path or ID; the navigator's default if empty."
)


class NavigateToPose(BtAction):
    """``<NavigateToPose goal="{goal}"/>``: asks a navigator (its own tree) to go to
    ``goal``; SUCCESS when it arrives, FAILURE with its ``error_code_id``. A new
    ``goal`` while RUNNING is sent to the navigator, which preempts."""

    ACTION = NavigateToPoseAction
    WATCHED = ("goal",)
    PORTS = action_ports(
        "Navigate to pose",
        NavigateToPoseAction.name,
        input_port("goal", PoseStamped, description='The goal, e.g. "{goal}".'),
        _TREE,
    )

    def make_goal(self) -> Any:
        return self.ACTION.goal_type()(
            pose=self.get_input_or_blackboard("goal"),
            behavior_tree=self.get_input("behavior_tree", None) or "",
        )


class NavigateThroughPoses(BtAction):
    """``<NavigateThroughPoses goals="{goals}"/>``: asks a navigator to pass through
    ``goals`` in order; SUCCESS at the last, FAILURE with its ``error_code_id``."""

    ACTION = NavigateThroughPosesAction
    WATCHED = ("goals",)
    PORTS = action_ports(
        "Navigate through poses",
        NavigateThroughPosesAction.name,
        input_port("goals", Goals, description='Goal poses, e.g. "{goals}".'),
        _TREE,
    )

    def make_goal(self) -> Any:
        return self.ACTION.goal_type()(
            poses=self.get_input_or_blackboard("goals"),
            behavior_tree=self.get_input("behavior_tree", None) or "",
        )
