"""CheckPoseOccupancy and RemoveInCollisionGoals (Nav2): costmap costs at poses."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import PortInfo, input_port, output_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import GetCosts, Goals, Msg, PoseStamped
from aiobt.nav.remote import service_ports
from aiobt.nav.services.base import BtService

UNKNOWN_COST = 255.0
GLOBAL_COSTS = GetCosts.service_name("global_costmap")
STATUSES = "vector<nav2_msgs::msg::WaypointStatus>"  # Nav2's spelling
PENDING, SKIPPED = 0, 2  # nav2_msgs/WaypointStatus
_CHECK: tuple[PortInfo, ...] = (
    input_port("cost_threshold", float, 254.0, "Cost above which a pose is in collision."),
    input_port("use_footprint", bool, True, "Use the footprint cost, not the point cost."),
    input_port("consider_unknown_as_obstacle", bool, False, "Unknown cost (255) is an obstacle."),
)


class _CostCheck(BtService):
    SERVICE = GLOBAL_COSTS
    RESPONSE = GetCosts.Response

    def _request(self, poses: list[PoseStamped]) -> Msg:
        return GetCosts.Request(use_footprint=self.get_input("use_footprint"), poses=poses)

    def _blocked(self, cost: float) -> bool:
        """Nav2's test: at or above ``cost_threshold``; unknown only if it is an obstacle."""
        if cost == UNKNOWN_COST and not self.get_input("consider_unknown_as_obstacle"):
            return False
        return cost >= float(self.get_input("cost_threshold"))


class CheckPoseOccupancy(_CostCheck):
    """``<CheckPoseOccupancy pose="{goal}"/>``: SUCCESS if the costmap is occupied at
    ``pose`` (cost >= ``cost_threshold``); FAILURE if it is free, or if the costmap
    does not answer within ``server_timeout``."""

    PORTS = service_ports(
        GLOBAL_COSTS,
        input_port("pose", PoseStamped, description="Pose to check if it is occupied."),
        *_CHECK,
    )

    def make_request(self) -> Msg:
        return self._request([self.get_input("pose")])

    def on_completion(self, response: Any) -> Status:
        if not response.success or not response.costs:
            self.log.error("%s: the GetCosts service failed", self.path)
            return FAILURE
        return SUCCESS if self._blocked(response.costs[0]) else FAILURE


class RemoveInCollisionGoals(_CostCheck):
    """``<RemoveInCollisionGoals input_goals="{goals}" output_goals="{goals}"/>``:
    ``output_goals`` keeps the goals whose cost is below ``cost_threshold``; the
    removed ones are marked SKIPPED in ``output_waypoint_statuses``. SUCCESS (also
    when every goal is removed); FAILURE without goals (as Nav2: nothing to ask) or
    if the costmap does not answer."""

    PORTS = service_ports(
        GLOBAL_COSTS,
        input_port("input_goals", Goals, description="Goals to check for collision."),
        *_CHECK,
        input_port("input_waypoint_statuses", STATUSES, description="Waypoint statuses."),
        output_port("output_goals", Goals, description="The goals not in collision."),
        output_port("output_waypoint_statuses", STATUSES, description="Removed ones SKIPPED."),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._goals = Goals()

    def make_request(self) -> Msg:
        self._goals = self.get_input("input_goals")
        return self._request(list(self._goals.goals))

    async def run(self) -> Status:
        goals = self.get_input("input_goals", None)
        if goals is not None and not goals.goals:
            self.set_output("output_goals", goals)
            return FAILURE
        return await super().run()

    def on_completion(self, response: Any) -> Status:
        if not response.success or len(response.costs) != len(self._goals.goals):
            self.log.error("%s: the GetCosts service failed", self.path)
            self.set_output("output_goals", self._goals)
            return FAILURE
        statuses = list(self.get_input("input_waypoint_statuses", None) or [])
        kept = []
        for goal, cost in zip(self._goals.goals, response.costs, strict=True):
            if not self._blocked(cost):
                kept.append(goal)
            elif not _skip(statuses, goal):
                self.log.error("%s: no pending waypoint status matches %s", self.path, goal)
                return FAILURE
        if not kept:
            self.log.info("%s: every goal is in collision and was removed", self.path)
        self.set_output("output_goals", self._goals.model_copy(update={"goals": kept}))
        self.set_output("output_waypoint_statuses", statuses)
        return SUCCESS


def _skip(statuses: list[Any], goal: PoseStamped) -> bool:
    """Mark the first PENDING status of ``goal`` SKIPPED (True when there are no statuses)."""
    if not statuses:
        return True
    for index, status in enumerate(statuses):
        if _field(status, "waypoint_pose") == goal and _field(status, "waypoint_status") == PENDING:
            statuses[index] = _with_status(status, SKIPPED)
            return True
    return False


def _field(status: Any, name: str) -> Any:
    return status.get(name) if isinstance(status, dict) else getattr(status, name, None)


def _with_status(status: Any, state: int) -> Any:
    if isinstance(status, dict):
        return {**status, "waypoint_status": state}
    return status.model_copy(update={"waypoint_status": type(status.waypoint_status)(state)})
