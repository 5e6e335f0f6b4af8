"""GoalUpdatedController (Nav2): tick the child only when the goal changes."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.status import IDLE, RUNNING, Status
from aiobt.nav.conditions.goal_updated import GOAL_PORTS

_NOTHING: Any = None


class GoalUpdatedController(DecoratorNode):
    """``<GoalUpdatedController>`` (Nav2): tick the child when ``goal``/``goals`` changed.

    ``goal`` and ``goals`` come from the ports if set, else from the
    blackboard entries of the same names (Nav2's getInputOrBlackboard).

    - the first tick of an activation (ticked while IDLE) remembers the goals
      and ticks the child;
    - later ticks tick the child if it is RUNNING or if either value differs
      (``!=``) from the one remembered; then the child's status is returned
      (a finished child is reset, so it starts afresh on the next update);
    - otherwise RUNNING (Nav2 returns its own status, just set to RUNNING).

    Nav2's quirk, matched here: the memory lives in this node's activation.
    Under a reactive parent (ReactiveSequence/ReactiveFallback) with a RUNNING
    sibling, the parent resets this node to IDLE on every tick once its child
    finished, so every tick is a "first tick": the child is ticked on every
    tick and a goal change cannot be told apart from no change.
    """

    __slots__ = ("_goal", "_goals", "_updated")
    PORTS = GOAL_PORTS

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._goal: Any = _NOTHING
        self._goals: Any = _NOTHING
        self._updated = False

    def execute_sync(self) -> Status:
        goal = self.get_input_or_blackboard("goal", _NOTHING)
        goals = self.get_input_or_blackboard("goals", _NOTHING)
        if self._status is IDLE:
            self._goal, self._goals = goal, goals
            self._updated = True
        self._set_status(RUNNING)
        if goal != self._goal or goals != self._goals:
            self._goal, self._goals = goal, goals
            self._updated = True
        child = self.child
        assert child is not None
        if not (self._updated or child._status is RUNNING):
            return RUNNING
        self._updated = False
        status = child.tick_sync()
        if status.is_completed:
            self.reset_child()
        return status
