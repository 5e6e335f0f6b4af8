"""GoalUpdater (Nav2): take a newer goal published while navigating."""

from __future__ import annotations

import logging
from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs import Goals, PoseStamped
from aiobt.nav.context import NavNode
from aiobt.nav.shared_topics import SharedTopic, shared_topics

log = logging.getLogger("aiobt.nav.goal_updater")

GOAL_UPDATE_TOPIC = "goal_update"  # Nav2's goal_updater_topic default
GOALS_UPDATE_TOPIC = "goals_update"  # Nav2's goals_updater_topic default


class GoalUpdater(NavNode, DecoratorNode):
    """``<GoalUpdater input_goal="{goal}" output_goal="{updated_goal}">child</GoalUpdater>``
    (Nav2).

    Listens on ``{ns}/goal_update`` (PoseStamped) and ``{ns}/goals_update``
    (Goals). Each tick writes ``output_goal``: the last goal received there if
    its stamp is not older than ``input_goal``'s, else ``input_goal``; likewise
    ``output_goals`` from ``input_goals`` (an empty update is ignored). A
    received goal without a stamp (0) is ignored, as Nav2 does. An output with
    neither input nor update is left alone (Nav2 writes an empty message).
    Then it ticks the child and returns its status.
    """

    PORTS = (
        input_port("input_goal", PoseStamped, description="The original goal pose."),
        input_port("input_goals", Goals, description="The original goals poses."),
        output_port(
            "output_goal",
            PoseStamped,
            description="The resulting updated goal. If no goal received by subscription, "
            "it will be the input_goal.",
        ),
        output_port(
            "output_goals",
            Goals,
            description="The resulting updated goals. If no goals received by subscription, "
            "it will be the input_goals.",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._goal: SharedTopic[PoseStamped] | None = None
        self._goals: SharedTopic[Goals] | None = None
        self._warned: set[str] = set()
        if self.nav.bus is not None:
            self._subscribe()

    def _subscribe(self) -> tuple[SharedTopic[PoseStamped], SharedTopic[Goals]]:
        if self._goal is None or self._goals is None:
            topics = shared_topics(self.nav, self.path)
            self._goal = topics.topic(GOAL_UPDATE_TOPIC, PoseStamped)
            self._goals = topics.topic(GOALS_UPDATE_TOPIC, Goals)
        return self._goal, self._goals

    def execute_sync(self) -> Status:
        goal_topic, goals_topic = self._subscribe()
        goal = self._newer("goal", self.get_input("input_goal", None), goal_topic.latest)
        if goal is not None:
            self.set_output("output_goal", goal)
        update = goals_topic.latest
        if update is not None and not update.goals:
            update = None
        goals = self._newer("goals", self.get_input("input_goals", None), update)
        if goals is not None:
            self.set_output("output_goals", goals)
        status = self.tick_child()
        if status.is_completed:
            self.reset_child()  # so that it starts afresh on the next tick
        return status

    def _newer(self, what: str, current: Any, update: PoseStamped | Goals | None) -> Any:
        """``update`` if it is stamped and not older than ``current``, else ``current``."""
        if update is None:
            return current
        if update.header.stamp == 0.0:
            self._warn_once(what, f"the received {what} has no timestamp; ignored")
            return current
        current_stamp = current.header.stamp if current is not None else 0.0
        if update.header.stamp >= current_stamp:
            return update
        self._warn_once(
            f"old {what}",
            f"the received {what} ({update.header.stamp:.3f}) is older than the current "
            f"one ({current_stamp:.3f}); ignored",
        )
        return current

    def _warn_once(self, what: str, message: str) -> None:
        if what not in self._warned:
            self._warned.add(what)
            log.warning("%s: %s", self.path, message)
