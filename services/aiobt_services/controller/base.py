"""The controller plugin interface (Nav2's nav2_core::Controller, in Python)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, Protocol

import numpy as np

from aiobt.costmap.checker import CollisionChecker
from aiobt.geometry import FloatArray, PlanarPath, Pose2D, Velocity

from .errors import no_valid_control
from .speed_limit import SpeedLimit

NO_TRAJECTORY: FloatArray = np.zeros((0, 3))
NO_TRAJECTORY.setflags(write=False)


@dataclass(slots=True, frozen=True)
class ControlContext:
    """What a controller sees each cycle besides the pose and speed."""

    dt: float
    goal_xy_tolerance: float
    collision: CollisionChecker | None
    lead: float = 0.0  # clock s until a command sent now acts (transport under a speed-up)


class Controller(Protocol):
    """Computes one velocity command per control cycle.

    ``compute_velocity`` raises :class:`ControllerError` (NO_VALID_CONTROL) when
    no safe command exists; the caller stops the robot and applies its patience
    (``failure_tolerance``: then PATIENCE_EXCEEDED, or at once with 0).
    """

    def set_plan(self, path: PlanarPath) -> None: ...

    def reset(self) -> None: ...

    def set_speed_limit(self, limit: SpeedLimit) -> None:
        """Nav2's ``setSpeedLimit``: from now on, the top speed under ``limit``."""
        ...

    def compute_velocity(self, pose: Pose2D, speed: Velocity, ctx: ControlContext) -> Velocity: ...

    @property
    def trajectory(self) -> FloatArray:
        """Poses ``(n, 3)`` (x, y, yaw, in the plan's frame) the robot is expected to follow
        after the last :meth:`compute_velocity` (Nav2's ``local_plan``); none before one."""
        ...


class PlanFollower:
    """What RPP and DWB share: the plan and the segment the robot was last projected onto."""

    __slots__ = ("_path", "_segment", "trajectory")
    name: ClassVar[str]  # in the "no path" error

    def __init__(self) -> None:
        self._path: PlanarPath | None = None
        self._segment = 0
        self.trajectory = NO_TRAJECTORY

    def set_plan(self, path: PlanarPath) -> None:
        self._path = path
        self._segment = 0
        self.trajectory = NO_TRAJECTORY

    def reset(self) -> None:
        self._path = None
        self._segment = 0
        self.trajectory = NO_TRAJECTORY

    def _require_path(self) -> PlanarPath:
        if self._path is None:
            raise no_valid_control(f"{self.name} has no path to follow")
        return self._path
