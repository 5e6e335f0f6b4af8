"""The differential-drive command path: clamping, acceleration limits, timeout.

Pure logic, no physics: :class:`DriveController` turns the latest velocity
command into the base velocity for the next physics step.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass

log = logging.getLogger("aiobt_services.robot.drive")


@dataclass(slots=True, frozen=True)
class DriveLimits:
    """Velocity and acceleration limits of the base, and the command timeout."""

    max_linear: float = 1.0  # m/s, forwards and backwards
    max_angular: float = 2.0  # rad/s
    max_linear_accel: float = 2.5  # m/s^2
    max_angular_accel: float = 6.0  # rad/s^2
    cmd_timeout: float = 0.5  # s of sim time without a command -> stop

    def __post_init__(self) -> None:
        for name in ("max_linear", "max_angular", "max_linear_accel", "max_angular_accel"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"DriveLimits.{name} must be a finite number > 0, got {value}")
        if not (math.isfinite(self.cmd_timeout) and self.cmd_timeout > 0.0):
            raise ValueError(f"DriveLimits.cmd_timeout must be > 0, got {self.cmd_timeout}")


@dataclass(slots=True, frozen=True)
class CommandVerdict:
    """What became of one velocity command."""

    accepted: bool
    linear: float = 0.0
    angular: float = 0.0
    clamped: bool = False
    reason: str = ""


def _approach(current: float, target: float, max_delta: float) -> float:
    return current + max(-max_delta, min(max_delta, target - current))


class DriveController:
    """Holds the commanded and the current base velocity (body frame)."""

    __slots__ = ("_cmd", "_cmd_time", "_interval", "_timed_out", "angular", "limits", "linear")

    def __init__(self, limits: DriveLimits | None = None) -> None:
        self.limits = limits or DriveLimits()
        self.linear = 0.0
        self.angular = 0.0
        self._cmd = (0.0, 0.0)
        self._cmd_time = -math.inf
        self._timed_out = True
        self._interval: float | None = None  # smoothed time between commands of a stream

    def command(self, linear: float, angular: float, now: float) -> CommandVerdict:
        """Take a command at sim time ``now``: NaN/inf dropped, excess clamped."""
        if not (math.isfinite(linear) and math.isfinite(angular)):
            reason = f"non-finite velocity command (linear={linear}, angular={angular})"
            return CommandVerdict(accepted=False, reason=reason)
        lim = self.limits
        lin = max(-lim.max_linear, min(lim.max_linear, linear))
        ang = max(-lim.max_angular, min(lim.max_angular, angular))
        clamped = (lin, ang) != (linear, angular)
        self._cmd = (lin, ang)
        gap = now - self._cmd_time
        if 0.0 < gap <= lim.cmd_timeout:  # a stream: learn its period
            self._interval = gap if self._interval is None else 0.8 * self._interval + 0.2 * gap
        elif gap > lim.cmd_timeout:
            self._interval = None
        self._cmd_time = now
        self._timed_out = False
        reason = "clamped to the base limits" if clamped else ""
        return CommandVerdict(True, lin, ang, clamped, reason)

    @property
    def command_time(self) -> float:
        """Sim time of the latest command taken (-inf before the first)."""
        return self._cmd_time

    def overdue(self, now: float, patience: float = 0.0) -> bool:
        """Is a stream driving the base late with its next command? True while the last
        command moves the base, the stream's next one is more than two of its periods
        late (at least 0.05 s, and at least ``patience`` s) and the command timeout has
        not yet run out."""
        if self._interval is None or self._cmd == (0.0, 0.0):
            return False
        age = now - self._cmd_time
        return max(2.0 * self._interval, 0.05, patience) < age <= self.limits.cmd_timeout

    def stop(self) -> None:
        """Forget the command and the current velocity at once (teleport, reset)."""
        self._cmd = (0.0, 0.0)
        self.linear = self.angular = 0.0

    def update(self, now: float, dt: float) -> tuple[float, float]:
        """Velocity to apply for the step of length ``dt`` ending after ``now``."""
        target_lin, target_ang = self._cmd
        if now - self._cmd_time > self.limits.cmd_timeout:
            if not self._timed_out and (target_lin or target_ang):
                log.info("no velocity command for %.2f s: stopping", self.limits.cmd_timeout)
            self._timed_out = True
            target_lin = target_ang = 0.0
        lim = self.limits
        self.linear = _approach(self.linear, target_lin, lim.max_linear_accel * dt)
        self.angular = _approach(self.angular, target_ang, lim.max_angular_accel * dt)
        return self.linear, self.angular
