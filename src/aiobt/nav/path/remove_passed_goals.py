"""RemovePassedGoals (Nav2): drop the via-points the robot has reached."""

from __future__ import annotations

import logging
from typing import Any

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import Goals, PoseStamped, WaypointState, WaypointStatus
from aiobt.nav.path_math import distance
from aiobt.nav.robot_state import RobotStateNode

log = logging.getLogger("aiobt.nav.remove_passed_goals")


class RemovePassedGoals(RobotStateNode, SyncActionNode):
    """``<RemovePassedGoals input_goals="{goals}" output_goals="{goals}" radius="0.5"/>`` (Nav2).

    - SUCCESS, writing ``input_goals`` without its leading goals that lie within
      ``radius`` of the robot (the last goal is never removed); each removed
      goal's PENDING entry in ``input_waypoint_statuses`` is marked COMPLETED
      in ``output_waypoint_statuses``;
    - FAILURE when there is no robot pose, or a removed goal has no PENDING
      entry in the given statuses.
    """

    PORTS = (
        input_port(
            "radius",
            float,
            0.5,
            "The radius (m) around a via-point within which it counts as passed.",
        ),
        input_port("robot_base_frame", str, description="Robot base frame."),
        input_port("input_goals", Goals, description="The goals to check."),
        input_port(
            "input_waypoint_statuses",
            list[WaypointStatus],
            description="Original waypoint_statuses to mark waypoint status from.",
        ),
        output_port("output_goals", Goals, description="The goals not passed yet."),
        output_port(
            "output_waypoint_statuses",
            list[WaypointStatus],
            description="Waypoint_statuses with passed waypoints marked.",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._reported: set[str] = set()

    def _report_once(self, what: str, message: str) -> None:
        if what not in self._reported:
            self._reported.add(what)
            log.error("%s: %s", self.path, message)

    def on_tick(self) -> Status:
        goals: Goals = self.get_input("input_goals")
        if not goals.goals:
            self.set_output("output_goals", goals)
            return SUCCESS
        robot = self.robot_pose(goals.goals[0].header.frame_id)
        if robot is None:
            return FAILURE
        statuses: list[WaypointStatus] | None = self.get_input("input_waypoint_statuses", None)
        if statuses is None:
            self._report_once("statuses", "missing [input_waypoint_statuses] port input")
        radius: float = self.get_input("radius")
        remaining = list(goals.goals)
        marked = list(statuses or ())
        while len(remaining) > 1 and distance(remaining[0], robot) <= radius:
            if statuses is not None and not _complete(marked, remaining[0]):
                self._report_once("match", "a passed goal has no PENDING waypoint status")
                return FAILURE
            remaining.pop(0)
        self.set_output("output_goals", Goals.model_construct(header=goals.header, goals=remaining))
        self.set_output("output_waypoint_statuses", marked)
        return SUCCESS


def _complete(statuses: list[WaypointStatus], goal: PoseStamped) -> bool:
    """Mark the first PENDING status of ``goal`` COMPLETED (a copy); False if none."""
    for index, status in enumerate(statuses):
        if status.waypoint_status == WaypointState.PENDING and status.waypoint_pose == goal:
            statuses[index] = status.model_copy(update={"waypoint_status": WaypointState.COMPLETED})
            return True
    return False
