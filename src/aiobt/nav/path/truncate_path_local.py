"""TruncatePathLocal (Nav2): the part of a path around the robot."""

from __future__ import annotations

import logging
import math
from typing import Any

from aiobt.core.leaves import SyncActionNode
from aiobt.core.ports import input_port, output_port
from aiobt.core.status import FAILURE, SUCCESS, Status
from aiobt.msgs import Path, PoseStamped
from aiobt.nav.path_math import ClosestPoseSearch
from aiobt.nav.robot_state import RobotStateNode

log = logging.getLogger("aiobt.nav.truncate_path_local")


class TruncatePathLocal(RobotStateNode, SyncActionNode):
    """``<TruncatePathLocal input_path="{path}" output_path="{local}" distance_forward="8.0"
    distance_backward="4.0"/>`` (Nav2).

    - finds the path pose closest to the robot (``pose`` if given, else the
      robot pose in the path's frame; ``angular_distance_weight`` adds the
      heading difference), searching at most ``max_robot_pose_search_dist``
      metres on from the previous closest pose while the path stays the same;
    - SUCCESS, writing the poses from ``distance_backward`` behind it to
      ``distance_forward`` ahead (-1: to the end);
    - FAILURE when there is no robot pose (none received yet).
    """

    PORTS = (
        input_port("input_path", Path, description="The original path to be truncated."),
        input_port(
            "distance_forward",
            float,
            8.0,
            "The trimming distance in forward direction. Set to -1 to search full path forward.",
        ),
        input_port("distance_backward", float, 4.0, "The trimming distance in backward direction."),
        input_port("robot_base_frame", str, description="Robot base frame id."),
        input_port("transform_tolerance", float, 0.2, "Robot pose lookup tolerance."),
        input_port(
            "pose",
            PoseStamped,
            description="Manually specified pose to be used alternatively to current robot pose.",
        ),
        input_port(
            "angular_distance_weight",
            float,
            0.0,
            "Weight of angular distance relative to positional distance when finding the "
            "path pose closest to the robot.",
        ),
        input_port(
            "max_robot_pose_search_dist",
            float,
            float("inf"),
            "Maximum forward integrated distance along the path (from the last detected pose) "
            "searched for the pose closest to the robot; infinity searches the whole path.",
        ),
        output_port("output_path", Path, description="The resulting truncated path."),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._search = ClosestPoseSearch()

    def on_tick(self) -> Status:
        path: Path = self.get_input("input_path")
        forward: float = self.get_input("distance_forward")
        backward: float = self.get_input("distance_backward")
        search: float = self.get_input("max_robot_pose_search_dist")
        pose = self.get_input("pose", None)
        if pose is None:
            pose = self.robot_pose(path.header.frame_id)
            if pose is None:
                return FAILURE
        if not path.poses:
            self.set_output("output_path", path)
            return SUCCESS
        weight: float = self.get_input("angular_distance_weight")
        closest = self._search.closest(path, pose, search, weight)
        geometry = self._search.geometry
        stop = geometry.first_after(closest, forward if forward >= 0.0 else math.inf)
        start = geometry.first_before(closest, backward)
        poses = path.poses[start:stop]
        self.set_output("output_path", Path.model_construct(header=path.header, poses=poses))
        return SUCCESS
