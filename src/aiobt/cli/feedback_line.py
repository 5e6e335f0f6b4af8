"""``aiobt navigate``'s progress: one line, honest about the poses passed and the end.

- :class:`PassedPoses` counts ``--through`` poses down as the robot passes them
  (within ``radius``, in order; the last one only when the goal is reached). The
  navigator's own count drops only when its tree drops the goals (Nav2's
  RemovePassedGoals, ticked when it replans), so the lower of the two is shown.
- :class:`FeedbackLine` shows the newest feedback: one rewritten line on a
  terminal, a line a second otherwise; at the end the newest feedback is shown if
  it was not yet, so no stale "1.20 m" stands above "goal reached"; feedback
  before the first path (distance 0) is not shown.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import TextIO

from aiobt.display import plural
from aiobt.embed import Feedback

PASSED_RADIUS = 0.7  # m: a pose counts as passed within this (the through-poses tree's radius)


class PassedPoses:
    """How many of ``poses`` (X, Y[, YAW]) are still ahead of the robot."""

    def __init__(self, poses: Sequence[Sequence[float]], radius: float = PASSED_RADIUS) -> None:
        self.poses = [(p[0], p[1]) for p in poses]
        self.radius = radius
        self.passed = 0

    def update(self, x: float, y: float) -> int:
        """The poses left once the robot is at (x, y)."""
        while self.passed < len(self.poses) - 1:
            px, py = self.poses[self.passed]
            if math.hypot(px - x, py - y) > self.radius:
                break
            self.passed += 1
        return len(self.poses) - self.passed


class FeedbackLine:
    """Live feedback on ``out``; ``through``: the poses of a navigate_through_poses goal."""

    def __init__(self, out: TextIO, through: Sequence[Sequence[float]] = ()) -> None:
        self.out = out
        self.live = out.isatty()
        self.passed = PassedPoses(through) if through else None
        self.latest: Feedback | None = None
        self._shown = True
        self._last = 0.0
        self._planned = False

    def __call__(self, feedback: Feedback) -> None:
        # before the first path the distance reads 0 (Nav2's feedback): not worth a line
        self._planned |= feedback.distance_remaining > 0.0
        if not self._planned:
            return
        self.latest, self._shown = feedback, False
        now = time.monotonic()  # wall time by intent: how often a person reads the line
        if self.live or now - self._last >= 1.0:
            self._last = now
            self._show(feedback)

    def text(self, feedback: Feedback) -> str:
        text = (
            f"distance remaining {feedback.distance_remaining:6.2f} m  "
            f"time {feedback.navigation_time:6.1f} s  "
            f"{plural(feedback.number_of_recoveries, 'recovery')}"
        )
        remaining = getattr(feedback, "number_of_poses_remaining", None)
        if self.passed is not None and remaining is not None:
            position = feedback.current_pose.pose.position
            left = min(remaining, self.passed.update(position.x, position.y))
            text += f"  {plural(left, 'pose')} left"
        return text

    def _show(self, feedback: Feedback) -> None:
        self._shown = True
        text = self.text(feedback)
        self.out.write(f"\r{text:<70}" if self.live else f"{text}\n")
        self.out.flush()

    def note(self, text: str) -> None:
        """A line of news (a service went away) between the progress lines."""
        self.out.write(f"\r{text:<70}\n" if self.live else f"{text}\n")
        if self.live and self.latest is not None:
            self._show(self.latest)  # the live line again, below the news
        self.out.flush()

    def end(self) -> None:
        """The newest feedback if it was not shown yet; a terminal's line is ended."""
        if self.latest is not None and not self._shown:
            self._show(self.latest)
        if self.live:
            self.out.write("\n")
            self.out.flush()

    def distance_to(self, x: float, y: float) -> float | None:
        """How far the robot was from (x, y) at the newest feedback (None: no feedback)."""
        if self.latest is None:
            return None
        position = self.latest.current_pose.pose.position
        return math.hypot(position.x - x, position.y - y)
