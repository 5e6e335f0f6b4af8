"""The followed box's path: a closed loop through points, walked by arc length; a
seeded loop (an ellipse with bumps) and its check against the world's walls."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from aiobt.geometry import Pose2D

from .mapfile import MapInfo

FloatArray = npt.NDArray[np.float64]
LOOP_POINTS = 180
BUMPS = (2, 3, 4)  # the harmonics of the seeded bumps
BUMP_SIZE = 0.04  # of each radius, per harmonic


class PathError(ValueError):
    """A path the box cannot follow, naming where."""


@dataclass(slots=True, frozen=True)
class LoopPath:
    """A closed polyline (N x 2, the last point joined to the first)."""

    points: FloatArray
    _cumulative: FloatArray

    @classmethod
    def through(cls, points: npt.ArrayLike) -> LoopPath:
        pts = np.asarray(points, dtype=np.float64)
        if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 3 or not np.all(np.isfinite(pts)):
            raise PathError("a loop needs at least 3 finite (x, y) waypoints")
        seg = np.linalg.norm(np.diff(np.vstack([pts, pts[:1]]), axis=0), axis=1)
        if np.any(seg == 0.0):
            raise PathError("a loop's consecutive waypoints must differ")
        return cls(pts, np.concatenate([[0.0], np.cumsum(seg)]))

    @property
    def length(self) -> float:
        return float(self._cumulative[-1])

    def pose_at(self, s: float) -> Pose2D:
        """The point ``s`` m along the loop, heading along it."""
        s = s % self.length
        i = int(np.searchsorted(self._cumulative, s, side="right")) - 1
        a, b = self.points[i], self.points[(i + 1) % len(self.points)]
        frac = (s - self._cumulative[i]) / (self._cumulative[i + 1] - self._cumulative[i])
        x, y = a + frac * (b - a)
        return Pose2D(float(x), float(y), math.atan2(b[1] - a[1], b[0] - a[0]))

    def check_clear(self, world: MapInfo, clearance: float) -> None:
        """PathError naming the first point within ``clearance`` of a wall."""
        step = max(world.resolution, 0.05)
        for s in np.arange(0.0, self.length, step):
            p = self.pose_at(float(s))
            if not world.contains(p.x, p.y, margin=clearance) or world.disc_blocked(
                p.x, p.y, clearance
            ):
                raise PathError(
                    f"the path passes within {clearance:.2f} m of a wall or the world's edge "
                    f"at ({p.x:.2f}, {p.y:.2f}), {s:.1f} m along it"
                )


def seeded_loop(centre: tuple[float, float], radii: tuple[float, float], seed: int) -> LoopPath:
    """An ellipse round ``centre`` with seeded bumps, starting at a seeded point and
    running a seeded way round."""
    rng = np.random.default_rng(seed)
    theta = np.linspace(0.0, 2.0 * math.pi, LOOP_POINTS, endpoint=False)
    theta = theta + rng.uniform(0.0, 2.0 * math.pi)
    if rng.uniform() < 0.5:
        theta = theta[::-1]
    scale = np.ones_like(theta)
    for k in BUMPS:
        scale += BUMP_SIZE * rng.uniform(-1.0, 1.0) * np.cos(k * theta + rng.uniform(0, 6.3))
    rx, ry = radii
    xs = centre[0] + rx * scale * np.cos(theta)
    ys = centre[1] + ry * scale * np.sin(theta)
    return LoopPath.through(np.stack([xs, ys], axis=1))
