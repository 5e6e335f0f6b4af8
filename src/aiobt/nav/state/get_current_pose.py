"""GetCurrentPose (Nav2): write the robot pose to the blackboard."""

from __future__ import annotations

import logging

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import PoseStamped
from aiobt.nav.robot_state import ODOM, POSE, RobotStateNode

log = logging.getLogger("aiobt.nav.get_current_pose")


class GetCurrentPose(RobotStateNode, SyncActionNode):
    """``<GetCurrentPose current_pose="{pose}" global_frame="map"/>`` (Nav2).

    SUCCESS, writing the robot pose in ``global_frame`` (default ``map``;
    ``odom`` works too) to ``current_pose``; FAILURE when there is none.
    """

    READS = (POSE, ODOM)
    PORTS = (
        input_port("robot_base_frame", str, description="Robot base frame."),
        input_port("global_frame", str, description="Global frame (default: map)."),
        output_port(
            "current_pose", PoseStamped, description="The current pose in the global frame."
        ),
    )

    def on_tick(self) -> Status:
        pose = self.robot_pose(self.get_input("global_frame", ""))
        if pose is None:
            return FAILURE
        self.set_output("current_pose", pose)
        return SUCCESS
