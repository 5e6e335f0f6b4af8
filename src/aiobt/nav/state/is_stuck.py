"""IsStuck (Nav2): did the robot brake harder than it can (it hit something)?"""

from __future__ import annotations

from typing import Any

from aiobt.core.leaves import ConditionNode
from aiobt.nav.robot_state import ODOM, RobotStateNode


class IsStuck(RobotStateNode, ConditionNode):
    """``<IsStuck/>`` (Nav2).

    SUCCESS while the deceleration between the last two ``{ns}/odom``
    messages exceeds 10 m/s^2 (Nav2's brake limit); FAILURE otherwise and
    before any odometry.
    """

    READS = (ODOM,)
    PORTS = ()

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        if self.nav.bus is not None:
            self.robot.brake()  # the odometry it reads is kept from now (READS)

    def check(self) -> bool:
        return self.robot.brake().stuck
