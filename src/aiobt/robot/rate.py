"""A gate that opens at most once per period of robot time."""

from __future__ import annotations

import math


class RateGate:
    """``due(now)`` is True at most once per ``period`` seconds of ``now`` (robot time)."""

    __slots__ = ("_last", "period")

    def __init__(self, period: float) -> None:
        if not (math.isfinite(period) and period > 0.0):
            raise ValueError(f"publishing period must be finite and > 0 s, got {period!r}")
        self.period = period
        self._last: float | None = None

    def due(self, now: float) -> bool:
        # a clock that went back (a simulation restarted) opens the gate again
        if self._last is not None and 0.0 <= now - self._last < self.period:
            return False
        self._last = now
        return True

    def reset(self) -> None:
        """The next :meth:`due` is True (a new goal shows its costmap at once)."""
        self._last = None
