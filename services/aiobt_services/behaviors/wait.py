"""Wait: let ``duration`` seconds of robot time pass; never commands the base."""

from __future__ import annotations

from .base import BehaviorInputError, BehaviorStep, Inputs, require_finite


class WaitBehavior:
    """Succeeds once ``duration`` s of clock time have passed since the first cycle."""

    __slots__ = ("_end", "duration")

    def __init__(self, duration: float) -> None:
        self.duration = require_finite("wait duration", duration)
        if duration < 0.0:
            raise BehaviorInputError(f"wait duration must be >= 0, got {duration!r}")
        self._end: float | None = None

    def step(self, inputs: Inputs) -> BehaviorStep:
        if self._end is None:
            self._end = inputs.now + self.duration
        left = max(0.0, self._end - inputs.now)
        return BehaviorStep(None, left, done=left <= 0.0)
