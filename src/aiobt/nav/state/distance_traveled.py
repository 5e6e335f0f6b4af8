"""DistanceTraveled (Nav2): has the robot moved a given distance?"""

from __future__ import annotations

from typing import Any

from aiobt.core.leaves import ConditionNode
from aiobt.core.ports import input_port
from aiobt.core.status import IDLE
from aiobt.msgs import PoseStamped
from aiobt.nav.path_math import distance
from aiobt.nav.robot_state import RobotStateNode

FRAME_PORTS = (
    input_port("global_frame", str, description="Reference frame (default: map)."),
    input_port("robot_base_frame", str, description="Robot base frame."),
)


class DistanceTraveled(RobotStateNode, ConditionNode):
    """``<DistanceTraveled distance="1.0"/>`` (Nav2).

    - ticked while IDLE: remembers the robot pose, FAILURE;
    - then FAILURE until the robot is ``distance`` metres (straight line) from
      that pose, then SUCCESS and the current pose is remembered instead;
    - FAILURE without a robot pose.
    """

    PORTS = (
        input_port(
            "distance",
            float,
            1.0,
            "The distance that must travel before returning success (m).",
        ),
        *FRAME_PORTS,
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._start: PoseStamped | None = None

    def check(self) -> bool:
        frame: str = self.get_input("global_frame", "")
        current = self.robot_pose(frame)
        if self._status is IDLE or self._start is None:
            self._start = current
            return False
        if current is None or distance(self._start, current) < self.get_input("distance"):
            return False
        self._start = current
        return True
