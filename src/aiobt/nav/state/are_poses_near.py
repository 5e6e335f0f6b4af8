"""ArePosesNear (Nav2): are two poses within a tolerance?"""

from __future__ import annotations

import logging

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.msgs import PoseStamped
from aiobt.nav.frames import transform_pose
from aiobt.nav.path_math import distance
from aiobt.nav.robot_state import ODOM, POSE, RobotStateNode

log = logging.getLogger("aiobt.nav.are_poses_near")


class ArePosesNear(RobotStateNode, ConditionNode):
    """``<ArePosesNear ref_pose="{a}" target_pose="{b}" tolerance="0.5"/>`` (Nav2).

    SUCCESS when the poses are at most ``tolerance`` apart (planar). Poses in
    different frames are first brought into ``global_frame`` (default ``map``;
    ``map``/``odom`` via the robot's pose in both); FAILURE if that fails.
    """

    READS = (POSE, ODOM)
    PORTS = (
        input_port("ref_pose", PoseStamped, description="The initial pose to check."),
        input_port("target_pose", PoseStamped, description="The other pose to check against."),
        input_port(
            "global_frame",
            str,
            description="Global frame to transform poses to if not given in the same frame.",
        ),
        input_port("tolerance", float, 0.5, "Tolerance to check poses if nearby with respect to."),
    )

    def check(self) -> bool:
        first: PoseStamped = self.get_input("ref_pose")
        second: PoseStamped = self.get_input("target_pose")
        tolerance: float = self.get_input("tolerance")
        if first.header.frame_id == second.header.frame_id:
            return distance(first, second) <= tolerance
        frame: str = self.get_input("global_frame", "map")
        moved = [transform_pose(pose, frame, self.robot) for pose in (first, second)]
        if moved[0] is None or moved[1] is None:
            log.error("%s: failed to transform the poses to frame %r", self.path, frame)
            return False
        return distance(moved[0], moved[1]) <= tolerance
