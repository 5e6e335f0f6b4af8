"""ComputeRoute and ComputeAndTrackRoute (Nav2's route server)."""

from __future__ import annotations

from typing import Any, ClassVar

from aiobt.core.ports import PortInfo, input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs import Path, PoseStamped
from aiobt.msgs.remote_actions import ComputeAndTrackRoute as ComputeAndTrackRouteAction
from aiobt.msgs.remote_actions import ComputeRoute as ComputeRouteAction
from aiobt.msgs.route import Route
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports

DURATION = "builtin_interfaces::msg::Duration"  # Nav2's spelling; written as float seconds
_ENDS: tuple[PortInfo, ...] = (
    input_port("start", PoseStamped, description="Start pose. Optional."),
    input_port("goal", PoseStamped, description='Goal pose, e.g. "{goal}".'),
    input_port("start_id", int, description="Start node ID to use."),
    input_port("goal_id", int, description="Goal node ID to use."),
    input_port("use_start", bool, False, "Use the start pose instead of the robot's."),
    input_port("use_poses", bool, False, "Use the start and goal poses, not node IDs."),
)


class _RouteAction(BtAction):
    WATCHED: ClassVar[tuple[str, ...]] = (
        "start",
        "goal",
        "start_id",
        "goal_id",
        "use_start",
        "use_poses",
    )

    def make_goal(self) -> Any:
        if self.get_input("use_poses"):
            use_start = bool(self.get_input("use_start"))
            fields: dict[str, Any] = {"use_poses": True, "use_start": use_start,
                                      "goal": self.get_input_or_blackboard("goal")}  # fmt: skip
            if use_start:
                fields["start"] = self.get_input("start")
            return self.ACTION.goal_type()(**fields)
        return self.ACTION.goal_type()(
            start_id=self.get_input("start_id", 0), goal_id=self.get_input("goal_id", 0)
        )


class ComputeRoute(_RouteAction):
    """``<ComputeRoute goal="{goal}" use_poses="true" path="{path}" route="{route}"/>``:
    SUCCESS with ``route``, ``path`` and ``planning_time``; FAILURE with the route
    server's ``error_code_id`` (e.g. 405 NO_VALID_ROUTE), outputs emptied."""

    ACTION = ComputeRouteAction
    WATCHED = ()  # Nav2 sends a route request once per activation
    PORTS = action_ports(
        "Compute route",
        ComputeRouteAction.name,
        *_ENDS,
        output_port("route", Route, description="Route created by the action server."),
        output_port("path", Path, description="Path created by the action server."),
        output_port("planning_time", DURATION, description="Time to compute the route (s)."),
    )

    def on_success(self, result: Any) -> Status:
        self.set_output("path", result.path)
        self.set_output("route", result.route)
        self.set_output("planning_time", result.planning_time)
        return super().on_success(result)

    def on_aborted(self, result: Any) -> Status:
        self._reset()
        return super().on_aborted(result)

    def on_cancelled(self, result: Any | None) -> Status:
        self._reset()
        return super().on_cancelled(result)

    def _reset(self) -> None:
        self.set_output("path", Path())
        self.set_output("route", Route())
        self.set_output("planning_time", 0.0)


class ComputeAndTrackRoute(_RouteAction):
    """``<ComputeAndTrackRoute goal="{goal}" use_poses="true"/>``: RUNNING while the
    route server tracks the route, with its feedback on the outputs (``route``,
    ``path``, node and edge IDs, ``rerouted``); a changed goal is sent anew.
    SUCCESS with ``execution_duration``; FAILURE with its ``error_code_id``."""

    ACTION = ComputeAndTrackRouteAction
    PORTS = action_ports(
        "Compute route",
        ComputeAndTrackRouteAction.name,
        *_ENDS,
        output_port("execution_duration", DURATION, description="Time the route took (s)."),
        output_port("last_node_id", int, description="ID of the previous node."),
        output_port("next_node_id", int, description="ID of the next node."),
        output_port("current_edge_id", int, description="ID of the current edge."),
        output_port("route", Route, description="The route being tracked."),
        output_port("path", Path, description="The path being tracked."),
        output_port("rerouted", bool, description="Whether the plan has rerouted."),
    )

    def on_feedback(self, feedback: Any) -> None:
        for name in ("last_node_id", "next_node_id", "current_edge_id", "route", "path",
                     "rerouted"):  # fmt: skip
            self.set_output(name, getattr(feedback, name))

    def on_success(self, result: Any) -> Status:
        self._reset_feedback()
        self.set_output("execution_duration", result.execution_duration)
        return super().on_success(result)

    def on_aborted(self, result: Any) -> Status:
        self._reset_feedback()
        self.set_output("execution_duration", 0.0)
        return super().on_aborted(result)

    def on_cancelled(self, result: Any | None) -> Status:
        self._reset_feedback()
        self.set_output("execution_duration", 0.0)
        return super().on_cancelled(result)

    def _reset_feedback(self) -> None:
        self.on_feedback(self.ACTION.feedback_type()())
