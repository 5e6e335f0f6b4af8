"""FollowObject (Nav2's following server): keep a distance behind a moving object."""

from __future__ import annotations

from typing import Any

from aiobt.core.ports import input_port, output_port
from aiobt.core.status import Status
from aiobt.msgs.remote_actions import FollowObject as FollowObjectAction
from aiobt.nav.actions.base import BtAction
from aiobt.nav.remote import action_ports

DURATION = "builtin_interfaces::msg::Duration"  # Nav2's spelling; written as float seconds


class FollowObject(BtAction):
    """``<FollowObject pose_topic="dynamic_pose" max_duration="30"/>``: RUNNING while
    following; SUCCESS when the server ends it (``total_elapsed_time``), FAILURE
    with its ``error_code_id`` (e.g. 902 FAILED_TO_DETECT_OBJECT)."""

    ACTION = FollowObjectAction
    PORTS = action_ports(
        "Follow object",
        FollowObjectAction.name,
        input_port("pose_topic", str, "dynamic_pose", "Topic of the pose of the object."),
        input_port("max_duration", float, 0.0, "The maximum duration to follow (s)."),
        input_port("tracked_frame", str, description="Target frame to follow."),
        output_port("total_elapsed_time", DURATION, description="Total elapsed time (s)."),
    )

    def make_goal(self) -> Any:
        return self.ACTION.goal_type()(
            pose_topic=self.get_input("pose_topic"),
            tracked_frame=self.get_input("tracked_frame", None) or "",
            max_duration=self.get_input("max_duration"),
        )

    def on_success(self, result: Any) -> Status:
        self.set_output("total_elapsed_time", result.total_elapsed_time)
        return super().on_success(result)

    def on_aborted(self, result: Any) -> Status:
        self.set_output("total_elapsed_time", result.total_elapsed_time)
        return super().on_aborted(result)

    def on_cancelled(self, result: Any | None) -> Status:
        if result is not None:
            self.set_output("total_elapsed_time", result.total_elapsed_time)
        return super().on_cancelled(result)
