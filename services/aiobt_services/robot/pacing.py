"""When the next physics step is due, and how far the simulation falls behind.

:class:`Pacer` is the pure decision half of the service's loop: given the wall
time and the sim time it says how long to wait before the next step (0: step
now). Sim time runs ``speed`` times as fast as wall time; ``speed`` infinite
(``--speed max``) never waits. When the simulation falls more than
``max_lag`` wall seconds behind its target it does not try to catch up in a
burst (the robot would run ahead of its commands): the target is moved to now
and the sim time given up is counted. :meth:`Pacer.report` returns, at most
once per ``report_every`` wall seconds, how far behind the simulation fell and
how often, or (``--speed max``) the speed-up achieved, and how often the
runner waited for a late command (:meth:`Pacer.held`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(slots=True)
class _Window:
    """What happened since the last report."""

    wall: float
    sim: float
    lost: float = 0.0  # sim seconds given up by moving the target
    events: int = 0  # times the target was moved
    holds: int = 0  # times the sim waited for a late command
    held: float = 0.0  # wall seconds waited in all


def parse_speed(text: str) -> float:
    """``--speed``: a finite number > 0, or ``max`` (as fast as the machine allows)."""
    if text.strip().lower() == "max":
        return math.inf
    try:
        value = float(text)
    except ValueError:
        raise ValueError(f"speed must be a number > 0 or 'max', got {text!r}") from None
    if not (math.isfinite(value) and value > 0.0):
        raise ValueError(f"speed must be a finite number > 0 or 'max', got {text!r}")
    return value


def speed_label(speed: float) -> str:
    return "max" if math.isinf(speed) else f"x{speed:g}"


MET = 0.95  # of --speed achieved over a report's span: the speed was met (lag made up)


class Pacer:
    """Paces steps of ``dt`` sim seconds against a wall clock read by the caller."""

    __slots__ = (
        "_dt", "_max_lag", "_report_every", "_sim0", "_wall0", "_window", "fell_short", "speed",
    )  # fmt: skip

    def __init__(
        self, speed: float, dt: float, *, max_lag: float = 0.25, report_every: float = 5.0
    ) -> None:
        if not (speed > 0.0 and not math.isnan(speed)):
            raise ValueError(f"speed must be > 0 (or infinite for max), got {speed}")
        for name, value in (("dt", dt), ("max_lag", max_lag), ("report_every", report_every)):
            if not (math.isfinite(value) and value > 0.0):
                raise ValueError(f"Pacer {name} must be a finite number > 0, got {value}")
        self.speed = speed
        self._dt = dt
        self._max_lag = max_lag
        self._report_every = report_every
        self._wall0 = self._sim0 = 0.0
        self._window = _Window(0.0, 0.0)
        self.fell_short = False  # the last report's span achieved less than MET of speed

    @property
    def unpaced(self) -> bool:
        """``--speed max``: step as fast as the machine allows."""
        return math.isinf(self.speed)

    def start(self, wall: float, sim: float) -> None:
        self._wall0, self._sim0 = wall, sim
        self._window = _Window(wall, sim)

    def delay(self, wall: float, sim: float) -> float:
        """Wall seconds to wait before the step from ``sim`` (0: step now).

        Behind by more than ``max_lag`` wall seconds: the target moves to now
        (counted for the next report) instead of being caught up in a burst.
        """
        if self.unpaced:
            return 0.0
        target = self._sim0 + (wall - self._wall0) * self.speed
        behind = target - sim
        if behind > self._max_lag * self.speed:
            self._window.lost += behind
            self._window.events += 1
            self._wall0, self._sim0 = wall, sim
            return 0.0
        due = self._wall0 + (sim + self._dt - self._sim0) / self.speed
        return max(0.0, due - wall)

    def held(self, wall: float, sim: float, seconds: float) -> None:
        """The sim waited ``seconds`` of wall time for a late command: counted for the
        report, and the target restarts from now (the wait is not lag to catch up)."""
        self._window.holds += 1
        self._window.held += seconds
        self._wall0, self._sim0 = wall, sim

    def report(self, wall: float, sim: float) -> str | None:
        """A line on the last ``report_every`` s: lag (how far, how often) or achieved speed."""
        window = self._window
        span = wall - window.wall
        if span < self._report_every:
            return None
        achieved = (sim - window.sim) / span if span > 0.0 else 0.0
        self._window = _Window(wall, sim)
        met = self.unpaced or achieved >= MET * self.speed
        self.fell_short = not met
        holds = (
            f"; waited {window.holds} time(s), {window.held:.2f} s in all, for a late cmd_vel"
            if window.holds
            else ""
        )
        if self.unpaced:
            return f"running as fast as possible: x{achieved:.1f} over the last {span:.1f} s{holds}"
        if window.events == 0 and window.holds == 0:
            return None
        head = f"achieved x{achieved:.1f} over the last {span:.1f} s"
        if window.events == 0:
            return f"simulation at --speed {self.speed:g}: {head}{holds}"
        where = "at" if met else "behind"
        return (
            f"simulation {where} --speed {self.speed:g}: {head}; fell more than "
            f"{self._max_lag:g} s behind {window.events} time(s), {window.lost:.2f} s of sim "
            f"time given up{holds}"
        )
