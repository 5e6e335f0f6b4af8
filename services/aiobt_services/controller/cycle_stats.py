"""Per-goal control-loop statistics (cycles, achieved rate in robot time, cycle compute
time) and the loop's schedule."""

from __future__ import annotations

import math


class CycleStats:
    """Cycles of one FollowPath goal: when each began (robot clock seconds), how long
    its work took (seconds of wall time spent computing, not waiting) and how much of
    that the loop's thread ran (CPU seconds; the rest it waited for a core)."""

    __slots__ = (
        "_cpu", "_durations", "_first", "_last", "_lost", "_sleeps", "_slept", "_updates",
        "period",
    )  # fmt: skip

    def __init__(self, period: float) -> None:
        if not (math.isfinite(period) and period > 0.0):
            raise ValueError(f"control period must be finite and > 0, got {period!r}")
        self.period = period
        self._durations: list[float] = []
        self._cpu: list[float] = []
        self._updates: list[float] = []  # local costmap updates between cycles, wall s
        self._first = math.nan
        self._last = math.nan
        self._lost = 0  # control slots skipped (a cycle began >= 2 periods after the last)
        self._slept = (math.nan, math.nan)  # the last sleep before a cycle: robot s, wall s
        self._sleeps: list[tuple[float, float]] = []  # the sleeps before a loss

    def record(self, began: float, duration: float, cpu: float = math.nan) -> None:
        if not self._durations:
            self._first = began
        elif began - self._last >= 2.0 * self.period - 1e-9:  # slots skipped since the last
            self._lost += int((began - self._last) / self.period + 1e-9) - 1
            if not math.isnan(self._slept[1]):
                self._sleeps.append(self._slept)
        self._last = began
        self._slept = (math.nan, math.nan)
        self._durations.append(duration)
        self._cpu.append(cpu)

    def record_sleep(self, robot: float, wall: float) -> None:
        """The loop slept ``robot`` clock seconds, ``wall`` wall seconds before the next cycle
        (after a loss: a long wall time woke late; a short one, the robot's clock ran ahead)."""
        self._slept = (robot, wall)

    def record_update(self, duration: float) -> None:
        """A local costmap update made between two cycles took ``duration`` wall s."""
        self._updates.append(duration)

    @property
    def cycles(self) -> int:
        return len(self._durations)

    def rate(self) -> float:
        """Cycles per robot second between the first and the last cycle (nan if < 2)."""
        span = self._last - self._first
        if self.cycles < 2 or not span > 0.0:
            return math.nan
        return (self.cycles - 1) / span

    def percentile(self, q: float) -> float:
        """The ``q`` (0-100) percentile of the cycle times, in seconds (nearest rank)."""
        return _nearest_rank(self._durations, q)

    def cpu_percentile(self, q: float) -> float:
        """The ``q`` percentile of the cycles' CPU times, in seconds (nan: none recorded)."""
        return _nearest_rank([c for c in self._cpu if not math.isnan(c)], q)

    def summary(self) -> str:
        """One line: ``N cycles, rate R of C Hz, cycle p50 A ms p99 B ms max M ms, cpu p50
        D ms p99 E ms, costmap updates U p50 F ms p99 G ms, slots lost L (the sleeps before
        them: robot p50 H ms, wall p50 K ms p90 M ms)``; no parenthesis when none was lost."""
        updates = [_nearest_rank(self._updates, q) * 1e3 for q in (50, 99)]
        robot = _nearest_rank([r for r, _ in self._sleeps], 50) * 1e3
        wall = [_nearest_rank([w for _, w in self._sleeps], q) * 1e3 for q in (50, 90)]
        return (
            f"{self.cycles} cycles, rate {self.rate():.2f} of {1.0 / self.period:.2f} Hz, "
            f"cycle p50 {self.percentile(50) * 1e3:.2f} ms p99 {self.percentile(99) * 1e3:.2f} ms "
            f"max {self.percentile(100) * 1e3:.2f} ms, cpu p50 {self.cpu_percentile(50) * 1e3:.2f}"
            f" ms p99 {self.cpu_percentile(99) * 1e3:.2f} ms, costmap updates {len(self._updates)}"
            f" p50 {updates[0]:.2f} ms p99 {updates[1]:.2f} ms, slots lost {self._lost}"
            + (
                f" (the sleeps before them: robot p50 {robot:.0f} ms, wall p50 {wall[0]:.1f} ms"
                f" p90 {wall[1]:.1f} ms)"
                if self._lost
                else ""
            )
        )


def _nearest_rank(values: list[float], q: float) -> float:
    if not values:
        return math.nan
    ordered = sorted(values)
    rank = max(1, math.ceil(q / 100.0 * len(ordered)))
    return ordered[rank - 1]


class CycleSchedule:
    """When the next control cycle is due: a period after the previous cycle's deadline
    (rclcpp's ``Rate``, which Nav2's controller server loops on), not a period after the
    work ended, so the work and a late wake-up do not stretch the period.

    A cycle more than a whole period behind starts the schedule over at once (no burst
    of cycles to catch up); after a clock that went back (a simulation restarted) the
    next cycle is a period from now."""

    __slots__ = ("_deadline", "period")

    def __init__(self, period: float, start: float) -> None:
        if not (math.isfinite(period) and period > 0.0):
            raise ValueError(f"control period must be finite and > 0, got {period!r}")
        self.period = period
        self._deadline = start

    def delay(self, now: float) -> float:
        """Seconds from ``now`` until the next cycle (0: due already); moves the schedule."""
        if now < self._deadline - self.period:  # the clock went back
            self._deadline = now + self.period
        else:
            self._deadline += self.period
            if now - self._deadline > self.period:  # overran by more than a period
                self._deadline = now
        return max(0.0, self._deadline - now)
