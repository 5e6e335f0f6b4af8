"""ComputePathToPose (Nav2): a path from the planner server to one goal pose."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs import ComputePathToPose as ComputePathToPoseAction
from aiobt.msgs import Path, PoseStamped
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports

# Nav2's spelling of the type; the values come from the blackboard
POSES = "vector<geometry_msgs::msg::PoseStamped>"


class ComputePathToPose(BtAction):
    """``<ComputePathToPose goal="{goal}" path="{path}" planner_id="GridBased"/>``

    - SUCCESS: ``path`` is the planned path;
    - FAILURE: ``path`` empty, ``error_code_id`` the planner's code (e.g. 208
      NO_VALID_PATH), or the server did not accept the goal in time;
    - a new ``goal`` (or ``start``) while RUNNING is sent to the planner, which
      preempts the old request; the leaf stays RUNNING.
    ``start`` is used when given (or when ``use_start`` is true); the path passes
    through ``viapoints`` (in order) before the goal.
    """

    ACTION = ComputePathToPoseAction
    WATCHED = ("goal", "start", "viapoints")
    PORTS = action_ports(
        "Compute path to pose",
        ComputePathToPoseAction.name,
        input_port("start", PoseStamped, description="Start pose. Optional."),
        input_port("use_start", bool, description="Optional. Use (or ignore) the start pose."),
        input_port("goal", PoseStamped, description='Goal pose. e.g. "{goal}".'),
        input_port("viapoints", POSES, description="Optional. Intermediate viapoints."),
        input_port("planner_id", str, "", description="Planner plugin to use, e.g. GridBased."),
        output_port("path", Path, description="Path created by the action server."),
    )

    def make_goal(self) -> Any:
        goal = self.get_input_or_blackboard("goal")
        viapoints = self.get_input("viapoints", None) or []
        start = self.get_input("start", None)
        use_start = self.get_input("use_start", None)
        if use_start and start is None:
            self.log.error("%s: use_start is true but no start is given: planning from the robot",
                           self.path)  # fmt: skip
        use = bool(start is not None and (use_start is None or use_start))
        fields: dict[str, Any] = {"goal": goal, "use_start": use, "viapoints": list(viapoints)}
        if use:
            fields["start"] = start
        planner_id = self.get_input("planner_id", "")
        return self.ACTION.goal_type()(planner_id=planner_id or "", **fields)

    def on_success(self, result: Any) -> Status:
        self.set_output("path", result.path)
        return super().on_success(result)

    def on_aborted(self, result: Any) -> Status:
        self.set_output("path", Path())
        return super().on_aborted(result)

    def on_cancelled(self, result: Any | None) -> Status:
        self.set_output("path", Path())
        return super().on_cancelled(result)
