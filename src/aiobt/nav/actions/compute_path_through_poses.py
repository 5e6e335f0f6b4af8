"""ComputePathThroughPoses (Nav2): a path from the planner server through several goals."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs import ComputePathThroughPoses as ComputePathThroughPosesAction
from aiobt.msgs import Goals, Path, PoseStamped
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports

ALL_GOALS = -1  # Nav2's last_reached_index when the plan covers every goal (or none)


class ComputePathThroughPoses(BtAction):
    """``<ComputePathThroughPoses goals="{goals}" path="{path}"/>``

    - SUCCESS: ``path`` through every goal in order, ``last_reached_index`` -1 (all);
    - FAILURE: ``path`` empty, ``error_code_id`` the planner's (e.g. 308 NO_VALID_PATH);
    - new ``goals`` (or ``start``) while RUNNING are sent to the planner (it preempts).
    """

    ACTION = ComputePathThroughPosesAction
    WATCHED = ("goals", "start")
    PORTS = action_ports(
        "Compute path through poses",
        ComputePathThroughPosesAction.name,
        input_port("start", PoseStamped, description="Start pose. Optional."),
        input_port("goals", Goals, description='Goal poses, e.g. "{goals}".'),
        input_port("planner_id", str, "", description="Planner plugin to use, e.g. GridBased."),
        output_port("path", Path, description="Path created by the action server."),
        output_port("last_reached_index", int, description="Index of the last goal reached."),
    )

    def make_goal(self) -> Any:
        start = self.get_input("start", None)
        fields: dict[str, Any] = {"use_start": start is not None}
        if start is not None:
            fields["start"] = start
        return self.ACTION.goal_type()(
            goals=self.get_input_or_blackboard("goals"),
            planner_id=self.get_input("planner_id", "") or "",
            **fields,
        )

    def on_success(self, result: Any) -> Status:
        self.set_output("path", result.path)
        self.set_output("last_reached_index", ALL_GOALS)
        return super().on_success(result)

    def on_aborted(self, result: Any) -> Status:
        self._no_path()
        return super().on_aborted(result)

    def on_cancelled(self, result: Any | None) -> Status:
        self._no_path()
        return super().on_cancelled(result)

    def on_failure(self, code: int | None, message: str) -> None:
        self.set_output("last_reached_index", ALL_GOALS)
        super().on_failure(code, message)

    def _no_path(self) -> None:
        self.set_output("path", Path())
        self.set_output("last_reached_index", ALL_GOALS)
