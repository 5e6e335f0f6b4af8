"""DriveOnHeading and BackUp: drive straight a distance at a speed, odometry-accounted."""

from __future__ import annotations

import math
from dataclasses import dataclass

from aiobt_services.controller.collision import CollisionChecker
from aiobt_services.controller.geometry import STOP, Pose2D, Velocity
from aiobt_services.controller.latency import holding_time

from .base import (
    BehaviorInputError,
    BehaviorStep,
    Inputs,
    Outcome,
    Safety,
    TimedBehavior,
    require_finite,
)


@dataclass(slots=True, frozen=True)
class DriveParams:
    """Nav2's behavior-server parameters of drive_on_heading and backup (its defaults)."""

    acceleration_limit: float = 2.5  # m/s^2
    deceleration_limit: float = 2.5  # m/s^2 (Nav2 writes it negative: -2.5)
    minimum_speed: float = 0.10  # m/s: slower commands are raised to this
    approach_error: float = 0.01  # m: a stall's overshoot bound (not Nav2's; see approach_limit)


class DriveOnHeading(TimedBehavior):
    """Drives ``distance`` m along the current heading at ``speed`` m/s (Nav2's rules).

    ``distance`` and ``speed`` must have the same sign (both negative: backwards).
    The distance travelled is the straight-line distance from the pose at the
    first cycle. The speed ramps within the acceleration limits, slows so that
    it can stop at the end (``sqrt(2 a d)``) and is never below
    ``minimum_speed``; under a sim speed-up (a long ``lead``) the approach is
    slowed so that a stall of the loop cannot carry the base past the distance.
    The stop is sent where the base, still moving for the loop's ``lead``, ends
    at the distance. Each cycle the rest of the way (at most
    ``simulate_ahead_time`` plus the holding time at the speed) is checked;
    a collision fails the goal with COLLISION_AHEAD before the robot gets there.
    """

    __slots__ = ("_last", "_start", "_traveled", "distance", "params", "speed")

    def __init__(
        self,
        distance: float,
        speed: float,
        time_allowance: float = 10.0,
        collision: CollisionChecker | None = None,
        safety: Safety | None = None,
        params: DriveParams | None = None,
    ) -> None:
        super().__init__(time_allowance, collision, safety)
        self.distance = require_finite("distance", distance)
        self.speed = require_finite("speed", speed)
        if speed == 0.0:
            raise BehaviorInputError("speed must not be 0")
        if (distance > 0.0) != (speed > 0.0):
            raise BehaviorInputError(
                f"speed ({speed}) and distance ({distance}) must have the same sign "
                "(both negative to drive backwards)"
            )
        self.params = params or DriveParams()
        self._start: Pose2D | None = None
        self._traveled = 0.0
        self._last = 0.0

    def progress(self) -> float:
        return self._traveled

    def _cycle(self, inputs: Inputs, pose: Pose2D) -> BehaviorStep:
        if self._start is None:
            self._start = pose
        self._traveled = pose.distance_to(self._start)
        remaining = abs(self.distance) - self._traveled
        coming = self.in_flight(inputs.now, inputs.lead)
        if remaining <= self.stop_ahead(inputs.now, inputs.lead, self._last):
            self._last = 0.0
            return BehaviorStep(STOP, self._traveled, done=True)
        cmd = Velocity(self._next_speed(max(0.0, remaining - coming), inputs.lead), 0.0)
        checker = self.collision()
        if checker is not None:
            horizon = self.safety.simulate_ahead_time + holding_time(inputs.lead)
            check = checker.check_arc(pose, cmd, horizon, remaining)
            if check.collides:
                away = abs(cmd.v) * check.time_to_collision
                return self.fail(
                    Outcome.COLLISION_AHEAD,
                    f"collision ahead: obstacle {away:.2f} m away along the drive",
                )
        self._last = cmd.v
        self.sent(inputs.now, cmd.v)
        return BehaviorStep(cmd, self._traveled)

    def _next_speed(self, remaining: float, lead: float) -> float:
        """Nav2's: the speed (raised to ``minimum_speed``) within the acceleration limits,
        then slowed to ``sqrt(2 a d)`` to stop at the end, no lower than ``minimum_speed``;
        last, at most the approach limit (see :meth:`TimedBehavior.approach_limit`)."""
        p, period = self.params, self.safety.cycle_period
        current = abs(self._last)
        raised = max(abs(self.speed), p.minimum_speed)
        ramped = min(
            max(raised, current - p.deceleration_limit * period),
            current + p.acceleration_limit * period,
        )
        stopping = math.sqrt(2.0 * p.deceleration_limit * remaining)
        limit = self.approach_limit(remaining, lead, p.approach_error)
        return math.copysign(min(max(min(ramped, stopping), p.minimum_speed), limit), self.speed)


def back_up(
    distance: float,
    speed: float,
    time_allowance: float = 10.0,
    collision: CollisionChecker | None = None,
    safety: Safety | None = None,
) -> DriveOnHeading:
    """Nav2's BackUp: drive backwards ``|distance|`` at ``|speed|`` whatever their signs."""
    require_finite("distance", distance)
    require_finite("speed", speed)
    return DriveOnHeading(-abs(distance), -abs(speed), time_allowance, collision, safety)


__all__ = ["DriveOnHeading", "DriveParams", "back_up"]
