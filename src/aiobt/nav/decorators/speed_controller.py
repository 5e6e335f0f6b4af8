"""SpeedController (Nav2): tick the child at a rate that grows with the robot's speed."""

from __future__ import annotations

from typing import Any

from aiobt.core.composite import DecoratorNode
from aiobt.core.ports import input_port
from aiobt.core.status import IDLE, RUNNING, Status
from aiobt.nav.conditions.goal_updated import GOAL_PORTS
from aiobt.nav.robot_state import ODOM, RobotStateNode


class SpeedController(RobotStateNode, DecoratorNode):
    """``<SpeedController min_rate="0.1" max_rate="1.0" min_speed="0.0"
    max_speed="0.5">child</SpeedController>`` (Nav2).

    - the first tick of an activation, and the tick after ``goal``/``goals``
      change (ports, else blackboard), tick the child at once;
    - then the child is ticked while RUNNING, or once its period has passed
      on the tree's clock; at that point the period is set from the robot's
      smoothed speed (odometry of the last 0.3 s): ``1/min_rate`` below
      ``min_speed``, ``1/max_rate`` above ``max_speed``, the rate scaled
      linearly in between;
    - otherwise it returns its own status (RUNNING).

    Rates must be > 0 (checked on the first tick).
    """

    READS = (ODOM,)
    PORTS = (
        input_port(
            "min_rate", float, 0.1, "The minimum rate at which child node can be ticked (hz)."
        ),
        input_port(
            "max_rate", float, 1.0, "The maximum rate at which child node can be ticked (hz)."
        ),
        input_port(
            "min_speed",
            float,
            0.0,
            "The minimum robot speed below which the child node is ticked at minimum rate (m/s).",
        ),
        input_port(
            "max_speed",
            float,
            0.5,
            "The maximum robot speed above which the child node is ticked at maximum rate (m/s).",
        ),
        *GOAL_PORTS,
    )

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._period = 1.0
        self._start = 0.0
        self._first = False
        self._goal: Any = None
        self._goals: Any = None
        if self.nav.bus is not None:
            self.robot.speed()  # the smoother averages odometry from now on

    def _restart(self, max_rate: float) -> None:
        self._period = 1.0 / max_rate
        self._start = self.clock.now()
        self._first = True

    def execute_sync(self) -> Status:
        rates = (self.get_input("min_rate"), self.get_input("max_rate"))
        if min(rates) <= 0.0:
            raise self.logic_error(f"rates must be > 0, got min_rate/max_rate {rates}")
        goal = self.get_input_or_blackboard("goal", None)
        goals = self.get_input_or_blackboard("goals", None)
        if self._status is IDLE or goal != self._goal or goals != self._goals:
            self._goal, self._goals = goal, goals
            self._restart(rates[1])
        self._set_status(RUNNING)
        elapsed = self.clock.now() - self._start
        child = self.child
        assert child is not None
        if not (self._first or child._status is RUNNING or elapsed >= self._period):
            return self._status
        self._first = False
        if elapsed >= self._period:
            self._period = 1.0 / self._rate(*rates)
            self._start = self.clock.now()
        status = self.tick_child()
        if status.is_completed:
            self.reset_child()  # finished: it starts afresh next time
        return status

    def _rate(self, min_rate: float, max_rate: float) -> float:
        speed = self.robot.speed() or 0.0
        min_speed: float = self.get_input("min_speed")
        max_speed: float = self.get_input("max_speed")
        if speed < min_speed or max_speed < min_speed:
            return min_rate
        if speed > max_speed:
            return max_rate
        if max_speed == min_speed:
            return max_rate
        return (speed - min_speed) / (max_speed - min_speed) * (max_rate - min_rate) + min_rate
