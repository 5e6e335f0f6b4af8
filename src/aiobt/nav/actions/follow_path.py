"""FollowPath (Nav2): the controller server follows a path to its end."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs import FollowPath as FollowPathAction
from aiobt.msgs import Path, TrackingFeedback
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports
from aiobt.nav.robot_state import TRACKING, RobotState, robot_state

_IDS = ("controller_id", "goal_checker_id", "progress_checker_id", "path_handler_id")


class FollowPath(BtAction):
    """``<FollowPath path="{path}" controller_id="FollowPath"/>``

    - SUCCESS when the controller reaches the path's end (goal checker);
    - FAILURE with the controller's ``error_code_id`` (e.g. 104 PATIENCE_EXCEEDED,
      105 FAILED_TO_MAKE_PROGRESS), or 107 CONTROLLER_TIMED_OUT when the server
      does not accept the goal within ``server_timeout``;
    - a new non-empty ``path`` (or plugin id) while RUNNING goes to the controller,
      which switches to it smoothly; the leaf stays RUNNING without a halt;
    - ``tracking_feedback``: the controller's latest ``{ns}/tracking_feedback`` at
      each feedback while RUNNING, an empty one when the goal ends (Nav2).
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
            TrackingFeedback,
            description="Tracking feedback from the controller server.",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._robot: RobotState | None = None
        if self.nav.bus is not None and "tracking_feedback" in self.config.outputs:
            self._robot = robot_state(self.nav, self.path)
            self._robot.prepare(TRACKING)  # subscribed now: data before the first tick

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

    def on_feedback(self, feedback: Any) -> None:
        tracking = self._robot.tracking_feedback if self._robot is not None else None
        if tracking is not None:
            self.set_output("tracking_feedback", tracking)

    def on_success(self, result: Any) -> Status:
        self.set_output("tracking_feedback", TrackingFeedback())
        return super().on_success(result)

    def on_aborted(self, result: Any) -> Status:
        self.set_output("tracking_feedback", TrackingFeedback())
        return super().on_aborted(result)

    def on_cancelled(self, result: Any | None) -> Status:
        self.set_output("tracking_feedback", TrackingFeedback())
        return super().on_cancelled(result)
