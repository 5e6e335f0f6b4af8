"""What every behavior shares: inputs per cycle, outcomes, and the timed base.

Behaviors are pure state machines stepped once per cycle on the robot clock:
``step(inputs) -> BehaviorStep``. The service publishes the command, sends the
feedback and ends the goal when a step is terminal; nothing here does I/O.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections import deque
from dataclasses import dataclass
from enum import Enum

from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import STOP, Pose2D, Velocity
from aiobt.robot.freshness import FRESH, PoseAge
from aiobt.robot.latency import holding_time

MAX_LEAD = 2.0  # s: a longer command-to-motion delay is not compensated


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
    """One cycle's view of the world: clock time, odometry pose (and how fresh it is,
    :class:`~aiobt.robot.freshness.PoseAge`) and teleop input."""

    now: float
    pose: Pose2D | None = None
    pose_age: PoseAge = FRESH
    teleop: Velocity | None = None
    teleop_stamp: float = -math.inf
    lead: float = 0.0  # clock s from ``pose`` until a command sent now acts on the base


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
    """Shared knobs: how far ahead to check, when a pose is too old, the cycle period."""

    simulate_ahead_time: float = 2.0
    pose_timeout: float = 0.5
    initial_pose_wait: float = 1.0  # a goal may arrive before the first odometry does
    cycle_period: float = 0.05  # s between two steps (the service's rate)


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

    __slots__ = ("_collision", "_sent", "_started", "safety", "time_allowance")

    def __init__(
        self, time_allowance: float, collision: CollisionChecker | None, safety: Safety | None
    ) -> None:
        self.time_allowance = require_allowance(time_allowance)
        self._collision = collision
        self.safety = safety or Safety()
        self._started: float | None = None
        self._sent: deque[tuple[float, float]] = deque()

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
        stale = inputs.pose_age.stale("odom", self.safety.pose_timeout)
        if stale is not None:
            return self.fail(Outcome.TF_ERROR, stale)
        return self._cycle(inputs, inputs.pose)

    @abstractmethod
    def _cycle(self, inputs: Inputs, pose: Pose2D) -> BehaviorStep:
        """One control cycle with a fresh pose: the command and whether it is done."""

    def progress(self) -> float:
        """The feedback figure (distance, angle or time) so far."""
        return 0.0

    def sent(self, now: float, speed: float) -> None:
        """Record the speed (m/s or rad/s) commanded at ``now``, for :meth:`in_flight`."""
        history = self._sent
        history.append((now, abs(speed)))
        while len(history) > 1 and history[1][0] <= now - MAX_LEAD:
            history.popleft()

    def in_flight(self, now: float, lead: float) -> float:
        """Travel (m or rad) still to come from commands already sent: the base acts on
        each ``lead`` s late, so it still runs through the commands of the last ``lead`` s."""
        start, end, total = now - min(lead, MAX_LEAD), now, 0.0
        for stamp, speed in reversed(self._sent):
            total += speed * max(0.0, end - max(stamp, start))
            end = stamp
            if stamp <= start:
                break
        return total

    @staticmethod
    def approach_limit(remaining: float, lead: float, approach_error: float) -> float:
        """The highest speed at ``remaining`` (what is left once the commands in flight
        have acted) such that a stall of this loop carries the base at most
        ``approach_error`` past the target (see :func:`holding_time`)."""
        holding = holding_time(lead)
        return math.inf if holding <= 0.0 else (max(0.0, remaining) + approach_error) / holding

    def stop_ahead(self, now: float, lead: float, speed: float) -> float:
        """Travel before a stop sent now acts (:meth:`in_flight`) plus half a cycle at
        ``speed``: stopping once the rest of the way is within this keeps the error
        within half a cycle's travel, whatever the loop's delay."""
        return self.in_flight(now, lead) + 0.5 * abs(speed) * self.safety.cycle_period

    def fail(self, outcome: Outcome, message: str) -> BehaviorStep:
        return BehaviorStep(STOP, self.progress(), done=True, outcome=outcome, message=message)

    def collision(self) -> CollisionChecker | None:
        return self._collision
