"""FollowPath (Nav2): the controller server follows a path to its end."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port, output_port
from aiobt.msgs import FollowPath as FollowPathAction
from aiobt.msgs import Path
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports

_IDS = ("controller_id", "goal_checker_id", "progress_checker_id", "path_handler_id")


class FollowPath(BtAction):
    """``<FollowPath path="{path}" controller_id="FollowPath"/>``

    - SUCCESS when the controller reaches the path's end (goal checker);
    - FAILURE with the controller's ``error_code_id`` (e.g. 104 PATIENCE_EXCEEDED,
      105 FAILED_TO_MAKE_PROGRESS), or 107 CONTROLLER_TIMED_OUT when the server
      does not accept the goal within ``server_timeout``;
    - a new non-empty ``path`` (or plugin id) while RUNNING goes to the controller,
      which switches to it smoothly; the leaf stays RUNNING without a halt.
    """

    ACTION = FollowPathAction
    WATCHED = ("path", *_IDS)
    PORTS = action_ports(
        "Follow path",
        FollowPathAction.name,
        input_port("path", Path, description='The path to follow, e.g. "{path}".'),
        input_port("controller_id", str, description="Controller plugin, e.g. FollowPath."),
        input_port("goal_checker_id", str, description="Goal checker plugin."),
        input_port("progress_checker_id", str, description="Progress checker plugin."),
        input_port("path_handler_id", str, description="Path handler plugin."),
        output_port(
            "tracking_feedback",
            "nav2_msgs::msg::TrackingFeedback",
            description="Tracking feedback from the controller server.",
        ),
    )

    def make_goal(self) -> Any:
        ids = {name: self.get_input(name, None) or "" for name in _IDS}
        return self.ACTION.goal_type()(path=self.get_input_or_blackboard("path"), **ids)

    def goal_update(self, goal: Any) -> Any | None:
        new = self.make_goal()
        if not new.path.poses:  # Nav2 keeps following the current path
            new = new.model_copy(update={"path": goal.path})
        return new if new != goal else None

    def on_timeout(self, message: str) -> None:
        self.on_failure(int(self.ACTION.ErrorCode.CONTROLLER_TIMED_OUT), message)  # as Nav2
