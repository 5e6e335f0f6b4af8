"""GoalUpdated and GlobalUpdatedGoal (Nav2): has the navigation goal changed?"""

from __future__ import annotations

from typing import Any

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.core.status import IDLE
from aiobt.msgs import Goals, PoseStamped

# goal/goals from the ports, else the blackboard entries of the same names (Nav2)
GOAL_PORTS = (
    input_port(
        "goal",
        PoseStamped,  # exported as geometry_msgs::msg::PoseStamped; Nav2's ';' text works
        description='Destination to check. Takes in a blackboard variable, "{goal}" '
        "if not specified.",
    ),
    input_port(
        "goals",
        Goals,  # nav_msgs::msg::Goals
        description='Vector of goals to check. Takes in a blackboard variable, "{goals}" '
        "if not specified.",
    ),
)


class GoalUpdated(ConditionNode):
    """``<GoalUpdated/>`` (Nav2): SUCCESS when ``goal`` or ``goals`` changed since
    this node's previous tick, else FAILURE.

    ``goal``/``goals`` come from the ports if set, else from the blackboard
    entries of the same names. As in Nav2 the memory lives in the node's
    activation: a tick while IDLE only remembers the goals and returns FAILURE.
    Nav2's quirk, matched: under a reactive parent with a RUNNING sibling the
    parent resets this node every tick, so every tick is a first tick and it
    never fires — use GlobalUpdatedGoal there.
    """

    __slots__ = ("_goal", "_goals")
    PORTS = GOAL_PORTS

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._goal: Any = None
        self._goals: Any = None

    def _changed(self) -> bool:
        goal = self.get_input_or_blackboard("goal", None)
        goals = self.get_input_or_blackboard("goals", None)
        changed = bool(goal != self._goal or goals != self._goals)
        self._goal, self._goals = goal, goals
        return changed

    def check(self) -> bool:
        if self._status is IDLE:
            self._changed()
            return False
        return self._changed()


class GlobalUpdatedGoal(GoalUpdated):
    """``<GlobalUpdatedGoal/>`` (Nav2): like GoalUpdated, but it remembers the
    goals across resets, so it sees any change between two of its ticks even
    under a reactive parent. Its very first tick returns FAILURE."""

    __slots__ = ("_first",)

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._first = True

    def check(self) -> bool:
        if self._first:
            self._first = False
            self._changed()
            return False
        return self._changed()
