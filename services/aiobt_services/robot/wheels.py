"""The base's two wheel motors as a real base's driver reports them on ``joint_states``
(``sensor_msgs/JointState``, the TurtleBot names): each wheel's angle, turn rate and
effort. What Nav2's docking plugins read for stall detection (``use_stall_detection``):
pressed against the dock (or anything) the wheels stop while their motors push.

The turn rates are the wheels' as they rolled the body (:class:`~.sim.Simulation`'s
wheel motion: the command, or, against an obstacle, what the body achieved). The effort
is a speed loop's: ``torque_gain`` N m per rad/s the wheel falls short of its command,
plus rolling ``friction``, within the motor's ``stall_torque``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from aiobt.msgs.geometry import Header
from aiobt.msgs.joint_state import JointState


@dataclass(slots=True, frozen=True)
class WheelMotors:
    names: tuple[str, str] = ("wheel_left_joint", "wheel_right_joint")
    wheel_radius: float = 0.05  # m
    separation: float = 0.36  # m between the wheels' contact points
    torque_gain: float = 1.0  # N m per rad/s of shortfall
    stall_torque: float = 5.0  # N m, the most a motor gives
    friction: float = 0.2  # N m while rolling

    def rates(self, linear: float, angular: float) -> tuple[float, float]:
        """Left and right wheel turn rates (rad/s) for a body's motion."""
        half = 0.5 * self.separation * angular
        return (linear - half) / self.wheel_radius, (linear + half) / self.wheel_radius

    def effort(self, commanded: float, turning: float) -> float:
        push = self.torque_gain * (commanded - turning)
        push += math.copysign(self.friction, turning) if turning else 0.0
        return max(-self.stall_torque, min(self.stall_torque, push))


@dataclass(slots=True)
class WheelJoints:
    """Updated each physics step (cheaply: the body's motion asked and rolled, and the
    distance rolled); :meth:`state` is the ``joint_states`` message."""

    motors: WheelMotors = field(default_factory=WheelMotors)
    asked: tuple[float, float] = (0.0, 0.0)  # the body's (linear, angular) commanded
    rolled: tuple[float, float] = (0.0, 0.0)  # and achieved
    travel: list[float] = field(default_factory=lambda: [0.0, 0.0])  # m, rad rolled

    def update(self, commanded: tuple[float, float], rolled: tuple[float, float],
               dt: float) -> None:  # fmt: skip
        """``commanded`` and ``rolled``: the body's (linear, angular) asked and achieved."""
        self.asked, self.rolled = commanded, rolled
        self.travel[0] += rolled[0] * dt
        self.travel[1] += rolled[1] * dt

    def state(self, stamp: float) -> JointState:
        m = self.motors
        asked, turning = m.rates(*self.asked), m.rates(*self.rolled)
        return JointState.model_construct(
            header=Header.model_construct(stamp=stamp, frame_id="base_link"),
            name=list(m.names),
            position=list(m.rates(*self.travel)),  # the angles: the rates of the distance
            velocity=list(turning),
            effort=[m.effort(asked[i], turning[i]) for i in range(2)],
        )
