"""CheckStopStatus (Nav2): has the robot stood still long enough?"""

from __future__ import annotations

import logging
from typing import Any

from aiobt.core.convert import Milliseconds
from aiobt.core.leaves import SyncLeaf
from aiobt.core.ports import input_port
from aiobt.core.status import FAILURE, RUNNING, SUCCESS, Status
from aiobt.nav.robot_state import ODOM, RobotStateNode

log = logging.getLogger("aiobt.nav.check_stop_status")


class CheckStopStatus(RobotStateNode, SyncLeaf):
    """``<CheckStopStatus velocity_threshold="0.01" duration_stopped="1000"/>`` (Nav2).

    - FAILURE while the last odometry's linear x, y or angular z speed reaches
      ``velocity_threshold`` (and before any odometry);
    - RUNNING while below it for less than ``duration_stopped`` ms of the
      tree's clock, then SUCCESS (the count starts over).

    Evaluated on every tick, whatever its last status (as Nav2's).
    """

    READS = (ODOM,)
    PORTS = (
        input_port(
            "velocity_threshold",
            float,
            0.01,
            "Velocity threshold below which robot is considered stopped.",
        ),
        input_port(
            "duration_stopped",
            Milliseconds,
            Milliseconds(1000),
            "Duration (ms) the velocity must remain below the threshold.",
        ),
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._stopped_since: float | None = None

    def on_halt_sync(self) -> None:
        self._stopped_since = None

    def execute_sync(self) -> Status:
        odom = self.robot.odometry
        threshold: float = self.get_input("velocity_threshold")
        twist = odom.twist if odom is not None else None
        if (
            twist is None
            or max(abs(twist.linear.x), abs(twist.linear.y), abs(twist.angular.z)) >= threshold
        ):
            self._stopped_since = None
            return FAILURE
        now = self.clock.now()
        if self._stopped_since is None:
            self._stopped_since = now
        if now - self._stopped_since > self.get_input("duration_stopped") / 1000.0:
            self._stopped_since = None
            return SUCCESS
        return RUNNING
