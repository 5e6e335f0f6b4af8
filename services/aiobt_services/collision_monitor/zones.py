"""One polygon's verdict on the points: triggered (stop, slowdown, limit, with Nav2's
consecutive-cycle debounce) or the time before a collision (approach)."""

from __future__ import annotations

import math

import numpy as np

from .params import ZoneParams
from .shapes import Points, Shape
from .velocity_polygons import select

Vel = tuple[float, float, float]  # vx, vy, wz


def simulated_poses(velocity: Vel, step: float, horizon: float) -> np.ndarray:
    """Nav2's ``projectState`` steps up to ``horizon``: (k, 3) poses x, y, yaw after
    each step, the velocity turning with the base as it goes."""
    count = math.floor(horizon / step + 1e-9) + 1
    vx, vy, wz = velocity
    turn = np.arange(count) * (wz * step)  # the heading during each step
    c, s = np.cos(turn), np.sin(turn)
    moves = np.column_stack((vx * c - vy * s, vx * s + vy * c)) * step
    xy = np.cumsum(moves, axis=0)
    return np.column_stack((xy, turn + wz * step))


class Zone:
    """A polygon of the monitor and its trigger state."""

    __slots__ = ("_hits", "_misses", "active", "params", "shape")

    def __init__(self, params: ZoneParams) -> None:
        self.params = params
        self.shape: Shape = params.shape
        self.reset()

    def update(self, cmd: Vel) -> None:
        """A velocity polygon takes the shape of the first sub-polygon covering ``cmd``
        (none: it keeps its shape, as Nav2's)."""
        if self.params.sub_polygons:
            sub = select(self.params.sub_polygons, cmd, self.params.holonomic)
            if sub is not None:
                self.shape = sub.shape

    def reset(self) -> None:
        self._hits = 0
        self._misses = 0
        self.active = False

    def count(self, points: Points) -> int:
        return int(np.count_nonzero(self.shape.inside(points)))

    def triggered(self, points: Points) -> bool:
        """Whether ``min_points`` lie inside, after the consecutive-cycle debounce."""
        p = self.params
        hit = self.count(points) >= p.min_points
        if p.trigger_consecutive_points == 1 and p.release_consecutive_points == 1:
            self.active = hit
            return hit
        self._hits, self._misses = (self._hits + 1, 0) if hit else (0, self._misses + 1)
        if self._hits >= p.trigger_consecutive_points:
            self.active = True
        elif self._misses >= p.release_consecutive_points:
            self.active = False
        return self.active

    def collision_time(self, points: Points, velocity: Vel) -> float:
        """Seconds until ``min_points`` would be inside moving at ``velocity`` (Nav2's
        ``getCollisionTime``: 0 if already, the step's start time, -1 if not within
        ``time_before_collision``)."""
        p = self.params
        if self.count(points) >= p.min_points:
            return 0.0
        poses = simulated_poses(velocity, p.simulation_time_step, p.time_before_collision)
        travel = float(np.max(np.hypot(poses[:, 0], poses[:, 1])))
        reach = self.shape.reach + travel  # no point farther can enter the zone
        points = points[np.hypot(points[:, 0], points[:, 1]) <= reach]
        if len(points) < p.min_points:
            return -1.0
        c, s = np.cos(poses[:, 2]), np.sin(poses[:, 2])
        dx = points[None, :, 0] - poses[:, None, 0]
        dy = points[None, :, 1] - poses[:, None, 1]
        moved = np.stack(
            (dx * c[:, None] + dy * s[:, None], -dx * s[:, None] + dy * c[:, None]), -1
        )
        inside = self.shape.inside(moved.reshape(-1, 2)).reshape(len(poses), len(points))
        colliding = np.flatnonzero(np.count_nonzero(inside, axis=1) >= p.min_points)
        return float(colliding[0] * p.simulation_time_step) if colliding.size else -1.0
