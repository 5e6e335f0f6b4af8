"""The controller plugin interface (Nav2's nav2_core::Controller, in Python)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from .collision import CollisionChecker
from .geometry import PlanarPath, Pose2D, Velocity


@dataclass(slots=True, frozen=True)
class ControlContext:
    """What a controller sees each cycle besides the pose and speed."""

    dt: float
    goal_xy_tolerance: float
    collision: CollisionChecker | None


class Controller(Protocol):
    """Computes one velocity command per control cycle.

    ``compute_velocity`` raises :class:`ControllerError` (NO_VALID_CONTROL) when
    no safe command exists; the caller stops the robot and applies its patience
    (``failure_tolerance``: then PATIENCE_EXCEEDED, or at once with 0).
    """

    def set_plan(self, path: PlanarPath) -> None: ...

    def reset(self) -> None: ...

    def compute_velocity(self, pose: Pose2D, speed: Velocity, ctx: ControlContext) -> Velocity: ...
