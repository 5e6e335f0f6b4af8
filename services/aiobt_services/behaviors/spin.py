"""Spin: rotate in place by a signed angle, counting the turn across the wrap."""

from __future__ import annotations

import math
from dataclasses import dataclass

from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import STOP, Pose2D, Velocity, wrap_angle

from .base import BehaviorStep, Inputs, Outcome, Safety, TimedBehavior, require_finite

STILL = 1e-3  # rad per cycle: below this the base has stopped turning


@dataclass(slots=True)
class SpinParams:
    max_rotational_vel: float = 1.0
    min_rotational_vel: float = 0.4
    rotational_acc_lim: float = 3.2
    angle_tolerance: float = 0.02
    settle_tolerance: float = 0.03  # rad: once stopped, farther off than this turns again
    approach_error: float = 0.025  # rad: a stall's overshoot bound (not Nav2's; approach_limit)


class SpinBehavior(TimedBehavior):
    """Turns ``target_yaw`` radians (sign = direction; more than a turn is allowed).

    The angle turned is accumulated from wrapped yaw differences, so crossing
    +-pi or turning more than 2 pi is counted correctly. Speed follows
    ``sqrt(2 a remaining)`` clamped to [min, max] (and, under a sim speed-up,
    slowed so that a stall of the loop cannot carry it past the target); the stop is sent where the
    base, still turning for the loop's ``lead``, ends at the
    target. Once stopped (the yaw still for a cycle, or the ``lead`` if longer: a
    pose not yet updated is not a stop), it is done within ``settle_tolerance``;
    farther off (a stall, a late stop) it turns on or back. Fails COLLISION_AHEAD when
    the robot's cell is in collision (a circular robot sweeps nothing new).
    """

    __slots__ = ("_last_w", "_last_yaw", "_settling", "_turned", "params", "target_yaw")

    def __init__(
        self,
        target_yaw: float,
        time_allowance: float = 10.0,
        collision: CollisionChecker | None = None,
        params: SpinParams | None = None,
        safety: Safety | None = None,
    ) -> None:
        super().__init__(time_allowance, collision, safety)
        self.target_yaw = require_finite("target_yaw", target_yaw)
        self.params = params or SpinParams()
        self._turned = 0.0
        self._last_yaw: float | None = None
        self._last_w = 0.0
        self._settling: float | None = None  # clock time the base was last seen turning

    def progress(self) -> float:
        return abs(self._turned)

    def _cycle(self, inputs: Inputs, pose: Pose2D) -> BehaviorStep:
        delta = 0.0
        if self._last_yaw is not None:
            delta = wrap_angle(pose.yaw - self._last_yaw)
            self._turned += delta
        self._last_yaw = pose.yaw
        direction = math.copysign(1.0, self.target_yaw)
        p = self.params
        remaining = abs(self.target_yaw) - self._turned * direction  # < 0: past the target
        if self._settling is not None:
            if abs(delta) > STILL:
                self._settling = inputs.now  # still turning after the stop
            if inputs.now - self._settling < max(self.safety.cycle_period, inputs.lead):
                return BehaviorStep(STOP, self.progress())
            if abs(remaining) <= p.settle_tolerance:
                return BehaviorStep(STOP, self.progress(), done=True)
            self._settling = None  # a stall or a late stop left it off: turn on or back
        sense = math.copysign(1.0, remaining) * direction
        ahead = self.stop_ahead(inputs.now, inputs.lead, self._last_w)
        crossed = self._last_w != 0.0 and sense != math.copysign(1.0, self._last_w)
        if abs(remaining) <= max(ahead, p.angle_tolerance) or crossed:
            self._settling = inputs.now
            self._last_w = 0.0
            self.sent(inputs.now, 0.0)
            return BehaviorStep(STOP, self.progress())
        checker = self.collision()
        if checker is not None and checker.pose_collides(pose):
            return self.fail(
                Outcome.COLLISION_AHEAD, "collision ahead: the robot is in collision while spinning"
            )
        coming = max(0.0, abs(remaining) - self.in_flight(inputs.now, inputs.lead))
        speed = min(
            max(math.sqrt(2.0 * p.rotational_acc_lim * coming), p.min_rotational_vel),
            p.max_rotational_vel,
            self.approach_limit(coming, inputs.lead, p.approach_error),
        )
        self._last_w = sense * speed
        self.sent(inputs.now, speed)
        return BehaviorStep(Velocity(0.0, self._last_w), self.progress())
