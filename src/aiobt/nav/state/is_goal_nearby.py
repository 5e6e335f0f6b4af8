"""IsGoalNearby (Nav2): is the rest of the path shorter than a threshold?"""

from __future__ import annotations

import logging
import math
from typing import Any

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.msgs import Path
from aiobt.nav.path_math import ClosestPoseSearch
from aiobt.nav.robot_state import RobotStateNode

log = logging.getLogger("aiobt.nav.is_goal_nearby")


class IsGoalNearby(RobotStateNode, ConditionNode):
    """``<IsGoalNearby path="{path}" proximity_threshold="1.0"/>`` (Nav2).

    - SUCCESS when the path's length from the pose closest to the robot to its
      end is below ``proximity_threshold``;
    - FAILURE otherwise, and when the path is empty or there is no robot pose.

    ``max_robot_pose_search_dist`` >= 0 bounds the search for the closest pose
    to that many metres on from the previous one while the path stays the same
    (for paths that loop or cross themselves).
    """

    PORTS = (
        input_port("path", Path, description="The planned path to evaluate."),
        input_port(
            "proximity_threshold",
            float,
            1.0,
            'The remaining path length (m) considered as "nearby".',
        ),
        input_port(
            "max_robot_pose_search_dist",
            float,
            -1.0,
            "Maximum forward integrated distance along the path (from the last detected pose) "
            "searched for the pose closest to the robot; negative searches the whole path.",
        ),
        input_port("global_frame", str, description="The global reference frame."),
        input_port("robot_base_frame", str, description="Robot base frame."),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._search = ClosestPoseSearch()
        self._empty_reported = False

    def check(self) -> bool:
        path: Path = self.get_input("path")
        threshold: float = self.get_input("proximity_threshold")
        search: float = self.get_input("max_robot_pose_search_dist")
        if not path.poses:
            if not self._empty_reported:
                self._empty_reported = True
                # every navigation starts so (no plan yet): not worth a warning
                log.debug("%s: the path is empty", self.path)
            return False
        self._empty_reported = False
        robot = self.robot_pose(path.header.frame_id)
        if robot is None:
            return False
        closest = self._search.closest(path, robot, search if search >= 0.0 else math.inf)
        return self._search.geometry.length(closest) < threshold
