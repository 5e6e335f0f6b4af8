"""DistanceController (Nav2): tick the child each time the robot has moved a distance."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, IDLE, RUNNING, SKIPPED, SUCCESS, Status
from aiobt.msgs import PoseStamped
from aiobt.nav.path_math import distance
from aiobt.nav.robot_state import RobotStateNode
from aiobt.nav.state.distance_traveled import FRAME_PORTS


class DistanceController(RobotStateNode, DecoratorNode):
    """``<DistanceController distance="1.0">child</DistanceController>`` (Nav2).

    - ticked while IDLE: remembers the robot pose and ticks the child;
    - then ticks the child while it is RUNNING, or when the robot is
      ``distance`` metres (straight line) from the remembered pose; a child
      SUCCESS remembers the current pose and returns SUCCESS, a FAILURE
      returns FAILURE;
    - otherwise returns its own status (RUNNING);
    - FAILURE without a robot pose.
    """

    PORTS = (
        input_port(
            "distance",
            float,
            1.0,
            "The distance travelled to trigger an action such as planning a path (m).",
        ),
        *FRAME_PORTS,
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._start: PoseStamped | None = None
        self._first = False

    def execute_sync(self) -> Status:
        frame: str = self.get_input("global_frame", "")
        if self._status is IDLE:
            self._start = self.robot_pose(frame)
            if self._start is None:
                return FAILURE
            self._first = True
        self._set_status(RUNNING)
        current = self.robot_pose(frame)
        if current is None or self._start is None:
            return FAILURE
        child = self.child
        assert child is not None
        travelled = distance(self._start, current)
        if not (self._first or child._status is RUNNING or travelled >= self.get_input("distance")):
            return self._status
        self._first = False
        status = self.tick_child()
        if status is RUNNING or status is SKIPPED:
            return status
        self.reset_child()  # finished: it starts afresh next time
        if status is SUCCESS:
            self._start = current
            return SUCCESS
        return FAILURE
