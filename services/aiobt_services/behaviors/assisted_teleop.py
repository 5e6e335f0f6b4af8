"""AssistedTeleop: pass teleop twists through, slowed down before obstacles."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import STOP, Pose2D, Velocity, integrate_arc

from .base import BehaviorStep, Inputs, Safety, TimedBehavior


@dataclass(slots=True)
class TeleopParams:
    projection_time: float = 0.1
    teleop_timeout: float = 0.5


class AssistedTeleop(TimedBehavior):
    """Filters each teleop twist through a forward projection on the costmap.

    The twist is projected in ``projection_time`` steps up to
    ``simulate_ahead_time``; if the k-th projected pose collides, the twist is
    scaled by ``(k - 1) / steps`` so the robot stops short of the obstacle (0 if
    the very first step collides). A teleop input older than ``teleop_timeout``
    gives a zero twist. Ends by cancellation, :meth:`finish` (Nav2's
    preempt_teleop) or the time allowance (TIMEOUT; 0 means no limit).
    """

    __slots__ = ("_finished", "params")

    def __init__(
        self,
        time_allowance: float = 10.0,
        collision: CollisionChecker | None = None,
        params: TeleopParams | None = None,
        safety: Safety | None = None,
    ) -> None:
        super().__init__(time_allowance, collision, safety)
        self.params = params or TeleopParams()
        self._finished = False

    def finish(self) -> None:
        """End the behavior successfully at the next cycle."""
        self._finished = True

    def _cycle(self, inputs: Inputs, pose: Pose2D) -> BehaviorStep:
        elapsed = self.elapsed(inputs.now)
        if self._finished:
            return BehaviorStep(STOP, elapsed, done=True)
        teleop = inputs.teleop
        fresh = inputs.now - inputs.teleop_stamp <= self.params.teleop_timeout
        if teleop is None or not fresh or not teleop.is_finite():
            return BehaviorStep(STOP, elapsed)
        return BehaviorStep(self.filtered(pose, teleop), elapsed)

    def filtered(self, pose: Pose2D, twist: Velocity) -> Velocity:
        checker = self.collision()
        if checker is None or (twist.v == 0.0 and twist.w == 0.0):
            return twist
        steps = max(1, round(self.safety.simulate_ahead_time / self.params.projection_time))
        times = self.params.projection_time * np.arange(1, steps + 1, dtype=np.float64)
        poses = integrate_arc(pose, twist, times)
        blocked = checker.lethal_mask(checker.costmap.costs_at(poses[:, :2]))
        if not blocked.any():
            return twist
        first = int(np.argmax(blocked))  # index k-1 of the first colliding step
        scale = first / steps
        return Velocity(twist.v * scale, twist.w * scale)
