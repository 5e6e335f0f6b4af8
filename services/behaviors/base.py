"""What every behavior shares: inputs per cycle, outcomes, and the timed base.

Behaviors are pure state machines stepped once per cycle on the robot clock:
``step(inputs) -> BehaviorStep``. The service publishes the command, sends the
feedback and ends the goal when a step is terminal; nothing here does I/O.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass
from enum import Enum

from aiobt_services.controller.collision import CollisionChecker
from aiobt_services.controller.geometry import STOP, Pose2D, Velocity


class Outcome(Enum):
    """Failure classes; the service maps each to the action's Nav2 error code."""

    NONE = "NONE"
    UNKNOWN = "UNKNOWN"
    TIMEOUT = "TIMEOUT"
    TF_ERROR = "TF_ERROR"
    COLLISION_AHEAD = "COLLISION_AHEAD"
    INVALID_INPUT = "INVALID_INPUT"


class BehaviorInputError(ValueError):
    """A goal the behavior cannot run (NaN, negative duration, sign mismatch...)."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.outcome = Outcome.INVALID_INPUT
        self.message = message


@dataclass(slots=True, frozen=True)
class Inputs:
    """One cycle's view of the world: clock time, odometry pose and teleop input."""

    now: float
    pose: Pose2D | None = None
    pose_stamp: float = -math.inf
    teleop: Velocity | None = None
    teleop_stamp: float = -math.inf


@dataclass(slots=True, frozen=True)
class BehaviorStep:
    """``cmd`` None means "publish nothing" (Wait does not own the base)."""

    cmd: Velocity | None
    feedback: float
    done: bool = False
    outcome: Outcome = Outcome.NONE
    message: str = ""

    @property
    def succeeded(self) -> bool:
        return self.done and self.outcome is Outcome.NONE


@dataclass(slots=True)
class Safety:
    """Shared knobs: how far ahead to check, and when a pose is too old."""

    simulate_ahead_time: float = 2.0
    pose_timeout: float = 0.5
    initial_pose_wait: float = 1.0  # a goal may arrive before the first odometry does


def require_finite(name: str, value: float) -> float:
    if not math.isfinite(value):
        raise BehaviorInputError(f"{name} must be a finite number, got {value!r}")
    return value


def require_allowance(value: float) -> float:
    require_finite("time_allowance", value)
    if value < 0.0:
        raise BehaviorInputError(f"time_allowance must be >= 0 (0: no limit), got {value!r}")
    return value


class TimedBehavior(ABC):
    """Base of the moving behaviors: start time, time allowance, pose freshness.

    Subclasses implement :meth:`_cycle`, called with a fresh pose; a time
    allowance of 0 means no limit (Nav2's TimedBehavior).
    """

    __slots__ = ("_collision", "_started", "safety", "time_allowance")

    def __init__(
        self, time_allowance: float, collision: CollisionChecker | None, safety: Safety | None
    ) -> None:
        self.time_allowance = require_allowance(time_allowance)
        self._collision = collision
        self.safety = safety or Safety()
        self._started: float | None = None

    def elapsed(self, now: float) -> float:
        return 0.0 if self._started is None else now - self._started

    def step(self, inputs: Inputs) -> BehaviorStep:
        if self._started is None:
            self._started = inputs.now
        elapsed = inputs.now - self._started
        if self.time_allowance > 0.0 and elapsed > self.time_allowance:
            return self.fail(
                Outcome.TIMEOUT, f"exceeded time allowance of {self.time_allowance:.2f} s"
            )
        if inputs.pose is None and elapsed <= self.safety.initial_pose_wait:
            return BehaviorStep(STOP, self.progress())
        if inputs.pose is None or not inputs.pose.is_finite():
            return self.fail(
                Outcome.TF_ERROR,
                f"no valid robot pose (odometry) within {self.safety.initial_pose_wait:.1f} s",
            )
        age = inputs.now - inputs.pose_stamp
        if age > self.safety.pose_timeout:
            return self.fail(
                Outcome.TF_ERROR,
                f"robot pose is stale ({age:.2f} s old, pose_timeout "
                f"{self.safety.pose_timeout:.2f} s); stopping",
            )
        return self._cycle(inputs, inputs.pose)

    @abstractmethod
    def _cycle(self, inputs: Inputs, pose: Pose2D) -> BehaviorStep:
        """One control cycle with a fresh pose: the command and whether it is done."""

    def progress(self) -> float:
        """The feedback figure (distance, angle or time) so far."""
        return 0.0

    def fail(self, outcome: Outcome, message: str) -> BehaviorStep:
        return BehaviorStep(STOP, self.progress(), done=True, outcome=outcome, message=message)

    def collision(self) -> CollisionChecker | None:
        return self._collision
