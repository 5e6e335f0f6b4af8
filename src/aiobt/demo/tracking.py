"""How far the pose estimate was off the truth during the demo: ``{ns}/pose`` and
``{ns}/sim/pose`` paired by stamp (the robot stamps both with the step they were taken
at; the localization stamps its pose with the odometry's, taken at the same step)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

XY = tuple[float, float]
KEEP = 256  # unpaired messages kept per stream: 5 s at the robot's 50 Hz


@dataclass(slots=True)
class TrackingError:
    """The distance between estimate and truth at each stamp both have: RMS and worst."""

    pairs: int = 0
    _sum_sq: float = 0.0
    worst: float = 0.0
    _estimates: dict[float, XY] = field(default_factory=dict)
    _truths: dict[float, XY] = field(default_factory=dict)

    def on_estimate(self, stamp: float, at: XY) -> None:
        self._pair(stamp, at, self._estimates, self._truths)

    def on_truth(self, stamp: float, at: XY) -> None:
        self._pair(stamp, at, self._truths, self._estimates)

    def _pair(self, stamp: float, at: XY, mine: dict[float, XY], other: dict[float, XY]) -> None:
        match = other.pop(stamp, None)
        if match is None:
            mine[stamp] = at
            while len(mine) > KEEP:  # the other stream never had these stamps
                del mine[next(iter(mine))]
            return
        error = math.dist(at, match)
        self.pairs += 1
        self._sum_sq += error * error
        self.worst = max(self.worst, error)

    @property
    def rms(self) -> float:
        return math.sqrt(self._sum_sq / self.pairs) if self.pairs else 0.0

    def summary(self) -> str:
        """``pose estimate off the truth by 1.2 cm RMS, 4.0 cm at worst``; "" with no pair
        (no truth: not a simulation)."""
        if not self.pairs:
            return ""
        return (
            f"pose estimate off the truth by {100 * self.rms:.1f} cm RMS, "
            f"{100 * self.worst:.1f} cm at worst"
        )
