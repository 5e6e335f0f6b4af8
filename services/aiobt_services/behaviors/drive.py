"""DriveOnHeading and BackUp: drive straight a distance at a speed, odometry-accounted."""

from __future__ import annotations

import math
from dataclasses import dataclass

from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import STOP, Pose2D, Velocity
from aiobt.robot.latency import holding_time

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
    settle_tolerance: float = 0.01  # m: once stopped, farther off than this drives on or back


STILL = 5e-4  # m: the base moved less than this since the last cycle


class DriveOnHeading(TimedBehavior):
    """Drives ``distance`` m along the current heading at ``speed`` m/s (Nav2's rules).

    ``distance`` and ``speed`` must have the same sign (both negative: backwards).
    The distance travelled is the straight-line distance from the pose at the
    first cycle. The speed ramps within the acceleration limits, slows so that
    it can stop at the end (``sqrt(2 a d)``) and is never below
    ``minimum_speed``; under a sim speed-up (a long ``lead``) the approach is
    slowed so that a stall of the loop cannot carry the base past the distance.
    The stop is sent where the base, still moving for the loop's ``lead``, ends
    at the distance. Once the base has stood still for a cycle (or the ``lead``,
    if longer) it is done within ``settle_tolerance`` of the distance along the
    heading; farther off (a stall or a stop delayed beyond the lead, as under a
    loaded sim speed-up) it drives on or back, slowly. Each cycle the rest of the way (at most
    ``simulate_ahead_time`` plus the holding time at the speed) is checked;
    a collision fails the goal with COLLISION_AHEAD before the robot gets there.
    """

    __slots__ = ("_along", "_last", "_settling", "_start", "_traveled", "distance", "params",
                 "speed")  # fmt: skip

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
        self._along = 0.0  # signed travel along the start heading, in the drive's sense
        self._last = 0.0
        self._settling: float | None = None  # clock time the base was last seen moving

    def progress(self) -> float:
        return self._traveled

    def _cycle(self, inputs: Inputs, pose: Pose2D) -> BehaviorStep:
        if self._start is None:
            self._start = pose
        self._traveled = pose.distance_to(self._start)
        along, self._along = self._along, self._progress_along(pose)
        remaining = abs(self.distance) - self._along  # < 0: past the distance
        if self._settling is not None:
            if abs(self._along - along) > STILL:
                self._settling = inputs.now  # still moving after the stop
            if inputs.now - self._settling < max(self.safety.cycle_period, inputs.lead):
                return BehaviorStep(STOP, self._traveled)
            if abs(remaining) <= self.params.settle_tolerance:
                return BehaviorStep(STOP, self._traveled, done=True)
            self._settling = None  # a stall or a late stop left it off: drive on or back
        sense = math.copysign(1.0, remaining) * math.copysign(1.0, self.speed)
        crossed = self._last != 0.0 and sense != math.copysign(1.0, self._last)
        if abs(remaining) <= self.stop_ahead(inputs.now, inputs.lead, self._last) or crossed:
            self._settling = inputs.now
            self._last = 0.0
            self.sent(inputs.now, 0.0)
            return BehaviorStep(STOP, self._traveled)
        coming = self.in_flight(inputs.now, inputs.lead)
        speed = self._next_speed(max(0.0, abs(remaining) - coming), inputs.lead)
        cmd = Velocity(sense * speed, 0.0)
        checker = self.collision()
        if checker is not None:
            horizon = self.safety.simulate_ahead_time + holding_time(inputs.lead)
            check = checker.check_arc(pose, cmd, horizon, abs(remaining))
            if check.collides:
                away = speed * check.time_to_collision
                return self.fail(
                    Outcome.COLLISION_AHEAD,
                    f"collision ahead: obstacle {away:.2f} m away along the drive",
                )
        self._last = cmd.v
        self.sent(inputs.now, cmd.v)
        return BehaviorStep(cmd, self._traveled)

    def _progress_along(self, pose: Pose2D) -> float:
        """Travel from the start along its heading, positive in the drive's direction."""
        start = self._start
        assert start is not None
        ahead = (pose.x - start.x) * math.cos(start.yaw) + (pose.y - start.y) * math.sin(start.yaw)
        return math.copysign(1.0, self.speed) * ahead

    def _next_speed(self, remaining: float, lead: float) -> float:
        """Nav2's: the speed (raised to ``minimum_speed``) within the acceleration limits,
        then slowed to ``sqrt(2 a d)`` to stop at the end, no lower than ``minimum_speed``;
        last, at most the approach limit (see :meth:`TimedBehavior.approach_limit`).
        A magnitude: the caller gives it the sense (on, or back after an overshoot)."""
        p, period = self.params, self.safety.cycle_period
        current = abs(self._last)
        raised = max(abs(self.speed), p.minimum_speed)
        ramped = min(
            max(raised, current - p.deceleration_limit * period),
            current + p.acceleration_limit * period,
        )
        stopping = math.sqrt(2.0 * p.deceleration_limit * remaining)
        limit = self.approach_limit(remaining, lead, p.approach_error)
        return min(max(min(ramped, stopping), p.minimum_speed), limit)


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
