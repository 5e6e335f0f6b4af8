"""The robot in one frame, as a control cycle reads it."""

from __future__ import annotations

from dataclasses import dataclass

from aiobt.geometry import Pose2D, Velocity

from .freshness import FRESH, PoseAge


@dataclass(slots=True, frozen=True)
class RobotState:
    """A pose (and measured velocity) in one frame: ``stamp`` its arrival on the service's
    clock, ``age`` how fresh it is (:class:`~.freshness.PoseAge`, as of this cycle)."""

    pose: Pose2D
    velocity: Velocity
    stamp: float
    age: PoseAge = FRESH
