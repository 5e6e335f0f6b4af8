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
    """Updated each physics step; :meth:`state` is the ``joint_states`` message."""

    motors: WheelMotors = field(default_factory=WheelMotors)
    positions: list[float] = field(default_factory=lambda: [0.0, 0.0])
    velocities: list[float] = field(default_factory=lambda: [0.0, 0.0])
    efforts: list[float] = field(default_factory=lambda: [0.0, 0.0])

    def update(self, commanded: tuple[float, float], rolled: tuple[float, float],
               dt: float) -> None:  # fmt: skip
        """``commanded`` and ``rolled``: the body's (linear, angular) asked and achieved."""
        asked, turned = self.motors.rates(*commanded), self.motors.rates(*rolled)
        for i in range(2):
            self.positions[i] += turned[i] * dt
            self.velocities[i] = turned[i]
            self.efforts[i] = self.motors.effort(asked[i], turned[i])

    def state(self, stamp: float) -> JointState:
        return JointState.model_validate({
            "header": {"stamp": stamp, "frame_id": "base_link"},
            "name": list(self.motors.names), "position": list(self.positions),
            "velocity": list(self.velocities), "effort": list(self.efforts),
        })  # fmt: skip
