"""InitialPoseReceived (Nav2): has localization been given its initial pose?"""

from __future__ import annotations

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.nav.robot_state import INITIAL_POSE, RobotStateNode


class InitialPoseReceived(RobotStateNode, ConditionNode):
    """``<InitialPoseReceived initial_pose_received="{initial_pose_received}"/>`` (Nav2).

    SUCCESS if ``initial_pose_received`` (the port, else the blackboard entry of
    that name) is true. When neither is set: SUCCESS once a pose has been
    published on ``{ns}/initialpose`` (Nav2's navigator sets the entry from
    that topic), else FAILURE.
    """

    READS = (INITIAL_POSE,)
    PORTS = (
        input_port(
            "initial_pose_received",
            bool,
            description="Success if the value in the port is true. Takes in a blackboard "
            'variable, "{initial_pose_received}" if not specified.',
        ),
    )

    def check(self) -> bool:
        received = self.get_input_or_blackboard("initial_pose_received", None)
        if received is None:
            return self.nav.bus is not None and self.robot.initial_pose is not None
        return bool(received)
