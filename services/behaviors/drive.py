"""DriveOnHeading and BackUp: drive straight a distance at a speed, odometry-accounted."""

from __future__ import annotations

from aiobt_services.controller.collision import CollisionChecker
from aiobt_services.controller.geometry import STOP, Pose2D, Velocity

from .base import (
    BehaviorInputError,
    BehaviorStep,
    Inputs,
    Outcome,
    Safety,
    TimedBehavior,
    require_finite,
)


class DriveOnHeading(TimedBehavior):
    """Drives ``distance`` m along the current heading at ``speed`` m/s (signs must agree).

    The distance travelled is the straight-line distance from the pose at the
    first cycle (Nav2's accounting). Before each cycle the rest of the way (at
    most ``simulate_ahead_time`` at ``speed``) is checked; a collision fails the
    goal with COLLISION_AHEAD before the robot gets there.
    """

    __slots__ = ("_start", "_traveled", "distance", "speed")

    def __init__(
        self,
        distance: float,
        speed: float,
        time_allowance: float = 10.0,
        collision: CollisionChecker | None = None,
        safety: Safety | None = None,
    ) -> None:
        super().__init__(time_allowance, collision, safety)
        self.distance = require_finite("distance", distance)
        self.speed = require_finite("speed", speed)
        if speed == 0.0:
            raise BehaviorInputError("speed must not be 0")
        if distance * speed < 0.0:
            raise BehaviorInputError(
                f"speed ({speed}) and distance ({distance}) must have the same sign"
            )
        self._start: Pose2D | None = None
        self._traveled = 0.0

    def progress(self) -> float:
        return self._traveled

    def _cycle(self, inputs: Inputs, pose: Pose2D) -> BehaviorStep:
        if self._start is None:
            self._start = pose
        self._traveled = pose.distance_to(self._start)
        remaining = abs(self.distance) - self._traveled
        if remaining <= 0.0:
            return BehaviorStep(STOP, self._traveled, done=True)
        cmd = Velocity(self.speed, 0.0)
        checker = self.collision()
        if checker is not None:
            check = checker.check_arc(pose, cmd, self.safety.simulate_ahead_time, remaining)
            if check.collides:
                ahead = abs(self.speed) * check.time_to_collision
                return self.fail(
                    Outcome.COLLISION_AHEAD,
                    f"collision ahead: obstacle {ahead:.2f} m away along the drive",
                )
        return BehaviorStep(cmd, self._traveled)


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


__all__ = ["DriveOnHeading", "back_up"]
