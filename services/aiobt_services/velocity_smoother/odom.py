"""The measured velocity for CLOSED_LOOP feedback: Nav2's ``OdomSmoother``, the mean
twist of the odometry received in the last ``odom_duration`` seconds (by stamp)."""

from __future__ import annotations

import math
from collections import deque

import numpy as np

from .limits import Vec


class OdomAverage:
    """The mean of the twists ``[vx, vy, wz]`` stamped within ``duration`` of the newest."""

    __slots__ = ("_history", "duration")

    def __init__(self, duration: float) -> None:
        self.duration = duration
        self._history: deque[tuple[float, Vec]] = deque()

    def add(self, stamp: float, twist: Vec) -> None:
        """One odometry message; a non-finite twist is ignored (it would poison the mean)."""
        if not (math.isfinite(stamp) and bool(np.all(np.isfinite(twist)))):
            return
        if self._history and stamp < self._history[-1][0]:
            self._history.clear()  # time went back: a restarted robot
        self._history.append((stamp, twist))
        while self._history and self._history[0][0] < stamp - self.duration:
            self._history.popleft()

    def twist(self) -> Vec:
        """The mean twist; zero before any odometry (as Nav2's)."""
        if not self._history:
            return np.zeros(3)
        return np.asarray(np.mean([t for _, t in self._history], axis=0), np.float64)
